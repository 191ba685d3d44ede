"""Registration of the cone-beam CT maxilla (another subject, mm, its own axes) onto the Badin one.

1. Axes. Both scans are taken to be right-handed, so the CBCT's axes map onto Badin's by one of
   the 24 proper rotations that permute axes and flip signs in pairs (det +1). Each candidate is
   applied (mm -> m), the result converted to the project frame like any Badin point (which adds
   the project's reflection), centred on the Badin maxilla, and refined by a short ICP; the
   candidate with the lowest trimmed residual wins.
2. Similarity ICP (Besl and McKay 1992, with the closed-form similarity of Umeyama 1991):
   Badin maxilla samples are matched to their nearest points on the CBCT surface; the worst
   ``TRIM`` fraction of pairs is ignored each iteration, because the CBCT also holds bone the
   Badin mesh lacks (zygomatic arches, nasal floor), and a scale, rotation and translation are
   solved. Badin is the source since it is the smaller surface: every Badin point has a true
   partner on the CBCT, not the reverse.
3. The CBCT is moved by the inverse transform, so it lies in the project frame on the Badin
   maxilla; its winding is flipped once, for the reflection in step 1.
"""

import itertools

import numpy as np
from scipy.spatial import cKDTree

from glasshead.constants import BADIN_TO_PROJECT_AXES
from glasshead.geometry.frame import badin_to_project, fix_winding
from glasshead.geometry.surface_distance import SurfaceDistance, sample_surface, summarise

#: Fraction of worst pairs ignored in each ICP iteration.
TRIM = 0.2
#: ICP iterations for each axis candidate, and for the final refinement.
COARSE_ITERATIONS, FINE_ITERATIONS = 15, 60
#: Source points used for the coarse and the fine ICP.
COARSE_POINTS, FINE_POINTS = 1500, 6000


def proper_axis_rotations():
    """The 24 signed permutation matrices with determinant +1; (24, 3, 3) float64."""
    out = []
    for perm in itertools.permutations(range(3)):
        for signs in itertools.product((1.0, -1.0), repeat=3):
            m = np.zeros((3, 3))
            m[np.arange(3), perm] = signs
            if np.linalg.det(m) > 0:
                out.append(m)
    return np.array(out)


def similarity(src, dst):
    """Least-squares s, R, t with dst ~ s R src + t (Umeyama 1991); R proper. (k, 3) arrays."""
    mu_s, mu_d = src.mean(axis=0), dst.mean(axis=0)
    a, b = src - mu_s, dst - mu_d
    u, sig, vt = np.linalg.svd(b.T @ a / len(src))
    d = np.diag([1.0, 1.0, np.sign(np.linalg.det(u @ vt))])
    rot = u @ d @ vt
    scale = np.trace(np.diag(sig) @ d) / np.mean(np.sum(a * a, axis=1))
    return scale, rot, mu_d - scale * rot @ mu_s


def icp(src, target_tree, target_points, iterations, start=None, trim=TRIM):
    """Trimmed similarity ICP of src (k, 3) onto target points, the worst ``trim`` fraction of
    pairs left out each iteration; returns (s, R, t, trimmed rms)."""
    scale, rot, shift = start if start is not None else (1.0, np.eye(3), np.zeros(3))
    rms = np.inf
    for _ in range(iterations):
        moved = scale * src @ rot.T + shift
        dist, idx = target_tree.query(moved)
        keep = dist <= np.quantile(dist, 1.0 - trim)
        rms = float(np.sqrt(np.mean(dist[keep] ** 2)))
        scale, rot, shift = similarity(src[keep], target_points[idx[keep]])
    return scale, rot, shift, rms


def register_cbct(cbct_vertices_mm, cbct_faces, badin_vertices, badin_faces):
    """Place the CBCT maxilla on the Badin maxilla (project frame).

    cbct_vertices_mm (n, 3) float, its own axes; cbct_faces (m, 3) int.
    badin_vertices (k, 3) float, project frame mm; badin_faces (l, 3) int.
    Returns (vertices (n, 3) float64 project mm, faces (m, 3) int64, report dict).
    """
    cbct = np.asarray(cbct_vertices_mm, dtype=np.float64)
    badin_points, _ = sample_surface(badin_vertices, badin_faces, seed=1)
    rng = np.random.default_rng(2)
    chosen = rng.choice(len(badin_points), min(FINE_POINTS, len(badin_points)), replace=False)
    fine_src = badin_points[chosen]
    coarse_src = fine_src[:COARSE_POINTS]

    trials = []
    for axes in proper_axis_rotations():
        placed = badin_to_project(cbct @ axes.T / 1000.0)
        placed += badin_points.mean(axis=0) - placed.mean(axis=0)
        target_points, _ = sample_surface(placed, cbct_faces, seed=3)
        tree = cKDTree(target_points)
        fit = icp(coarse_src, tree, target_points, COARSE_ITERATIONS)
        trials.append((fit[3], axes, placed, target_points, tree, fit))
    trials.sort(key=lambda trial: trial[0])
    _, axes, placed, target_points, tree, coarse = trials[0]
    scale, rot, shift, rms = icp(fine_src, tree, target_points, FINE_ITERATIONS, coarse[:3])

    # Inverse similarity: Badin ~ (CBCT - t) R / s.
    vertices = (placed - shift) @ rot / scale
    faces = fix_winding(np.asarray(cbct_faces, dtype=np.int64), BADIN_TO_PROJECT_AXES)
    to_cbct = SurfaceDistance(vertices, faces).distance(badin_points)
    cbct_points, _ = sample_surface(vertices, faces, seed=4)
    to_badin = SurfaceDistance(badin_vertices, badin_faces).distance(cbct_points)
    report = {
        "axes_cbct_to_badin": axes.astype(int).tolist(),
        "runner_up_trimmed_rms_mm": round(trials[1][0], 3),
        "scale": round(float(1.0 / scale), 5),
        "icp_trimmed_rms_mm": round(rms, 3),
        "trim_fraction": TRIM,
        "badin_to_cbct": summarise(to_cbct),
        "cbct_to_badin": summarise(to_badin),
        "note": "cbct_to_badin includes CBCT bone that the Badin maxilla lacks (zygomatic arches)",
    }
    return vertices, faces, report
