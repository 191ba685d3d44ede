"""Geometry in the mid-sagittal plane (z = 0): a mesh's section there, polylines resampled by
arclength, distances to polylines, and the 2D similarity that carries another model's or
instrument's mid-sagittal frame into the project's.

``Similarity2D`` maps p = s R(theta) q + t for (x, y) and z_project = -s z: the z sign takes a
right-handed frame with the project's x (anterior) and y (superior), whose z points to the
subject's right (VocalTractLab's), into the project's (anterior, superior, left) frame. For
points on the plane z = 0 it is a plain 2D similarity.
"""

import math

import numpy as np

#: mm: consecutive points of a polyline closer than this are one point (``resample``).
DUPLICATE_MM = 1e-9


def resample(polyline, step_mm) -> np.ndarray:
    """Evenly spaced points along an open polyline (k, d), both ends included, at most
    ``step_mm`` of arclength apart: (m, d) float64, m >= 2. Consecutive duplicate points are
    dropped first (they would stall ``np.interp``)."""
    points = np.asarray(polyline, dtype=np.float64)
    step = np.linalg.norm(np.diff(points, axis=0), axis=1)
    arc = np.concatenate([[0.0], np.cumsum(step)])
    count = max(2, int(math.ceil(arc[-1] / step_mm)) + 1)
    at = np.linspace(0.0, arc[-1], count)
    keep = np.concatenate([[True], step > DUPLICATE_MM])
    return np.stack([np.interp(at, arc[keep], points[keep, k]) for k in range(points.shape[1])],
                    axis=1)


def midline_section(vertices, faces) -> list[np.ndarray]:
    """The z = 0 section of a mesh as a list of (k, 2) polylines (mm)."""
    import trimesh  # here, not at the top: the server imports this module and needs no trimesh

    mesh = trimesh.Trimesh(vertices, faces, process=False)
    section = mesh.section(plane_origin=[0.0, 0.0, 0.0], plane_normal=[0.0, 0.0, 1.0])
    if section is None:
        raise ValueError("the mesh does not cross the mid-sagittal plane")
    return [np.asarray(section.vertices[entity.points])[:, :2] for entity in section.entities]


def point_to_polylines(points, polylines) -> np.ndarray:
    """Distance (k,) from (k, 2) points to the nearest segment of any of the polylines."""
    points = np.asarray(points, dtype=np.float64)
    a = np.vstack([p[:-1] for p in polylines])
    b = np.vstack([p[1:] for p in polylines])
    ab = b - a
    t = np.einsum("kmj,mj->km", points[:, None] - a[None], ab) / np.maximum(
        np.einsum("mj,mj->m", ab, ab), 1e-12)
    closest = a[None] + np.clip(t, 0.0, 1.0)[..., None] * ab[None]
    return np.linalg.norm(points[:, None] - closest, axis=2).min(axis=1)


class Similarity2D:
    """p = s R(theta) q + t in the mid-sagittal plane; z maps to -s z (module docstring)."""

    def __init__(self, scale, rotation, translation):
        self.scale = float(scale)
        self.rotation = np.asarray(rotation, dtype=np.float64)[:2, :2]
        self.translation = np.asarray(translation, dtype=np.float64)[:2]

    @property
    def angle_deg(self) -> float:
        return float(np.degrees(np.arctan2(self.rotation[1, 0], self.rotation[0, 0])))

    def apply(self, points) -> np.ndarray:
        """(k, 2) or (k, 3) source mm -> project mm."""
        points = np.asarray(points, dtype=np.float64)
        out = points.copy()
        out[:, :2] = self.scale * points[:, :2] @ self.rotation.T + self.translation
        if points.shape[1] == 3:
            out[:, 2] = -self.scale * points[:, 2]
        return out

    def matrix(self) -> np.ndarray:
        """The 4 x 4 homogeneous matrix of the 3D map."""
        m = np.eye(4)
        m[:2, :2] = self.scale * self.rotation
        m[2, 2] = -self.scale
        m[:2, 3] = self.translation
        return m

    def to_json(self) -> dict:
        return {"scale": round(self.scale, 6), "rotation_deg": round(self.angle_deg, 4),
                "translation_mm": [round(float(v), 4) for v in self.translation],
                "z": "z_project = -scale * z_vtl",
                "matrix_4x4": [[round(float(v), 6) for v in row] for row in self.matrix()]}


def two_point_similarity(src_a, src_b, dst_a, dst_b) -> tuple[float, np.ndarray, np.ndarray]:
    """(scale, rotation (2, 2), translation (2,)) of the 2D similarity taking src_a to dst_a
    and src_b to dst_b."""
    u, w = src_b - src_a, dst_b - dst_a
    scale = np.linalg.norm(w) / np.linalg.norm(u)
    angle = np.arctan2(w[1], w[0]) - np.arctan2(u[1], u[0])
    rot = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    return float(scale), rot, dst_a - scale * rot @ src_a


def palate_clearance(tongue_xy, palate_xy) -> np.ndarray:
    """Signed vertical clearance (mm) from each tongue point to the palate line above it:
    positive below the palate, negative through it; NaN where the palate line does not reach.
    Both (k, 2) in one frame; palate_xy ordered by x."""
    palate_xy = np.asarray(palate_xy, dtype=np.float64)
    order = np.argsort(palate_xy[:, 0])
    x, y = palate_xy[order, 0], palate_xy[order, 1]
    tongue_xy = np.asarray(tongue_xy, dtype=np.float64)
    above = np.interp(tongue_xy[:, 0], x, y, left=np.nan, right=np.nan)
    return above - tongue_xy[:, 1]
