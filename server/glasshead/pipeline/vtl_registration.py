"""Registration of VocalTractLab's hard palate and upper incisor onto the project's maxilla.

VTL's frame (mm after ``pipeline.vtl_speaker``) has the project's x (anterior) and y (superior)
but its own origin, its own head tilt and a different speaker's size, so the map is a 2D
similarity in the mid-sagittal plane (``geometry.midsagittal.Similarity2D``):
p = s R(theta) q + t for (x, y), and z_project = -s z_vtl. The z sign takes VTL's axes as
right-handed (z = x cross y, the subject's right) into the project's (anterior, superior, left)
frame; VTL's model is left-right symmetric, so only triangle winding depends on it.

Source: VTL's midline of the hard palate and the incisor's lingual face and edge
(``vtl_speaker.palate_geometry()["registration_outline"]``). Target: the mid-sagittal section
of the project's maxilla (palatal vault and upper incisor). The fit is the build's trimmed
similarity ICP (``geometry.register_cbct.icp``, Umeyama's closed form, worst 20 % of pairs
ignored per iteration) run on points of the z = 0 plane, so its rotation stays about z. It
starts from the two ends: the back of VTL's hard palate onto the back of the maxilla's midline
and VTL's incisal edge onto the maxilla's lowest midline point.
"""

import numpy as np
from scipy.spatial import cKDTree

from glasshead.geometry.midsagittal import (
    Similarity2D,
    point_to_polylines,
    resample,
    two_point_similarity,
)
from glasshead.geometry.register_cbct import FINE_ITERATIONS, TRIM, icp
from glasshead.geometry.surface_distance import SurfaceDistance, sample_surface, summarise

#: Spacing (mm) of the points the outlines are resampled to.
STEP_MM = 0.25
#: VTL's axes into the project's: z is mirrored (see the module docstring).
VTL_TO_PROJECT_AXES = np.diag([1.0, 1.0, -1.0])


def _planar(points2):
    return np.column_stack([points2, np.zeros(len(points2))])


def register_palate(vtl_outline, maxilla_section, iterations=FINE_ITERATIONS):
    """Fit VTL's registration outline (k, 2) onto the maxilla's midline polylines.

    Returns (Similarity2D, report): the report has the start, the ICP's trimmed RMS and the
    untrimmed distances of the whole moved outline to the section (mean, RMS, p95, max, mm).
    """
    source = resample(vtl_outline, STEP_MM)
    target = np.vstack([resample(p, STEP_MM) for p in maxilla_section])
    # Start: back of the hard palate to back of the section, incisal edge to its lowest point.
    edge = np.asarray(vtl_outline)[-2:].mean(axis=0)
    scale, rot, shift = two_point_similarity(np.asarray(vtl_outline[0]), edge,
                                             target[np.argmin(target[:, 0])],
                                             target[np.argmin(target[:, 1])])
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

