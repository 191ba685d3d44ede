"""The CBCT subject's larynx, hyoid and cervical spine, carried into the project frame.

These meshes share the CBCT maxilla's frame (millimetres, that scan's own axes), so they are
carried over by the transform that ``register_cbct`` finds for the maxilla. That function
returns the placed maxilla, not the transform; the transform is an affine map (an axis
permutation, mm -> m -> project mm with its reflection, then a similarity), so it is recovered
exactly by least squares from the maxilla's vertices before and after (``cbct_affine``).

The vertebrae come with an Amira matrix (``vertebrae.transform``): a uniform scale of 1.2, a
rotation of 94.3 degrees about x and a translation in Amira's centimetres (ArtiSynth's
``JawModel.transformVertebrae`` multiplies it by 10). The matrix may or may not have been
applied to the mesh already: ArtiSynth's dynjaw model saved the moved mesh and no longer applies
it. So both placements, the mesh as stored and the mesh moved by the matrix, are checked against
the other bones (``check_vertebrae``), and exactly one must pass.
"""

import numpy as np

from glasshead.geometry.frame import fix_winding
from glasshead.geometry.meshio import MeshFormatError

#: mm. Largest residual allowed when the registration's affine map is recovered from the
#: maxilla (float64 rounding gives about 1e-13 mm).
AFFINE_FIT_TOLERANCE_MM = 1e-6
#: Amira writes lengths in centimetres; the CBCT meshes are in millimetres.
AMIRA_CM_TO_MM = 10.0
#: Largest angle between the spine's long axis and the vertical for an upright neck, degrees.
UPRIGHT_MAX_DEG = 30.0
#: mm. How far the spine may reach in front of the pharyngeal wall or the cricoid in one slice
#: and still count as behind them: the two subjects' necks differ and the registration is fitted
#: on the maxilla, about 100 mm above. Carried over, the stored spine reaches 4.5 mm into the
#: Badin pharyngeal wall at C2-C3; a misplaced one lies 40 mm or more off.
NECK_OVERLAP_TOLERANCE_MM = 10.0
#: Half-width of the band about the mid-sagittal plane used to compare front and back, mm.
MIDLINE_BAND_MM = 15.0
#: Height of the slices in which front and back are compared, mm.
SLICE_MM = 5.0


def cbct_affine(cbct_vertices, placed_vertices):
    """The affine map that took the CBCT maxilla into the project frame, as (4, 4) float64.

    cbct_vertices (n, 3) float, its own axes (mm); placed_vertices (n, 3) float, the same
    vertices in the project frame. Raises ``ValueError`` when no affine map fits them.
    """
    src = np.asarray(cbct_vertices, dtype=np.float64)
    dst = np.asarray(placed_vertices, dtype=np.float64)
    if src.shape != dst.shape or src.ndim != 2 or src.shape[1] != 3 or len(src) < 4:
        raise ValueError(f"need two (n, 3) arrays of the same shape, n >= 4; got {src.shape} "
                         f"and {dst.shape}")
    homogeneous = np.c_[src, np.ones(len(src))]
    solution, *_ = np.linalg.lstsq(homogeneous, dst, rcond=None)
    residual = float(np.abs(homogeneous @ solution - dst).max())
    if residual > AFFINE_FIT_TOLERANCE_MM:
        raise ValueError(f"the registered maxilla is not an affine image of the CBCT one "
                         f"(residual {residual:.3g} mm)")
    return np.vstack([solution.T, [0.0, 0.0, 0.0, 1.0]])


def transform_points(matrix, points):
    """(n, 3) points moved by the (4, 4) affine ``matrix`` (column vectors)."""
    points = np.asarray(points, dtype=np.float64)
    return points @ matrix[:3, :3].T + matrix[:3, 3]


def carry(matrix, vertices, faces):
    """A mesh moved by ``matrix``: (vertices (n, 3) float64, faces (m, 3) int64), the winding
    reversed when the matrix mirrors space (the project frame is a mirror of the CBCT's)."""
    return transform_points(matrix, vertices), fix_winding(np.asarray(faces, np.int64),
                                                           matrix[:3, :3])


def amira_to_mm(matrix):
    """The Amira matrix (4, 4) with its translation converted from centimetres to millimetres."""
    out = np.array(matrix, dtype=np.float64)
    out[:3, 3] *= AMIRA_CM_TO_MM
    return out


def midline_clearance(front, back, band=MIDLINE_BAND_MM, slice_mm=SLICE_MM):
    """How far ``front`` lies anterior to ``back`` near the mid-sagittal plane.

    front, back: (n, 3), (m, 3) float points in the project frame. Points with |z| < band are
    cut into horizontal slices ``slice_mm`` high; in each slice that holds both, the clearance
    is the front's smallest x minus the back's largest x (positive: front lies wholly anterior).
    Returns {"min_mm", "median_mm", "slices"} (None values when no slice holds both).
    """
    front, back = np.asarray(front, np.float64), np.asarray(back, np.float64)
    front = front[np.abs(front[:, 2]) < band]
    back = back[np.abs(back[:, 2]) < band]
    gaps = []
    if len(front) and len(back):
        low = max(front[:, 1].min(), back[:, 1].min())
        high = min(front[:, 1].max(), back[:, 1].max())
        for bottom in np.arange(low, high, slice_mm):
            f = front[(front[:, 1] >= bottom) & (front[:, 1] < bottom + slice_mm)]
            b = back[(back[:, 1] >= bottom) & (back[:, 1] < bottom + slice_mm)]
            if len(f) and len(b):
                gaps.append(f[:, 0].min() - b[:, 0].max())
    if not gaps:
        return {"min_mm": None, "median_mm": None, "slices": 0}
    return {"min_mm": round(float(min(gaps)), 2), "median_mm": round(float(np.median(gaps)), 2),
            "slices": len(gaps)}


def long_axis_tilt_deg(points):
    """Angle in degrees between the principal axis of (n, 3) points and the vertical (y)."""
    points = np.asarray(points, np.float64)
    _, _, vt = np.linalg.svd(points - points.mean(axis=0), full_matrices=False)
    return float(np.degrees(np.arccos(min(1.0, abs(vt[0, 1])))))


def check_vertebrae(vertebrae, pharynx, cricoid, cranium):
    """Does a placement of the spine fit the other bones? All (n, 3) points, project frame.

    The spine must be upright, behind the posterior pharyngeal wall and the cricoid near the
    midline (behind in the median slice, and nowhere more than ``NECK_OVERLAP_TOLERANCE_MM`` in
    front of them), and below the cranium. Returns the measures and ``ok``.
    """
    tilt = long_axis_tilt_deg(vertebrae)
    behind_pharynx = midline_clearance(pharynx, vertebrae)
    behind_cricoid = midline_clearance(cricoid, vertebrae)
    below_cranium = float(np.asarray(cranium)[:, 1].min() - np.asarray(vertebrae)[:, 1].max())
    ok = (tilt <= UPRIGHT_MAX_DEG and below_cranium > 0.0
          and all(c["slices"] > 0 and c["median_mm"] > 0.0
                  and c["min_mm"] > -NECK_OVERLAP_TOLERANCE_MM
                  for c in (behind_pharynx, behind_cricoid)))
    return {"ok": bool(ok), "long_axis_from_vertical_deg": round(tilt, 1),
            "pharynx_in_front_mm": behind_pharynx, "cricoid_in_front_mm": behind_cricoid,
            "below_cranium_mm": round(below_cranium, 2)}


def place_vertebrae(stored, amira_matrix, to_project, others, path):
    """Choose the placement of the spine that fits the other bones.

    stored (n, 3) float: vertebrae.obj as read (CBCT frame, mm). amira_matrix (4, 4): from
    ``sources.read_amira_transform``. to_project (4, 4): ``cbct_affine``. others: dict of
    (n, 3) project-frame points for "pharynx", "cricoid" and "cranium". path: the transform
    file, named in the error when neither placement or both fit.
    Returns (vertices (n, 3) float64 in the CBCT frame, report dict).
    """
    moved = transform_points(amira_to_mm(amira_matrix), stored)
    candidates = {"as_stored": stored, "moved_by_transform": moved}
    checks = {name: check_vertebrae(transform_points(to_project, points), others["pharynx"],
                                    others["cricoid"], others["cranium"])
              for name, points in candidates.items()}
    passing = [name for name, check in checks.items() if check["ok"]]
    if len(passing) != 1:
        raise MeshFormatError(
            path, f"{'no' if not passing else 'more than one'} placement of vertebrae.obj fits "
                  f"the other bones (upright, behind the pharynx and the cricoid, below the "
                  f"cranium): {checks}")
    chosen = passing[0]
    report = {
        "matrix_column_major": np.round(amira_matrix, 6).tolist(),
        "translation_units": "cm (Amira), applied as mm x 10",
        "scale": round(float(np.cbrt(np.linalg.det(amira_matrix[:3, :3]))), 4),
        "placement": chosen,
        "checks": checks,
        "reason": ("the mesh as stored already lies behind the pharynx (ArtiSynth's dynjaw "
                   "model saved it after moving it); moved again by the matrix it would lie "
                   "across the neck" if chosen == "as_stored" else
                   "the mesh as stored does not fit the other bones; moved by the matrix it "
                   "does"),
    }
    return candidates[chosen], report
