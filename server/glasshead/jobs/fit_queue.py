"""The fit queue: the ``fit_jobs`` rows in state ``queued``, in the database every server shares.

A server takes a job only when one of its fit workers is free (``claim_next``), so a busy
server never holds a job another could run. Taking one moves its row from ``queued`` to
``running`` in one short transaction:

- PostgreSQL: ``SELECT id ... WHERE state = 'queued' ORDER BY id LIMIT 1 FOR UPDATE SKIP
  LOCKED``, then the ``UPDATE``. Servers claiming at the same moment each lock a different row
  (a locked row is skipped, never waited for), so each job is taken once and nobody queues
  behind another's claim. A new row is announced with ``NOTIFY glasshead_fit_jobs`` in the
  transaction that stores it (``announce``; PostgreSQL delivers it at commit, and drops it with
  a rollback), and every server with fit workers ``LISTEN``s on a connection of its own
  (``Listener``), so a job queued on any server starts on whichever has a free worker at once.
- SQLite (one machine): the oldest queued row is claimed by an ``UPDATE ... WHERE state =
  'queued'`` (SQLite runs one writer at a time: of several claims of one row exactly one
  changes it; the others try the next). There is no NOTIFY; the runner that stored the row is
  woken directly, and other processes on the same file find it by their sweep.

A row left ``running`` by a server that died keeps its state; ``fail_stale`` marks failed the
running rows unchanged for longer than a live fit ever leaves them (it writes its progress
several times a second).
"""

import logging
import threading
from collections.abc import Callable
from datetime import timedelta

from sqlalchemy import Engine, func, select, text, update
from sqlalchemy.engine import make_url
from sqlalchemy.orm import Session

from glasshead.store.base import utc_now
from glasshead.store.fit_jobs import FitJob

log = logging.getLogger("glasshead.fits")

#: The PostgreSQL notification channel of new fit jobs.
CHANNEL = "glasshead_fit_jobs"
#: Seconds a listener waits for a notification before it looks whether it should stop.
LISTEN_POLL_S = 0.5
#: Seconds before a listener whose connection failed connects again.
RECONNECT_S = 2.0
STOPPED_MESSAGE = "the server stopped while this fit was running; upload it again"
#: The progress a claimed job starts with.
START_PROGRESS = {"evaluations": 0, "best_error": None, "fraction": 0.0}


def is_postgres(bind: Engine | Session) -> bool:
    engine = bind.get_bind() if isinstance(bind, Session) else bind
    return engine.dialect.name == "postgresql"


def claim_next(session: Session) -> int | None:
    """Move the oldest queued job to ``running`` and return its id; None when none is queued
    (or every queued one is being claimed by another server right now)."""
    while True:
        candidate = (select(FitJob.id).where(FitJob.state == "queued").order_by(FitJob.id)
                     .limit(1))
        if is_postgres(session):
            candidate = candidate.with_for_update(skip_locked=True)
        job_id = session.scalar(candidate)
        if job_id is None:
            session.rollback()
            return None
        now = utc_now()
        claimed = session.execute(
            update(FitJob).where(FitJob.id == job_id, FitJob.state == "queued")
            .values(state="running", started_at=now, updated_at=now, message=None,
                    progress=dict(START_PROGRESS)))
        session.commit()
        if claimed.rowcount == 1:
            return job_id
        # SQLite: another process claimed it between the SELECT and the UPDATE; try the next.


def announce(session: Session) -> None:
    """Tell every listening server, when this transaction commits, that a job was queued
    (PostgreSQL; nothing on SQLite, whose servers sweep)."""
    if is_postgres(session):
        session.execute(text("SELECT pg_notify(:channel, '')"), {"channel": CHANNEL})


def queued_count(session: Session) -> int:
    return session.scalar(select(func.count()).select_from(FitJob)
                          .where(FitJob.state == "queued"))


def fail_stale(session: Session, older_than_s: float) -> int:
    """Mark failed the running jobs whose rows have not changed for ``older_than_s`` (their
    server died); returns how many."""
    now = utc_now()
    failed = session.execute(
        update(FitJob).where(FitJob.state == "running",
                             FitJob.updated_at < now - timedelta(seconds=older_than_s))
        .values(state="failed", message=STOPPED_MESSAGE, finished_at=now, updated_at=now))
    session.commit()
    return failed.rowcount


def fail(session: Session, job_id: int, message: str, states=("queued", "running")) -> None:
    """Mark the job failed with ``message`` if it is in one of ``states``."""
    now = utc_now()
    session.execute(update(FitJob).where(FitJob.id == job_id, FitJob.state.in_(states))
                    .values(state="failed", message=message, finished_at=now, updated_at=now))
    session.commit()


def psycopg_conninfo(database_url: str) -> str:
    """A SQLAlchemy PostgreSQL URL as a libpq URI psycopg connects with."""
    return make_url(database_url).set(drivername="postgresql").render_as_string(
        hide_password=False)


class Listener:
    """A thread with a PostgreSQL connection of its own that calls ``on_notify()`` at every
    ``NOTIFY glasshead_fit_jobs``, and once after each (re)connection, since notifications sent
    while it was not connected are lost. ``stop()`` ends it within ``LISTEN_POLL_S``."""

    def __init__(self, database_url: str, on_notify: Callable[[], None]):
        self.conninfo = psycopg_conninfo(database_url)
        self.on_notify = on_notify
        self._stop = threading.Event()
        #: Set once the first LISTEN is in place (tests wait for it).
        self.listening = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True, name="fit-job-listener")

    def start(self) -> "Listener":
        self._thread.start()
        return self

    def stop(self) -> None:
        self._stop.set()
        self._thread.join(timeout=LISTEN_POLL_S + 5.0)

    def _run(self) -> None:
        import psycopg

        while not self._stop.is_set():
            try:
                with psycopg.connect(self.conninfo, autocommit=True) as connection:
                    connection.execute(f"LISTEN {CHANNEL}")
                    self.listening.set()
                    self.on_notify()
                    while not self._stop.is_set():
                        for _ in connection.notifies(timeout=LISTEN_POLL_S):
                            self.on_notify()
            except Exception:  # the database restarted, the network dropped: listen again
                if self._stop.is_set():
                    return
                log.warning("fit job listener lost its connection; reconnecting",
                            exc_info=True)
                self._stop.wait(RECONNECT_S)
