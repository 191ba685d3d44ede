"""tract-collision.json: the tongue against the velum and the pharyngeal wall.

Fixtures: the velum mesh's faces and the pharyngeal wall (float32 vertices, base64, and faces)
from the build; the velum's poses are those of velum.json's rig fixture (the JS test reads
both files). Cases: ``POSES`` seeded random tongue poses (every parameter uniform over its
range), each first corrected against the palate, at a random velum opening and at the three
measured openings. Input: the vertices that matter (every vertex the tract corrects, a spread
of those it only tests and of those it screens), as float32 bytes both sides read bit for bit.
Expected: each vertex's flag (screened by the depth tables, tested, corrected) and every
corrected position.

A vertex is kept only when its flag holds with the vertex moved ``FLIP_MM`` toward and away from
T, so that no case sits on a decision boundary a last-digit difference could flip.
"""

import numpy as np

from glasshead.constants import FLAG_CORRECTED, FLAG_SCREENED, FLAG_TESTED, VELUM_PARAMETER
from glasshead.geometry.collision import correct_vertices
from glasshead.geometry.collision_format import decode_collision_tables
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.geometry.tract_collision import TRACT_COLLISION_MESHES, correct_tract, prepare_tract
from glasshead.geometry.velum import prepare_velum
from glasshead.pipeline.outputs import load_built_meshes
from glasshead.vectors import sources
from glasshead.vectors.common import case, document, encode_f32, rounded, tolerance
from glasshead.vectors.velum import velum_definition

FORMAT_VERSION = 1
SEED = 20261123
POSES = 6
#: Vertices kept per case from those only tested, and from those screened.
TESTED_KEPT = 40
SCREENED_KEPT = 12
FLIP_MM = 1e-4
RESULT_DECIMALS = 6
REFUSED = (1.5, -0.25)

TOLERANCES = {
    "position_mm": tolerance(1e-4, "mm",
                             "JavaScript stores corrected positions as float32 (about 4e-6 mm "
                             "at 60 mm); both twins compute the same float64 crossing"),
}


def _collider():
    rig = prepare_velum(velum_definition())
    built = load_built_meshes(sources.built_assets(), ["velum_rest", "pharynx"])
    meshes = {name: (v, f) for name, (v, f, _) in built.items()}
    velum_faces = meshes["velum_rest"][1]
    pharynx_vertices, pharynx_faces = meshes["pharynx"]
    return prepare_tract(rig, velum_faces, pharynx_vertices, pharynx_faces), meshes


def _stable(points, collider, opening, flags):
    """True where the flag is the same with each vertex moved FLIP_MM along its ray from T."""
    rel = points - collider.origin
    unit = rel / np.maximum(np.linalg.norm(rel, axis=1, keepdims=True), 1e-12)
    ok = np.ones(len(points), dtype=bool)
    for sign in (-1.0, 1.0):
        moved = points + sign * FLIP_MM * unit
        ok &= correct_tract(moved, collider, opening)[1] == flags
    return ok


def _case_vertices(points, collider, opening, rng):
    """Indices of the vertices a case keeps (see the module docstring)."""
    _, flags, _ = correct_tract(points, collider, opening)
    stable = _stable(points, collider, opening, flags)
    keep = []
    for flag, limit in ((FLAG_CORRECTED, None), (FLAG_TESTED, TESTED_KEPT),
                        (FLAG_SCREENED, SCREENED_KEPT)):
        rows = np.flatnonzero((flags == flag) & stable)
        if limit is not None and len(rows) > limit:
            rows = np.sort(rng.choice(rows, limit, replace=False))
        keep.extend(rows.tolist())
    return np.array(sorted(keep), dtype=np.int64)


def tract_document():
    collider, meshes = _collider()
    tongue = TongueRig(sources.tongue_rig_definition())
    tables = decode_collision_tables((sources.built_assets() / "collision-tables.bin")
                                     .read_bytes())
    params = tongue.definition["parameters"]
    low = np.array([p["min"] for p in params], dtype=np.float64)
    high = np.array([p["max"] for p in params], dtype=np.float64)
    rng = np.random.default_rng(SEED)
    r = collider.rest_share
    cases = []
    for k in range(POSES):
        values = low + (high - low) * rng.random(len(low))
        palate, _, _ = correct_vertices(tongue.vertices(values), tables)
        points = palate.astype(np.float32).astype(np.float64)
        for opening in (0.0, r, 1.0, float(np.round(rng.random(), 6))):
            rows = _case_vertices(points, collider, opening, rng)
            chosen = points[rows]
            out, flags, counts = correct_tract(chosen, collider, opening)
            moved = np.flatnonzero(flags == FLAG_CORRECTED)
            cases.append(case(
                f"tongue pose {k} (seed {SEED}) after the palate, {VELUM_PARAMETER} {opening:g}",
                {VELUM_PARAMETER: opening, "vertices_f32": encode_f32(chosen.ravel())},
                {"flags": flags.tolist(), "corrected": moved.tolist(),
                 "corrected_positions": rounded(out[moved].ravel(), RESULT_DECIMALS),
                 "counts": counts}))
    for opening in REFUSED:
        cases.append(case(f"{VELUM_PARAMETER} {opening:g} is refused",
                          {VELUM_PARAMETER: opening, "vertices_f32": encode_f32([0.0, 0.0, 0.0])},
                          {"error": "outside its range [0, 1]"}))
    velum_faces = meshes["velum_rest"][1]
    pharynx_vertices, pharynx_faces = meshes["pharynx"]
    return document(
        "tract-collision.json",
        "Tongue vertices (already corrected against the palate) corrected against the velum at "
        "an opening and the pharyngeal wall: flags and positions, from the built meshes.",
        FORMAT_VERSION, cases,
        constants={"seed": SEED, "meshes": list(TRACT_COLLISION_MESHES),
                   "origin": collider.origin.tolist(), "screen_x": collider.screen_x,
                   "velum_poses": "velum.json fixtures.rig", "flip_mm": FLIP_MM},
        tolerances=TOLERANCES,
        fixtures={"velum_faces": velum_faces.ravel().tolist(),
                  "pharynx_vertices_f32": encode_f32(pharynx_vertices.ravel()),
                  "pharynx_faces": pharynx_faces.ravel().tolist()})


def files():
    return {"tract-collision.json": tract_document()}
