"""Fits to several measurements at once: a contour, EPG frames and flesh points (fit kinds
``combined`` and ``ema``), as Cohen, Beskow and Massaro planned ("simultaneous fitting of
cineradiographic data, EPG, and x-ray microbeam data").

The objective (mm^2), over the sagittal parameters, the jaw, the coronal groups when there is an
EPG term (``fit_contact.free_groups``) and the five lip parameters when a lip point is given:

    w_contour * rms^2            the outline's rays against the uploaded contour (``objective2d``);
                                 without one, the rest tongue's own outline at weight 1, which
                                 holds what the other measurements do not show near rest
  + the 2D fit's volume terms and pulls toward neutral, the volume bound as steep as the
    contact fits' (every fit keeps its volume within 5 %)
  + w_epg * EPG_WEIGHT * E^2     E: the EPG error toward the wanted pattern (``objective_epg``,
                                 with the contact fits' margins), mm
  + w_ema * FLESH_WEIGHT * F^2   F: the RMS distance of the given flesh points from the rig's
                                 (``geometry.flesh_points``), mm; a point given in 2D is
                                 compared in x and y only
  + NEUTRAL_WEIGHT * sum of the lip parameters' squared shares of their range from neutral

``w_*`` are the upload's weights (default 1 each): a weight of 2 makes that measurement count
twice as much as by default. ``FLESH_WEIGHT`` = 10: a millimetre of sensor error costs as much
as 3.2 mm of outline RMS, so the sensors decide where their points go and the outline (or the
rest tongue) shapes the rest; EMA has no more than four tongue sensors.

The upper incisor is the reference every EMA head is corrected to: when the points include it,
each is first shifted by what puts it on the head's upper incisor (``shift_mm`` in the report),
and it is not a term. The jaw is free over its whole range (an EMA frame measures it).
"""

import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

import numpy as np

from glasshead.epg import synthetic
from glasshead.epg.classes import agreement
from glasshead.epg.sequence import rows_to_strings
from glasshead.fitting import fit2d, fit_contact
from glasshead.fitting.objective2d import Objective2D
from glasshead.fitting.objective_epg import EpgObjective
from glasshead.fitting.optimizer import minimize_restarted
from glasshead.geometry.face_rig import LIP_MESHES
from glasshead.geometry.flesh_points import FleshPointRig

#: mm^2 per mm^2: weight of the squared RMS sensor distance against the squared outline RMS.
FLESH_WEIGHT = 10.0
#: The reference point (not fitted; see the module docstring).
REFERENCE = "upper_incisor"
#: The measurements a combined fit takes, in the order of its report.
TERMS = ("contour", "epg", "ema")


@dataclass
class Measurements:
    """What one fit is given: any of a contour (n, 2), an EPG goal (2, 8, 8: wanted, weights)
    and flesh points {name: (2,) or (3,) mm}, each with its weight (default 1)."""

    contour: np.ndarray | None = None
    epg: np.ndarray | None = None
    flesh: Mapping[str, np.ndarray] | None = None
    weights: Mapping[str, float] = field(default_factory=dict)

    def weight(self, term: str) -> float:
        value = float(self.weights.get(term, 1.0))
        if not (math.isfinite(value) and value >= 0):
            raise ValueError(f"the {term} weight must be a finite number >= 0, got {value}")
        return value

    @property
    def terms(self) -> list[str]:
        given = {"contour": self.contour, "epg": self.epg, "ema": self.flesh}
        return [term for term in TERMS if given[term] is not None]


def shifted_points(flesh: Mapping[str, np.ndarray], reference: np.ndarray
                   ) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """(the points without the reference, each shifted by what puts the given reference on
    ``reference`` (3,); the shift (3,), zero when the reference is not given)."""
    shift = np.zeros(3)
    if REFERENCE in flesh:
        given = np.asarray(flesh[REFERENCE], dtype=np.float64)
        shift[:len(given)] = reference[:len(given)] - given
    return ({name: np.asarray(p, dtype=np.float64) + shift[:len(p)]
             for name, p in flesh.items() if name != REFERENCE}, shift)


class MeasuredObjective:
    """The objective of the module docstring over x = [tongue groups..., lip parameters...]."""

    def __init__(self, rig, section, flesh_rig: FleshPointRig, probes,
                 measurements: Measurements, rest_outline: np.ndarray):
        self.rig, self.flesh_rig, self.measurements = rig, flesh_rig, measurements
        epg = measurements.epg is not None
        self.groups = fit_contact.free_groups(
            rig, jaw=True, coronal=fit_contact.CORONAL_GROUPS if epg else ())
        members = [m for _, ms in self.groups for m in ms]
        contour = measurements.contour
        self.plane = Objective2D(
            rig, rest_outline if contour is None else contour, members, base=rig.neutral,
            volume_weight=fit2d.VOLUME_WEIGHT, neutral_weight=fit2d.NEUTRAL_WEIGHT,
            volume_bound_pct=fit2d.VOLUME_BOUND_PCT,
            volume_bound_weight=fit_contact.VOLUME_BOUND_WEIGHT * fit2d.VOLUME_BOUND_WEIGHT,
            section=section, outline_weight=1.0 if contour is None else
            measurements.weight("contour"))
        self.expand = fit_contact.group_expansion(self.groups)
        index = [rig.parameter_names.index(ms[0]) for _, ms in self.groups]
        lower, upper = rig.minimum[index].copy(), rig.maximum[index].copy()
        x0 = np.clip(rig.neutral[index], lower, upper)
        self.epg = None
        if measurements.epg is not None:
            wanted, weights = measurements.epg
            self.epg = EpgObjective(probes, wanted.astype(np.uint8), rig.triangles,
                                    weights=weights, margin=fit_contact.MARGIN_MM,
                                    press_mm=fit_contact.PRESS_MM)
        self.targets: dict[str, np.ndarray] = {}
        self.shift = np.zeros(3)
        if measurements.flesh is not None:
            reference = flesh_rig.incisors[REFERENCE]
            self.targets, self.shift = shifted_points(measurements.flesh, reference)
        self.names = tuple(self.targets)
        lips = any(name in LIP_MESHES for name in self.names)
        ranges = flesh_rig.lip_ranges if lips else {}
        neutral = {p["name"]: float(p["neutral"]) for p in flesh_rig.face["parameters"]}
        self.lip_names = list(ranges)
        self.lip_neutral = np.array([neutral[n] for n in self.lip_names])
        self.lip_span = np.array([ranges[n][1] - ranges[n][0] for n in self.lip_names])
        self.tongue_size = len(self.groups)
        self.lower = np.concatenate([lower, [ranges[n][0] for n in self.lip_names]])
        self.upper = np.concatenate([upper, [ranges[n][1] for n in self.lip_names]])
        self.x0 = np.concatenate([x0, np.clip(self.lip_neutral, self.lower[len(x0):],
                                              self.upper[len(x0):])])
        self.epg_weight = fit_contact.EPG_WEIGHT * measurements.weight("epg")
        self.flesh_weight = FLESH_WEIGHT * measurements.weight("ema")

    def tongue_x(self, x) -> np.ndarray:
        return self.expand @ np.asarray(x, dtype=np.float64)[:self.tongue_size]

    def values(self, x) -> np.ndarray:
        """The tongue rig's values (P,) for x."""
        return self.plane.values(self.tongue_x(x))

    def lips(self, x) -> dict[str, float]:
        return dict(zip(self.lip_names, (float(v) for v in x[self.tongue_size:]), strict=True))

    def flesh_errors(self, x, values=None) -> dict[str, float]:
        """{point: distance from its measured position, mm} (x and y only for a 2D point)."""
        if not self.names:
            return {}
        values = self.values(x) if values is None else values
        posed = self.flesh_rig.posed(values, self.lips(x), self.names)
        return {name: float(np.linalg.norm(posed[name][:len(target)] - target))
                for name, target in self.targets.items()}

    def flesh_rms(self, x, values=None) -> float:
        errors = list(self.flesh_errors(x, values).values())
        return float(np.sqrt(np.mean(np.square(errors)))) if errors else 0.0

    def __call__(self, x) -> float:
        x = np.asarray(x, dtype=np.float64)
        tongue = self.tongue_x(x)
        value = self.plane(tongue)
        values = self.plane.values(tongue)
        if self.epg is not None and self.epg_weight:
            value += self.epg_weight * self.epg(self.rig.vertices(values)) ** 2
        if self.names and self.flesh_weight:
            value += self.flesh_weight * self.flesh_rms(x, values) ** 2
        if self.lip_names:
            share = (x[self.tongue_size:] - self.lip_neutral) / self.lip_span
            value += fit2d.NEUTRAL_WEIGHT * float(np.sum(share**2))
        return value


def fit_measured(inputs, measurements: Measurements, rest: np.ndarray, *, method: str,
                 max_evals: int, progress: Callable[[int, float], None]
                 ) -> tuple[dict[str, float], dict]:
    """Fit ``measurements`` (``inputs``: ``authored.FitInputs`` with its flesh-point rig; ``rest``
    the rest tongue's outline, ``authored.rest_outline``) from the rest tongue, restarted from
    the best point while a restart gains; returns (the rig's and the lips' fitted values by
    name, the report: the common figures and ``terms``, each measurement's weight and error)."""
    if not measurements.terms:
        raise ValueError("a fit needs a contour, EPG frames or flesh points")
    if inputs.flesh is None and measurements.flesh is not None:
        raise ValueError("fitting flesh points needs the flesh-point rig in the fit's inputs")
    rig = inputs.rig
    objective = MeasuredObjective(rig, inputs.section, inputs.flesh, inputs.probes,
                                  measurements, rest)
    started = time.perf_counter()
    result = minimize_restarted(objective, objective.x0, objective.lower, objective.upper,
                                method=method, max_evals=max_evals,
                                restarts=fit_contact.RESTARTS,
                                restart_gain=fit_contact.RESTART_GAIN, progress=progress,
                                ftol_abs=fit2d.FTOL_ABS, xtol_abs=fit2d.XTOL_ABS)
    tongue = objective.tongue_x(result.x)
    values = objective.values(result.x)
    errors = objective.plane.errors(tongue)
    names = [g for g, _ in objective.groups] + objective.lip_names
    report = {
        "method": method, "rms_mm": float(np.sqrt(np.mean(errors**2))),
        "evaluations": result.evaluations, "seconds": time.perf_counter() - started,
        "volume_change_pct": objective.plane.volume_change(tongue),
        "at_limit": fit2d.at_limit(result.x, objective.lower, objective.upper, names),
        "stop": result.stop, "terms": _terms(objective, inputs, result.x, values, errors),
    }
    params = {n: float(v) for n, v in zip(rig.parameter_names, values, strict=True)}
    params.update(objective.lips(result.x))
    return params, report


def epg_figures(inputs, values, wanted, weights) -> dict:
    """How the rig's ``values`` meet a wanted EPG pattern (8, 8) with its ``weights``:
    ``error_mm`` (``objective_epg``, no margins), ``agreement`` of the synthetic EPG (the
    corrected tongue, as every view shows it), ``wanted_rows`` and ``rows``."""
    wanted = np.asarray(wanted).astype(np.uint8)
    grid = synthetic.synthetic_frame(inputs.rig, values, inputs.tables, inputs.probes).grid
    plain = EpgObjective(inputs.probes, wanted, inputs.rig.triangles, weights=weights)
    return {"error_mm": plain(inputs.rig.vertices(values)), "agreement": agreement(grid, wanted),
            "wanted_rows": rows_to_strings(wanted), "rows": rows_to_strings(grid)}


def _terms(objective: MeasuredObjective, inputs, x, values, errors) -> dict:
    measurements = objective.measurements
    terms: dict[str, dict] = {}
    if measurements.contour is not None:
        terms["contour"] = {"weight": objective.plane.outline_weight,
                            "rms_mm": float(np.sqrt(np.mean(errors**2))),
                            "max_error_mm": float(np.abs(errors).max())}
    if objective.epg is not None and measurements.epg is not None:
        terms["epg"] = {"weight": objective.epg_weight,
                        **epg_figures(inputs, values, *measurements.epg)}
    if measurements.flesh is not None:
        terms["ema"] = {"weight": objective.flesh_weight,
                        "rms_mm": objective.flesh_rms(x, values),
                        "errors_mm": objective.flesh_errors(x, values),
                        "shift_mm": [round(float(v), 4) for v in objective.shift]}
    return terms
