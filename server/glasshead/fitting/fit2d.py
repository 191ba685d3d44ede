"""Mid-sagittal fits: the rig's tongue against VocalTractLab's tongue outlines.

Which parameters move:

- the 14 sagittal tongue parameters (group "tongue sagittal"), free within their ranges;
- in ``fit_shape``, the three section widths, free but held near neutral (``WIDTH_WEIGHT``): an
  outline does not show the width, but an incompressible tongue that grows in the mid-sagittal
  plane narrows, so they give way where the volume would otherwise pass its bound
  (``fit_outline``, which the phoneme targets and authors' contours use, leaves them as given:
  the width decides the EPG's lateral contact, which an outline cannot check);
- the other coronal parameters stay neutral: they shape the cross-sections, and the only one
  that moves the midline (groove depth, and its paramedian pair) cannot be told apart from a
  height in a mid-sagittal outline; the 3D surface fit sets them;
- the jaw: ``jaw="vtl"`` (default) sets ``jaw_opening`` from the shape's jaw angle JA, counted
  from each model's rest (``vtl_mapping.jaw_opening``): JD3's standard JA is -2 degrees (VTL's
  parameter table), the rig's rest is 0, and JA is negative when open, so opening =
  VTL_JA_REST - JA, clipped to the rig's range
  (JD3's JA spans -6.2 .. -1.3 over the shapes: 0 .. 4.2 degrees). The two jaws pivot at
  different places, so this is a mapping of intent, not of geometry. ``jaw="free"`` fits it
  within its range instead (from that same value).

Every fit starts from the neutral tongue at that jaw opening, with the objective of
``objective2d`` (volume penalty and pull toward neutral, weights below), and reports the plain
RMS error, the volume change and the parameters that ended at a range limit.
"""

import json
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from glasshead.constants import TONGUE_RIG_FILE, VTL_OBSERVATIONS_FILE
from glasshead.fitting.objective2d import ROOT_CUT_DEG, MidSagittalSection, Objective2D
from glasshead.fitting.optimizer import minimize_restarted
from glasshead.fitting.vtl_mapping import jaw_opening_from_vtl
from glasshead.geometry.tongue_rig import SECTIONS
from glasshead.geometry.tongue_surface import TongueRig

SAGITTAL_GROUP = "tongue sagittal"
#: Objective weights (see objective2d): 5 % volume change costs as much as 0.5 mm RMS; moving
#: one parameter over its whole range costs 0.02 mm^2, enough to break ties only.
VOLUME_WEIGHT = 0.01
NEUTRAL_WEIGHT = 0.02
#: The tongue is nearly incompressible: beyond VOLUME_BOUND_PCT of its rest volume (on the
#: objective's coarse surface, within 0.15 % of the exact change) every further percent costs
#: VOLUME_BOUND_WEIGHT mm^2, as much as a 1 mm RMS misfit, so every fit stays within 5 %.
VOLUME_BOUND_PCT = 4.5
VOLUME_BOUND_WEIGHT = 1.0
#: The widths' own pull toward neutral (in place of NEUTRAL_WEIGHT): narrowing the three
#: sections by 1 mm each (2.1 % of the volume) costs 0.10 mm^2, about what the volume penalty
#: charges for going from 3.5 to 4.5 % (0.08). So a width moves little (about 1 mm at most)
#: while the volume keeps within its bound, and gives way where the bound presses: the uvulars
#: narrow 2 to 3 mm.
WIDTH_WEIGHT = 5.0
#: The turn of the tongue's body is pulled harder than the other sagittal parameters (its whole
#: range costs 0.5 mm^2): with the body's straight moves it can make the same outline in several
#: ways, and at the common weight the front vowels took up to 25 degrees of it against a forward
#: dorsum, poses that blend badly with their neighbours in running speech. 66 of 69 fits stay
#: within 1 mm with it, as without it.
TURN_PARAMETER = "tongue_retraction"
TURN_WEIGHT = 0.5
#: A parameter within this fraction of its range of a limit is reported as at the limit.
LIMIT_FRACTION = 0.005
MAX_EVALS = 3000
#: ``fit_shape`` restarts BOBYQA from its best point, with fresh models, while a restart lowers
#: the objective by more than RESTART_GAIN of it (at most RESTARTS times, within MAX_EVALS): a
#: ray's crossing moves from one segment of the rig's outline to the next, the quadratic models
#: go stale and the ftol test stops the method early (`tt-postalveolar-closure(a)` stopped at
#: 1.09 mm and went on to 0.81 mm).
RESTARTS = 2
RESTART_GAIN = 0.01
#: Stopping tests: 1e-6 mm^2 of objective, 1e-3 mm (or degree) of parameter, far below what
#: the outlines resolve.
FTOL_ABS = 1e-6
XTOL_ABS = 1e-3


@dataclass
class FitReport:
    """One fit: the shape, the method and its cost, the misfit and the fitted values."""

    shape: str
    method: str
    evaluations: int
    seconds: float
    rms_mm: float
    max_error_mm: float
    volume_change_pct: float
    at_limit: list[str]
    rays: int
    stop: str
    params: dict[str, float] = field(default_factory=dict)

    def to_json(self):
        return asdict(self)


def sagittal_parameters(rig: TongueRig) -> list[str]:
    return [p for p in rig.parameter_names if rig.parameters[p]["group"] == SAGITTAL_GROUP]


def width_parameters(rig: TongueRig) -> list[str]:
    """The sections' widths (a sideways stretch: they leave the midline as it is)."""
    return [f"{section}_width" for section in SECTIONS if f"{section}_width" in rig.parameters]


def outline_parameters(rig: TongueRig) -> list[str]:
    """What a fit of a VTL shape moves: the sagittal parameters and the widths."""
    return sagittal_parameters(rig) + width_parameters(rig)


def own_pulls(rig: TongueRig, free) -> dict[str, float]:
    """The free parameters pulled toward neutral by a weight of their own: the widths and the
    turn."""
    pulls = {name: WIDTH_WEIGHT for name in width_parameters(rig)}
    pulls[TURN_PARAMETER] = TURN_WEIGHT
    return {name: pulls[name] for name in free if name in pulls}


def fit_outline(rig: TongueRig, outline, *, method="bobyqa", free=None, base=None,
                volume_weight=VOLUME_WEIGHT, neutral_weight=NEUTRAL_WEIGHT,
                volume_bound_pct=VOLUME_BOUND_PCT, volume_bound_weight=VOLUME_BOUND_WEIGHT,
                max_evals=MAX_EVALS, section=None, name="", ftol_abs=FTOL_ABS,
                xtol_abs=XTOL_ABS, root_cut_deg=ROOT_CUT_DEG, restarts=0,
                **options) -> FitReport:
    """Fit the free parameters (default: the sagittal ones) to one mid-sagittal outline (n, 2),
    starting from ``base`` (P,) values (default neutral), which also hold the others;
    ``restarts`` (see RESTARTS) restarts the method from its best point; other keyword options
    go to ``optimizer.minimize``."""
    free = list(free) if free is not None else sagittal_parameters(rig)
    objective = Objective2D(rig, outline, free, base=base, volume_weight=volume_weight,
                            neutral_weight=neutral_weight, volume_bound_pct=volume_bound_pct,
                            volume_bound_weight=volume_bound_weight, section=section,
                            root_cut_deg=root_cut_deg, neutral_weights=own_pulls(rig, free))
    x0 = objective.base[objective.index]
    result = minimize_restarted(objective, x0, objective.lower, objective.upper, method=method,
                                max_evals=max_evals, ftol_abs=ftol_abs, xtol_abs=xtol_abs,
                                restarts=restarts, restart_gain=RESTART_GAIN, **options)
    errors = objective.errors(result.x)
    margin = LIMIT_FRACTION * (objective.upper - objective.lower)
    near = (result.x <= objective.lower + margin) | (result.x >= objective.upper - margin)
    at_limit = [n for n, hit in zip(free, near, strict=True) if hit]
    values = objective.values(result.x)
    return FitReport(
        shape=name, method=method, evaluations=result.evaluations, seconds=result.seconds,
        rms_mm=float(np.sqrt(np.mean(errors**2))), max_error_mm=float(np.abs(errors).max()),
        volume_change_pct=objective.volume_change(result.x), at_limit=at_limit,
        rays=len(errors), stop=result.stop,
        params={n: float(v) for n, v in zip(rig.parameter_names, values, strict=True)})


def fit_shape(rig: TongueRig, shape, *, method="bobyqa", jaw="vtl", section=None,
              **options) -> FitReport:
    """Fit one VTL shape record (from vtl-observations.json) by its tongue outline."""
    if jaw not in ("vtl", "free"):
        raise ValueError(f"jaw must be 'vtl' or 'free', got {jaw!r}")
    base = rig.neutral.copy()
    base[rig.jaw_parameter] = jaw_opening_from_vtl(shape, rig)
    free = outline_parameters(rig) + ([rig.jaw["parameter"]] if jaw == "free" else [])
    options.setdefault("restarts", RESTARTS)
    return fit_outline(rig, shape["tongue_outline"], method=method, free=free, base=base,
                       section=section, name=shape["name"], **options)


def fit_all(rig: TongueRig, observations, *, method="bobyqa", names=None,
            **options) -> list[FitReport]:
    """Fit every shape of an observations document (or those named), in its order."""
    section = MidSagittalSection(rig)
    return [fit_shape(rig, s, method=method, section=section, **options)
            for s in select_shapes(observations, names)]


def select_shapes(observations, names=None) -> list[dict]:
    """The shapes of an observations document named in ``names`` (all when None), in the
    document's order; ValueError naming any that it lacks."""
    shapes = observations["shapes"]
    if names is None:
        return list(shapes)
    wanted = set(names)
    missing = wanted - {s["name"] for s in shapes}
    if missing:
        raise ValueError(f"no such shapes: {', '.join(sorted(missing))}")
    return [s for s in shapes if s["name"] in wanted]


def load_inputs(assets_dir):
    """(rig, observations document) from a built assets directory."""
    assets_dir = Path(assets_dir)
    rig = TongueRig(json.loads((assets_dir / TONGUE_RIG_FILE).read_text()))
    observations = json.loads((assets_dir / VTL_OBSERVATIONS_FILE).read_text())
    return rig, observations


def main(argv=None):
    import sys

    from glasshead.settings import get_settings

    argv = sys.argv[1:] if argv is None else argv
    method = argv[0] if argv else "bobyqa"
    rig, observations = load_inputs(get_settings().assets_dir)
    started = time.perf_counter()
    reports = fit_all(rig, observations, method=method)
    for r in reports:
        print(f"{r.shape:32s} {r.rms_mm:6.2f} mm  max {r.max_error_mm:5.2f}  "
              f"dV {r.volume_change_pct:+5.1f} %  {r.evaluations:5d} evals "
              f"{r.seconds:5.2f} s  {','.join(r.at_limit)}")
    rms = np.array([r.rms_mm for r in reports])
    print(f"{len(reports)} shapes, {method}: median RMS {np.median(rms):.2f} mm, "
          f"{int(np.sum(rms <= 1.0))} within 1.0 mm; {time.perf_counter() - started:.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
