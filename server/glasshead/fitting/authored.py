"""Authors' fits: one observation (``glasshead.uploads``) fitted into a target.

What each kind fits (``fit_observation``):

- ``contour``: ``fit2d.fit_outline``, the 14 sagittal parameters from the neutral tongue, the
  jaw and the coronal parameters held neutral (a mid-sagittal contour cannot show them);
- ``surface``: ``fit3d.fit_surface`` to the surface's vertices;
- ``ema`` (one frame of flesh points) and ``combined`` (two or more of a contour, EPG frames and
  flesh points, each with its weight): ``fit_measured.fit_measured``, whose report adds
  ``terms``, each measurement's weight and error;
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

The inputs (``FitInputs.from_assets``) are built from assets already loaded (the asset store's
values); nothing here reads a file or a database. The job that runs a fit in a worker process,
its row and its progress writes are ``glasshead.jobs.fit_job``.
"""

import inspect
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from glasshead.epg.classes import ELECTRODES
from glasshead.epg.contacts import Probes, probes_from_layout
from glasshead.fitting import fit2d, fit_contact, fit_measured
from glasshead.fitting.objective2d import MidSagittalSection
from glasshead.fitting.objective_epg import EpgObjective
from glasshead.fitting.optimizer import METHODS, minimize
from glasshead.geometry.flesh_points import FleshPointRig
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.uploads_flesh import points_by_name

#: By kind; a combined fit with EPG frames takes subplex, as an EPG fit does (``default_method``).
DEFAULT_METHOD = {"contour": "bobyqa", "surface": "bobyqa", "epg": "sbplx", "ema": "bobyqa",
                  "combined": "bobyqa"}
#: Evaluations a fit may spend when the upload names no cap.
MAX_EVALS = {"contour": fit2d.MAX_EVALS, "epg": 1500, "ema": 1500, "combined": 2000}
#: progress(evaluations, best_error, fraction of the evaluation budget spent)
Progress = Callable[[int, float, float], None]


@dataclass
class FitInputs:
    """The built assets a fit reads: the tongue rig and its section, the EPG probes, the
    collision tables (for the synthetic EPG) and the lips' and velum's neutral values."""

    rig: TongueRig
    section: MidSagittalSection
    probes: Probes
    tables: object
    others: dict[str, float]
    #: The flesh points, for the ``ema`` and ``combined`` kinds (None: those kinds fail).
    flesh: FleshPointRig | None = None

    @classmethod
    def from_assets(cls, rig: TongueRig, epg_layout: dict, collision_tables,
                    face_rig: dict, velum_rig: dict,
                    flesh: FleshPointRig | None = None) -> "FitInputs":
        """The inputs from loaded assets: the tongue rig, the EPG layout document (its
        ``reading62`` grid), the decoded collision tables, the face and velum rig
        definitions (their parameters' neutral values) and the flesh points' rig."""
        others = {spec["name"]: float(spec["neutral"])
                  for definition in (face_rig, velum_rig) for spec in definition["parameters"]}
        return cls(rig, MidSagittalSection(rig),
                   probes_from_layout(epg_layout["grids"]["reading62"]), collision_tables,
                   others, flesh)


def default_method(kind: str, points=None) -> str:
    """The optimiser a fit of ``kind`` takes when the upload names none: subplex for any fit
    with an EPG term (its hinge error is flat where BOBYQA's models stall)."""
    if kind == "combined" and isinstance(points, dict) and "epg" in points:
        return "sbplx"
    return DEFAULT_METHOD[kind]


def measurements_of(kind: str, points, weights: dict | None = None) -> fit_measured.Measurements:
    """The ``Measurements`` of an ``ema`` observation ((k, 4) rows) or a ``combined`` one
    ({kind: array}), with the upload's weights by kind."""
    parts = {"ema": points} if kind == "ema" else dict(points)
    epg = parts.get("epg")
    return fit_measured.Measurements(
        contour=parts.get("contour"), epg=None if epg is None else np.asarray(epg),
        flesh=points_by_name(parts["ema"]) if "ema" in parts else None,
        weights=dict(weights or {}))


def own_outline(section: MidSagittalSection, values) -> np.ndarray:
    """(k, 2) the posed tongue's mid-sagittal upper contour, root to tip: the section runs from
    the tip over the dorsum to the back of the root (its most posterior point), reversed."""
    outline = section.outline(values)
    back = int(np.argmin(outline[:, 0]))
    return outline[:back + 1][::-1].copy()


def rest_outline(section: MidSagittalSection, rig: TongueRig) -> np.ndarray:
    """(k, 2) the neutral tongue's mid-sagittal upper contour, root to tip (``own_outline``)."""
    return own_outline(section, rig.neutral)


def _budget(kind: str, max_evals: int | None) -> int | None:
    if max_evals is not None:
        return int(max_evals)
    if kind == "surface":
        from glasshead.fitting.fit3d import fit_surface

        default = inspect.signature(fit_surface).parameters["max_evals"].default
        return None if default is inspect.Parameter.empty else int(default)
    return MAX_EVALS[kind]


def fit_observation(inputs: FitInputs, kind: str, points, *,
                    method: str | None = None, max_evals: int | None = None,
                    progress: Progress | None = None, name: str = "",
                    weights: dict | None = None) -> dict:
    """Fit one observation (``uploads.Observation.points`` of ``kind``; ``weights`` by part for
    a combined one); returns ``params`` (every rig parameter) and ``report`` (see the module
    docstring)."""
    method = method or default_method(kind, points)
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
    elif kind in ("ema", "combined"):
        fitted, report = fit_measured.fit_measured(
            inputs, measurements_of(kind, points, weights), rest_outline(inputs.section, rig),
            method=method, max_evals=budget or MAX_EVALS[kind], progress=step)
        return {"params": {**inputs.others, **{n: round(v, 6) for n, v in fitted.items()}},
                "report": report}
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
    figures = fit_measured.epg_figures(inputs, values, wanted, weights)
    report = {
        "method": method, "rms_mm": float(np.sqrt(np.mean(errors**2))),
        "evaluations": done, "seconds": time.perf_counter() - started,
        "volume_change_pct": objective.plane.volume_change(full),
        "at_limit": fit2d.at_limit(result.x, objective.lower, objective.upper,
                                   [g for g, _ in objective.groups]),
        "stop": result.stop, "epg_error_mm": figures.pop("error_mm"), **figures,
    }
    params = {n: float(v) for n, v in zip(rig.parameter_names, values, strict=True)}
    return _EpgFit(params), report
