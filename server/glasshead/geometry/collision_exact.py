"""Exact point and ray queries against triangles: the references the collision tables answer to.

- ``closest_points_on_triangles``: Ericson, Real-Time Collision Detection (2005), 5.1.5, "Closest
  point on triangle to point", by Voronoi regions of the vertices, edges and face; the project's
  one closest-point kernel (the build's surface distances use it too).
- ``closest_points_on_segments``: Ericson (2005), 5.1.2, "Closest point on line segment to
  point".
- ``ray_triangle_hits``: Moller and Trumbore (1997), "Fast, minimum storage ray-triangle
  intersection", two-sided: the kernel of ``geometry.ray_triangle`` over arrays of 3-vectors.
- ``first_hits_from_origin``: the exact answer to "does the segment from O to P cross the maxilla,
  and where first", brute force over all triangles, the definition of inside used by the tables.
- ``project_onto_closest``: the paper's slow exact correction (closest polygon, edge or vertex,
  penetration detected by the sign of a dot product with the surface normal).
"""

import numpy as np
import numpy.typing as npt

from glasshead.constants import COLLISION_TOL
from glasshead.geometry.ray_triangle import inside_triangle, ray_triangle

Floats = npt.NDArray[np.float64]

#: Squared sine of the angle at a below which a triangle counts as flat (a segment or a point):
#: the closest point is then taken on its edges, wrong by at most its width, 1e-6 of an edge.
FLAT_SIN2 = 1e-12


def _dot(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    return np.einsum("...i,...i->...", u, v)


def _flat(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """True where triangle (a, b, c) is flat: |ab x ac|^2 <= FLAT_SIN2 |ab|^2 |ac|^2, written
    with Lagrange's identity |ab x ac|^2 = |ab|^2 |ac|^2 - (ab . ac)^2."""
    ab, ac = b - a, c - a
    product = _dot(ab, ab) * _dot(ac, ac)
    return _dot(ab, ac) ** 2 >= (1.0 - FLAT_SIN2) * product


def closest_points_on_segments(p: npt.ArrayLike, a: npt.ArrayLike, b: npt.ArrayLike) -> Floats:
    """Closest points on segments (a, b) to points p, all (..., 3) broadcast together; a
    zero-length segment answers a. Returns (..., 3) float64."""
    p, a, b = np.broadcast_arrays(*(np.asarray(x, dtype=np.float64) for x in (p, a, b)))
    ab = b - a
    length2 = _dot(ab, ab)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(length2 > 0.0, _dot(p - a, ab) / length2, 0.0)
    return a + ab * np.clip(t, 0.0, 1.0)[..., None]


def closest_points_on_triangles(p: npt.ArrayLike, a: npt.ArrayLike, b: npt.ArrayLike,
                                c: npt.ArrayLike) -> Floats:
    """Closest points on triangles (a, b, c) to points p (Ericson 5.1.5), all broadcast together.

    p, a, b, c : (..., 3) float, mm or any one unit. Returns (..., 3) float64 in that unit.
    The one closest-point kernel of the project: the collision baseline, the liner and the
    build's surface distances (``geometry.surface_distance``) all call it. A degenerate triangle
    (its sine of the angle at a below 1e-6, see ``FLAT_SIN2``), where the Voronoi tests divide
    rounding noise, answers the closest point of its three edges instead.
    """
    a, b, c = (np.asarray(x, dtype=np.float64) for x in (a, b, c))
    flat = _flat(a, b, c)  # before broadcasting: once per triangle, not per point and triangle
    p, a, b, c = np.broadcast_arrays(np.asarray(p, dtype=np.float64), a, b, c)
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = _dot(ab, ap), _dot(ac, ap)
    bp = p - b
    d3, d4 = _dot(ab, bp), _dot(ac, bp)
    cp = p - c
    d5, d6 = _dot(ab, cp), _dot(ac, cp)
    va = d3 * d6 - d5 * d4
    vb = d5 * d2 - d1 * d6
    vc = d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = va + vb + vc
        v_face, w_face = vb / denom, vc / denom
        t_ab = d1 / (d1 - d3)
        t_ac = d2 / (d2 - d6)
        t_bc = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        out = a + ab * v_face[..., None] + ac * w_face[..., None]
        # Regions are tested from last to first so that the first matching region wins.
        regions = [
            ((va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0), b + (c - b) * t_bc[..., None]),
            ((vb <= 0) & (d2 >= 0) & (d6 <= 0), a + ac * t_ac[..., None]),
            ((d6 >= 0) & (d5 <= d6), c),
            ((vc <= 0) & (d1 >= 0) & (d3 <= 0), a + ab * t_ab[..., None]),
            ((d3 >= 0) & (d4 <= d3), b),
            ((d1 <= 0) & (d2 <= 0), a),
        ]
    for mask, point in regions:
        out = np.where(mask[..., None], point, out)
    undecided = np.broadcast_to(flat, out.shape[:-1]) | ~np.all(np.isfinite(out), axis=-1)
    if np.any(undecided):
        q = p[undecided]
        starts, ends = np.stack([a, b, c])[:, undecided], np.stack([b, c, a])[:, undecided]
        edges = closest_points_on_segments(q[None], starts, ends)
        nearest = np.argmin(_dot(edges - q[None], edges - q[None]), axis=0)
        out[undecided] = edges[nearest, np.arange(len(q))]
    return out


def ray_triangle_hits(direction: npt.ArrayLike, a: npt.ArrayLike, e1: npt.ArrayLike,
                      e2: npt.ArrayLike, origin: npt.ArrayLike | None = None) -> Floats:
    """Two-sided Moller-Trumbore hits of rays ``origin + t * direction`` with triangles: the one
    kernel (``geometry.ray_triangle``) over arrays of 3-vectors.

    direction, a, e1, e2 : (..., 3) float, broadcast together; e1 = b - a, e2 = c - a.
    origin : (..., 3) float or None for the zero vector.
    Returns t, (...,) float64: the ray parameter of the hit, +inf where the ray misses (parallel
    rays miss). Barycentric tests are widened by ``COLLISION_TOL.barycentric`` so that a ray
    through an edge shared by two triangles cannot slip between them.

    The kernel is given the components in the order x, z, y. That order is a reflection, which
    only flips the determinant's sign (u, v and t are unchanged), and its dot products then sum
    (x + z) + y, the order of the einsum this function summed with before: the liner's tables
    keep their bits.
    """
    direction = np.asarray(direction, dtype=np.float64)
    a, e1, e2 = (np.asarray(x, dtype=np.float64) for x in (a, e1, e2))
    s = -a if origin is None else np.asarray(origin, dtype=np.float64) - a
    x, z, y = 0, 2, 1
    det, u, v, t = ray_triangle(s[..., x], s[..., z], s[..., y],
                                direction[..., x], direction[..., z], direction[..., y],
                                e1[..., x], e1[..., z], e1[..., y],
                                e2[..., x], e2[..., z], e2[..., y])
    with np.errstate(invalid="ignore"):  # u + v is nan where det == 0, a miss either way
        hit = inside_triangle(det, u, v, COLLISION_TOL.barycentric) & (t > 0.0)
    return np.where(hit, t, np.inf)


def first_hits_from_origin(points: npt.ArrayLike, origin: npt.ArrayLike, vertices: npt.ArrayLike,
                           faces: npt.ArrayLike, chunk: int = 256) -> tuple[Floats, Floats]:
    """Exact first crossing of each segment O -> P with a triangle mesh, brute force.

    points : (n, 3) float; origin : (3,) float; vertices : (v, 3) float; faces : (m, 3) int.
    Returns (t, radius): t (n,) float64 is the segment parameter of the first crossing (hit point
    O + t (P - O)), +inf when the ray from O through P hits nothing at all; radius (n,) float64
    is the distance from O to that first hit along the ray (+inf when none). P is inside the
    maxilla exactly when t < 1.
    """
    points = np.asarray(points, dtype=np.float64)
    if points.ndim != 2 or points.shape[1] != 3:
        raise ValueError(f"points must have shape (n, 3), got {points.shape}")
    origin = np.asarray(origin, dtype=np.float64).reshape(3)
    tri = np.asarray(vertices, dtype=np.float64)[np.asarray(faces)] - origin
    a, e1, e2 = tri[:, 0], tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    rel = points - origin
    t = np.full(len(points), np.inf)
    for start in range(0, len(points), chunk):
        d = rel[start:start + chunk, None, :]
        t[start:start + chunk] = ray_triangle_hits(d, a[None], e1[None], e2[None]).min(axis=1)
    with np.errstate(invalid="ignore"):
        radius = t * np.linalg.norm(rel, axis=1)
    radius[~np.isfinite(t)] = np.inf
    return t, radius


def project_onto_closest(points: npt.ArrayLike, vertices: npt.ArrayLike, faces: npt.ArrayLike,
                         chunk: int = 128) -> tuple[Floats, npt.NDArray[np.bool_]]:
    """The paper's exact slow correction: project penetrating points onto the closest triangle.

    For each point the closest point on the mesh (closest triangle, edge or vertex, Ericson
    5.1.5) is found by brute force; the point is penetrating when it lies behind that triangle,
    i.e. (P - closest) . normal < 0 with normals facing the oral cavity, and is then moved to the
    closest point. points (n, 3), vertices (v, 3), faces (m, 3).
    Returns (corrected (n, 3) float64, moved (n,) bool).
    """
    points = np.asarray(points, dtype=np.float64)
    tri = np.asarray(vertices, dtype=np.float64)[np.asarray(faces)]
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    corrected = points.copy()
    moved = np.zeros(len(points), dtype=bool)
    for start in range(0, len(points), chunk):
        p = points[start:start + chunk, None, :]
        closest = closest_points_on_triangles(p, tri[None, :, 0], tri[None, :, 1], tri[None, :, 2])
        dist2 = ((closest - p) ** 2).sum(axis=2)
        nearest = np.argmin(dist2, axis=1)
        rows = np.arange(len(nearest))
        q = closest[rows, nearest]
        behind = _dot(points[start:start + chunk] - q, normals[nearest]) < 0.0
        corrected[start:start + chunk][behind] = q[behind]
        moved[start:start + chunk] = behind
    return corrected, moved
