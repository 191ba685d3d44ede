"""Benchmark: 3D surface fits of the tongue rig to VocalTractLab's tongue sheets.

Three comparisons, each against a baseline measured in the same run:

1. the objective: one evaluation of ``Objective3D`` on /a/ (rig surface, walked first hits of
   every ray, whose certificate sums the volume on the way) against the same error from the
   exhaustive first hits (``ray_walk.exhaustive_first_hits``, the definition), checked equal
   on the way;
2. the methods: PRAXIS and SBPLX against BOBYQA over the same shapes, each from the shape's
   mid-sagittal fit: median evaluations, wall and CPU seconds and RMS per fit, and the ratio of
   each median to BOBYQA's;
3. the start: BOBYQA from neutral (the jaw from VTL) against BOBYQA from the 2D fit.

    .venv/bin/python bench/fit3d.py [--shapes all|vowels|a,i,u] [--runs N] [--table] [--json]

``--table`` also prints every shape's fit (BOBYQA from the 2D fit) as a markdown table row,
with the RMS of three regions of the sheet (``regions``); ``--methods bobyqa`` fits with
BOBYQA alone (no comparison), for the table of every shape.
Wall seconds depend on the shared machine's load; CPU seconds (the process's) much less.
GLASSHEAD_BENCH_QUICK=1: the shape /a/ alone, BOBYQA alone, 10 runs of the objective.
"""

import argparse
import json
import os
import statistics
import time
from pathlib import Path

import numpy as np

from glasshead.fitting.first_hits import exhaustive_first_hits
from glasshead.fitting.fit2d import load_inputs
from glasshead.fitting.fit3d import (
    VTL_POINTS,
    VTL_RIBS,
    FitReport3D,
    Objective3D,
    fit_all3d,
    free_groups,
    shape_vertices,
    visible_mask,
)
from glasshead.fitting.objective2d import MidSagittalSection
from glasshead.fitting.objective3d import RayError3D
from glasshead.fitting.optimizer import METHODS
from glasshead.fitting.vtl_mapping import jaw_opening_from_vtl

REPO = Path(__file__).resolve().parents[1]
SEED = 1998
BASELINE_METHOD = "bobyqa"
QUICK = os.environ.get("GLASSHEAD_BENCH_QUICK") == "1"
#: Poses of the objective benchmark: each variable moved by up to this fraction of its range
#: from the last pose, as a fit's successive evaluations move.
STEP_FRACTION = 0.01
#: The goal for a full 3D fit, its 2D start included: CPU seconds.
GOAL_SECONDS = 5.0


def median_ms(fn, runs):
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return 1000 * statistics.median(times)


def bench_objective(rig, shape, runs):
    section = MidSagittalSection(rig)
    base = rig.neutral.copy()
    base[rig.jaw_parameter] = jaw_opening_from_vtl(shape, rig)
    origin = np.append(rig.control_points(base)[1], 0.0)
    vertices = shape_vertices(shape)
    mask = visible_mask(vertices, origin, grid=(VTL_RIBS, VTL_POINTS))
    objective = Objective3D(rig, vertices, mask, free_groups(rig), base=base, origin=origin,
                            section=section)
    rng = np.random.default_rng(SEED)
    span = objective.upper - objective.lower
    xs = [objective.x0]
    for _ in range(63):
        xs.append(np.clip(xs[-1] + rng.uniform(-STEP_FRACTION, STEP_FRACTION, len(span)) * span,
                          objective.lower, objective.upper))
    state = {"k": 0}

    def next_x():
        state["k"] += 1
        return xs[state["k"] % len(xs)]

    surface = rig.vertices(objective.values(xs[5]))
    objective.error.residuals(rig.vertices(objective.values(xs[4])))
    walked = objective.error.residuals(surface)
    error = objective.error
    triangle, t = exhaustive_first_hits(error.origin, error.directions, surface, rig.triangles)
    exhaustive = np.where(triangle >= 0, (t - 1.0) * error.length, error.penalty)
    assert np.array_equal(walked, exhaustive), "walked and exhaustive residuals differ"

    def exhaustive_error():
        v = rig.vertices(objective.values(next_x()))
        tri, tt = exhaustive_first_hits(error.origin, error.directions, v, rig.triangles)
        return np.where(tri >= 0, (tt - 1.0) * error.length, error.penalty)

    rows = {
        "surface_ms": median_ms(lambda: rig.vertices(objective.values(next_x())), runs),
        "residuals_ms": median_ms(
            lambda: error.residuals(rig.vertices(objective.values(next_x()))), runs),
        "objective_ms": median_ms(lambda: objective(next_x()), runs),
        "exhaustive_ms": median_ms(exhaustive_error, max(1 if QUICK else 3, runs // 50)),
        "rays": len(error.directions),
        "triangles": len(rig.triangles),
    }
    return rows


def regions(rig, shape, report):
    """RMS (mm) of the fitted residuals in three regions of a VTL sheet's compared vertices:
    the root (behind the origin and below its horizontal, above the root cut), the lateral
    margins (each rib's two outer points, elsewhere) and the rest of the upper surface."""
    values = rig.values_from(report.params)
    origin = np.asarray(report.origin)
    vertices = shape_vertices(shape)
    mask = visible_mask(vertices, origin, grid=(VTL_RIBS, VTL_POINTS))
    error = RayError3D(rig.triangles, rig.vertices(values), vertices[mask], origin)
    r = error.residuals(rig.vertices(values))
    offset = vertices[mask] - origin
    across = np.tile(np.arange(VTL_POINTS), VTL_RIBS)[mask]
    root = (offset[:, 0] < 0) & (offset[:, 1] < 0)
    margin = ~root & ((across == 0) | (across == VTL_POINTS - 1))
    rest = ~root & ~margin

    def rms(part):
        return float(np.sqrt(np.mean(r[part] ** 2))) if part.any() else float("nan")

    assert abs(rms(np.ones(len(r), dtype=bool)) - report.rms_mm) < 1e-9
    return {"root": rms(root), "margins": rms(margin), "upper": rms(rest),
            "root_rays": int(root.sum())}


def pick(observations, which):
    shapes = observations["shapes"]
    if which == "all":
        return [s["name"] for s in shapes]
    if which == "vowels":
        return [s["name"] for s in shapes if s["class"]["kind"] == "vowel"]
    return which.split(",")


def summarise(reports: list[FitReport3D]):
    return {
        "fits": len(reports),
        "evaluations": statistics.median(r.evaluations for r in reports),
        "seconds": statistics.median(r.seconds for r in reports),
        "cpu_seconds": statistics.median(r.cpu_seconds for r in reports),
        "total_cpu_seconds": statistics.median(r.cpu_seconds + r.start_cpu_seconds
                                               for r in reports),
        "most_total_cpu_seconds": max(r.cpu_seconds + r.start_cpu_seconds for r in reports),
        "over_goal_seconds": sum(r.cpu_seconds + r.start_cpu_seconds > GOAL_SECONDS
                                 for r in reports),
        "rms_mm": statistics.median(r.rms_mm for r in reports),
        "within_1_5mm": sum(r.rms_mm <= 1.5 for r in reports),
        "at_max_evals": sum(r.stop == "max evaluations reached" for r in reports),
    }


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shapes", default="a" if QUICK else "a,e,i,o,u")
    parser.add_argument("--runs", type=int, default=10 if QUICK else 200)
    parser.add_argument("--table", action="store_true")
    parser.add_argument("--json", action="store_true")
    parser.add_argument("--methods", default=BASELINE_METHOD if QUICK else ",".join(METHODS))
    args = parser.parse_args(argv)
    rig, observations = load_inputs(REPO / "assets" / "build")
    by_name = {s["name"]: s for s in observations["shapes"]}

    compare = args.methods.split(",") != [BASELINE_METHOD]
    objective = bench_objective(rig, by_name["a"], args.runs)
    names = pick(observations, args.shapes)
    order = [BASELINE_METHOD] + [m for m in args.methods.split(",") if m != BASELINE_METHOD]
    reports = {m: fit_all3d(rig, observations, method=m, names=names) for m in order}
    methods = {m: summarise(r) for m, r in reports.items()}
    neutral = []
    if compare:
        neutral = fit_all3d(rig, observations, method=BASELINE_METHOD, names=names,
                            from_2d=False)
        methods["bobyqa, from neutral"] = summarise(neutral)
    base = methods[BASELINE_METHOD]
    if args.json:
        print(json.dumps({"objective": objective, "methods": methods,
                          "fits": {m: [r.to_json() for r in rs] for m, rs in reports.items()},
                          "from_neutral": [r.to_json() for r in neutral]}))
        return 0

    o = objective
    print(f"objective on /a/ ({o['rays']} rays, {o['triangles']} triangles), medians per "
          f"evaluation, poses {STEP_FRACTION:.0%} of each range apart:")
    print(f"  surface {o['surface_ms']:.2f} ms; surface + walked first hits "
          f"{o['residuals_ms']:.2f} ms (the volume with them); objective "
          f"{o['objective_ms']:.2f} ms")
    print(f"  surface + exhaustive first hits {o['exhaustive_ms']:.1f} ms: walked "
          f"{o['exhaustive_ms'] / o['residuals_ms']:.0f}x faster (residuals equal)")
    print(f"fits over {len(names)} shapes ({args.shapes}), medians per fit; ratio to "
          f"{BASELINE_METHOD} from the 2D fit:")
    for m, s in methods.items():
        evals, cpu = s["evaluations"] / base["evaluations"], s["cpu_seconds"] / base["cpu_seconds"]
        print(f"  {m:20s} {s['evaluations']:6.0f} evals ({evals:.2f}x)  {s['seconds']:5.2f} s "
              f"wall, {s['cpu_seconds']:5.2f} s CPU ({cpu:.2f}x; with the 2D fit "
              f"{s['total_cpu_seconds']:.2f} s, at most {s['most_total_cpu_seconds']:.2f} s, "
              f"{s['over_goal_seconds']} over {GOAL_SECONDS:g} s)  RMS {s['rms_mm']:.2f} mm  "
              f"within 1.5 mm {s['within_1_5mm']}/{s['fits']}  at max evals {s['at_max_evals']}")
    if args.table:
        print("\n| shape | RMS (mm) | from (mm) | root / margins / upper (mm) | max (mm) | "
              "volume (%) | evals | CPU s (with 2D) | at a limit |")
        print("|---|---|---|---|---|---|---|---|---|")
        for r in reports[BASELINE_METHOD]:
            g = regions(rig, by_name[r.shape], r)
            print(f"| `{r.shape}` | {r.rms_mm:.2f} | {r.start_rms_mm:.2f} | "
                  f"{g['root']:.1f} / {g['margins']:.1f} / {g['upper']:.1f} | "
                  f"{r.max_error_mm:.1f} | {r.volume_change_pct:+.1f} | {r.evaluations} | "
                  f"{r.cpu_seconds:.2f} ({r.cpu_seconds + r.start_cpu_seconds:.2f}) | "
                  f"{', '.join(r.at_limit)} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
