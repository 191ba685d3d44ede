"""The jaw pose: opening as a rotation about the temporomandibular axis plus a forward slide.

Twin of ``web/src/core/jaw.js``. The mandible rotates about a z-parallel axis through the
condyles (the top-back of the ramus) and its condyles slide forward and down along the articular
eminence as it opens; up to about 25 degrees a slide that grows linearly with the angle is a fair
model. The rig's ``jaw_opening`` runs 0 to 10 degrees, what speech uses (docs/face-rig.md); the
shared vectors try this kernel over the model's whole 0 to 25.

The pose is a (3, 4) float64 matrix [R | t] acting on project-frame points (mm):
``p' = R p + t`` with ``R`` the rotation by -opening about +z (the chin, at +x, goes down) and
``t = pivot - R pivot + opening * translation_per_degree``.

Things that ride on the jaw partly (the tongue) blend each point toward its posed position by a
weight: ``p + w * (pose(p) - p)``; weight 1 rides fully, 0 stays.
"""

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
import numpy.typing as npt

#: Height of the band at the top of each condyle whose centre is taken as the pivot, mm.
CONDYLE_BAND_MM = 5.0
#: Forward and downward slide of the condyles along the articular eminence per degree of opening,
#: mm / deg: about 12 mm forward at 25 degrees, as the condyles of a wide-open jaw travel.
TRANSLATION_PER_DEGREE = (0.5, -0.15)


def jaw_definition(pivot, translation_per_degree=TRANSLATION_PER_DEGREE, parameter="jaw_opening",
                   source=None):
    """The jaw block of the rig definition (JSON-ready)."""
    pivot = np.asarray(pivot, dtype=np.float64).reshape(-1)
    if pivot.size != 2 or not np.all(np.isfinite(pivot)):
        raise ValueError("pivot must be 2 finite numbers (x, y), mm")
    return {
        "parameter": parameter,
        "pivot": [float(pivot[0]), float(pivot[1])],
        "axis": [0.0, 0.0, 1.0],
        "translation_per_degree": [float(t) for t in translation_per_degree],
        "rotation": "opening by a degrees rotates by -a degrees about +z through the pivot "
                    "(chin down), then translates by a * translation_per_degree",
        "source": source or {},
    }


def jaw_pose(opening_deg: float, jaw: Mapping[str, Any]) -> npt.NDArray[np.float64]:
    """(3, 4) float64 pose [R | t] for an opening in degrees and a jaw block."""
    opening = float(opening_deg)
    if not math.isfinite(opening):
        raise ValueError(f"jaw opening must be finite, got {opening_deg!r}")
    angle = -math.radians(opening)
    c, s = math.cos(angle), math.sin(angle)
    px, py = jaw["pivot"]
    tx, ty = jaw["translation_per_degree"]
    pose = np.zeros((3, 4))
    pose[0, 0], pose[0, 1], pose[1, 0], pose[1, 1], pose[2, 2] = c, -s, s, c, 1.0
    pose[0, 3] = px - (c * px - s * py) + opening * tx
    pose[1, 3] = py - (s * px + c * py) + opening * ty
    return pose


def apply_jaw_pose(points: npt.ArrayLike, pose: npt.ArrayLike,
                   weights: npt.ArrayLike | None = None) -> npt.NDArray[np.float64]:
    """Move points with the jaw, each by its weight.

    points : (n, 2) or (n, 3) float, mm (2-column points are in the mid-sagittal plane).
    pose : (3, 4) float from ``jaw_pose``. weights : (n,) float or None (all 1).
    Returns float64 of the same shape.
    """
    p = np.asarray(points, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] not in (2, 3):
        raise ValueError(f"points must be (n, 2) or (n, 3), got {p.shape}")
    matrix = np.asarray(pose, dtype=np.float64)
    if matrix.shape != (3, 4):
        raise ValueError(f"pose must be (3, 4), got {matrix.shape}")
    dims = p.shape[1]
    moved = p @ matrix[:dims, :dims].T + matrix[:dims, 3]
    if weights is None:
        return moved
    w = np.asarray(weights, dtype=np.float64).reshape(-1, 1)
    if w.shape[0] != p.shape[0]:
        raise ValueError("weights must have one value per point")
    return p + w * (moved - p)


def estimate_condyle(jaw_vertices: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Pivot (x, y), mm, of the temporomandibular axis from a mandible mesh in the project frame.

    jaw_vertices : (n, 3) float, mm. The condyles are the highest points of the back half of the
    mandible (the coronoid processes, in front of them, are lower); the pivot is the mean of the
    vertices in the top ``CONDYLE_BAND_MM`` of that back half. The axis is z-parallel, so the two
    condyles (mirror images) give one (x, y).
    """
    v = np.asarray(jaw_vertices, dtype=np.float64)
    if v.ndim != 2 or v.shape[1] != 3 or len(v) < 4:
        raise ValueError("jaw_vertices must be (n, 3) with n >= 4")
    back = v[v[:, 0] < 0.5 * (v[:, 0].min() + v[:, 0].max())]
    if back.size == 0:
        raise ValueError("the mandible has no back half")
    band = back[back[:, 1] > back[:, 1].max() - CONDYLE_BAND_MM]
    return band[:, :2].mean(axis=0)
