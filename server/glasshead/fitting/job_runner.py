"""The bounded pool of worker processes that runs the fit jobs (``jobs.run_job``).

One ``FitRunner`` per application, made in ``create_app`` and started and stopped by its
lifespan. The pool (``settings.fit_workers`` processes, 1 by default) is a
``ProcessPoolExecutor`` over spawned processes: a fork of the server would copy its event loop
and threads. A worker is started at the first job and reads the assets once.

The queue is the database: a job is a row in state ``queued`` and the executor is handed only
its id. ``queue_full`` answers whether ``settings.fit_queue_limit`` jobs already wait (the API
answers 503). At shutdown the waiting futures are cancelled (their rows stay ``queued``) and a fit
still running is stopped with its worker and marked failed.

Several servers (workers of one server, or app containers behind a load balancer) share the
database, so none may decide alone about another's jobs. A running fit writes its progress to its
row several times a second; a row left ``running`` with no change for ``STALE_AFTER_S`` has lost
its worker (its server crashed or was killed) and is marked failed, by whichever server sweeps
first. Every server sweeps at start and then every ``SWEEP_S``, and hands the ``queued`` rows it
does not hold to its pool, so a job queued by a server that died is run by another; claiming a
job is one conditional UPDATE (``jobs.claim_job``), so a job two servers hand on runs once.
"""

import logging
import multiprocessing
import threading
from concurrent.futures import Future, ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from datetime import timedelta

from sqlalchemy import func, select, update
from sqlalchemy.orm import Session

from glasshead.fitting.jobs import run_job
from glasshead.store.base import utc_now
from glasshead.store.db import engine_for
from glasshead.store.fit_jobs import FitJob

log = logging.getLogger("glasshead.fits")

#: Times a job that never started is handed to a new pool after its pool broke.
RESUBMITS = 2
STOPPED_MESSAGE = "the server stopped while this fit was running; upload it again"
#: A running job whose row has not changed for this long has lost its worker (a fit writes its
#: progress several times a second and takes seconds, not minutes).
STALE_AFTER_S = 60.0
#: How often a server looks for stale running jobs and for queued jobs nobody holds.
SWEEP_S = 5.0


class FitRunner:
    """Hands queued fit jobs to a pool of worker processes (see the module docstring)."""

    def __init__(self, database_url: str, assets_dir, *, workers: int = 1, queue_limit: int = 8):
        if workers < 1 or queue_limit < 1:
            raise ValueError("a fit runner needs at least one worker and a queue of one")
        self.database_url = database_url
        self.assets_dir = str(assets_dir)
        self.workers = workers
        self.queue_limit = queue_limit
        self._executor: ProcessPoolExecutor | None = None
        self._futures: dict[int, Future] = {}
        self._stopping = False
        self._lock = threading.RLock()
        self._retries: dict[int, int] = {}
        self._wake = threading.Event()
        self._sweeper: threading.Thread | None = None

    def start(self) -> None:
        """Sweep once (fail the stale running jobs, hand on the queued ones), then every
        ``SWEEP_S`` in a background thread until ``shutdown``."""
        self.sweep()
        self._sweeper = threading.Thread(target=self._sweep_until_stopped, daemon=True,
                                         name="fit-job-sweeper")
        self._sweeper.start()

    def sweep(self) -> None:
        """Mark failed the running jobs unchanged for ``STALE_AFTER_S``; hand every queued job
        this runner does not already hold to the pool."""
        stale_before = utc_now() - timedelta(seconds=STALE_AFTER_S)
        with Session(engine_for(self.database_url)) as session:
            session.execute(update(FitJob).where(FitJob.state == "running",
                                                 FitJob.updated_at < stale_before).values(
                state="failed", message=STOPPED_MESSAGE, finished_at=utc_now(),
                updated_at=utc_now()))
            session.commit()
            waiting = session.scalars(select(FitJob.id).where(FitJob.state == "queued")
                                      .order_by(FitJob.id)).all()
        for job_id in waiting:
            if job_id not in self._futures:
                self.submit(job_id)

    def _sweep_until_stopped(self) -> None:
        while not self._wake.wait(SWEEP_S):
            try:
                self.sweep()
            except Exception:  # a database hiccup: the next sweep tries again
                log.exception("fit job sweep failed")

    def queue_full(self, session: Session) -> bool:
        queued = session.scalar(select(func.count()).select_from(FitJob)
                                .where(FitJob.state == "queued"))
        return queued >= self.queue_limit

    def submit(self, job_id: int) -> None:
        with self._lock:
            if self._stopping:
                return  # left queued for the next start
            for _attempt in range(2):
                if self._executor is None:
                    self._executor = ProcessPoolExecutor(
                        max_workers=self.workers,
                        mp_context=multiprocessing.get_context("spawn"))
                try:
                    future = self._executor.submit(run_job, self.database_url, self.assets_dir,
                                                   job_id)
                    break
                except BrokenProcessPool:  # a worker died: the pool takes no more work
                    self._executor.shutdown(wait=False, cancel_futures=True)
                    self._executor = None
            self._futures[job_id] = future
        future.add_done_callback(lambda done, job_id=job_id: self._done(job_id, done))

    def _done(self, job_id: int, future: Future) -> None:
        self._futures.pop(job_id, None)
        if future.cancelled():
            return
        error = future.exception()
        if error is None:
            return
        # The worker itself broke (killed, out of memory, ...): the job it ran fails, and jobs
        # the broken pool held that never started are handed to a new pool.
        if self._stopping:
            self._fail(job_id, STOPPED_MESSAGE, states=("running",))
            return
        with Session(engine_for(self.database_url)) as session:
            state = session.scalar(select(FitJob.state).where(FitJob.id == job_id))
        self._retries[job_id] = self._retries.get(job_id, 0) + 1
        if state == "queued" and self._retries[job_id] <= RESUBMITS:
            self.submit(job_id)
            return
        log.error("fit job %s: worker failed: %r", job_id, error)
        self._fail(job_id, f"the worker process failed: {error.__class__.__name__}")

    def _fail(self, job_id: int, message: str, states=("queued", "running")) -> None:
        with Session(engine_for(self.database_url)) as session:
            session.execute(update(FitJob).where(FitJob.id == job_id, FitJob.state.in_(states))
                            .values(state="failed", message=message, finished_at=utc_now(),
                                    updated_at=utc_now()))
            session.commit()

    def shutdown(self) -> None:
        """Cancel what waits, stop what runs (its job is marked failed), end the workers."""
        with self._lock:
            executor, self._executor = self._executor, None
            self._stopping = True
        self._wake.set()
        if executor is None:
            return
        running = [job_id for job_id, future in list(self._futures.items())
                   if not future.cancel()]
        # A fit can run for minutes: its worker is stopped rather than waited for. The
        # executor's process table is the only handle on its workers (Python < 3.14).
        for process in list(getattr(executor, "_processes", {}).values()):
            if process.is_alive():
                process.terminate()
        executor.shutdown(wait=True, cancel_futures=True)
        for job_id in running:  # those the pool had taken but not started stay queued
            self._fail(job_id, STOPPED_MESSAGE, states=("running",))
