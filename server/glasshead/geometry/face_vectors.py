"""The face rig's shared test vectors, ``tests/vectors/face-rig.json`` (registered in
``geometry.vectors``).

The document embeds the built rig, the jaw block of the tongue rig (the face follows its jaw pose)
and the rest positions of the four meshes (from the built GLBs, rounded to 0.1 micrometre: both
sides read these same numbers). Cases: the neutral pose, each parameter alone at its minimum and
maximum, closure at three jaw openings, and ``RANDOM_CASES`` seeded random sets with the jaw
opening among them (a quarter of them asking for closure). Expected: the lip gaps, the closure
vector, the count of points the teeth moved and the positions of probe vertices spread over the
moving part of each mesh; tests/test_face_rig_vectors.py also compares every vertex of every case
live, Python against node.
"""

import numpy as np

from glasshead.constants import FACE_VERTEX_TOLERANCE_MM
from glasshead.geometry import face_rig
from glasshead.geometry.jaw import jaw_pose

SEED = 20241122
RANDOM_CASES = 120
#: Share of the random sets with lip_opening 0 (closure asked for).
CLOSED_SHARE = 0.25
PROBES_PER_MESH = 12
PARAM_DECIMALS = 4
RESULT_DECIMALS = 5
REST_DECIMALS = 4
JAW_RANGE_DEG = (0.0, 25.0)

GENERATOR = "python -m glasshead.geometry.vectors face-rig.json"


def rest_positions():
    """Rest vertices of the built meshes: dict name -> (n, 3) float64 (float32 GLB values)."""
    from glasshead.pipeline.face_rig_sources import read_scene_meshes
    from glasshead.settings import get_settings

    meshes = read_scene_meshes(get_settings().assets_dir)
    if not meshes:
        raise FileNotFoundError("the face vectors need the built meshes: run `glasshead build`")
    return {name: meshes[name][0][0] for name in face_rig.MESH_NAMES}


def parameter_sets(rig, seed=SEED):
    """(description, {name: value}) including ``jaw_opening`` in degrees."""
    specs = rig["parameters"]
    sets = [("neutral (every parameter at its neutral value, jaw closed)", {"jaw_opening": 0.0})]
    for spec in specs:
        for label in ("min", "max"):
            sets.append((f"{spec['name']} alone at its {label} {spec[label]:g}",
                         {spec["name"]: float(spec[label]), "jaw_opening": 0.0}))
    for opening in (0.0, 12.5, 25.0):
        sets.append((f"lips closed at jaw opening {opening:g} deg",
                     {"lip_opening": 0.0, "jaw_opening": opening}))
    rng = np.random.default_rng(seed)
    low = np.array([s["min"] for s in specs] + [JAW_RANGE_DEG[0]])
    high = np.array([s["max"] for s in specs] + [JAW_RANGE_DEG[1]])
    names = [s["name"] for s in specs] + ["jaw_opening"]
    for case in range(RANDOM_CASES):
        values = np.clip(np.round(rng.uniform(low, high), PARAM_DECIMALS), low, high)
        if rng.random() < CLOSED_SHARE:
            values[names.index("lip_opening")] = 0.0
        sets.append((f"random set {case} (seed {seed})", dict(zip(names, values.tolist()))))
    return sets


def probe_indices(prepared, count=PROBES_PER_MESH):
    """Per mesh, ``count`` vertices spread through those that can move."""
    probes = {}
    for name, mesh in prepared.items():
        moving = np.flatnonzero((mesh["weights"] != 0) | np.any(mesh["coeffs"] != 0, axis=1))
        pick = np.linspace(0, len(moving) - 1, count).round().astype(int)
        probes[name] = sorted(set(moving[pick].tolist()))
    return probes


def pose_case(rig, prepared, jaw, params):
    """(posed dict, info) for one case's params (lip values and ``jaw_opening``)."""
    lips = {k: v for k, v in params.items() if k != "jaw_opening"}
    return face_rig.pose_face(rig, prepared, lips, jaw_pose(params["jaw_opening"], jaw))


def _round(values):
    return np.round(np.asarray(values, dtype=np.float64), RESULT_DECIMALS).tolist()


def face_document():
    from glasshead.asset_store import AssetStore
    from glasshead.settings import get_settings

    store = AssetStore(get_settings().assets_dir)
    rig = {k: v for k, v in store.get("face_rig").items() if k != "inputs_sha256"}
    jaw = store.get("tongue_rig").definition["jaw"]
    rest = {name: np.round(points, REST_DECIMALS) for name, points in rest_positions().items()}
    prepared = face_rig.prepare_meshes(rig, rest)
    probes = probe_indices(prepared)
    cases = []
    for description, params in parameter_sets(rig):
        posed, info = pose_case(rig, prepared, jaw, params)
        cases.append({
            "description": description,
            "input": {"params": params},
            "expected": {
                "natural_gap_mm": round(float(info["natural_gap"]), RESULT_DECIMALS),
                "lip_gap_mm": round(float(info["lip_gap"]), RESULT_DECIMALS),
                "closure_mm": _round(info["closure"]),
                "teeth_clamped": int(info["teeth_clamped"]),
                "probe_positions": {name: _round(posed[name][probes[name]]) for name in probes},
            },
        })
    return {
        "description": "Face rig poses: the skin, lips and head shell for lip parameters and jaw "
                       "openings, from the embedded rig, jaw and rest meshes; neutral, each "
                       f"parameter alone at its extremes, closure at three jaw openings and "
                       f"{RANDOM_CASES} random sets drawn uniformly with numpy seed {SEED}",
        "generator": GENERATOR,
        "seed": SEED,
        "tolerance": {"vertex_mm": FACE_VERTEX_TOLERANCE_MM},
        "rig": rig,
        "jaw": jaw,
        "rest": {name: points.ravel().tolist() for name, points in rest.items()},
        "probe_vertices": probes,
        "cases": cases,
    }
