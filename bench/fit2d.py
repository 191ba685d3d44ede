"""Benchmark: mid-sagittal fits of the tongue rig to VocalTractLab's outlines.

Two comparisons, each against a baseline measured in the same run:

1. the objective: one evaluation of ``Objective2D`` (rig section + ray crossings, with and
   without the volume penalty) against a naive per-ray Python loop over the section's segments,
   and against testing every ray against every segment in numpy (``Rays.crossings_all``);
2. the methods: PRAXIS and SBPLX against BOBYQA over the same shapes: median evaluations, time
   and RMS error per fit, and the ratio of each median to BOBYQA's.

    .venv/bin/python bench/fit2d.py [--shapes all|vowels|a,i,u] [--runs N] [--table] [--json]
        [--methods bobyqa,praxis,sbplx]

``--table`` also prints every shape's fit (BOBYQA) as a markdown table row.
GLASSHEAD_BENCH_QUICK=1: the shape /a/ alone, BOBYQA alone, 20 runs of the objective.
"""

import argparse
import json
import os
import statistics
import time
from pathlib import Path

import numpy as np

from glasshead.fitting.fit2d import (
    NEUTRAL_WEIGHT,
    VOLUME_BOUND_PCT,
    VOLUME_BOUND_WEIGHT,
    VOLUME_WEIGHT,
    FitReport,
    fit_all,
    load_inputs,
)
from glasshead.fitting.objective2d import MidSagittalSection, Objective2D
from glasshead.fitting.optimizer import METHODS

REPO = Path(__file__).resolve().parents[1]
SEED = 1998
BASELINE_METHOD = "bobyqa"
QUICK = os.environ.get("GLASSHEAD_BENCH_QUICK") == "1"


def naive_crossings(rays, polyline):
    """Per ray, every segment in plain Python: the crossing nearest the observed point."""
    ox, oy = rays.origin
    points = [(float(x) - ox, float(y) - oy) for x, y in polyline]
    points.append(points[0])
    out = []
    for (dx, dy), r in zip(rays.directions.tolist(), rays.distances.tolist(), strict=True):
        best, gap = 0.0, float("inf")
        for (ax, ay), (bx, by) in zip(points[:-1], points[1:], strict=True):
            sa, sb = dx * ay - dy * ax, dx * by - dy * bx
            if sa * sb > 0 or sa == sb:
                continue
            s = sa / (sa - sb)
            t = dx * (ax + s * (bx - ax)) + dy * (ay + s * (by - ay))
            if t > 0 and abs(t - r) < gap:
                best, gap = t, abs(t - r)
        out.append(best)
    return np.array(out)


def median_ms(fn, runs):
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return 1000 * statistics.median(times)


def bench_objective(rig, shape, runs):
    section = MidSagittalSection(rig)
    free = [p for p in rig.parameter_names if rig.parameters[p]["group"] == "tongue sagittal"]
    plain = Objective2D(rig, shape["tongue_outline"], free, section=section)
    weighted = Objective2D(rig, shape["tongue_outline"], free, section=section,
                           volume_weight=VOLUME_WEIGHT, neutral_weight=NEUTRAL_WEIGHT,
                           volume_bound_pct=VOLUME_BOUND_PCT,
                           volume_bound_weight=VOLUME_BOUND_WEIGHT)
    rng = np.random.default_rng(SEED)
    xs = rng.uniform(plain.lower, plain.upper, (32, len(free)))
    state = {"k": 0}

    def next_x():
        state["k"] += 1
        return xs[state["k"] % len(xs)]

    polyline = section.outline(plain.values(xs[0]))
    fast = plain.rays.crossings(polyline)
    assert np.allclose(fast, naive_crossings(plain.rays, polyline), atol=1e-9)
    rows = {
        "section_ms": median_ms(lambda: section.outline(plain.values(next_x())), runs),
        "crossings_ms": median_ms(lambda: plain.rays.crossings(polyline), runs),
        "crossings_all_ms": median_ms(lambda: plain.rays.crossings_all(polyline), runs),
        "crossings_naive_ms": median_ms(lambda: naive_crossings(plain.rays, polyline),
                                        max(1 if QUICK else 5, runs // 20)),
        "objective_ms": median_ms(lambda: plain(next_x()), runs),
        "objective_volume_ms": median_ms(lambda: weighted(next_x()), runs),
        "rays": len(plain.rays.points),
        "segments": len(polyline),
    }
    rows["objective_naive_ms"] = rows["section_ms"] + rows["crossings_naive_ms"]
    return rows


def pick(observations, which):
    shapes = observations["shapes"]
    if which == "all":
        return [s["name"] for s in shapes]
    if which == "vowels":
        return [s["name"] for s in shapes if s["class"]["kind"] == "vowel"]
    return which.split(",")


def summarise(reports: list[FitReport]):
    return {
        "fits": len(reports),
        "evaluations": statistics.median(r.evaluations for r in reports),
        "seconds": statistics.median(r.seconds for r in reports),
        "rms_mm": statistics.median(r.rms_mm for r in reports),
        "within_1mm": sum(r.rms_mm <= 1.0 for r in reports),
        "at_max_evals": sum(r.stop == "max evaluations reached" for r in reports),
    }


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shapes", default="a" if QUICK else "vowels")
    parser.add_argument("--runs", type=int, default=20 if QUICK else 400)
    parser.add_argument("--table", action="store_true")
    parser.add_argument("--json", action="store_true")
    parser.add_argument("--methods", default=BASELINE_METHOD if QUICK else ",".join(METHODS))
    args = parser.parse_args(argv)
    rig, observations = load_inputs(REPO / "assets" / "build")
    by_name = {s["name"]: s for s in observations["shapes"]}

    objective = bench_objective(rig, by_name["a"], args.runs)
    names = pick(observations, args.shapes)
    order = [BASELINE_METHOD] + [m for m in args.methods.split(",") if m != BASELINE_METHOD]
    reports = {m: fit_all(rig, observations, method=m, names=names) for m in order}
    methods = {m: summarise(r) for m, r in reports.items()}
    base = methods[BASELINE_METHOD]
    if args.json:
        print(json.dumps({"objective": objective, "methods": methods,
                          "fits": {m: [r.to_json() for r in rs] for m, rs in reports.items()}}))
        return 0

    o = objective
    print(f"objective on /a/ ({o['rays']} rays, {o['segments']}-segment section), medians:")
    print(f"  section {o['section_ms']:.3f} ms; crossings {o['crossings_ms']:.3f} ms "
          f"(every segment, numpy {o['crossings_all_ms']:.3f} ms, "
          f"per-ray Python loop {o['crossings_naive_ms']:.1f} ms: "
          f"{o['crossings_naive_ms'] / o['crossings_ms']:.0f}x)")
    print(f"  objective {o['objective_ms']:.3f} ms, with the volume penalty "
          f"{o['objective_volume_ms']:.3f} ms; naive {o['objective_naive_ms']:.1f} ms: "
          f"{o['objective_naive_ms'] / o['objective_ms']:.0f}x faster")
    print(f"methods over {len(names)} shapes ({args.shapes}), medians per fit; ratio to "
          f"{BASELINE_METHOD}:")
    for m, s in methods.items():
        evals, seconds = s["evaluations"] / base["evaluations"], s["seconds"] / base["seconds"]
        print(f"  {m:7s} {s['evaluations']:7.0f} evals ({evals:.2f}x)  {s['seconds']:6.2f} s "
              f"({seconds:.2f}x)  "
              f"RMS {s['rms_mm']:.2f} mm  within 1 mm {s['within_1mm']}/{s['fits']}  "
              f"at max evals {s['at_max_evals']}")
    if args.table:
        print("\n| shape | RMS (mm) | max (mm) | volume (%) | evals | s | at a limit |")
        print("|---|---|---|---|---|---|---|")
        for r in reports[BASELINE_METHOD]:
            print(f"| `{r.shape}` | {r.rms_mm:.2f} | {r.max_error_mm:.1f} | "
                  f"{r.volume_change_pct:+.1f} | {r.evaluations} | {r.seconds:.2f} | "
                  f"{', '.join(r.at_limit)} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
