"""Conversion of source meshes into the project frame (see ``glasshead.constants``)."""

import numpy as np

from glasshead.constants import BADIN_ORIGIN_M, BADIN_TO_PROJECT_AXES, M_TO_MM


def badin_to_project(points_m):
    """Map Badin points to the project frame.

    points_m : (n, 3) float, metres, Badin axes (x posterior, y right, z up).
    Returns (n, 3) float64 in millimetres, project axes.
    """
    points = np.asarray(points_m, dtype=np.float64)
    if points.ndim != 2 or points.shape[1] != 3:
        raise ValueError(f"points must have shape (n, 3), got {points.shape}")
    return (points - BADIN_ORIGIN_M) @ BADIN_TO_PROJECT_AXES.T * M_TO_MM


def flips_handedness(axes):
    """True when the 3x3 axis map ``axes`` is a reflection, so triangle winding must flip."""
    return bool(np.linalg.det(np.asarray(axes, dtype=np.float64)) < 0)


def fix_winding(faces, axes):
    """Reverse the winding of (m, 3) int ``faces`` when ``axes`` mirrors space."""
    faces = np.asarray(faces)
    return faces[:, ::-1].copy() if flips_handedness(axes) else faces.copy()
