"""The mid-sagittal error of Cohen, Beskow and Massaro (1998): rays from an origin inside the
tongue through the observed outline; at each ray, the distance along it between the observed
point and where it crosses the rig's mid-sagittal outline; the root mean square over the rays.

The rig's outline is the z = 0 section of its surface, not its sagittal B-spline: the section's
midline radius is a B-spline over the page angle, so it blends the neighbouring coronal controls
(ratios up to 2) and the groove offsets, and lies up to 1.2 mm off the sagittal curve at rest.
``MidSagittalSection`` evaluates that section exactly, at REFINE times the surface's stations.

What is compared (``compared_outline``). A VocalTractLab tongue outline runs from the root at
the hyoid up the pharyngeal side, over the dorsum to the tip and back along a stub of the
underside. Kept: the contour from where the root's rays rise above ROOT_CUT_DEG below the
origin's horizontal, over the dorsum, to the tip (the first point after the highest one from
which the outline stops running forward). Left out:

- the underside after the tip: VTL's is two or three points dropping to the floor of the mouth,
  a construction of its model rather than a measured contour, and imaging rarely sees it;
- the root below ROOT_CUT_DEG: VTL's root runs down to the hyoid body (y down to -53 mm in /u/),
  while the rig's root ends about 28 degrees below the hub's horizontal, where it turns into
  the floor of the mouth; rays further down would cross the rig's floor, not a root.

The kept part is resampled every SPACING_MM of arclength, so that every millimetre of contour
weighs the same whatever VTL's point spacing (3-4 mm, with duplicates at the tip).

The origin is the rig's hub posed at the fit's base values (``fit2d``: neutral tongue, the
shape's jaw opening), fixed for the fit: inside the tongue, and the point round which the
rig's pages turn in order, so each ray crosses the rig's section once. The error is also
defined when a ray crosses more than once (the crossing nearest the observed point counts) or
not at all (the crossing is taken at the origin).

The objective a fit minimises (mm^2) adds optional, weighted terms to the squared RMS:

    rms^2 + volume_weight * (100 dV / V0)^2 + neutral_weight * sum(((x - neutral) / range)^2)
          + volume_bound_weight * max(0, |100 dV / V0| - volume_bound_pct)^2

dV / V0 is the relative volume change from the rest volume (the tongue is incompressible: a
mid-sagittal fit could otherwise swell it to match a 2D outline); the neutral term pulls each
free parameter, normalised by its range, toward its neutral value, so parameters the outline
does not determine stay there instead of wandering to a range limit (``neutral_weights`` gives
some parameters a weight of their own, see ``fit2d.WIDTH_WEIGHT``). The bound term is a steep
wall: nothing inside the band, and outside it every percent costs as much as a large misfit, so
a fit keeps the volume within the band unless the outline cannot be matched any other way.
"""

from collections.abc import Mapping, Sequence

import numpy as np

from glasshead.geometry.midsagittal import resample
from glasshead.geometry.tongue_surface import TongueRig

#: Rays behind the origin more than this far below its horizontal are left out (see above).
ROOT_CUT_DEG = 30.0
#: Arclength between compared points along the observed outline, mm.
SPACING_MM = 1.0
#: Fewest compared points an observation needs.
MIN_POINTS = 8
#: Section samples per surface station interval.
REFINE = 4


def _as_outline(outline, what="observed outline"):
    points = np.asarray(outline, dtype=np.float64)
    if points.ndim != 2 or points.shape[1] != 2:
        raise ValueError(f"{what} must be (n, 2) mid-sagittal points, got shape {points.shape}")
    if not np.all(np.isfinite(points)):
        raise ValueError(f"{what} has non-finite coordinates (NaN or inf)")
    if len(points) < MIN_POINTS:
        raise ValueError(f"{what} has {len(points)} points; at least {MIN_POINTS} are needed")
    return points


def tip_index(outline) -> int:
    """Index of the tip of a root-to-tip outline: the first point after the highest one from
    which the next point is no further forward."""
    points = np.asarray(outline, dtype=np.float64)
    k = int(np.argmax(points[:, 1]))
    while k + 1 < len(points) and points[k + 1, 0] >= points[k, 0]:
        k += 1
    return k


def compared_outline(outline, origin, *, root_cut_deg=ROOT_CUT_DEG, spacing_mm=SPACING_MM):
    """The part of an observed root-to-tip outline (n, 2) that is compared, resampled (m, 2).

    Raises ValueError for a malformed outline or one with too few points left to compare.
    """
    points = _as_outline(outline)
    origin = np.asarray(origin, dtype=np.float64)
    points = points[:tip_index(points) + 1]
    offset = points - origin
    elevation = np.degrees(np.arctan2(offset[:, 1], np.abs(offset[:, 0])))
    below = (offset[:, 0] < 0) & (elevation < -root_cut_deg)
    start = int(np.nonzero(below)[0].max()) + 1 if below.any() else 0
    points = points[start:]
    if len(points) < 2:
        raise ValueError("the observed outline has nothing left to compare after the root cut "
                         "and the tip")
    compared = resample(points, spacing_mm)
    if len(compared) < MIN_POINTS:
        raise ValueError(f"the observed outline leaves {len(compared)} compared points; at "
                         f"least {MIN_POINTS} are needed")
    return compared


class Rays:
    """Rays from ``origin`` (2,) through ``points`` (m, 2): unit directions and distances."""

    def __init__(self, origin, points):
        self.origin = np.asarray(origin, dtype=np.float64)
        self.points = np.asarray(points, dtype=np.float64)
        offset = self.points - self.origin
        self.distances = np.linalg.norm(offset, axis=1)
        if np.any(self.distances < 1e-6):
            raise ValueError("an observed point lies on the ray origin")
        self.directions = offset / self.distances[:, None]
        # cross(d, p) = d . (p_y, -p_x): one product gives every ray's side of every vertex.
        self._normals = np.stack([self.directions[:, 1], -self.directions[:, 0]], axis=1)
        self._angles = np.arctan2(self.directions[:, 1], self.directions[:, 0])

    def crossings(self, polyline):
        """Distance along each ray (m,) to its crossing with a closed polyline (k, 2) nearest
        the observed point; 0 where a ray does not cross it.

        When the polyline turns once round the origin in order (the rig's section round its
        hub does), each ray crosses exactly one segment, found by bisection on the vertices'
        polar angles; otherwise every ray is tested against every segment (``crossings_all``).
        """
        offset = np.asarray(polyline, dtype=np.float64) - self.origin
        angle = np.arctan2(offset[:, 1], offset[:, 0])
        turn = np.diff(angle, append=angle[:1])
        turn = (turn + np.pi) % (2 * np.pi) - np.pi
        total = turn.sum()
        if abs(abs(total) - 2 * np.pi) < 1e-6 and np.all(turn * total > 0):
            return self._crossings_star(offset, angle, turn, 1.0 if total > 0 else -1.0)
        return self.crossings_all(polyline)

    def _crossings_star(self, offset, angle, turn, sense):
        # Polar angles made increasing from the vertex of least angle; each ray lies in exactly
        # one span between consecutive vertices.
        start = int(np.argmin(sense * angle))
        order = np.r_[start:len(offset), 0:start + 1]
        swept = sense * angle[start] + np.concatenate([[0.0], np.cumsum(sense * turn[order[:-1]])])
        ray = (sense * self._angles - swept[0]) % (2 * np.pi) + swept[0]
        k = np.clip(np.searchsorted(swept, ray, side="right") - 1, 0, len(offset) - 1)
        a, b = offset[order[k]], offset[order[k + 1]]
        side_a = np.einsum("ij,ij->i", self._normals, a)
        side_b = np.einsum("ij,ij->i", self._normals, b)
        with np.errstate(divide="ignore", invalid="ignore"):
            s = np.where(side_a != side_b, side_a / (side_a - side_b), 0.0)
        point = a + s[:, None] * (b - a)
        return np.maximum(np.einsum("ij,ij->i", self.directions, point), 0.0)

    def crossings_all(self, polyline):
        """``crossings`` testing every ray against every segment: any closed polyline."""
        closed = np.vstack([polyline, polyline[:1]]) - self.origin
        side = self._normals @ closed.T       # (m, k + 1): signed distance of vertices to ray
        along = self.directions @ closed.T    # (m, k + 1): their projection on the ray
        a, b = side[:, :-1], side[:, 1:]
        hit = (a * b <= 0) & (a != b)
        with np.errstate(divide="ignore", invalid="ignore"):
            s = np.where(hit, a / (a - b), 0.0)
        t = along[:, :-1] + s * (along[:, 1:] - along[:, :-1])
        hit &= t > 0
        gap = np.where(hit, np.abs(t - self.distances[:, None]), np.inf)
        best = np.argmin(gap, axis=1)
        rows = np.arange(len(best))
        return np.where(hit[rows, best], t[rows, best], 0.0)

    def errors(self, polyline):
        """Signed error per ray (m,), mm: rig crossing minus observed distance (+: rig outside)."""
        return self.crossings(polyline) - self.distances


def _refined(params, refine):
    params = np.asarray(params, dtype=np.float64)
    following = np.append(params[1:], params[0] + 1.0)
    steps = np.arange(refine) / refine
    return (params[:, None] + (following - params)[:, None] * steps).ravel()


def _coarse(rig: TongueRig) -> TongueRig:
    """The rig on every other station and page angle: the volume penalty's surface."""
    definition = dict(rig.definition)
    surface = dict(definition["surface"])
    surface["station_params"] = surface["station_params"][::2]
    surface["page_angles_deg"] = surface["page_angles_deg"][::2]
    definition["surface"] = surface
    return TongueRig(definition)


class MidSagittalSection:
    """The z = 0 section of a rig's surface as a closed polyline, at REFINE times its stations.

    It evaluates the rig's own surface code on pages with the angles (-45, 0, 45) and keeps the
    0 degree sample: vertex = hub + radius(0) * page direction, z = 0. It also keeps the rest
    volume and a coarse copy of the rig for the volume penalty, so that objectives for many
    observations share them.
    """

    def __init__(self, rig: TongueRig, refine: int = REFINE):
        definition = dict(rig.definition)
        surface = dict(definition["surface"])
        surface["station_params"] = _refined(surface["station_params"], refine).tolist()
        surface["page_angles_deg"] = [-45.0, 0.0, 45.0]
        definition["surface"] = surface
        self.rig = rig
        self._section_rig = TongueRig(definition)
        self.rest_volume = rig.volume(rig.neutral)
        self.volume_rig = _coarse(rig)
        self.coarse_rest_volume = self.volume_rig.volume(rig.neutral)

    def control_points(self, values):
        """The rig's posed control points for values (P,), which ``outline`` and the volume
        rig can share (``TongueRig.page_radii``'s ``posed``)."""
        return self._section_rig.control_points(values)

    def outline(self, values, posed=None) -> np.ndarray:
        """(k, 2) float64 mid-sagittal outline, mm, for parameter values (P,) (``posed``:
        ``control_points(values)`` when the caller has them)."""
        hub, _stations, direction, radii, _stretch = self._section_rig.page_radii(values, posed)
        return hub + radii[:, 1, None] * direction

    def hub(self, values) -> np.ndarray:
        """The rig's hub (2,) posed for parameter values (P,)."""
        return self.control_points(values)[1]


class Objective2D:
    """The mid-sagittal objective over a subset of a rig's parameters.

    ``free``: names of the parameters the fit moves; every other parameter stays at ``base``
    (P,) values (default neutral). ``origin`` defaults to the hub posed at ``base``.
    ``outline_weight`` scales the rays' term (rms^2) against the others (1 in every fit of one
    outline; a combined fit weighs it against other measurements).
    ``__call__(x)`` (x: the free values) returns the objective (mm^2, see the module docstring);
    ``evaluations`` counts the calls.
    """

    def __init__(self, rig: TongueRig, outline, free: Sequence[str], *, base=None, origin=None,
                 volume_weight=0.0, neutral_weight=0.0, volume_bound_pct=None,
                 volume_bound_weight=0.0, root_cut_deg=ROOT_CUT_DEG,
                 spacing_mm=SPACING_MM, section: MidSagittalSection | None = None,
                 neutral_weights: Mapping[str, float] | None = None, outline_weight=1.0):
        unknown = [name for name in free if name not in rig.parameters]
        if unknown or not free:
            raise ValueError(f"free parameters must be known rig parameters; got {list(free)}")
        if volume_weight < 0 or neutral_weight < 0 or volume_bound_weight < 0:
            raise ValueError("the volume and neutral weights cannot be negative")
        if not outline_weight >= 0:
            raise ValueError("the outline's weight cannot be negative")
        if volume_bound_pct is not None and not volume_bound_pct > 0:
            raise ValueError("the volume bound must be a positive percentage")
        self.rig = rig
        self.section = section or MidSagittalSection(rig)
        self.free = list(free)
        self.index = np.array([rig.parameter_names.index(name) for name in self.free])
        self.base = rig.neutral.copy() if base is None else np.array(base, dtype=np.float64)
        self.lower, self.upper = rig.minimum[self.index], rig.maximum[self.index]
        self.neutral = rig.neutral[self.index]
        self.origin = self.section.hub(self.base) if origin is None \
            else np.asarray(origin, dtype=np.float64)
        self.rays = Rays(self.origin, compared_outline(outline, self.origin,
                                                       root_cut_deg=root_cut_deg,
                                                       spacing_mm=spacing_mm))
        self.volume_weight = float(volume_weight)
        self.neutral_weight = float(neutral_weight)
        self.outline_weight = float(outline_weight)
        # The pull toward neutral per free parameter: neutral_weight unless named otherwise.
        weights = dict(neutral_weights or {})
        if any(w < 0 for w in weights.values()):
            raise ValueError("the volume and neutral weights cannot be negative")
        self.pull = np.array([float(weights.get(name, neutral_weight)) for name in self.free])
        self.own_pulls = bool(weights)
        self.volume_bound_pct = None if volume_bound_pct is None else float(volume_bound_pct)
        self.volume_bound_weight = float(volume_bound_weight)
        self.evaluations = 0

    def values(self, x) -> np.ndarray:
        """All rig values (P,) for free values x."""
        values = self.base.copy()
        values[self.index] = x
        return values

    def errors(self, x) -> np.ndarray:
        """Signed per-ray errors (m,), mm, for free values x."""
        return self.rays.errors(self.section.outline(self.values(x)))

    def rms(self, x) -> float:
        """Root mean square of the per-ray errors, mm."""
        return float(np.sqrt(np.mean(self.errors(x) ** 2)))

    def volume_change(self, x, exact=True, posed=None) -> float:
        """Relative volume change from the rest volume, percent; ``exact=False`` uses the
        penalty's coarse surface (within 0.15 % of the exact change over the sagittal and jaw
        ranges, at a third of the cost), from ``posed`` control points when given."""
        rig, rest = (self.rig, self.section.rest_volume) if exact \
            else (self.section.volume_rig, self.section.coarse_rest_volume)
        return 100.0 * (rig.volume(self.values(x), posed) / rest - 1.0)

    def __call__(self, x) -> float:
        self.evaluations += 1
        x = np.asarray(x, dtype=np.float64)
        values = self.values(x)
        posed = self.section.control_points(values)  # once, for the outline and the volume
        value = float(np.mean(self.rays.errors(self.section.outline(values, posed)) ** 2))
        if self.outline_weight != 1.0:
            value *= self.outline_weight
        bound_pct = self.volume_bound_pct if self.volume_bound_weight > 0 else None
        if self.volume_weight or bound_pct is not None:
            change = self.volume_change(x, exact=False, posed=posed)
            value += self.volume_weight * change**2
            if bound_pct is not None:
                value += self.volume_bound_weight * max(0.0, abs(change) - bound_pct) ** 2
        share = (x - self.neutral) / (self.upper - self.lower)
        # One weight for all sums as before: the contact fits of the phoneme targets follow
        # different paths on a change in the last bit of their objective.
        if self.own_pulls:
            value += float(np.sum(self.pull * share**2))
        elif self.neutral_weight:
            value += self.neutral_weight * float(np.sum(share**2))
        return value
