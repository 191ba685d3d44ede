"""Authors' fits: one observation (``fitting.uploads``) fitted into a target, and the job that runs
it in a worker process.

What each kind fits (``fit_observation``):

- ``contour``: ``fit2d.fit_outline``, the 14 sagittal parameters from the neutral tongue, the
  jaw and the coronal parameters held neutral (a mid-sagittal contour cannot show them);
- ``surface``: ``fit3d.fit_surface`` to the surface's vertices;
- ``epg``: the contact fit (``fit_contact.ContactObjective``: the sagittal parameters, the jaw
  closing only and the coronal groups of every section) toward the wanted pattern, with the rest
  tongue's own mid-sagittal outline (``rest_outline``) as the outline term: an EPG frame says
  where the tongue meets the palate and nothing about the rest of it, so the rest of it is held
  near rest. The result's synthetic EPG (the corrected tongue, as every view shows it) is
  compared with the wanted pattern: ``agreement`` is the share of the 62 electrodes that agree.

Every fit reports ``rms_mm``, ``evaluations``, ``seconds``, ``volume_change_pct``, ``at_limit``
and ``method``, and its target holds every articulation parameter: the tongue rig's (tongue and
jaw) as fitted, the lips and the velum at their rigs' neutral values.

Default methods (``DEFAULT_METHOD``): BOBYQA for the smooth outline and surface errors; subplex
for EPG, whose hinge error is flat wherever an electrode is already on its wanted side, where
BOBYQA's quadratic models stall. Toward the majority of engassim's first three /n/ segments (131
frames) from the rest tongue, BOBYQA with its restarts stops after 221 evaluations at 0.82
agreement; subplex reaches 0.87 in 600 evaluations (1.6 s) and 0.94 in 1500 (4.5 s).

A job (``run_job``) runs in a worker process with its own database session: it takes its queued
row, writes ``progress`` at most every ``PROGRESS_INTERVAL_S`` seconds, and ends it ``done``
(``params`` and ``report``) or ``failed`` (``message``). A row deleted while its fit runs stops
the fit at the next progress write.
"""

import inspect
import time
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np
from sqlalchemy import update
from sqlalchemy.orm import Session

from glasshead.constants import (
    COLLISION_TABLES_FILE,
    EPG_LAYOUT_FILE,
    FACE_RIG_FILE,
    TONGUE_RIG_FILE,
    VELUM_RIG_FILE,
)
from glasshead.epg import synthetic
from glasshead.epg.classes import ELECTRODES, agreement
from glasshead.epg.contacts import Probes, probes_from_layout
from glasshead.epg.sequence import rows_to_strings
from glasshead.fitting import fit2d, fit_contact
from glasshead.fitting.objective2d import MidSagittalSection
from glasshead.fitting.objective_epg import EpgObjective
from glasshead.fitting.optimizer import METHODS, minimize
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.store.base import utc_now
from glasshead.store.db import engine_for
from glasshead.store.fit_jobs import FitJob

DEFAULT_METHOD = {"contour": "bobyqa", "surface": "bobyqa", "epg": "sbplx"}
#: Evaluations a fit may spend when the upload names no cap.
MAX_EVALS = {"contour": fit2d.MAX_EVALS, "epg": 1500}
#: Seconds between progress writes to a job's row (a fit evaluates hundreds of times a second).
PROGRESS_INTERVAL_S = 0.25

#: progress(evaluations, best_error, fraction of the evaluation budget spent)
Progress = Callable[[int, float, float], None]


class JobDeletedError(Exception):
    """The job's row was deleted (or finished elsewhere) while its fit ran."""


@dataclass
class FitInputs:
    """The built assets a fit reads: the tongue rig and its section, the EPG probes, the
    collision tables (for the synthetic EPG) and the lips' and velum's neutral values."""

    rig: TongueRig
    section: MidSagittalSection
    probes: Probes
    tables: object
    others: dict[str, float]

    @classmethod
    def load(cls, assets_dir: Path) -> "FitInputs":
        import json

        from glasshead.geometry.collision_format import decode_collision_tables

        rig = TongueRig(json.loads((assets_dir / TONGUE_RIG_FILE).read_text()))
        layout = json.loads((assets_dir / EPG_LAYOUT_FILE).read_text())
        others = {}
        for name in (FACE_RIG_FILE, VELUM_RIG_FILE):
            for spec in json.loads((assets_dir / name).read_text())["parameters"]:
                others[spec["name"]] = float(spec["neutral"])
        return cls(rig, MidSagittalSection(rig), probes_from_layout(layout["grids"]["reading62"]),
                   decode_collision_tables((assets_dir / COLLISION_TABLES_FILE).read_bytes()),
                   others)


@lru_cache(maxsize=2)
def _inputs(assets_dir: str, stamp: tuple) -> FitInputs:
    return FitInputs.load(Path(assets_dir))


def load_inputs(assets_dir) -> FitInputs:
    """The inputs of ``assets_dir``, read once per process and again when a file changes."""
    assets_dir = Path(assets_dir)
    files = (TONGUE_RIG_FILE, EPG_LAYOUT_FILE, COLLISION_TABLES_FILE, FACE_RIG_FILE,
             VELUM_RIG_FILE)
    missing = [f for f in files if not (assets_dir / f).is_file()]
    if missing:
        raise FileNotFoundError(f"built assets missing in {assets_dir}: {', '.join(missing)} "
                                "(run glasshead build)")
    return _inputs(str(assets_dir), tuple((assets_dir / f).stat().st_mtime_ns for f in files))


def rest_outline(section: MidSagittalSection, rig: TongueRig) -> np.ndarray:
    """(k, 2) the neutral tongue's mid-sagittal upper contour, root to tip: the section runs
    from the tip over the dorsum to the back of the root (its most posterior point), reversed."""
    outline = section.outline(rig.neutral)
    back = int(np.argmin(outline[:, 0]))
    return outline[:back + 1][::-1].copy()


def _budget(kind: str, max_evals: int | None) -> int | None:
    if max_evals is not None:
        return int(max_evals)
    if kind == "surface":
        from glasshead.fitting.fit3d import fit_surface

        default = inspect.signature(fit_surface).parameters["max_evals"].default
        return None if default is inspect.Parameter.empty else int(default)
    return MAX_EVALS[kind]


def fit_observation(inputs: FitInputs, kind: str, points: np.ndarray, *,
                    method: str | None = None, max_evals: int | None = None,
                    progress: Progress | None = None, name: str = "") -> dict:
    """Fit one observation (``uploads.Observation.points`` of ``kind``); returns ``params``
    (every rig parameter) and ``report`` (see the module docstring)."""
    method = method or DEFAULT_METHOD[kind]
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r}; choose one of: {', '.join(METHODS)}")
    budget = _budget(kind, max_evals)

    def step(evaluations: int, best_error: float) -> None:
        if progress is not None:
            fraction = min(1.0, evaluations / budget) if budget else 0.0
            progress(evaluations, float(best_error), fraction)

    options = {} if budget is None else {"max_evals": budget}
    rig = inputs.rig
    if kind == "contour":
        fit = fit2d.fit_outline(rig, points, method=method, section=inputs.section, name=name,
                                progress=step, **options)
        report = _common(fit)
        report["max_error_mm"] = fit.max_error_mm
    elif kind == "surface":
        from glasshead.fitting.fit3d import fit_surface

        fit = fit_surface(rig, points, method=method, progress=step, name=name,
                          section=inputs.section, **options)
        report = _common(fit)
        report["max_error_mm"] = fit.max_error_mm
    elif kind == "epg":
        fit, report = fit_epg(inputs, points[0], points[1], method=method,
                              max_evals=budget, progress=step)
    else:
        raise ValueError(f"unknown kind {kind!r}")
    params = {**{n: round(float(v), 6) for n, v in fit.params.items()}, **inputs.others}
    return {"params": params, "report": report}


def _common(fit) -> dict:
    return {"method": fit.method, "rms_mm": fit.rms_mm, "evaluations": fit.evaluations,
            "seconds": fit.seconds, "volume_change_pct": fit.volume_change_pct,
            "at_limit": list(fit.at_limit), "stop": fit.stop}


@dataclass
class _EpgFit:
    params: dict


def fit_epg(inputs: FitInputs, wanted, weights, *, method: str, max_evals: int,
            progress: Callable[[int, float], None]) -> tuple[_EpgFit, dict]:
    """The contact fit toward ``wanted`` (8, 8) with ``weights`` (8, 8) from the rest tongue,
    restarted from its best point while a restart gains (as ``fit_contact.fit_contact``)."""
    rig = inputs.rig
    wanted = np.asarray(wanted).astype(np.uint8)
    weights = np.asarray(weights, dtype=np.float64)
    if not (weights * ELECTRODES).sum() > 0:
        weights = ELECTRODES.astype(np.float64)  # no electrode is clear: count every one
    epg = EpgObjective(inputs.probes, wanted, rig.triangles, weights=weights,
                       margin=fit_contact.MARGIN_MM, press_mm=fit_contact.PRESS_MM)
    objective = fit_contact.ContactObjective(rig, rest_outline(inputs.section, rig), epg,
                                             base=rig.neutral, groups=fit_contact.free_groups(rig),
                                             section=inputs.section)
    done = 0

    def step(evaluations: int, best_error: float) -> None:
        progress(done + evaluations, best_error)

    started = time.perf_counter()
    settings = {"method": method, "ftol_abs": fit2d.FTOL_ABS, "xtol_abs": fit2d.XTOL_ABS,
                "progress": step}
    result = minimize(objective, objective.x0, objective.lower, objective.upper,
                      max_evals=max_evals, **settings)
    done = result.evaluations
    for _ in range(fit_contact.RESTARTS):
        left = max_evals - done
        if left < 4 * len(result.x):
            break
        again = minimize(objective, result.x, objective.lower, objective.upper,
                         max_evals=left, **settings)
        done += again.evaluations
        gained = result.error - again.error
        if again.error < result.error:
            result = again
        if gained <= fit_contact.RESTART_GAIN * abs(result.error):
            break
    full = objective.expand @ result.x
    errors = objective.plane.errors(full)
    values = objective.values(result.x)
    grid = synthetic.synthetic_frame(rig, values, inputs.tables, inputs.probes).grid
    plain = EpgObjective(inputs.probes, wanted, rig.triangles, weights=weights)
    margin = fit2d.LIMIT_FRACTION * (objective.upper - objective.lower)
    near = (result.x <= objective.lower + margin) | (result.x >= objective.upper - margin)
    report = {
        "method": method, "rms_mm": float(np.sqrt(np.mean(errors**2))),
        "evaluations": done, "seconds": time.perf_counter() - started,
        "volume_change_pct": objective.plane.volume_change(full),
        "at_limit": [g for (g, _), hit in zip(objective.groups, near, strict=True) if hit],
        "stop": result.stop, "epg_error_mm": plain(rig.vertices(values)),
        "agreement": agreement(grid, wanted), "wanted_rows": rows_to_strings(wanted),
        "rows": rows_to_strings(grid),
    }
    params = {n: float(v) for n, v in zip(rig.parameter_names, values, strict=True)}
    return _EpgFit(params), report


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


def claim_job(session: Session, job_id: int) -> bool:
    """Mark the queued job ``job_id`` running, in one conditional UPDATE; False when it is not
    queued (any more). Several servers (workers, replicas) may each hand the same queued job to
    their pool at start-up: only one of them runs it."""
    now = utc_now()
    claimed = session.execute(
        update(FitJob).where(FitJob.id == job_id, FitJob.state == "queued")
        .values(state="running", started_at=now, updated_at=now,
                progress={"evaluations": 0, "best_error": None, "fraction": 0.0}))
    session.commit()
    return claimed.rowcount == 1


def run_job(database_url: str, assets_dir: str, job_id: int) -> str:
    """Run the queued job ``job_id`` (in a worker process); returns its final state."""
    with Session(engine_for(database_url), expire_on_commit=False) as session:
        if not claim_job(session, job_id):
            job = session.get(FitJob, job_id)
            return "gone" if job is None else job.state
        job = session.get(FitJob, job_id)
        kind, method, name = job.kind, job.method, job.name
        points, options = job.get_observation(), dict(job.source.get("options", {}))
        writer = ProgressWriter(session, job_id)
        try:
            result = fit_observation(load_inputs(assets_dir), kind, points, method=method,
                                     max_evals=options.get("max_evals"), progress=writer,
                                     name=name)
        except JobDeletedError:
            session.rollback()
            return "deleted"
        except Exception as error:  # any failure of the fit is the job's, reported on its row
            session.rollback()
            return _finish(session, job_id, "failed", writer.latest,
                           message=f"{error.__class__.__name__}: {error}")
        final = {**writer.latest, "fraction": 1.0}
        return _finish(session, job_id, "done", final, params=result["params"],
                       report=result["report"])


def _finish(session: Session, job_id: int, state: str, progress: dict, **values) -> str:
    now = utc_now()
    changed = session.execute(
        update(FitJob).where(FitJob.id == job_id, FitJob.state == "running")
        .values(state=state, progress=progress, finished_at=now, updated_at=now, **values))
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
    job = FitJob(name=name, kind=observation.kind, method=method, state="done",
                 progress={"evaluations": report["evaluations"], "best_error": None,
                           "fraction": 1.0},
                 source={**observation.source,
                         "options": {} if max_evals is None else {"max_evals": max_evals}},
                 params=result["params"], report=report, started_at=now, finished_at=now)
    job.set_observation(observation.points)
    with Session(engine, expire_on_commit=False) as session:
        session.add(job)
        session.commit()
        return job.id
