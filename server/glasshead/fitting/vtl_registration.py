"""Registration of VocalTractLab's hard palate and upper incisor onto the project's maxilla.

VTL's frame (mm after ``fitting.vtl``) has the project's x (anterior) and y (superior) but its
own origin, its own head tilt and a different speaker's size, so the map is a 2D similarity in
the mid-sagittal plane: p = s R(theta) q + t for (x, y), and z_project = -s z_vtl. The z sign
takes VTL's axes as right-handed (z = x cross y, the subject's right) into the project's
(anterior, superior, left) frame; VTL's model is left-right symmetric, so only triangle winding
depends on it.

Source: VTL's midline of the hard palate and the incisor's lingual face and edge
(``vtl.palate_geometry()["registration_outline"]``). Target: the mid-sagittal section of the
project's maxilla (palatal vault and upper incisor). The fit is the build's trimmed similarity
ICP (``geometry.register_cbct.icp``, Umeyama's closed form, worst 20 % of pairs ignored per
iteration) run on points of the z = 0 plane, so its rotation stays about z. It starts from the
two ends: the back of VTL's hard palate onto the back of the maxilla's midline and VTL's incisal
edge onto the maxilla's lowest midline point.
"""

import numpy as np
import trimesh
from scipy.spatial import cKDTree

from glasshead.geometry.register_cbct import FINE_ITERATIONS, TRIM, icp
from glasshead.geometry.surface_distance import SurfaceDistance, sample_surface, summarise

#: Spacing (mm) of the points the outlines are resampled to.
STEP_MM = 0.25
#: VTL's axes into the project's: z is mirrored (see the module docstring).
VTL_TO_PROJECT_AXES = np.diag([1.0, 1.0, -1.0])


def resample(polyline, step=STEP_MM):
    """Points every ``step`` mm along a (k, 2) or (k, 3) polyline, both ends included."""
    polyline = np.asarray(polyline, dtype=np.float64)
    lengths = np.linalg.norm(np.diff(polyline, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(lengths)])
    at = np.linspace(0.0, s[-1], max(2, int(np.ceil(s[-1] / step)) + 1))
    return np.stack([np.interp(at, s, polyline[:, k]) for k in range(polyline.shape[1])], axis=1)


def midline_section(vertices, faces):
    """The z = 0 section of a mesh as a list of (k, 2) polylines (mm)."""
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    section = mesh.section(plane_origin=[0.0, 0.0, 0.0], plane_normal=[0.0, 0.0, 1.0])
    if section is None:
        raise ValueError("the mesh does not cross the mid-sagittal plane")
    return [np.asarray(section.vertices[entity.points])[:, :2] for entity in section.entities]


def point_to_polylines(points, polylines):
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
    """p = s R(theta) q + t in the mid-sagittal plane; z maps to -s z."""

    def __init__(self, scale, rotation, translation):
        self.scale = float(scale)
        self.rotation = np.asarray(rotation, dtype=np.float64)[:2, :2]
        self.translation = np.asarray(translation, dtype=np.float64)[:2]

    @property
    def angle_deg(self):
        return float(np.degrees(np.arctan2(self.rotation[1, 0], self.rotation[0, 0])))

    def apply(self, points):
        """(k, 2) or (k, 3) VTL mm -> project mm."""
        points = np.asarray(points, dtype=np.float64)
        out = points.copy()
        out[:, :2] = self.scale * points[:, :2] @ self.rotation.T + self.translation
        if points.shape[1] == 3:
            out[:, 2] = -self.scale * points[:, 2]
        return out

    def matrix(self):
        """The 4 x 4 homogeneous matrix of the 3D map."""
        m = np.eye(4)
        m[:2, :2] = self.scale * self.rotation
        m[2, 2] = -self.scale
        m[:2, 3] = self.translation
        return m

    def to_json(self):
        return {"scale": round(self.scale, 6), "rotation_deg": round(self.angle_deg, 4),
                "translation_mm": [round(float(v), 4) for v in self.translation],
                "z": "z_project = -scale * z_vtl",
                "matrix_4x4": [[round(float(v), 6) for v in row] for row in self.matrix()]}


def _two_point(src_a, src_b, dst_a, dst_b):
    """The 2D similarity taking src_a to dst_a and src_b to dst_b."""
    u, w = src_b - src_a, dst_b - dst_a
    scale = np.linalg.norm(w) / np.linalg.norm(u)
    angle = np.arctan2(w[1], w[0]) - np.arctan2(u[1], u[0])
    rot = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    return scale, rot, dst_a - scale * rot @ src_a


def _planar(points2):
    return np.column_stack([points2, np.zeros(len(points2))])


def register_palate(vtl_outline, maxilla_section, iterations=FINE_ITERATIONS):
    """Fit VTL's registration outline (k, 2) onto the maxilla's midline polylines.

    Returns (Similarity2D, report): the report has the start, the ICP's trimmed RMS and the
    untrimmed distances of the whole moved outline to the section (mean, RMS, p95, max, mm).
    """
    source = resample(vtl_outline)
    target = np.vstack([resample(p) for p in maxilla_section])
    # Start: back of the hard palate to back of the section, incisal edge to its lowest point.
    edge = np.asarray(vtl_outline)[-2:].mean(axis=0)
    scale, rot, shift = _two_point(np.asarray(vtl_outline[0]), edge,
                                   target[np.argmin(target[:, 0])], target[np.argmin(target[:, 1])])
    start = (scale, _embed(rot), np.append(shift, 0.0))
    target3 = _planar(target)
    scale, rot3, shift3, trimmed = icp(_planar(source), cKDTree(target3), target3, iterations,
                                       start)
    if rot3[2, 2] < 0.999999:  # planar data must give a rotation about z
        raise RuntimeError("the palate registration left the mid-sagittal plane")
    transform = Similarity2D(scale, rot3, shift3)
    moved = transform.apply(source)
    report = {
        "method": "trimmed similarity ICP (geometry.register_cbct.icp) in the z = 0 plane",
        "trim_fraction": TRIM,
        "iterations": iterations,
        "source_points": len(source),
        "icp_trimmed_rms_mm": round(float(trimmed), 3),
        "midline": summarise(point_to_polylines(moved, maxilla_section)),
    }
    return transform, report


def _embed(rot2):
    rot = np.eye(3)
    rot[:2, :2] = rot2
    return rot


def surface_residual(transform, surfaces, vertices, faces):
    """Distances from VTL surfaces [(vertices, triangles), ...] moved into the project frame to
    the mesh (vertices, faces): summarise() of area-uniform samples and vertices, mm."""
    query = SurfaceDistance(vertices, faces)
    samples = [sample_surface(transform.apply(v), t, seed=5)[0] for v, t in surfaces]
    return summarise(query.distance(np.vstack(samples)))


def palate_clearance(tongue_xy, palate_xy):
    """Signed vertical clearance (mm) from each tongue point to the palate line above it:
    positive below the palate, negative through it; NaN where the palate line does not reach.
    Both (k, 2) in one frame; palate_xy ordered by x."""
    palate_xy = np.asarray(palate_xy, dtype=np.float64)
    order = np.argsort(palate_xy[:, 0])
    x, y = palate_xy[order, 0], palate_xy[order, 1]
    tongue_xy = np.asarray(tongue_xy, dtype=np.float64)
    above = np.interp(tongue_xy[:, 0], x, y, left=np.nan, right=np.nan)
    return above - tongue_xy[:, 1]
