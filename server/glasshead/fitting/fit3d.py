"""3D surface fits: the rig's tongue against measured tongue surfaces (VocalTractLab's sheets).

The error is the paper's 3D error (``objective3d.RayError3D``): rays from an origin O inside the
tongue to each observed vertex, the residual the distance along the ray from the vertex to the
rig's first crossing, walked over the triangle adjacency from the previous evaluation's hits.

Which parameters move: the 14 sagittal and the 21 coronal tongue parameters, within their
ranges (``fit_surface``), or with ``symmetric`` the coronal ones left and right alike, in
``fit_contact``'s 15 groups, the three asymmetries held: 29 variables. ``fit_shape3d`` fits
VTL's sheets symmetrically, since VTL builds each from a half surface and its mirror (a
symmetric sheet's best fit is symmetric; the grouping saves the method from finding that out).
The jaw stays where the caller puts it (``fit_shape3d``: from VTL's jaw angle, as ``fit2d`` sets
it). ``fit_shape3d`` starts from the mid-sagittal fit of the shape's outline, which sets the
sagittal parameters; the 3D fit then mostly shapes the cross-sections.

The origin is the rig's hub posed at the starting values (the hub moves with the jaw and, as
far as the pages allow, with the root: ``geometry.tongue_rig``), on z = 0, inside the tongue,
fixed for the fit. From the 2D fit's result it comes forward with a root drawn in, where the
2D fit's own origin (the hub at its start) stayed behind.

What is compared (``visible_mask``), the 3D form of the 2D rule (``objective2d``):

- the root below the rig's root cut: an observed vertex behind O whose direction from O, seen
  in the mid-sagittal plane (its x and y), falls more than ROOT_CUT_DEG below O's horizontal
  is left out. VTL's root runs down to the hyoid, the rig's root ends about 28 degrees below the
  hub, where it turns into the floor of the mouth: such rays would meet the rig's floor;
- for a rib grid (VTL's sheet: ribs from root to tip, points across), the underside after the
  tip: the ribs after the tip rib, found on the ribs' middle points as ``objective2d.tip_index``
  finds it on an outline (the first rib after the highest one from which the next rib is no
  further forward). VTL's last three or four ribs drop to the floor of the mouth or collapse
  onto the tip: a construction of its model, which imaging rarely sees. An ungridded surface
  (``fit_surface`` with ``mask=None``) gets the root cut only; a caller that knows more passes
  its own mask.

The objective (mm^2) is the 2D fit's, with the squared 3D RMS in place of the 2D one:

    rms^2 + volume_weight (100 dV / V0)^2 + neutral_weight sum(((x - neutral) / range)^2)
          + volume_bound_weight max(0, |100 dV / V0| - volume_bound_pct)^2

with fit2d's weights, the neutral pull on every free variable. The volume terms take the exact
volume of the posed surface, which the walk's certificate sums on the way (``FirstHits.volume``:
free, where the 2D fit's coarse surface of ``MidSagittalSection`` cost a fifth of an
evaluation). Reports give the plain RMS over the compared rays, the exact volume change and the
parameters at a range limit (``fit2d.LIMIT_FRACTION``).

The method (BOBYQA by default) is restarted from its best point, with fresh models, while a
restart gains more than RESTART_GAIN (at most RESTARTS times, within MAX_EVALS in all): its
quadratic models go stale where rays slip from one rig triangle to the next.

Speed: an evaluation is the rig's surface (2,978 vertices) and the walk of every ray, about
1.3 ms of CPU for VTL's 270 to 360 kept vertices, and BOBYQA adds about 0.3 ms of its own. A
surface with more than MAX_RAYS kept vertices is fitted, and its RMS reported, on an evenly
spread subset (every vertex's first hit costs the same, and 1,000 rays resolve 35 parameters
many times over).
"""

import time
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np
import numpy.typing as npt

from glasshead.fitting import fit2d, fit_contact
from glasshead.fitting.fit2d import (
    NEUTRAL_WEIGHT,
    VOLUME_BOUND_PCT,
    VOLUME_BOUND_WEIGHT,
    VOLUME_WEIGHT,
    FitReport,
    sagittal_parameters,
    select_shapes,
)
from glasshead.fitting.objective2d import ROOT_CUT_DEG, MidSagittalSection
from glasshead.fitting.objective3d import RayError3D
from glasshead.fitting.optimizer import Progress, minimize_restarted, with_changes
from glasshead.fitting.vtl_mapping import jaw_opening_from_vtl
from glasshead.geometry.tongue_surface import TongueRig

CORONAL_PREFIX = "tongue coronal"
#: Evaluations of a fit, restarts included: BOBYQA needed 658 to 2,500 on VTL's 69 sheets, and
#: 2,500 take about 3.8 s of CPU, inside the 5 s goal with the 2D fit.
MAX_EVALS = 2500
#: Fewest kept vertices a surface needs: fewer cannot determine 35 parameters.
MIN_RAYS = 40
#: Kept vertices beyond this are thinned to an evenly spread subset for the fit.
MAX_RAYS = 1000
#: Stopping tests: 1e-5 mm^2 of objective (0.005 mm of RMS near 1 mm), 1e-3 mm of parameter.
FTOL_ABS = 1e-5
XTOL_ABS = 1e-3
#: Restarts of the method from its best point, while one gains more than RESTART_GAIN of the
#: objective.
RESTARTS = 2
RESTART_GAIN = 0.01
#: The method's first step, as a fraction of each variable's range (smaller steps stopped some
#: fits early: /e/ at 1.93 mm after 109 evaluations with a twentieth).
STEP_FRACTION = 0.1
#: The accuracy goal: a fit's 3D RMS error, mm.
GOAL_RMS_MM = 1.5
#: VTL's tongue sheet: ribs from root to tip, points across each rib.
VTL_RIBS, VTL_POINTS = 37, 11


@dataclass
class FitReport3D(FitReport):
    """A 3D fit's report: fit2d's fields (``seconds`` of wall time), the process CPU time of
    the fit (the machine is shared: wall time varies with its load), the RMS at the start, the
    cost of the mid-sagittal fit it started from (0 when it started elsewhere) and the rays'
    origin (x, y, z) mm."""

    cpu_seconds: float = 0.0
    origin: tuple[float, ...] = ()
    start_rms_mm: float = 0.0
    start_evaluations: int = 0
    start_seconds: float = 0.0
    start_cpu_seconds: float = 0.0


def coronal_parameters(rig: TongueRig) -> list[str]:
    return [p for p in rig.parameter_names
            if rig.parameters[p]["group"].startswith(CORONAL_PREFIX)]


def surface_parameters(rig: TongueRig) -> list[str]:
    """The parameters a 3D fit moves: sagittal, then coronal."""
    return sagittal_parameters(rig) + coronal_parameters(rig)


def check_observed(observed) -> np.ndarray:
    """(k, 3) float64 observed vertices, or ValueError."""
    points = np.asarray(observed, dtype=np.float64)
    if points.ndim != 2 or points.shape[1] != 3:
        raise ValueError(f"observed surface must be (k, 3) vertices, got shape {points.shape}")
    if not np.all(np.isfinite(points)):
        raise ValueError("observed surface has non-finite coordinates (NaN or inf)")
    if len(points) < MIN_RAYS:
        raise ValueError(f"observed surface has {len(points)} vertices; at least {MIN_RAYS} "
                         "are needed")
    return points


def tip_rib(middles) -> int:
    """Index of the tip rib of a root-to-tip rib sequence, from the ribs' middle points (r, 2+):
    the first rib after the highest one from which the next is no further forward."""
    middles = np.asarray(middles, dtype=np.float64)
    k = int(np.argmax(middles[:, 1]))
    while k + 1 < len(middles) and middles[k + 1, 0] >= middles[k, 0]:
        k += 1
    return k


def visible_mask(observed, origin, *, grid=None, root_cut_deg=ROOT_CUT_DEG) -> np.ndarray:
    """(k,) bool: the observed vertices a fit compares (module docstring). ``grid`` (ribs,
    points) when the vertices are a root-to-tip rib grid, rib-major: then the ribs after the tip
    are left out too."""
    points = check_observed(observed)
    origin = np.asarray(origin, dtype=np.float64)
    offset = points[:, :2] - origin[:2]
    elevation = np.degrees(np.arctan2(offset[:, 1], np.abs(offset[:, 0])))
    keep = ~((offset[:, 0] < 0) & (elevation < -root_cut_deg))
    if grid is not None:
        ribs, across = grid
        if ribs * across != len(points):
            raise ValueError(f"a {ribs} x {across} grid needs {ribs * across} vertices, "
                             f"got {len(points)}")
        middles = points.reshape(ribs, across, 3)[:, across // 2]
        rib = np.repeat(np.arange(ribs), across)
        keep &= rib <= tip_rib(middles)
    return keep


def spread_subset(count: int, limit: int = MAX_RAYS) -> np.ndarray:
    """Indices of an evenly spread subset of at most ``limit`` of ``count`` items."""
    if count <= limit:
        return np.arange(count)
    return np.unique(np.linspace(0, count - 1, limit).round().astype(np.int64))


class Objective3D:
    """The 3D objective over grouped free variables (see the module docstring).

    observed (k, 3) mm with ``mask`` (k,) bool of the rays to compare; ``groups`` (name, rig
    parameters) of each free variable, the members of a group moved together; every other
    parameter held at ``base`` (P,); ``__call__(x)`` (one value per group) in mm^2.
    """

    def __init__(self, rig: TongueRig, observed, mask, groups, *, base, origin,
                 section: MidSagittalSection, volume_weight=VOLUME_WEIGHT,
                 neutral_weight=NEUTRAL_WEIGHT, volume_bound_pct=VOLUME_BOUND_PCT,
                 volume_bound_weight=VOLUME_BOUND_WEIGHT, max_rays=MAX_RAYS):
        members = [m for _, ms in groups for m in ms]
        unknown = [name for name in members if name not in rig.parameters]
        if unknown or not groups:
            raise ValueError(f"free parameters must be known rig parameters; got {unknown}")
        if volume_weight < 0 or neutral_weight < 0 or volume_bound_weight < 0:
            raise ValueError("the volume and neutral weights cannot be negative")
        self.rig = rig
        self.section = section
        self.groups = [(name, list(ms)) for name, ms in groups]
        self.names = [name for name, _ in self.groups]
        self.members = np.array([rig.parameter_names.index(m) for m in members])
        # x (one value per group) -> the members' values.
        self.expand = fit_contact.group_expansion(self.groups)
        first = np.array([rig.parameter_names.index(ms[0]) for _, ms in self.groups])
        # a group's range: where every member is within its own
        inside = [self.members[self.expand[:, k] > 0] for k in range(len(self.groups))]
        self.lower = np.array([rig.minimum[ks].max() for ks in inside])
        self.upper = np.array([rig.maximum[ks].min() for ks in inside])
        self.neutral = rig.neutral[first]
        self.base = np.array(base, dtype=np.float64)
        self.x0 = np.clip(self.base[first], self.lower, self.upper)
        kept = np.asarray(observed, dtype=np.float64)[mask]
        self.origin = np.asarray(origin, dtype=np.float64)
        rest = rig.vertices(self.base)
        self.rays = kept[spread_subset(len(kept), max_rays)]
        self.error = RayError3D(rig.triangles, rest, self.rays, self.origin)
        self.volume_weight = float(volume_weight)
        self.neutral_weight = float(neutral_weight)
        self.volume_bound_pct = float(volume_bound_pct)
        self.volume_bound_weight = float(volume_bound_weight)

    def values(self, x) -> np.ndarray:
        """All rig values (P,) for free values x (one per group)."""
        values = self.base.copy()
        values[self.members] = self.expand @ np.asarray(x, dtype=np.float64)
        return values

    def residuals(self, x) -> np.ndarray:
        """(rays,) residuals, mm, of the rays compared (every kept vertex, or the subset)."""
        return self.error.residuals(self.rig.vertices(self.values(x)))

    def volume_change(self, x) -> float:
        """Volume change of the surface from the rest volume, percent."""
        return self._percent_of_rest(self.rig.volume(self.values(x)))

    def _percent_of_rest(self, volume: float) -> float:
        return 100.0 * (volume / self.section.rest_volume - 1.0)

    def __call__(self, x) -> float:
        x = np.asarray(x, dtype=np.float64)
        r = self.error.residuals(self.rig.vertices(self.values(x)))
        value = float(np.mean(r * r))
        if self.volume_weight or self.volume_bound_weight:
            # the volume of the surface just posed: the walk's certificate summed it
            hits = self.error.hits
            assert hits is not None  # residuals() just set them
            change = self._percent_of_rest(hits.volume)
            value += self.volume_weight * change**2
            value += self.volume_bound_weight * max(0.0, abs(change)
                                                    - self.volume_bound_pct) ** 2
        if self.neutral_weight:
            value += self.neutral_weight * float(
                np.sum(((x - self.neutral) / (self.upper - self.lower)) ** 2))
        return value


def free_groups(rig: TongueRig, symmetric=False) -> list[tuple[str, list[str]]]:
    """(name, rig parameters) of each free variable: the sagittal and coronal parameters one by
    one, or with ``symmetric`` the coronal ones left and right alike (``fit_contact``'s groups:
    width, groove depth and width, edge heights together, side bulge per section), the
    asymmetries left at the base values."""
    if symmetric:
        return fit_contact.free_groups(rig, jaw=False)
    return [(name, [name]) for name in surface_parameters(rig)]


@dataclass(frozen=True, eq=False)
class SurfaceFit:
    """How ``fit_surface`` fits: the method, the start, the free variables and the vertices
    compared, the objective's weights (fit2d's), the rays kept and the stopping tests. Every
    field has the fits' default."""

    method: str = "bobyqa"
    #: (P,) values to start from, which also hold the parameters not fitted (default: neutral).
    base: npt.ArrayLike | None = None
    #: (k,) bool of the vertices to compare (default: ``visible_mask``'s root cut).
    mask: npt.ArrayLike | None = None
    #: The free variables, (name, rig parameters) each (default: ``free_groups(rig, symmetric)``).
    groups: Sequence[tuple[str, Sequence[str]]] | None = None
    symmetric: bool = False
    volume_weight: float = VOLUME_WEIGHT
    neutral_weight: float = NEUTRAL_WEIGHT
    volume_bound_pct: float = VOLUME_BOUND_PCT
    volume_bound_weight: float = VOLUME_BOUND_WEIGHT
    max_rays: int = MAX_RAYS
    restarts: int = RESTARTS
    step_fraction: float = STEP_FRACTION
    ftol_abs: float = FTOL_ABS
    xtol_abs: float = XTOL_ABS
    #: The rig's section, shared by many fits (made from the rig when None).
    section: MidSagittalSection | None = None
    #: The report's shape name.
    name: str = ""


@dataclass(frozen=True, eq=False)
class ShapeFit3D(SurfaceFit):
    """How ``fit_shape3d`` fits a VTL sheet: ``SurfaceFit``'s fields (its ``base``, ``mask`` and
    ``name`` are the shape's), the coronal groups symmetric, from the mid-sagittal fit of the
    shape's outline (``from_2d``) or from neutral, the jaw from VTL either way."""

    symmetric: bool = True
    from_2d: bool = True


def fit_surface(rig: TongueRig, observed, options: SurfaceFit | None = None, /, *,
                max_evals: int = MAX_EVALS, progress: Progress | None = None,
                **changes) -> FitReport3D:
    """Fit the rig's surface to observed vertices (k, 3) float mm in the project frame, within
    ``max_evals`` evaluations; ``progress(evaluations, best_error)`` after every evaluation
    (counted over the restarts); keyword ``changes`` replace fields of ``options``
    (``optimizer.with_changes``). Raises ValueError for a malformed surface or base, a mask of
    the wrong shape, or fewer than MIN_RAYS vertices left to compare.
    """
    options = with_changes(options or SurfaceFit(), changes)
    base, mask = options.base, options.mask
    points = check_observed(observed)
    start = rig.neutral.copy() if base is None else np.array(base, dtype=np.float64)
    if start.shape != rig.neutral.shape or not np.all(np.isfinite(start)):
        raise ValueError(f"base must be {rig.neutral.shape} finite values, got {start.shape}")
    start = np.clip(start, rig.minimum, rig.maximum)
    origin = np.append(rig.control_points(start)[1], 0.0)
    if mask is None:
        keep = visible_mask(points, origin)
    else:
        keep = np.asarray(mask)
        if keep.shape != (len(points),) or keep.dtype != bool:
            raise ValueError(f"mask must be a ({len(points)},) bool array, got "
                             f"{keep.dtype} {keep.shape}")
    if int(keep.sum()) < MIN_RAYS:
        raise ValueError(f"the mask leaves {int(keep.sum())} vertices to compare; at least "
                         f"{MIN_RAYS} are needed")
    groups = options.groups or free_groups(rig, options.symmetric)
    objective = Objective3D(rig, points, keep, groups, base=start, origin=origin,
                            section=options.section or MidSagittalSection(rig),
                            volume_weight=options.volume_weight,
                            neutral_weight=options.neutral_weight,
                            volume_bound_pct=options.volume_bound_pct,
                            volume_bound_weight=options.volume_bound_weight,
                            max_rays=options.max_rays)
    before = objective.residuals(objective.x0)
    started, cpu = time.perf_counter(), time.process_time()
    # BOBYQA's models go stale where rays slip from one triangle to the next: restart from
    # the best point, with fresh models, while that still gains.
    result = minimize_restarted(objective, objective.x0, objective.lower, objective.upper,
                                method=options.method, max_evals=max_evals, progress=progress,
                                restarts=options.restarts, restart_gain=RESTART_GAIN,
                                ftol_abs=options.ftol_abs, xtol_abs=options.xtol_abs,
                                initial_step=options.step_fraction
                                * (objective.upper - objective.lower))
    seconds, cpu = time.perf_counter() - started, time.process_time() - cpu
    errors = objective.residuals(result.x)
    values = objective.values(result.x)
    return FitReport3D(
        shape=options.name, method=options.method, evaluations=result.evaluations,
        seconds=seconds,
        cpu_seconds=cpu,
        rms_mm=float(np.sqrt(np.mean(errors**2))), max_error_mm=float(np.abs(errors).max()),
        volume_change_pct=objective.volume_change(result.x),
        at_limit=fit2d.at_limit(result.x, objective.lower, objective.upper, objective.names),
        rays=len(errors), stop=result.stop,
        params={n: float(v) for n, v in zip(rig.parameter_names, values, strict=True)},
        start_rms_mm=float(np.sqrt(np.mean(before**2))),
        origin=tuple(float(x) for x in origin))


def shape_vertices(shape) -> np.ndarray:
    """A VTL shape record's tongue sheet (ribs * points, 3) mm, project frame."""
    return np.asarray(shape["tongue_surface_vertices"], dtype=np.float64)


def fit_shape3d(rig: TongueRig, shape, options: ShapeFit3D | None = None, /, *,
                max_evals: int = MAX_EVALS, progress: Progress | None = None,
                **changes) -> FitReport3D:
    """Fit one VTL shape record by its tongue sheet (see ``ShapeFit3D``), with the rib-grid
    mask."""
    options = with_changes(options or ShapeFit3D(), changes)
    section = options.section or MidSagittalSection(rig)
    base = rig.neutral.copy()
    base[rig.jaw_parameter] = jaw_opening_from_vtl(shape, rig)
    started, cpu = time.perf_counter(), time.process_time()
    start_evaluations = 0
    if options.from_2d:
        outline = fit2d.fit_outline(rig, shape["tongue_outline"],
                                    fit2d.OutlineFit(base=base, section=section,
                                                     name=shape["name"]))
        base = np.array([outline.params[n] for n in rig.parameter_names])
        start_evaluations = outline.evaluations
    start_seconds, start_cpu = time.perf_counter() - started, time.process_time() - cpu
    vertices = shape_vertices(shape)
    origin = np.append(rig.control_points(base)[1], 0.0)
    mask = visible_mask(vertices, origin, grid=(VTL_RIBS, VTL_POINTS)) \
        if len(vertices) == VTL_RIBS * VTL_POINTS else None
    report = fit_surface(rig, vertices, replace(options, base=base, mask=mask,
                                                name=shape["name"], section=section),
                         max_evals=max_evals, progress=progress)
    report.start_evaluations = start_evaluations
    report.start_seconds = start_seconds
    report.start_cpu_seconds = start_cpu
    return report


def fit_all3d(rig: TongueRig, observations, options: ShapeFit3D | None = None, /, *,
              names: Sequence[str] | None = None, max_evals: int = MAX_EVALS,
              **changes) -> list[FitReport3D]:
    """``fit_shape3d`` of every shape of an observations document (or those named), in its
    order, on one section of the rig."""
    options = with_changes(options or ShapeFit3D(), changes)
    options = replace(options, section=options.section or MidSagittalSection(rig))
    return [fit_shape3d(rig, s, options, max_evals=max_evals)
            for s in select_shapes(observations, names)]
