"""Shared test vectors for the collision correction, checked by pytest and tests/js.

Run ``python -m glasshead.geometry.collision_vectors`` to rewrite:

- ``tests/vectors/collision-tables.bin``: small tables built from the real Badin maxilla reduced
  to about 300 triangles (coarse, so the file stays small; the kernels do not care);
- ``tests/vectors/collision-correct.json``: cases ``{description, input: {vertices},
  expected: {vertices, flags, counts}}`` answered by the Python twin, and refusal cases
  ``{description, input: {patch}, expected: {error}}`` where bytes of the tables file are
  overwritten and both loaders must refuse it with a message containing ``error``;
- ``tests/vectors/collision-constants.json``: the collision constants both sides must share.

Every input point is a float32 number kept away from the decision boundaries (voxel faces, cell
edges, the floor, the rmin sphere and the surface itself) so that the float64 and float32
pipelines of the two twins cannot round differently across one.
"""

import hashlib
import json
import sys
import tempfile
from pathlib import Path

import numpy as np

from glasshead import constants as C
from glasshead.geometry.collision import correct_vertices, screen
from glasshead.geometry.collision_format import decode_collision_tables
from glasshead.geometry.frame import badin_to_project, fix_winding
from glasshead.geometry.meshio import read_obj
from glasshead.settings import REPO_ROOT, get_settings

VECTORS_DIR = REPO_ROOT / "tests" / "vectors"
TABLES_NAME = "collision-tables.bin"
CASES_NAME = "collision-correct.json"
CONSTANTS_NAME = "collision-constants.json"
VECTORS_FORMAT_VERSION = 1
#: Reduction of the maxilla for the vector tables, their step and voxel count.
REDUCED_TRIANGLES = 300
STEP_DEG = 4.0
VOXELS = 16
#: Smallest relative distance of an input from any decision boundary.
MARGIN = 1e-5


def badin_mesh(name):
    """A Badin mesh (vertices, faces) in the project frame, from the reference data."""
    path = Path(get_settings().data_dir) / "anatomy" / "artisynth-badin" / f"{name}.obj"
    v, f = read_obj(path)
    return badin_to_project(v), fix_winding(f, C.BADIN_TO_PROJECT_AXES)


def build_vector_tables():
    """Bytes of the small vector tables (deterministic)."""
    import fast_simplification

    from glasshead.pipeline.collision_tables import TABLES_FILE, build_collision_tables

    v, f = badin_mesh("maxilla")
    rv, rf = fast_simplification.simplify(v.astype(np.float32), f.astype(np.int32),
                                          target_count=REDUCED_TRIANGLES)
    with tempfile.TemporaryDirectory() as tmp:
        build_collision_tables(rv.astype(np.float64), rf.astype(np.int64), tmp,
                               step_deg=STEP_DEG, voxels=VOXELS)
        return (Path(tmp) / TABLES_FILE).read_bytes()


def _robust(points, tables):
    """Mask of points far enough from every boundary where the two twins could disagree."""
    h = tables.header
    o = np.array(h["origin"])
    p = points - o
    ok = np.abs(points[:, 1] - h["floor_y"]) > MARGIN
    bmin = np.array(h["voxels"]["bounds"]["min"])
    bmax = np.array(h["voxels"]["bounds"]["max"])
    g = (points - bmin) * (np.array(h["voxels"]["shape"]) / (bmax - bmin))
    ok &= np.all(np.abs(g - np.round(g)) > MARGIN, axis=1)
    liner = h["liner"]
    for angle, start in ((np.arctan2(p[:, 0], p[:, 1]), liner["lon0"]),
                         (np.arctan2(p[:, 2], np.hypot(p[:, 0], p[:, 1])), liner["lat0"])):
        u = (angle - start) / liner["step"]
        ok &= np.abs(u - np.round(u)) > MARGIN
    r = np.linalg.norm(p, axis=1)
    u = np.floor((np.arctan2(p[:, 0], p[:, 1]) - liner["lon0"]) / liner["step"]).astype(int)
    w = np.floor((np.arctan2(p[:, 2], np.hypot(p[:, 0], p[:, 1])) - liner["lat0"])
                 / liner["step"]).astype(int)
    inside = (u >= 0) & (u < liner["nlon"]) & (w >= 0) & (w < liner["nlat"])
    rmin = np.where(inside, tables["cell_rmin"][np.clip(w, 0, liner["nlat"] - 1),
                                                np.clip(u, 0, liner["nlon"] - 1)], np.inf)
    with np.errstate(invalid="ignore"):
        ok &= ~(np.abs(r - rmin) <= MARGIN * r)
    # Away from the surface along the ray: scaling by 1 +- margin keeps the flag.
    base = correct_vertices(points, tables)[1]
    for scale in (1 - 10 * MARGIN, 1 + 10 * MARGIN):
        ok &= correct_vertices(o + p * scale, tables)[1] == base
    return ok


def _case(description, points, tables):
    out, flags, counts = correct_vertices(points, tables)
    return {"description": description,
            "input": {"vertices": points.tolist()},
            "expected": {"vertices": out.tolist(), "flags": flags.tolist(), "counts": counts}}


def _pick(points, mask, count, rng):
    idx = np.flatnonzero(mask)
    if len(idx) < count:
        raise RuntimeError(f"only {len(idx)} candidate points for a vector case")
    return points[np.sort(rng.choice(idx, count, replace=False))]


def build_cases(tables):
    """The correction and refusal cases for the given tables (CollisionTables)."""
    rng = np.random.default_rng(20260601)
    h = tables.header
    bmin = np.array(h["voxels"]["bounds"]["min"])
    bmax = np.array(h["voxels"]["bounds"]["max"])
    span = bmax - bmin
    cloud = rng.uniform(bmin - 0.3 * span, bmax + 0.3 * span, size=(40000, 3))
    cloud = cloud.astype(np.float32).astype(np.float64)
    cloud = cloud[_robust(cloud, tables)]
    _, flags, _ = correct_vertices(cloud, tables)
    classes = screen(cloud, tables)
    in_box = np.all((cloud >= bmin) & (cloud < bmax), axis=1)
    below = cloud[:, 1] <= h["floor_y"]
    rel = cloud - np.array(h["origin"])
    liner = h["liner"]
    u = np.floor((np.arctan2(rel[:, 0], rel[:, 1]) - liner["lon0"]) / liner["step"]).astype(int)
    w = np.floor((np.arctan2(rel[:, 2], np.hypot(rel[:, 0], rel[:, 1])) - liner["lat0"])
                 / liner["step"]).astype(int)
    in_grid = (u >= 0) & (u < liner["nlon"]) & (w >= 0) & (w < liner["nlat"])
    kind = np.where(in_grid, tables["cell_kind"][np.clip(w, 0, liner["nlat"] - 1),
                                                 np.clip(u, 0, liner["nlon"] - 1)], 255)

    cases = [
        _case("points at or below the floor plane through O are screened and never move",
              _pick(cloud, below, 12, rng), tables),
        _case("points in ok voxels are screened and never move",
              _pick(cloud, ~below & (classes == C.VOXEL_OK), 12, rng), tables),
        _case("points outside the voxel grid and above the floor are tested",
              _pick(cloud, ~below & ~in_box, 12, rng), tables),
        _case("points in directions where every ray misses are tested and never move",
              _pick(cloud, ~below & (classes != C.VOXEL_OK) & ((kind == C.CELL_EMPTY)
                                                                | ~in_grid), 12, rng), tables),
        _case("points short of the surface in borderline voxels are tested and left unchanged",
              _pick(cloud, (flags == C.FLAG_TESTED) & in_grid & (kind != C.CELL_EMPTY), 16,
                    rng), tables),
        _case("points beyond a plane cell's triangle move along the line toward O onto it",
              _pick(cloud, (flags == C.FLAG_CORRECTED) & (kind == C.CELL_PLANE), 16, rng),
              tables),
        _case("points beyond a list cell's triangles move onto the first one hit from O",
              _pick(cloud, (flags == C.FLAG_CORRECTED) & (kind == C.CELL_LIST), 16, rng), tables),
    ]
    if np.any(classes == C.VOXEL_NOT_OK):
        cases.append(_case("points in not-ok voxels go straight to correction",
                           _pick(cloud, classes == C.VOXEL_NOT_OK, 4, rng), tables))
    # A whole tongue: the Badin rest tongue raised and advanced into the palate.
    tongue, _ = badin_mesh("tongue")
    posed = (tongue + [6.0, 14.0, 1.5]).astype(np.float32).astype(np.float64)
    posed = posed[_robust(posed, tables)]
    cases.append(_case("a raised tongue: every vertex screened, tested or corrected as one frame",
                       posed, tables))
    refusals = [
        {"description": "tables of another format version are refused, never misread",
         "input": {"patch": {"offset": 8, "bytes": [C.COLLISION_TABLES_FORMAT_VERSION + 1, 0, 0,
                                                    0]}},
         "expected": {"error": "format version"}},
        {"description": "a file that is not collision tables is refused",
         "input": {"patch": {"offset": 0, "bytes": list(b"NOTATABL")}},
         "expected": {"error": "magic"}},
        {"description": "a corrupted payload is refused by its checksum",
         "input": {"patch": {"offset": -5, "bytes": [255]}},
         "expected": {"error": "CRC-32"}},
        {"description": "a truncated file is refused",
         "input": {"truncate": 64},
         "expected": {"error": "truncated"}},
    ]
    return cases, refusals


def constants_vector():
    return {
        "description": "collision constants shared by constants.py and constants.js",
        "expected": {
            "COLLISION_TABLES_FORMAT_VERSION": C.COLLISION_TABLES_FORMAT_VERSION,
            "COLLISION_TABLES_MAGIC": C.COLLISION_TABLES_MAGIC.decode("ascii"),
            "COLLISION_LINER_STEP_DEG": C.COLLISION_LINER_STEP_DEG,
            "COLLISION_VOXELS": C.COLLISION_VOXELS,
            "VOXEL_OK": C.VOXEL_OK, "VOXEL_BORDER": C.VOXEL_BORDER,
            "VOXEL_NOT_OK": C.VOXEL_NOT_OK,
            "CELL_EMPTY": C.CELL_EMPTY, "CELL_PLANE": C.CELL_PLANE, "CELL_LIST": C.CELL_LIST,
            "FLAG_SCREENED": C.FLAG_SCREENED, "FLAG_TESTED": C.FLAG_TESTED,
            "FLAG_CORRECTED": C.FLAG_CORRECTED,
            "COLLISION_MAX_VERTICES": C.COLLISION_MAX_VERTICES,
            "COLLISION_TOL": {k: getattr(C.COLLISION_TOL, k)
                              for k in ("angle", "length", "barycentric", "surface", "depth")},
        },
    }


def build_all():
    """(tables bytes, cases document, constants document)."""
    data = build_vector_tables()
    tables = decode_collision_tables(data)
    cases, refusals = build_cases(tables)
    document = {
        "description": "Collision correction: Python reference answers on shared tables",
        "format_version": VECTORS_FORMAT_VERSION,
        "tables": TABLES_NAME,
        "tables_sha256": hashlib.sha256(data).hexdigest(),
        "tolerance_mm": 1e-3,
        "cases": cases,
        "refusals": refusals,
    }
    return data, document, constants_vector()


def main(argv=None):
    data, document, consts = build_all()
    VECTORS_DIR.mkdir(parents=True, exist_ok=True)
    (VECTORS_DIR / TABLES_NAME).write_bytes(data)
    (VECTORS_DIR / CASES_NAME).write_text(json.dumps(document, indent=1) + "\n")
    (VECTORS_DIR / CONSTANTS_NAME).write_text(json.dumps(consts, indent=1) + "\n")
    total = sum(len(c["input"]["vertices"]) for c in document["cases"])
    print(f"wrote {len(document['cases'])} cases ({total} vertices), "
          f"{len(document['refusals'])} refusals, tables {len(data)} bytes")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
