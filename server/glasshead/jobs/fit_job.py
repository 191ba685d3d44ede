"""One fit job, run in a worker process: its row's states, its progress writes and its result.

The server's runner (``jobs.fit_runner``) claims a queued row (``jobs.fit_queue.claim_next``:
``queued`` -> ``running``) and hands only its id to a worker; the worker (``run_job``) opens
its own database session from the database URL, reads the built assets through its process's
asset store (``jobs.compute.worker_store``: loaded once, again when a file's content changes),
fits (``fitting.authored.fit_observation``), writes ``progress`` at most every
``PROGRESS_INTERVAL_S`` seconds and ends the row ``done`` (``params`` and ``report``) or
``failed`` (``message``). A row deleted while its fit runs stops the fit at the next progress
write. Every write is conditional on the row still being ``running``, so a row another server
has failed (as stale) or deleted is never written back.

``save_fit`` stores a fit made in the calling process (``glasshead fit --save``) as a finished
job.
"""

import time

import numpy as np
from sqlalchemy import update
from sqlalchemy.orm import Session

from glasshead.asset_store import AssetStore
from glasshead.fitting.authored import FitInputs, fit_observation
from glasshead.flesh_point_assets import flesh_point_rig
from glasshead.jobs.compute import worker_store
from glasshead.store.base import utc_now
from glasshead.store.db import engine_for
from glasshead.store.fit_jobs import FitJob

#: Seconds between progress writes to a job's row (a fit evaluates hundreds of times a second).
PROGRESS_INTERVAL_S = 0.25


class JobDeletedError(Exception):
    """The job's row was deleted (or finished elsewhere) while its fit ran."""


def fit_inputs(store: AssetStore) -> FitInputs:
    """The fit's inputs from the built assets in ``store`` (AssetUnavailableError, naming the
    file and ``glasshead build``, when one is missing or corrupt)."""
    return FitInputs.from_assets(store.get("tongue_rig"), store.get("epg_layout"),
                                 store.get("collision_tables"), store.get("face_rig"),
                                 store.get("velum_rig").definition, flesh_point_rig(store))


class ProgressWriter:
    """The progress callback of a job: writes ``{evaluations, best_error, fraction}`` to its
    row at most every ``interval_s`` seconds; raises ``JobDeletedError`` once the row is gone."""

    def __init__(self, session: Session, job_id: int, interval_s: float = PROGRESS_INTERVAL_S):
        self.session, self.job_id, self.interval_s = session, job_id, interval_s
        self.last = time.monotonic()
        self.latest: dict = {}

    def __call__(self, evaluations: int, best_error: float, fraction: float) -> None:
        self.latest = {"evaluations": int(evaluations),
                       "best_error": best_error if np.isfinite(best_error) else None,
                       "fraction": round(float(fraction), 4)}
        now = time.monotonic()
        if now - self.last < self.interval_s:
            return
        self.last = now
        changed = self.session.execute(
            update(FitJob).where(FitJob.id == self.job_id, FitJob.state == "running")
            .values(progress=self.latest, updated_at=utc_now()))
        self.session.commit()
        if changed.rowcount == 0:
            raise JobDeletedError(self.job_id)


def run_job(database_url: str, assets_dir: str, job_id: int) -> str:
    """Fit the claimed (``running``) job ``job_id``, in a worker process; returns its final
    state. A job that is not running (gone, finished, still queued) is left as it is and its
    state returned ("gone" when deleted)."""
    with Session(engine_for(database_url), expire_on_commit=False) as session:
        job = session.get(FitJob, job_id)
        if job is None or job.state != "running":
            return "gone" if job is None else job.state
        kind, method, name = job.kind, job.method, job.name
        points, options = job.get_observation(), dict(job.source.get("options", {}))
        session.commit()  # end the read: the progress writes are transactions of their own
        writer = ProgressWriter(session, job_id)
        try:
            result = fit_observation(fit_inputs(worker_store(assets_dir)), kind, points,
                                     method=method, max_evals=options.get("max_evals"),
                                     progress=writer, name=name,
                                     weights=options.get("weights"))
        except JobDeletedError:
            session.rollback()
            return "deleted"
        except Exception as error:  # any failure of the fit is the job's, reported on its row
            session.rollback()
            return finish(session, job_id, "failed", writer.latest,
                          message=f"{error.__class__.__name__}: {error}")
        final = {**writer.latest, "fraction": 1.0}
        return finish(session, job_id, "done", final, params=result["params"],
                      report=result["report"])


def finish(session: Session, job_id: int, state: str, progress: dict | None = None,
           **values) -> str:
    """End the running job ``job_id`` in ``state`` with ``values`` (and ``progress`` when
    given); returns ``state``, or "deleted" when the row is gone or no longer running."""
    now = utc_now()
    if progress is not None:
        values["progress"] = progress
    changed = session.execute(
        update(FitJob).where(FitJob.id == job_id, FitJob.state == "running")
        .values(state=state, finished_at=now, updated_at=now, **values))
    session.commit()
    return state if changed.rowcount else "deleted"


def save_fit(database_url: str, observation, result: dict, *, name: str, method: str,
             max_evals: int | None = None) -> int:
    """Store a fit made in this process (``glasshead fit --save``) as a finished job, so that it
    lists with the API's fitted targets; returns its id. Brings the database up to date first."""
    from glasshead.store.db import upgrade_to_head

    engine = engine_for(database_url)
    upgrade_to_head(engine)
    now = utc_now()
    report = result["report"]
    options = dict(observation.source.get("options", {}))
    if max_evals is not None:
        options["max_evals"] = max_evals
    job = FitJob(name=name, kind=observation.kind, method=method, state="done",
                 progress={"evaluations": report["evaluations"], "best_error": None,
                           "fraction": 1.0},
                 source={**observation.source, "options": options},
                 params=result["params"], report=report, started_at=now, finished_at=now)
    job.set_observation(observation.points)
    with Session(engine, expire_on_commit=False) as session:
        session.add(job)
        session.commit()
        return job.id
