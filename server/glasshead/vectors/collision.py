"""collision-tables.bin and collision-correct.json: the collision correction's shared vectors.

- ``collision-tables.bin``: small tables built from the real Badin maxilla reduced to about 300
  triangles (coarse, so the file stays small; the kernels do not care);
- ``collision-correct.json``: cases ``{input: {vertices}, expected: {vertices, flags, counts}}``
  answered by the Python twin, then refusal cases ``{input: {patch} or {truncate}, expected:
  {error}}`` where bytes of the tables file are overwritten (or cut) and both loaders must refuse
  it with a message containing ``error``.

Every input point is a float32 number kept away from the decision boundaries (voxel faces, cell
edges, the floor, the rmin sphere and the surface itself) by ``MARGIN`` (relative), so that the
float64 and float32 pipelines of the two twins, or two CPUs, cannot round differently across
one: the flags are compared exactly, the positions within a tolerance.
"""

import hashlib
import tempfile
from pathlib import Path

import numpy as np

from glasshead.constants import (
    CELL_EMPTY,
    CELL_LIST,
    CELL_PLANE,
    COLLISION_TABLES_FORMAT_VERSION,
    FLAG_CORRECTED,
    FLAG_TESTED,
    VOXEL_NOT_OK,
    VOXEL_OK,
)
from glasshead.geometry.collision import correct_vertices, screen
from glasshead.geometry.collision_format import decode_collision_tables
from glasshead.vectors.common import document, tolerance
from glasshead.vectors.sources import badin_mesh

TABLES_NAME = "collision-tables.bin"
CASES_NAME = "collision-correct.json"
FORMAT_VERSION = 2
SEED = 20260601
#: Reduction of the maxilla for the vector tables, their step and voxel count.
REDUCED_TRIANGLES = 300
STEP_DEG = 4.0
VOXELS = 16
#: Smallest relative distance of an input from any decision boundary.
MARGIN = 1e-5

TOLERANCES = {
    "vertex_mm": tolerance(1e-3, "mm", "float32 positions, as the browser holds them, corrected "
                                       "against float32 tables (about 4e-6 mm of rounding)"),
    "reference_mm": tolerance(1e-9, "mm", "float64 positions: the twins intersect the same "
                                          "triangle along the same ray, so only the last digits "
                                          "(about 1e-14 mm) differ between them or between CPUs"),
}


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


def robust_mask(points, tables):
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
    # A point exactly on the plane z = O_z (the mid-sagittal plane) has latitude exactly 0, in
    # both twins and on every CPU (atan2(0, x) = 0), so its cell is found alike even where 0 is
    # a cell edge: it is exact, not near.
    on_plane = p[:, 2] == 0.0
    for angle, start, exact in ((np.arctan2(p[:, 0], p[:, 1]), liner["lon0"], False),
                                (np.arctan2(p[:, 2], np.hypot(p[:, 0], p[:, 1])), liner["lat0"],
                                 on_plane)):
        u = (angle - start) / liner["step"]
        ok &= (np.abs(u - np.round(u)) > MARGIN) | exact
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
    """The correction cases, then the refusal cases, for the given tables (CollisionTables)."""
    rng = np.random.default_rng(SEED)
    h = tables.header
    bmin = np.array(h["voxels"]["bounds"]["min"])
    bmax = np.array(h["voxels"]["bounds"]["max"])
    span = bmax - bmin
    cloud = rng.uniform(bmin - 0.3 * span, bmax + 0.3 * span, size=(40000, 3))
    cloud = cloud.astype(np.float32).astype(np.float64)
    cloud = cloud[robust_mask(cloud, tables)]
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
              _pick(cloud, ~below & (classes == VOXEL_OK), 12, rng), tables),
        _case("points outside the voxel grid and above the floor are tested",
              _pick(cloud, ~below & ~in_box, 12, rng), tables),
        _case("points in directions where every ray misses are tested and never move",
              _pick(cloud, ~below & (classes != VOXEL_OK) & ((kind == CELL_EMPTY) | ~in_grid),
                    12, rng), tables),
        _case("points short of the surface in borderline voxels are tested and left unchanged",
              _pick(cloud, (flags == FLAG_TESTED) & in_grid & (kind != CELL_EMPTY), 16, rng),
              tables),
        _case("points beyond a plane cell's triangle move along the line toward O onto it",
              _pick(cloud, (flags == FLAG_CORRECTED) & (kind == CELL_PLANE), 16, rng),
              tables),
        _case("points beyond a list cell's triangles move onto the first one hit from O",
              _pick(cloud, (flags == FLAG_CORRECTED) & (kind == CELL_LIST), 16, rng), tables),
    ]
    if np.any(classes == VOXEL_NOT_OK):
        cases.append(_case("points in not-ok voxels go straight to correction",
                           _pick(cloud, classes == VOXEL_NOT_OK, 4, rng), tables))
    # A whole tongue: the Badin rest tongue raised and advanced into the palate.
    tongue, _ = badin_mesh("tongue")
    posed = (tongue + [6.0, 14.0, 1.5]).astype(np.float32).astype(np.float64)
    posed = posed[robust_mask(posed, tables)]
    cases.append(_case("a raised tongue: every vertex screened, tested or corrected as one frame",
                       posed, tables))
    cases += [
        {"description": "tables of another format version are refused, never misread",
         "input": {"patch": {"offset": 8, "bytes": [COLLISION_TABLES_FORMAT_VERSION + 1, 0, 0,
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
    return cases


def cases_document(data, tables):
    """The collision-correct.json document for the tables ``data`` (bytes) decoded as ``tables``."""
    return document(
        CASES_NAME,
        "Collision correction: Python reference answers on the shared tables in fixtures; then "
        "damaged copies of those tables that both loaders must refuse",
        FORMAT_VERSION, build_cases(tables),
        constants={"seed": SEED, "margin_relative": MARGIN, "reduced_triangles": REDUCED_TRIANGLES,
                   "step_deg": STEP_DEG, "voxels": VOXELS},
        tolerances=TOLERANCES,
        fixtures={"tables": {"file": TABLES_NAME, "sha256": hashlib.sha256(data).hexdigest()}})


def files():
    data = build_vector_tables()
    doc = cases_document(data, decode_collision_tables(data))
    total = sum(len(c["input"].get("vertices", [])) for c in doc["cases"])
    print(f"    {CASES_NAME}: {len(doc['cases'])} cases ({total} vertices), tables {len(data)} "
          "bytes")
    return {TABLES_NAME: data, CASES_NAME: doc}
