"""Each server's fit workers, taking jobs from the queue in the database (``jobs.fit_queue``).

One ``FitRunner`` per application, made in ``create_app`` and started and stopped by its
lifespan. Its workers are a ``jobs.pool.WorkerPool`` of ``settings.fit_workers`` spawned
processes (1 by default), at the compute workers' lower priority; with 0 the server stores
fits for other servers to run and runs none itself. A worker that dies (out of memory, a signal)
costs only the job it ran, which is marked failed; the worker is replaced for the next job.

A dispatcher thread claims a queued job (``fit_queue.claim_next``) whenever one of this
server's workers is free and hands only its id to the pool (``fit_job.run_job``); otherwise it
sleeps until woken: by this server storing a job (``wake``), by a ``NOTIFY`` from any server
(PostgreSQL, ``fit_queue.Listener``), by one of its jobs ending, or by its sweep. The sweep
marks failed the running rows unchanged for ``STALE_AFTER_S`` (their server died mid-job) and
claims what waits: every ``SWEEP_S`` on SQLite, where the other processes on the same file hear
of a job no other way; every ``SAFETY_SWEEP_S`` on PostgreSQL, only as a safety net (a server
that died mid-job, a notification sent while a listener was reconnecting).

``queue_full`` answers whether ``settings.fit_queue_limit`` jobs already wait (the API answers
503); the rows are counted, so the limit is shared by every server. At shutdown nothing more is
claimed, a fit still running is stopped with its worker and marked failed, and queued rows stay
queued for whichever server is up.
"""

import logging
import threading
import time
from concurrent.futures import Future
from functools import partial

from sqlalchemy import update
from sqlalchemy.engine import make_url
from sqlalchemy.orm import Session

from glasshead.jobs import fit_queue
from glasshead.jobs.compute import WORKER_NICENESS
from glasshead.jobs.fit_job import run_job
from glasshead.jobs.pool import WorkerDiedError, WorkerPool
from glasshead.store.db import engine_for
from glasshead.store.fit_jobs import FitJob

log = logging.getLogger("glasshead.fits")

#: A running job whose row has not changed for this long has lost its worker (a fit writes its
#: progress several times a second and takes seconds, not minutes).
STALE_AFTER_S = 60.0
#: How often a server on SQLite looks for queued jobs stored by other processes.
SWEEP_S = 5.0
#: How often a server on PostgreSQL (woken by NOTIFY) looks anyway.
SAFETY_SWEEP_S = 30.0


class FitRunner:
    """Claims queued fit jobs for a pool of worker processes (see the module docstring)."""

    def __init__(self, database_url: str, assets_dir, *, workers: int = 1, queue_limit: int = 8):
        if workers < 0 or queue_limit < 1:
            raise ValueError("a fit runner needs 0 or more workers and a queue of one")
        self.database_url = database_url
        self.assets_dir = str(assets_dir)
        self.workers = workers
        self.queue_limit = queue_limit
        self.postgres = make_url(database_url).get_backend_name() == "postgresql"
        self.sweep_s = SAFETY_SWEEP_S if self.postgres else SWEEP_S
        self._pool: WorkerPool | None = None
        self._running: dict[int, Future] = {}
        self._lock = threading.Lock()
        self._wake = threading.Event()
        self._stopping = False
        self._dispatcher: threading.Thread | None = None
        self._listener: fit_queue.Listener | None = None

    @property
    def running(self) -> list[int]:
        """The ids of the jobs this server's workers run now."""
        with self._lock:
            return list(self._running)

    def _session(self) -> Session:
        return Session(engine_for(self.database_url))

    def start(self) -> None:
        """Fail the jobs left running by a server that died; with workers, start taking jobs
        (the listener on PostgreSQL, the dispatcher and its sweep)."""
        with self._session() as session:
            fit_queue.fail_stale(session, STALE_AFTER_S)
        if self.workers == 0:
            return
        self._pool = WorkerPool(self.workers, name="fit", niceness=WORKER_NICENESS)
        if self.postgres:
            self._listener = fit_queue.Listener(self.database_url, self.wake).start()
        self._dispatcher = threading.Thread(target=self._dispatch, daemon=True,
                                            name="fit-job-dispatcher")
        self._dispatcher.start()
        self.wake()

    def wake(self) -> None:
        """Look for a queued job now (a worker may be free)."""
        self._wake.set()

    def announce(self, session: Session) -> None:
        """In the transaction that stores a job: tell every server when it commits."""
        fit_queue.announce(session)

    def queue_full(self, session: Session) -> bool:
        return fit_queue.queued_count(session) >= self.queue_limit

    def _dispatch(self) -> None:
        next_sweep = time.monotonic() + self.sweep_s
        while True:
            self._wake.wait(timeout=max(0.0, next_sweep - time.monotonic()))
            self._wake.clear()
            if self._stopping:
                return
            try:
                if time.monotonic() >= next_sweep:
                    next_sweep = time.monotonic() + self.sweep_s
                    with self._session() as session:
                        fit_queue.fail_stale(session, STALE_AFTER_S)
                self._claim_while_free()
            except Exception:  # a database hiccup: the next wake or sweep tries again
                log.exception("taking fit jobs failed")

    def _claim_while_free(self) -> None:
        while True:
            with self._lock:
                if self._stopping or len(self._running) >= self.workers:
                    return
                with self._session() as session:
                    job_id = fit_queue.claim_next(session)
                if job_id is None:
                    return
                future = self._pool.submit(run_job, self.database_url, self.assets_dir, job_id)
                self._running[job_id] = future
            future.add_done_callback(partial(self._done, job_id))

    def _done(self, job_id: int, future: Future) -> None:
        with self._lock:
            self._running.pop(job_id, None)
            stopping = self._stopping
        if future.cancelled():  # claimed, never started: the next server up takes it
            self._requeue(job_id)
        elif (error := future.exception()) is not None:
            if stopping:
                message = fit_queue.STOPPED_MESSAGE
            elif isinstance(error, WorkerDiedError):
                how = error.signal_name or f"exit code {error.exit_code}"
                message = (f"the worker process stopped ({how}) while it fitted; nothing else "
                           "was affected; upload it again")
            else:
                message = f"the worker process failed: {error.__class__.__name__}: {error}"
            log.error("fit job %s: %s", job_id, message)
            with self._session() as session:
                fit_queue.fail(session, job_id, message, states=("running",))
        self.wake()

    def _requeue(self, job_id: int) -> None:
        with self._session() as session:
            session.execute(update(FitJob).where(FitJob.id == job_id, FitJob.state == "running")
                            .values(state="queued", started_at=None))
            session.commit()

    def shutdown(self) -> None:
        """Claim nothing more; stop what runs (its job is marked failed); end the workers."""
        with self._lock:
            self._stopping = True
        self._wake.set()
        if self._dispatcher is not None:
            self._dispatcher.join(timeout=30)
        if self._listener is not None:
            self._listener.stop()
        if self._pool is not None:
            # A fit can run for minutes: its worker is stopped rather than waited for.
            self._pool.shutdown(kill_running=True)
