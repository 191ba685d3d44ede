"""face-rig.json: the face rig's shared vectors.

Fixtures: the built rig, the jaw block of the tongue rig (the face follows its jaw pose), the rest
positions of the four meshes (from the built GLBs, rounded to 0.1 micrometre: both sides read
these same numbers) and the probe vertices. Cases: the neutral pose, each parameter alone at its
minimum and maximum, closure at three jaw openings, and ``RANDOM_CASES`` seeded random sets with
the jaw opening among them (a quarter of them asking for closure). Expected: the lip gaps, the
closure vector, the count of points the teeth moved and the positions of the probe vertices;
tests/test_face_rig_vectors.py also compares every vertex of every case live, Python against
node.

The count of points the teeth moved is an integer decided by floats (is a point behind an
incisor's face, by less than the table's depth?). Every case is checked to keep that count when
both decisions move by ``MARGIN_MM`` either way, so that float32 JavaScript, or another CPU,
cannot flip one point; a case that fails stops the generator (change the seed).
"""

import numpy as np

from glasshead.constants import FACE_VERTEX_TOLERANCE_MM
from glasshead.geometry import face_rig
from glasshead.geometry.jaw import jaw_pose
from glasshead.geometry.tongue_parameters import JAW_PARAMETER
from glasshead.vectors import sources
from glasshead.vectors.common import case, document, rounded, tolerance

FORMAT_VERSION = 2
SEED = 20241122
RANDOM_CASES = 120
#: Share of the random sets with lip_opening 0 (closure asked for).
CLOSED_SHARE = 0.25
PROBES_PER_MESH = 12
PARAM_DECIMALS = 4
RESULT_DECIMALS = 5
REST_DECIMALS = 4
JAW_RANGE_DEG = JAW_PARAMETER[2:4]
#: mm. The teeth's decisions of every case hold with the face and the depth moved this much.
MARGIN_MM = 1e-4

TOLERANCES = {
    "vertex_mm": tolerance(FACE_VERTEX_TOLERANCE_MM, "mm",
                           "JavaScript poses float32 rest positions into float32 output "
                           "(about 4e-6 mm of rounding at 50 mm); a wrong vertex is off by far "
                           "more"),
    "gap_mm": tolerance(1e-4, "mm", "lip gaps and closure in JavaScript come from float32 "
                                    "positions (a few 1e-6 mm off)"),
    "stored_mm": tolerance(1e-5, "mm", "stored values are rounded to 5 decimals (at most 5e-6 "
                                       "off); the float64 reference reproduces them on any CPU "
                                       "within that"),
}


def fixed_sets(rig):
    """(description, {name: value}) of the neutral, one-at-a-time extreme and closure cases,
    ``jaw_opening`` in degrees."""
    sets = [("neutral (every parameter at its neutral value, jaw closed)", {"jaw_opening": 0.0})]
    for spec in rig["parameters"]:
        for label in ("min", "max"):
            sets.append((f"{spec['name']} alone at its {label} {spec[label]:g}",
                         {spec["name"]: float(spec[label]), "jaw_opening": 0.0}))
    for opening in (0.0, 0.5 * JAW_RANGE_DEG[1], JAW_RANGE_DEG[1]):
        sets.append((f"lips closed at jaw opening {opening:g} deg",
                     {"lip_opening": 0.0, "jaw_opening": opening}))
    return sets


def random_draws(rig, seed=SEED):
    """Endless seeded parameter sets drawn uniformly over every range and the jaw's (a quarter of
    them with lip_opening 0): yields {name: value}."""
    specs = rig["parameters"]
    rng = np.random.default_rng(seed)
    low = np.array([s["min"] for s in specs] + [JAW_RANGE_DEG[0]])
    high = np.array([s["max"] for s in specs] + [JAW_RANGE_DEG[1]])
    names = [s["name"] for s in specs] + ["jaw_opening"]
    while True:
        values = np.clip(np.round(rng.uniform(low, high), PARAM_DECIMALS), low, high)
        if rng.random() < CLOSED_SHARE:
            values[names.index("lip_opening")] = 0.0
        yield dict(zip(names, values.tolist(), strict=True))


def parameter_sets(rig, seed=SEED, keep=lambda params: True):
    """The fixed sets, then the first ``RANDOM_CASES`` random draws that ``keep`` accepts, each
    described with its draw number (so that a test can draw them again from the seed)."""
    sets = fixed_sets(rig)
    kept = 0
    for draw, params in enumerate(random_draws(rig, seed)):
        if kept == RANDOM_CASES:
            break
        if keep(params):
            sets.append((f"random set {kept} (seed {seed}, draw {draw})", params))
            kept += 1
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


def shifted_teeth(rig, face_mm, depth_mm):
    """A copy of the rig whose incisor faces stand ``face_mm`` further forward and whose depth is
    ``depth_mm`` larger: what a point's two teeth decisions see when they move by that much."""
    teeth = {name: dict(row, x=(np.asarray(row["x"], dtype=np.float64) + face_mm).tolist(),
                        depth=float(row["depth"]) + depth_mm)
             for name, row in rig["teeth"].items()}
    return dict(rig, teeth=teeth)


def teeth_decisions_hold(rig, prepared, jaw, params, count, margin=MARGIN_MM):
    """True when the count of points the teeth move stays ``count`` with every decision moved
    by ``margin`` either way (each shift below can only add points, or only remove them)."""
    for face_mm, depth_mm in ((margin, margin), (-margin, -margin), (0.0, margin),
                              (0.0, -margin)):
        _, info = pose_case(shifted_teeth(rig, face_mm, depth_mm), prepared, jaw, params)
        if info["teeth_clamped"] != count:
            return False
    return True


def natural_difference(rig, prepared, jaw, params):
    """mm. Lowest point of the upper lip minus highest of the lower, before closure (as in
    ``face_rig.pose_face``): closure applies only where this is above 0."""
    lips = {k: v for k, v in params.items() if k != "jaw_opening"}
    values = face_rig.lip_parameters(rig, lips)
    screw = face_rig.jaw_screw(jaw_pose(params["jaw_opening"], jaw))
    posed = {}
    for name in ("upper_lip", "lower_lip"):
        mesh = prepared[name]
        shaped = mesh["rest"] + face_rig.shape_offsets(mesh["coeffs"], values, rig["field"])
        posed[name] = face_rig.skin_jaw(shaped, mesh["weights"], screw)
    upper, lower = prepared["upper_lip"], prepared["lower_lip"]
    _, upper_y, lower_y = face_rig.lip_gap(posed["upper_lip"], upper["midline_edges"],
                                           posed["lower_lip"], lower["midline_edges"])
    return upper_y - lower_y


def face_document():
    rig = sources.face_rig_definition()
    jaw = sources.tongue_rig_definition()["jaw"]
    rest = {name: np.round(points, REST_DECIMALS)
            for name, points in sources.scene_meshes(face_rig.MESH_NAMES).items()}
    prepared = face_rig.prepare_meshes(rig, rest)
    probes = probe_indices(prepared)

    def clear(params):
        _, info = pose_case(rig, prepared, jaw, params)
        return (teeth_decisions_hold(rig, prepared, jaw, params, info["teeth_clamped"])
                and abs(natural_difference(rig, prepared, jaw, params)) > MARGIN_MM)

    cases = []
    for description, params in parameter_sets(rig, keep=clear):
        # Random draws that are not clear were skipped; a fixed case has no second draw.
        if not description.startswith("random set") and not clear(params):
            raise RuntimeError(f"face-rig.json, {description}: a decision (a point against the "
                               f"teeth, or the lips touching) lies within {MARGIN_MM} mm")
        posed, info = pose_case(rig, prepared, jaw, params)
        cases.append(case(description, {"params": params}, {
            "natural_gap_mm": round(float(info["natural_gap"]), RESULT_DECIMALS),
            "lip_gap_mm": round(float(info["lip_gap"]), RESULT_DECIMALS),
            "closure_mm": rounded(info["closure"], RESULT_DECIMALS),
            "teeth_clamped": int(info["teeth_clamped"]),
            "probe_positions": {name: rounded(posed[name][probes[name]], RESULT_DECIMALS)
                                for name in probes},
        }))
    return document(
        "face-rig.json",
        "Face rig poses: the skin, lips and head shell for lip parameters and jaw openings, from "
        "the rig, jaw and rest meshes in fixtures; neutral, each parameter alone at its extremes, "
        f"closure at three jaw openings and {RANDOM_CASES} random sets drawn uniformly with numpy "
        f"seed {SEED} (draws near a decision skipped); probe_positions are the positions of "
        "fixtures.probe_vertices",
        FORMAT_VERSION, cases,
        constants={"seed": SEED, "random_cases": RANDOM_CASES, "margin_mm": MARGIN_MM},
        tolerances=TOLERANCES,
        fixtures={"rig": rig, "jaw": jaw,
                  "rest": {name: points.ravel().tolist() for name, points in rest.items()},
                  "probe_vertices": probes})


def files():
    return {"face-rig.json": face_document()}
