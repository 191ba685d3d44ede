"""tongue-surface.json, tongue-jaw.json and tongue-bspline.json: the tongue's shared vectors.

- tongue-surface.json: the rig definition (a fixture), then the neutral set, every parameter
  alone at its minimum and at its maximum, and ``RANDOM_CASES`` seeded random sets across every
  range (jaw included). Expected: volume, centroid, bounds and the positions of ``PROBES``
  vertices spread over the surface (tests/test_tongue_vectors.py also compares every vertex of
  every case live, Python against node; storing them all would take megabytes).
- tongue-jaw.json: jaw poses and posed, weighted points.
- tongue-bspline.json: basis tables for the rig's own knot vectors and random clamped ones.

None of them holds a flag that depends on a float: only floats (with tolerances) and integers
that follow from the inputs alone (counts, and spans found by comparing exact input numbers).
"""

import numpy as np

from glasshead.constants import TONGUE_VERTEX_TOLERANCE_MM, TONGUE_VOLUME_RELATIVE_TOLERANCE
from glasshead.geometry.bspline import basis_table, clamped_knots
from glasshead.geometry.jaw import apply_jaw_pose, jaw_pose
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.vectors import sources
from glasshead.vectors.common import case, document, rounded, tolerance

FORMAT_VERSION = 2
#: Seed of the random parameter sets (printed into the file's description).
SEED = 20240923
RANDOM_CASES = 200
PROBES = 32
#: Decimals kept: parameter values are rounded before they are evaluated, results after.
PARAM_DECIMALS = 4
RESULT_DECIMALS = 5

#: Stored results are rounded to RESULT_DECIMALS, so the float64 reference reproduces them
#: within half a unit of the last decimal kept, plus its own last-digit noise (about 1e-13).
STORED = "stored values are rounded to 5 decimals (at most 5e-6 off); the float64 reference " \
         "reproduces them on any CPU within that"
SURFACE_TOLERANCES = {
    "vertex_mm": tolerance(TONGUE_VERTEX_TOLERANCE_MM, "mm",
                           "JavaScript evaluates in float32 (about 4e-6 mm of rounding at 50 mm) "
                           "against the float64 reference; a wrong vertex is off by far more"),
    "normal": tolerance(1e-4, "1", "unit normals from float32 positions in JavaScript"),
    "volume_relative": tolerance(TONGUE_VOLUME_RELATIVE_TOLERANCE, "relative",
                                 "volume summed from float32 positions in JavaScript"),
    "stored_mm": tolerance(1e-5, "mm", STORED),
    "stored_volume_mm3": tolerance(1e-4, "mm3", "the volume is stored rounded to 5 decimals; "
                                                "float64 sums over the mesh differ in the last "
                                                "digits (about 1e-11 mm3) between CPUs"),
}


def rig_and_definition():
    definition = sources.tongue_rig_definition()
    return definition, TongueRig(definition)


def probe_indices(vertex_count, count=PROBES):
    """Both poles and ``count - 2`` ring vertices evenly spread through the vertex list."""
    ring = np.linspace(2, vertex_count - 1, count - 2).round().astype(int)
    return [0, 1] + sorted(set(ring.tolist()))


def parameter_sets(rig, seed=SEED):
    """(description, {name: value}) for the neutral, one-at-a-time extreme and random cases."""
    names = rig.parameter_names
    sets: list[tuple[str, dict[str, float]]] = [
        ("neutral (every parameter at its neutral value)", {})]
    for k, name in enumerate(names):
        for label, value in (("minimum", rig.minimum[k]), ("maximum", rig.maximum[k])):
            sets.append((f"{name} alone at its {label} {value:g}", {name: float(value)}))
    rng = np.random.default_rng(seed)
    for number in range(RANDOM_CASES):
        values = np.round(rng.uniform(rig.minimum, rig.maximum), PARAM_DECIMALS)
        values = np.clip(values, rig.minimum, rig.maximum)
        params = dict(zip(names, values.tolist(), strict=True))
        sets.append((f"random set {number} (seed {seed})", params))
    return sets


def surface_document(definition, rig):
    probes = probe_indices(rig.vertex_count)
    cases = []
    for description, params in parameter_sets(rig):
        surface = rig.evaluate(rig.values_from(params))
        v = surface.vertices
        cases.append(case(description, {"params": params}, {
            "vertex_count": len(v),
            "triangle_count": len(surface.triangles),
            "volume_mm3": round(surface.volume, RESULT_DECIMALS),
            "centroid": rounded(v.mean(axis=0), RESULT_DECIMALS),
            "bounds_min": rounded(v.min(axis=0), RESULT_DECIMALS),
            "bounds_max": rounded(v.max(axis=0), RESULT_DECIMALS),
            "probe_positions": rounded(v[probes], RESULT_DECIMALS),
        }))
    return document(
        "tongue-surface.json",
        "Tongue surfaces of the rig in fixtures: neutral, each parameter at its extremes, and "
        f"{RANDOM_CASES} random parameter sets drawn uniformly within every range with numpy "
        f"seed {SEED}; probe_positions are the positions of fixtures.probe_vertices",
        FORMAT_VERSION, cases,
        constants={"seed": SEED, "random_cases": RANDOM_CASES},
        tolerances=SURFACE_TOLERANCES,
        fixtures={"rig": definition, "probe_vertices": probes})


def jaw_document(definition):
    jaw = definition["jaw"]
    rng = np.random.default_rng(SEED + 1)
    points = np.round(rng.uniform([-60, -50, -30], [30, 20, 30], (8, 3)), 3)
    weights = np.round(rng.uniform(0, 1, 8), 3)
    weights[:2] = (0.0, 1.0)
    openings = [0.0, 5.0, 12.5, 25.0] + np.round(rng.uniform(0, 25, 6), 3).tolist()
    cases = []
    for opening in openings:
        pose = jaw_pose(opening, jaw)
        cases.append(case(f"jaw opened {opening:g} degrees",
                          {"opening_deg": opening, "points": points.tolist(),
                           "weights": weights.tolist()},
                          {"pose": rounded(pose.reshape(-1), RESULT_DECIMALS),
                           "points": rounded(apply_jaw_pose(points, pose, weights),
                                             RESULT_DECIMALS)}))
    return document(
        "tongue-jaw.json",
        "Jaw poses (row-major 3 x 4: rotation entries and, at indices 3, 7 and 11, the "
        f"translation) and points moved by them, each by its weight (seed {SEED + 1})",
        FORMAT_VERSION, cases,
        constants={"seed": SEED + 1},
        tolerances={"rotation": tolerance(1e-5, "1", STORED),
                    "translation_mm": tolerance(1e-5, "mm", STORED),
                    "point_mm": tolerance(1e-5, "mm", STORED)},
        fixtures={"jaw": jaw})


def bspline_document(definition):
    rng = np.random.default_rng(SEED + 2)
    sagittal, coronal = definition["sagittal"], definition["coronal"]
    inputs = [
        ("the rig's closed sagittal curve", sagittal["knots"], sagittal["degree"],
         np.r_[0.0, rng.uniform(0, 1, 30), np.arange(19) / 19]),
        ("the rig's coronal sections (degrees)", coronal["knots"], coronal["degree"],
         np.r_[-90.0, 90.0, rng.uniform(-90, 90, 30), coronal["knots"][4:-4]]),
    ]
    for degree in (1, 2, 3, 4):
        inner = np.sort(rng.uniform(0.05, 0.95, 5))
        inputs.append((f"random clamped knots, degree {degree}",
                       clamped_knots(inner, degree).tolist(), degree,
                       np.r_[0.0, 1.0, inner[2], rng.uniform(0, 1, 12)]))
    cases = []
    for description, knots, degree, params in inputs:
        first, values = basis_table(knots, degree, params)
        cases.append(case(description,
                          {"knots": list(map(float, knots)), "degree": degree,
                           "params": params.tolist()},
                          {"first": first.tolist(), "values": values.tolist()}))
    return document(
        "tongue-bspline.json",
        "B-spline basis tables (The NURBS Book A2.1 and A2.2): for each parameter, the first "
        f"control point it weights and the degree + 1 weights (seed {SEED + 2})",
        FORMAT_VERSION, cases,
        constants={"seed": SEED + 2},
        tolerances={"basis": tolerance(1e-12, "1", "basis weights lie in [0, 1]; the twins' "
                                                   "float64 recurrences round differently in "
                                                   "the last bits (about 1e-16)")})


def files():
    definition, rig = rig_and_definition()
    out = {"tongue-surface.json": surface_document(definition, rig),
           "tongue-jaw.json": jaw_document(definition),
           "tongue-bspline.json": bspline_document(definition)}
    print(f"    tongue-surface.json: seed {SEED}, {len(out['tongue-surface.json']['cases'])} cases")
    return out
