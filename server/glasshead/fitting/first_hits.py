"""First hits of rays from one origin with a triangle mesh: what they are (``FirstHits``) and
their definition, the exhaustive search (``exhaustive_first_hits``).

For ray i, origin O and direction d_i, every triangle is tested with the project's two-sided
Moller-Trumbore kernel (``geometry.ray_triangle``, op by op) in origin-relative coordinates
(s = O - a computed as -(a - O), e1 = b - a, e2 = c - a from the shifted vertices), with the
barycentric slack ``COLLISION_TOL.barycentric`` and t > 0; the first hit is the smallest
(t, triangle index). ``fitting.ray_walk.RayWalker`` returns exactly that triangle and that t,
faster.
"""

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from glasshead.constants import COLLISION_TOL
from glasshead.geometry.ray_triangle import inside_triangle, ray_triangle

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]

SLACK = COLLISION_TOL.barycentric


@dataclass
class FirstHits:
    """Per ray: ``triangle`` (k,) int64 (-1: no hit), ``t`` (k,) the ray parameter (inf: none),
    ``point`` (k, 3) O + t d (nan: none), ``fallback`` (k,) bool rays whose walk found no hit and
    were searched without a bound, ``overturned`` (k,) bool rays where a nearer triangle than the
    walk's was found (a fold in front of it, or a tie on an edge), ``shortcut`` (k,) bool rays
    answered by the crossing count (no sphere search), ``back_facing`` |B|, the triangles that
    do not face away from O in this pose, and ``volume`` the signed volume enclosed by the mesh
    in this pose, mm^3 (the sum of det[a - O, b - O, c - O] / 6, which the certificate computes
    anyway; a closed mesh's is the same from any O)."""

    triangle: Ints
    t: Floats
    point: Floats
    fallback: npt.NDArray[np.bool_]
    overturned: npt.NDArray[np.bool_]
    shortcut: npt.NDArray[np.bool_]
    back_facing: int
    volume: float


def check_rays(origin: npt.ArrayLike, directions: npt.ArrayLike) -> tuple[Floats, Floats]:
    """(origin (3,), directions (k, 3)) as float64, or ValueError with what is wrong."""
    o = np.asarray(origin, dtype=np.float64)
    d = np.asarray(directions, dtype=np.float64)
    if o.shape != (3,):
        raise ValueError(f"origin must have shape (3,), got {o.shape}")
    if d.ndim != 2 or d.shape[1] != 3:
        raise ValueError(f"directions must have shape (k, 3), got {d.shape}")
    if not np.all(np.isfinite(o)):
        raise ValueError("origin must be finite")
    bad = ~np.all(np.isfinite(d), axis=1)
    if np.any(bad):
        raise ValueError(f"directions must be finite: {int(bad.sum())} rays have NaN or inf "
                         f"(first: ray {int(np.flatnonzero(bad)[0])})")
    zero = ~np.any(d != 0.0, axis=1)
    if np.any(zero):
        raise ValueError(f"directions must be non-zero: {int(zero.sum())} rays have length 0 "
                         f"(first: ray {int(np.flatnonzero(zero)[0])})")
    return o, d


def points(o: Floats, d: Floats, t: Floats) -> Floats:
    with np.errstate(invalid="ignore"):
        p = o + t[:, None] * d
    p[~np.isfinite(t)] = np.nan
    return p


def exhaustive_first_hits(origin: npt.ArrayLike, directions: npt.ArrayLike,
                          vertices: npt.ArrayLike, triangles: npt.ArrayLike,
                          chunk: int = 64) -> tuple[Ints, Floats]:
    """The reference: (triangle (k,) int64, -1 for none; t (k,) float64, inf for none) of the
    first hit of each ray O + t d with every triangle, by the smallest (t, index)."""
    o, d = check_rays(origin, directions)
    tri = np.asarray(triangles, dtype=np.int64)
    corners = (np.asarray(vertices, dtype=np.float64) - o)[tri]
    a = corners[:, 0]
    e1, e2 = corners[:, 1] - a, corners[:, 2] - a
    s = -a
    triangle = np.full(len(d), -1, dtype=np.int64)
    best = np.full(len(d), np.inf)
    for lo in range(0, len(d), chunk):
        dd = d[lo:lo + chunk, None, :]
        det, u, v, t = ray_triangle(s[:, 0], s[:, 1], s[:, 2], dd[..., 0], dd[..., 1], dd[..., 2],
                                    e1[:, 0], e1[:, 1], e1[:, 2], e2[:, 0], e2[:, 1], e2[:, 2])
        t = np.where(inside_triangle(det, u, v, SLACK) & (t > 0.0), t, np.inf)
        idx = np.argmin(t, axis=1)  # the first of equal minima: the smallest index
        tt = t[np.arange(len(idx)), idx]
        hit = np.isfinite(tt)
        triangle[lo:lo + chunk] = np.where(hit, idx, -1)
        best[lo:lo + chunk] = tt
    return triangle, best
