"""Fit the rest shape of the tongue rig to the MRI tongue (Badin et al., via ArtiSynth).

The rig is radial about its hub (see ``geometry.tongue_rig``), so the MRI surface is sampled the
same way: rays from the hub at a grid of page directions theta and page angles phi give the
MRI's radius lambda(theta, phi) and how obliquely each ray meets the surface. The fit moves

- each sagittal control point along its own ray from the hub (its radius),
- the coronal ratios of the three sections (kept left-right symmetric: the MRI tongue is),
- the section blend of the control points whose blend is free,
- the pole half-width,

to minimise the radial misfit, weighted so that it approximates the surface distance integrated
over the surface (scipy least squares, trust region). Afterwards the surface sampling (stations
along the curve, page angles between the poles) is spread by arclength and turning, and the
result is measured with true closest-point distances in both directions.
"""

import numpy as np
import trimesh
from scipy.optimize import least_squares

from glasshead.geometry.bspline import basis_matrix, periodic_knots
from glasshead.geometry.tongue_parameters import (
    CORONAL_DEGREE,
    DEFAULT_SECTION_WEIGHTS,
    HUB_MM,
    PAGE_SAMPLES,
    POLE_CONTROLS,
    SAGITTAL_DEGREE,
    SAGITTAL_POINTS,
    SECTIONS,
    STATIONS,
    coronal_control_angles_deg,
    coronal_knots_deg,
)

#: Ray grid of the fit: page directions every 2 degrees, page angles every 3 (poles excluded).
FIT_THETA_DEG = np.arange(0.0, 360.0, 2.0)
FIT_PHI_DEG = np.arange(-87.0, 87.5, 3.0)
#: Stations used to evaluate the rig during the fit (dense, so interpolating between them in
#: theta costs far less than the misfit being measured).
FIT_STATIONS = 360
#: Floor on the cosine between a ray and the MRI normal in the weights (grazing rays would
#: otherwise count a large radial miss as a tiny distance, and the reverse).
MIN_OBLIQUITY = 0.15
#: Pull of the free blends toward their defaults (keeps each section where it is named).
BLEND_PRIOR = 0.3
#: Turning, in mm of arclength per radian, when spreading the surface samples: curved parts
#: (the tip, the lateral edges of the dorsum) get more of them.
TURNING_MM_PER_RAD = 8.0

#: Coronal controls fitted (left-right mirrored); the midline ratio stays 1, so the sagittal curve
#: is the tongue's mid-sagittal contour and not a scaled copy of it.
_SYMMETRIC_CONTROLS = (2, 3, 4, 5, 6)
_HALF = len(_SYMMETRIC_CONTROLS)


def ray_radii(vertices, triangles, hub, theta_deg, phi_deg):
    """MRI radius and obliquity along rays from the hub.

    vertices (n, 3) float, triangles (m, 3) int: a closed mesh around the hub.
    Returns (radius, cosine): (t, p) float64 each, for t page directions theta and p page
    angles phi. Where a ray crosses the surface more than once the outermost crossing counts.
    """
    mesh = trimesh.Trimesh(vertices, triangles, process=False)
    theta = np.radians(np.asarray(theta_deg, dtype=np.float64))
    phi = np.radians(np.asarray(phi_deg, dtype=np.float64))
    t, p = np.meshgrid(theta, phi, indexing="ij")
    directions = np.stack([np.cos(p) * np.cos(t), np.cos(p) * np.sin(t), np.sin(p)], -1)
    directions = directions.reshape(-1, 3)
    origins = np.tile([hub[0], hub[1], 0.0], (len(directions), 1))
    hits, ray, face = mesh.ray.intersects_location(origins, directions, multiple_hits=True)
    distance = np.einsum("ij,ij->i", hits - origins[ray], directions[ray])
    radius = np.full(len(directions), np.nan)
    cosine = np.zeros(len(directions))
    order = np.lexsort((distance, ray))
    last = np.r_[ray[order][1:] != ray[order][:-1], True]
    outer = order[last]
    radius[ray[outer]] = distance[outer]
    cosine[ray[outer]] = np.abs(np.einsum("ij,ij->i", mesh.face_normals[face[outer]],
                                          directions[ray[outer]]))
    if np.isnan(radius).any():
        raise ValueError("some rays from the hub miss the MRI tongue: the hub is not inside it")
    return radius.reshape(t.shape), cosine.reshape(t.shape)


class RestShapeProblem:
    """The least-squares problem of the rest-shape fit (see the module docstring)."""

    def __init__(self, mri_vertices, mri_triangles, hub=HUB_MM):
        self.hub = np.asarray(hub, dtype=np.float64)
        self.radius, cosine = ray_radii(mri_vertices, mri_triangles, self.hub, FIT_THETA_DEG,
                                        FIT_PHI_DEG)
        phi = np.radians(FIT_PHI_DEG)
        obliquity = np.maximum(cosine, MIN_OBLIQUITY)
        weight = self.radius * np.sqrt(np.cos(phi)[None, :] * obliquity)
        self.weight = weight / np.sqrt(np.mean(weight**2))
        self.theta = np.radians(FIT_THETA_DEG)
        self.angles = np.radians([a for _n, _r, a, _w, _b in SAGITTAL_POINTS])
        self.free_blends = [k for k, p in enumerate(SAGITTAL_POINTS) if p[4] is None]
        count = len(SAGITTAL_POINTS)
        u = np.arange(FIT_STATIONS) / FIT_STATIONS
        self.station_basis = basis_matrix(periodic_knots(count, SAGITTAL_DEGREE), SAGITTAL_DEGREE,
                                          u, count=count)
        self.page_basis = basis_matrix(coronal_knots_deg(), CORONAL_DEGREE, FIT_PHI_DEG)
        self.pole_half_width0 = float(np.mean(ray_radii(mri_vertices, mri_triangles, self.hub,
                                                        [0.0], [-89.9, 89.9])[0]))

    # x = [radii (18), half ratios (3 x 5), free blends (13 x 3), pole half-width]
    def initial(self):
        mid = np.argmin(np.abs(FIT_PHI_DEG))
        radii = np.interp(self.angles, self.theta, self.radius[:, mid], period=2 * np.pi)
        pole = self.pole_half_width0
        ratio_profile = np.mean((self.radius - pole) / (self.radius[:, mid:mid + 1] - pole), axis=0)
        greville = coronal_control_angles_deg()[list(_SYMMETRIC_CONTROLS)]
        half = np.interp(greville, FIT_PHI_DEG, ratio_profile)
        blends = np.array([DEFAULT_SECTION_WEIGHTS[SAGITTAL_POINTS[k][0]]
                           for k in self.free_blends])
        return np.concatenate([radii, np.tile(half, len(SECTIONS)), blends.reshape(-1),
                               [self.pole_half_width0]])

    def bounds(self):
        n = len(SAGITTAL_POINTS)
        lower = np.concatenate([np.full(n, 5.0), np.full(_HALF * len(SECTIONS), -0.5),
                                np.zeros(3 * len(self.free_blends)), [5.0]])
        upper = np.concatenate([np.full(n, 90.0), np.full(_HALF * len(SECTIONS), 3.0),
                                np.ones(3 * len(self.free_blends)), [40.0]])
        return lower, upper

    def unpack(self, x):
        """(positions (18, 2), section weights (18, 3), ratios {section: (15,)},
        pole half-width)."""
        n = len(SAGITTAL_POINTS)
        radii = x[:n]
        positions = self.hub + radii[:, None] * np.stack([np.cos(self.angles),
                                                          np.sin(self.angles)], -1)
        halves = x[n:n + _HALF * len(SECTIONS)].reshape(len(SECTIONS), _HALF)
        ratios = {}
        for s, section in enumerate(SECTIONS):
            full = np.zeros(15)
            full[7] = 1.0
            for value, k in zip(halves[s], _SYMMETRIC_CONTROLS, strict=True):
                full[k] = full[14 - k] = value
            ratios[section] = full
        weights = np.array([p[4] if p[4] is not None else (0.0, 0.0, 0.0)
                            for p in SAGITTAL_POINTS], dtype=np.float64)
        free = x[n + _HALF * len(SECTIONS):-1].reshape(-1, 3) + 1e-9
        weights[self.free_blends] = free / free.sum(axis=1, keepdims=True)
        return positions, weights, ratios, float(x[-1])

    def rig_radii(self, x):
        """Rig radius on the fit's ray grid, (t, p) float64."""
        positions, weights, ratios, pole = self.unpack(x)
        stations = self.station_basis @ positions - self.hub
        radius = np.linalg.norm(stations, axis=1)
        theta = np.unwrap(np.arctan2(stations[:, 1], stations[:, 0]))
        blend = self.station_basis @ weights
        controls = pole + (radius[:, None] - pole) * (blend @ np.array([ratios[s]
                                                                       for s in SECTIONS]))
        controls[:, list(POLE_CONTROLS)] = pole
        radii = controls @ self.page_basis.T
        # Radii at the ray directions: linear in theta between stations, periodically.
        start = theta[0]
        span = theta - start
        target = (self.theta - start) % (2 * np.pi)
        extended = np.r_[span, span[0] + 2 * np.pi]
        rows = np.vstack([radii, radii[:1]])
        if np.any(np.diff(extended) <= 0):
            return None
        index = np.clip(np.searchsorted(extended, target, side="right"), 1, len(extended) - 1)
        w = (target - extended[index - 1]) / (extended[index] - extended[index - 1])
        return rows[index - 1] * (1 - w)[:, None] + rows[index] * w[:, None]

    def residuals(self, x):
        rig = self.rig_radii(x)
        if rig is None:  # pages out of order: a large, smooth-enough penalty
            rig = np.zeros_like(self.radius)
        misfit = ((rig - self.radius) * self.weight).reshape(-1)
        free = x[len(SAGITTAL_POINTS) + _HALF * len(SECTIONS):-1].reshape(-1, 3)
        prior = np.array([DEFAULT_SECTION_WEIGHTS[SAGITTAL_POINTS[k][0]]
                          for k in self.free_blends])
        scale = np.sqrt(misfit.size) * BLEND_PRIOR
        return np.concatenate([misfit, scale * (free - prior).reshape(-1)])

    def solve(self, max_nfev=200):
        lower, upper = self.bounds()
        x0 = np.clip(self.initial(), lower + 1e-9, upper - 1e-9)
        result = least_squares(self.residuals, x0, bounds=(lower, upper), x_scale="jac",
                               max_nfev=max_nfev, method="trf", tr_solver="lsmr")
        return result.x


def spread_samples(density, count, interior=False):
    """Positions in [0, 1) (or strictly inside (0, 1)) splitting a density into equal shares.

    density : (k,) float >= 0 sampled on a uniform grid of [0, 1). Returns (count,) float64.
    """
    cumulative = np.r_[0.0, np.cumsum(density)]
    cumulative /= cumulative[-1]
    grid = np.arange(len(cumulative)) / len(density)
    shares = np.arange(1, count + 1) / (count + 1) if interior else np.arange(count) / count
    return np.interp(shares, cumulative, grid)


def station_params(positions, count=STATIONS):
    """Stations along the closed sagittal curve, spread by arclength plus turning."""
    n = len(positions)
    u = np.arange(4096) / 4096
    curve = basis_matrix(periodic_knots(n, SAGITTAL_DEGREE), SAGITTAL_DEGREE, u, count=n) \
        @ positions
    step = np.roll(curve, -1, axis=0) - curve
    heading = np.arctan2(step[:, 1], step[:, 0])
    turning = np.abs(np.angle(np.exp(1j * (np.roll(heading, -1) - heading))))
    density = np.linalg.norm(step, axis=1) + TURNING_MM_PER_RAD * turning
    return spread_samples(density, count)


def page_angles_deg(radii_by_station, phi_deg, count=PAGE_SAMPLES):
    """Page angles between the poles, spread by the mean arclength plus turning of the pages.

    radii_by_station : (s, k) float, page radii of the rest shape at angles ``phi_deg`` (k,),
    a fine uniform grid over [-90, 90].
    """
    phi = np.radians(phi_deg)
    x = radii_by_station * np.cos(phi)
    z = radii_by_station * np.sin(phi)
    dx, dz = np.diff(x, axis=1), np.diff(z, axis=1)
    heading = np.unwrap(np.arctan2(dz, dx), axis=1)
    turning = np.abs(np.diff(heading, axis=1))
    length = np.hypot(dx, dz)
    density = length[:, :-1] + TURNING_MM_PER_RAD * turning
    density = density.mean(axis=0)
    shares = spread_samples(density, count, interior=True)
    angles = -90.0 + 180.0 * shares
    return 0.5 * (angles - angles[::-1])  # exactly mirror-symmetric, so is the rest shape
