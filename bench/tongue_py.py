"""Benchmark: the Python reference tongue evaluator (numpy), surface with normals.

Times ``TongueRig.surface`` without the volume (vertices + normals, as the JS benchmark does)
over seeded random parameter sets, and prints the median per surface. ``--json`` prints one JSON
line instead (bench/tongue.bench.mjs reads it).

    .venv/bin/python bench/tongue_py.py [--runs N] [--json]
    GLASSHEAD_BENCH_QUICK=1: 20 runs.
"""

import argparse
import json
import os
import statistics
import time
from pathlib import Path

import numpy as np

from glasshead.geometry.mesh_volume import vertex_normals
from glasshead.geometry.tongue_surface import TongueRig

REPO = Path(__file__).resolve().parents[1]
SEED = 1998
QUICK = os.environ.get("GLASSHEAD_BENCH_QUICK") == "1"


def load_definition():
    """The built rig, else the one embedded in the shared vectors; returns (definition, source)."""
    built = REPO / "assets" / "build" / "tongue-rig.json"
    if built.is_file():
        return json.loads(built.read_text()), str(built.relative_to(REPO))
    vectors = REPO / "tests" / "vectors" / "tongue-surface.json"
    return json.loads(vectors.read_text())["fixtures"]["rig"], \
        str(vectors.relative_to(REPO)) + " (rig)"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=20 if QUICK else 300)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    definition, source = load_definition()
    rig = TongueRig(definition)
    rng = np.random.default_rng(SEED)
    sets = rng.uniform(rig.minimum, rig.maximum, (64, len(rig.neutral)))
    for values in sets[:10]:  # warm-up
        vertex_normals(rig.vertices(values), rig.triangles)
    times = []
    for run in range(args.runs):
        values = sets[run % len(sets)]
        start = time.perf_counter()
        vertices = rig.vertices(values)
        vertex_normals(vertices, rig.triangles)
        times.append((time.perf_counter() - start) * 1e3)
    median = statistics.median(times)
    if args.json:
        print(json.dumps({"median_ms": median, "vertices": rig.vertex_count, "runs": args.runs,
                          "source": source}))
    else:
        print(f"rig: {source}")
        print(f"Python (numpy) tongue surface + normals: median {median:.3f} ms over {args.runs} "
              f"runs, {rig.vertex_count} vertices, {len(rig.triangles)} triangles")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
