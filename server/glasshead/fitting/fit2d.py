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
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path

import numpy as np
import numpy.typing as npt

from glasshead.constants import TONGUE_RIG_FILE, VTL_OBSERVATIONS_FILE
from glasshead.fitting.objective2d import ROOT_CUT_DEG, MidSagittalSection, Objective2D
from glasshead.fitting.optimizer import Progress, minimize_restarted, with_changes
from glasshead.fitting.vtl_mapping import jaw_opening_from_vtl
from glasshead.geometry.tongue_parameters import SECTIONS
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


def at_limit(x, lower, upper, names) -> list[str]:
    """The ``names`` of the variables of ``x`` that ended within ``LIMIT_FRACTION`` of their
    range of a limit (``lower``, ``upper``: arrays as x)."""
    margin = LIMIT_FRACTION * (upper - lower)
    near = (x <= lower + margin) | (x >= upper - margin)
    return [n for n, hit in zip(names, near, strict=True) if hit]


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


@dataclass(frozen=True, eq=False)
class OutlineFit:
    """How ``fit_outline`` fits: the method, what moves and from where, the objective's weights
    (``objective2d``) and the stopping tests. Every field has the fits' default."""

    method: str = "bobyqa"
    #: The parameters the fit moves (default: the sagittal ones).
    free: Sequence[str] | None = None
    #: (P,) values to start from, which also hold the parameters not fitted (default: neutral).
    base: npt.ArrayLike | None = None
    volume_weight: float = VOLUME_WEIGHT
    neutral_weight: float = NEUTRAL_WEIGHT
    volume_bound_pct: float = VOLUME_BOUND_PCT
    volume_bound_weight: float = VOLUME_BOUND_WEIGHT
    root_cut_deg: float = ROOT_CUT_DEG
    #: Restarts of the method from its best point (see RESTARTS).
    restarts: int = 0
    ftol_abs: float = FTOL_ABS
    xtol_abs: float = XTOL_ABS
    #: The rig's section, shared by many fits (made from the rig when None).
    section: MidSagittalSection | None = None
    #: The report's shape name.
    name: str = ""


@dataclass(frozen=True, eq=False)
class ShapeFit(OutlineFit):
    """How ``fit_shape`` fits a VTL shape: ``OutlineFit``'s fields (its ``free``, ``base`` and
    ``name`` are the shape's), restarted, with the jaw from VTL's JA (``jaw="vtl"``) or free
    from there (``jaw="free"``)."""

    restarts: int = RESTARTS
    jaw: str = "vtl"


def fit_outline(rig: TongueRig, outline, options: OutlineFit | None = None, /, *,
                max_evals: int = MAX_EVALS, progress: Progress | None = None,
                **changes) -> FitReport:
    """Fit ``options.free`` to one mid-sagittal outline (n, 2) from ``options.base``, within
    ``max_evals`` evaluations, calling ``progress`` after each; keyword ``changes`` replace
    fields of ``options`` (``optimizer.with_changes``)."""
    options = with_changes(options or OutlineFit(), changes)
    free = list(options.free) if options.free is not None else sagittal_parameters(rig)
    objective = Objective2D(rig, outline, free, base=options.base,
                            volume_weight=options.volume_weight,
                            neutral_weight=options.neutral_weight,
                            volume_bound_pct=options.volume_bound_pct,
                            volume_bound_weight=options.volume_bound_weight,
                            section=options.section, root_cut_deg=options.root_cut_deg,
                            neutral_weights=own_pulls(rig, free))
    x0 = objective.base[objective.index]
    result = minimize_restarted(objective, x0, objective.lower, objective.upper,
                                method=options.method, max_evals=max_evals,
                                ftol_abs=options.ftol_abs, xtol_abs=options.xtol_abs,
                                restarts=options.restarts, restart_gain=RESTART_GAIN,
                                progress=progress)
    errors = objective.errors(result.x)
    limited = at_limit(result.x, objective.lower, objective.upper, free)
    values = objective.values(result.x)
    return FitReport(
        shape=options.name, method=options.method, evaluations=result.evaluations,
        seconds=result.seconds,
        rms_mm=float(np.sqrt(np.mean(errors**2))), max_error_mm=float(np.abs(errors).max()),
        volume_change_pct=objective.volume_change(result.x), at_limit=limited,
        rays=len(errors), stop=result.stop,
        params={n: float(v) for n, v in zip(rig.parameter_names, values, strict=True)})


def fit_shape(rig: TongueRig, shape, options: ShapeFit | None = None, /, *,
              max_evals: int = MAX_EVALS, progress: Progress | None = None,
              **changes) -> FitReport:
    """Fit one VTL shape record (from vtl-observations.json) by its tongue outline: the outline
    parameters (and the jaw, when free) from neutral with the jaw from VTL."""
    options = with_changes(options or ShapeFit(), changes)
    if options.jaw not in ("vtl", "free"):
        raise ValueError(f"jaw must be 'vtl' or 'free', got {options.jaw!r}")
    base = rig.neutral.copy()
    base[rig.jaw_parameter] = jaw_opening_from_vtl(shape, rig)
    free = outline_parameters(rig) + ([rig.jaw["parameter"]] if options.jaw == "free" else [])
    return fit_outline(rig, shape["tongue_outline"],
                       replace(options, free=free, base=base, name=shape["name"]),
                       max_evals=max_evals, progress=progress)


def fit_all(rig: TongueRig, observations, options: ShapeFit | None = None, /, *,
            names: Sequence[str] | None = None, max_evals: int = MAX_EVALS,
            **changes) -> list[FitReport]:
    """``fit_shape`` of every shape of an observations document (or those named), in its
    order, on one section of the rig."""
    options = with_changes(options or ShapeFit(), changes)
    options = replace(options, section=options.section or MidSagittalSection(rig))
    return [fit_shape(rig, s, options, max_evals=max_evals)
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
