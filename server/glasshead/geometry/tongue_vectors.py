"""Documents of the tongue's shared test vectors (registered in ``geometry.vectors``).

- tongue-surface.json: the rig definition itself, then the neutral set, every parameter alone at
  its minimum and at its maximum, and ``RANDOM_CASES`` seeded random sets across every range
  (jaw included). Expected: volume, centroid, bounds and the positions of ``PROBES`` vertices
  spread over the surface (every vertex of every case is compared live, Python against node, by
  tests/test_tongue_vectors.py; storing them all would take megabytes).
- tongue-jaw.json: jaw poses and posed, weighted points.
- tongue-bspline.json: basis tables for the rig's own knot vectors and random clamped ones.
"""

import numpy as np

from glasshead.constants import TONGUE_VERTEX_TOLERANCE_MM, TONGUE_VOLUME_RELATIVE_TOLERANCE
from glasshead.geometry.bspline import basis_table, clamped_knots
from glasshead.geometry.jaw import apply_jaw_pose, jaw_pose

#: Seed of the random parameter sets (printed into the file's description).
SEED = 20240923
RANDOM_CASES = 200
PROBES = 32
#: Decimals kept: parameter values are rounded before they are evaluated, results after.
PARAM_DECIMALS = 4
RESULT_DECIMALS = 5

GENERATOR = "python -m glasshead.geometry.vectors"


def _rig():
    """The built rig (rebuilt first if its inputs changed) and its evaluator."""
    from glasshead.asset_store import AssetStore
    from glasshead.pipeline.tongue_rig import build_tongue_rig
    from glasshead.settings import get_settings

    settings = get_settings()
    build_tongue_rig(settings.data_dir, settings.assets_dir)
    rig = AssetStore(settings.assets_dir).get("tongue_rig")
    return rig.definition, rig


def probe_indices(vertex_count, count=PROBES):
    """Both poles and ``count - 2`` ring vertices evenly spread through the vertex list."""
    ring = np.linspace(2, vertex_count - 1, count - 2).round().astype(int)
    return [0, 1] + sorted(set(ring.tolist()))


def parameter_sets(rig, seed=SEED):
    """(description, {name: value}) for the neutral, one-at-a-time extreme and random cases."""
    names = rig.parameter_names
    sets = [("neutral (every parameter at its neutral value)", {})]
    for k, name in enumerate(names):
        for label, value in (("minimum", rig.minimum[k]), ("maximum", rig.maximum[k])):
            sets.append((f"{name} alone at its {label} {value:g}", {name: float(value)}))
    rng = np.random.default_rng(seed)
    for case in range(RANDOM_CASES):
        values = np.round(rng.uniform(rig.minimum, rig.maximum), PARAM_DECIMALS)
        values = np.clip(values, rig.minimum, rig.maximum)
        sets.append((f"random set {case} (seed {seed})",
                     dict(zip(names, values.tolist()))))
    return sets


def _round(values):
    return np.round(np.asarray(values, dtype=np.float64), RESULT_DECIMALS).tolist()


def surface_document():
    definition, rig = _rig()
    probes = probe_indices(rig.vertex_count)
    cases = []
    for description, params in parameter_sets(rig):
        surface = rig.evaluate(rig.values_from(params))
        v = surface.vertices
        cases.append({
            "description": description,
            "input": {"params": params},
            "expected": {
                "vertex_count": len(v),
                "triangle_count": len(surface.triangles),
                "volume_mm3": round(surface.volume, RESULT_DECIMALS),
                "centroid": _round(v.mean(axis=0)),
                "bounds_min": _round(v.min(axis=0)),
                "bounds_max": _round(v.max(axis=0)),
                "probe_positions": _round(v[probes]),
            },
        })
    print(f"tongue-surface.json: seed {SEED}, {len(cases)} cases")
    return {
        "description": f"Tongue surfaces of the embedded rig: neutral, each parameter at its "
                       f"extremes, and {RANDOM_CASES} random parameter sets drawn uniformly "
                       f"within every range with numpy seed {SEED}",
        "generator": GENERATOR + " tongue-surface.json",
        "seed": SEED,
        "tolerance": {"vertex_mm": TONGUE_VERTEX_TOLERANCE_MM,
                      "volume_relative": TONGUE_VOLUME_RELATIVE_TOLERANCE},
        "probe_vertices": probes,
        "rig": definition,
        "cases": cases,
    }


def jaw_document():
    definition, _ = _rig()
    jaw = definition["jaw"]
    rng = np.random.default_rng(SEED + 1)
    points = np.round(rng.uniform([-60, -50, -30], [30, 20, 30], (8, 3)), 3)
    weights = np.round(rng.uniform(0, 1, 8), 3)
    weights[:2] = (0.0, 1.0)
    openings = [0.0, 5.0, 12.5, 25.0] + np.round(rng.uniform(0, 25, 6), 3).tolist()
    cases = []
    for opening in openings:
        pose = jaw_pose(opening, jaw)
        cases.append({
            "description": f"jaw opened {opening:g} degrees",
            "input": {"opening_deg": opening, "points": points.tolist(), "weights": weights.tolist()},
            "expected": {"pose": _round(pose.reshape(-1)),
                         "points": _round(apply_jaw_pose(points, pose, weights))},
        })
    return {"description": "Jaw poses (row-major 3 x 4) and points moved by them, each by its "
                           f"weight (seed {SEED + 1})",
            "generator": GENERATOR + " tongue-jaw.json", "jaw": jaw, "cases": cases}


def bspline_document():
    definition, _ = _rig()
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
        cases.append({"description": description,
                      "input": {"knots": list(map(float, knots)), "degree": degree,
                                "params": params.tolist()},
                      "expected": {"first": first.tolist(), "values": values.tolist()}})
    return {"description": "B-spline basis tables (The NURBS Book A2.1 and A2.2): for each "
                           "parameter, the first control point it weights and the degree + 1 "
                           f"weights (seed {SEED + 2})",
            "generator": GENERATOR + " tongue-bspline.json", "cases": cases}
