"""Exact point-to-surface distances and Hausdorff distances between triangle meshes.

Closest point on a triangle: ``geometry.collision_exact.closest_points_on_triangles`` (Ericson,
Real-Time Collision Detection, 5.1.5, vectorised), the kernel the collision baseline uses.
Candidate triangles are pruned with a k-d tree over triangle centroids: a first pass over the
``FIRST_PASS`` nearest centroids gives an upper bound u on each point's distance; every triangle
that could be closer has its centroid within u + R of the point (R = its centroid-to-corner
reach), and a second pass checks all of those. Triangles are grouped by reach in powers of two,
one tree per group, so a few long slivers do not widen every search. The result is exact, not a
sampling estimate of the far surface. (``trimesh.proximity.closest_point`` was measured against
this on the maxilla, 20 000 points in its bounding box: it was slower and up to 1.4e-4 mm off
at points within 0.03 mm of the surface.)
"""

import numpy as np
from scipy.spatial import cKDTree

from glasshead.geometry.collision_exact import closest_points_on_triangles

#: Nearest triangle centroids examined in the first (upper bound) pass.
FIRST_PASS = 8
#: Surface samples per mm^2 for Hausdorff estimates (the maximum is over these samples and every
#: vertex; at 1 per mm^2 samples are about 1 mm apart).
SAMPLES_PER_MM2 = 1.0
#: Cap on samples drawn from one mesh, to bound the build's time.
MAX_SAMPLES = 40_000


class SurfaceDistance:
    """Distance queries to one triangle mesh: vertices (n, 3) float, faces (m, 3) int."""

    def __init__(self, vertices, faces):
        self.vertices = np.asarray(vertices, dtype=np.float64)
        self.faces = np.asarray(faces, dtype=np.int64)
        if self.faces.ndim != 2 or self.faces.shape[1] != 3 or len(self.faces) == 0:
            raise ValueError("faces must be a non-empty (m, 3) array")
        tri = self.vertices[self.faces]
        self.centroids = tri.mean(axis=1)
        reach = np.linalg.norm(tri - self.centroids[:, None], axis=2).max(axis=1)
        level = np.ceil(np.log2(np.maximum(reach, 1e-9))).astype(int)
        self.tree = cKDTree(self.centroids)
        self.groups = []  # (reach bound, face ids, tree over their centroids)
        for lv in np.unique(level):
            ids = np.flatnonzero(level == lv)
            self.groups.append((float(reach[ids].max()), ids, cKDTree(self.centroids[ids])))

    def _distance_to(self, points, face_ids):
        tri = self.vertices[self.faces[face_ids]]
        q = closest_points_on_triangles(points, tri[:, 0], tri[:, 1], tri[:, 2])
        return np.linalg.norm(points - q, axis=1)

    def distance(self, points):
        """Unsigned distance from each of points (k, 3) to the surface; (k,) float64."""
        points = np.asarray(points, dtype=np.float64)
        k = min(FIRST_PASS, len(self.faces))
        _, near = self.tree.query(points, k=k)
        near = near.reshape(len(points), k)
        rows = np.repeat(np.arange(len(points)), k)
        best = np.full(len(points), np.inf)
        np.minimum.at(best, rows, self._distance_to(points[rows], near.ravel()))
        bound = best.copy()
        for reach, face_ids, tree in self.groups:
            balls = tree.query_ball_point(points, bound + reach)
            counts = np.fromiter((len(b) for b in balls), dtype=np.int64, count=len(balls))
            rows = np.repeat(np.arange(len(points)), counts)
            ids = face_ids[np.fromiter((i for b in balls for i in b), dtype=np.int64,
                                       count=int(counts.sum()))]
            for start in range(0, len(rows), 1_000_000):  # bounded memory
                chunk = slice(start, start + 1_000_000)
                np.minimum.at(best, rows[chunk], self._distance_to(points[rows[chunk]], ids[chunk]))
        return best


def sample_surface(vertices, faces, seed=0):
    """Deterministic points on a surface: area-uniform samples, then every used vertex.

    Returns (points (k, 3) float64, face_of (k,) int64): the face each point lies on (for a
    vertex, one face that uses it), so callers can restrict a measure to a set of faces.
    """
    vertices = np.asarray(vertices, dtype=np.float64)
    faces = np.asarray(faces, dtype=np.int64)
    tri = vertices[faces]
    area = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    count = int(min(MAX_SAMPLES, max(1000, area.sum() * SAMPLES_PER_MM2)))
    rng = np.random.default_rng(seed)
    which = rng.choice(len(faces), size=count, p=area / area.sum())
    u, v = rng.random(count), rng.random(count)
    flip = u + v > 1
    u[flip], v[flip] = 1 - u[flip], 1 - v[flip]
    t = tri[which]
    points = t[:, 0] + (t[:, 1] - t[:, 0]) * u[:, None] + (t[:, 2] - t[:, 0]) * v[:, None]
    corner_face = np.repeat(np.arange(len(faces)), 3)
    used, first = np.unique(faces.ravel(), return_index=True)
    return np.vstack([points, vertices[used]]), np.concatenate([which, corner_face[first]])


class SampledSurface:
    """A mesh with its deterministic samples, for repeated directed distances and Hausdorff."""

    def __init__(self, vertices, faces):
        self.vertices = np.asarray(vertices, dtype=np.float64)
        self.faces = np.asarray(faces, dtype=np.int64)
        self.points, self.face_of = sample_surface(self.vertices, self.faces)
        self.query = SurfaceDistance(self.vertices, self.faces)


def hausdorff(a, b, a_mask=None, b_mask=None):
    """Symmetric Hausdorff distance between two ``SampledSurface`` meshes (their units).

    With masks ((m,) bool per face), only samples on the masked faces of each mesh are
    measured, against the whole other mesh. Returns (whole, masked or None) floats.
    """
    da = b.query.distance(a.points)
    db = a.query.distance(b.points)
    whole = float(max(da.max(), db.max()))
    if a_mask is None or b_mask is None:
        return whole, None
    masked = max(da[np.asarray(a_mask)[a.face_of]].max(initial=0.0),
                 db[np.asarray(b_mask)[b.face_of]].max(initial=0.0))
    return whole, float(masked)


def summarise(distances):
    """Mean, RMS, 95th percentile and maximum of (k,) distances, rounded to micrometres."""
    d = np.asarray(distances, dtype=np.float64)
    return {
        "mean_mm": round(float(d.mean()), 3),
        "rms_mm": round(float(np.sqrt(np.mean(d * d))), 3),
        "p95_mm": round(float(np.percentile(d, 95)), 3),
        "max_mm": round(float(d.max()), 3),
    }
