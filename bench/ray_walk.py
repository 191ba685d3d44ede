"""Benchmark: one evaluation of the 3D ray error (1,000 rays, the built tongue rig), against
Embree (trimesh, rebuilt per evaluation since the tongue changes), a naive numpy walk and brute
force, all in the same run.

Consecutive poses differ a little, as in an optimisation (each parameter moves by 1 % of its
range per step from a random start). The rig evaluation itself (vertices) is not timed in the
error; its time is printed apart. Prints medians, ratios, the share of rays certified by the
crossing count (the rest go through the sphere hierarchy or, when few, an exhaustive test), the
size of the back-facing set B, the share of rays that fell back to the unbounded search and the
naive walk's wrong answers.

    .venv/bin/python bench/ray_walk.py [steps]
    GLASSHEAD_BENCH_QUICK=1: 11 steps (brute force on 2 of them).
"""

import json
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np
import trimesh
from trimesh.ray.ray_pyembree import RayMeshIntersector

from glasshead.fitting.first_hits import exhaustive_first_hits
from glasshead.fitting.objective3d import RayError3D
from glasshead.fitting.ray_walk import RayWalker

REPO = Path(__file__).resolve().parents[1]
RAYS = 1000
GOAL_MS = 2.0
QUICK = os.environ.get("GLASSHEAD_BENCH_QUICK") == "1"


def timed(fn):
    start = time.perf_counter()
    out = fn()
    return (time.perf_counter() - start) * 1e3, out


def embree_first(vertices, triangles, origin, directions):
    mesh = trimesh.Trimesh(vertices, triangles, process=False)
    caster = RayMeshIntersector(mesh)
    return caster.intersects_first(np.repeat(origin[None], len(directions), 0), directions)


def main():
    steps = int(sys.argv[1]) if len(sys.argv) > 1 else (11 if QUICK else 60)
    path = REPO / "assets" / "build" / "tongue-rig.json"
    if not path.is_file():
        sys.exit(f"{path} is missing: run `glasshead build` first")
    from glasshead.geometry.tongue_surface import TongueRig
    rig = TongueRig(json.loads(path.read_text()))
    rest = rig.vertices(rig.neutral)
    origin = np.r_[rig.hub, 0.0]
    rng = np.random.default_rng(2024)
    observed = rest[rng.choice(len(rest), RAYS, replace=False)] + rng.normal(0, 0.5, (RAYS, 3))
    directions = observed - origin
    error = RayError3D(rig.triangles, rest, observed, origin)
    naive = RayWalker(rig.triangles, rest)

    values = rng.uniform(rig.minimum, rig.maximum)
    span = rig.maximum - rig.minimum
    error(rig.vertices(values))  # the exhaustive start
    naive_prev = error.previous.copy()
    times = {"ours": [], "embree": [], "naive": [], "brute": [], "rig": []}
    fallback = overturned = naive_wrong = embree_wrong = shortcut = 0
    back = []
    worst_naive_mm = 0.0
    for step in range(steps):
        values = np.clip(values + rng.normal(0.0, 0.01, values.shape) * span,
                         rig.minimum, rig.maximum)
        ms, vertices = timed(lambda v=values: rig.vertices(v))
        times["rig"].append(ms)
        ms, _ = timed(lambda v=vertices: error(v))
        times["ours"].append(ms)
        hits = error.hits
        fallback += int(hits.fallback.sum())
        overturned += int(hits.overturned.sum())
        shortcut += int(hits.shortcut.sum())
        back.append(hits.back_facing)
        ms, (tri_n, t_n) = timed(lambda v=vertices, s=naive_prev: naive.naive_walk(
            origin, directions, v, s))
        times["naive"].append(ms)
        naive_prev = np.where(tri_n >= 0, tri_n, naive_prev)
        ms, tri_e = timed(lambda v=vertices: embree_first(v, rig.triangles, origin, directions))
        times["embree"].append(ms)
        if step % 10 == 0:  # brute force is slow: time it on a few poses
            ms, (tri_b, t_b) = timed(lambda v=vertices: exhaustive_first_hits(
                origin, directions, v, rig.triangles))
            times["brute"].append(ms)
            assert np.array_equal(tri_b, hits.triangle), "walk differs from the exhaustive search"
        wrong = tri_n != hits.triangle
        naive_wrong += int(wrong.sum())
        embree_wrong += int((tri_e != hits.triangle).sum())
        both = wrong & np.isfinite(t_n) & np.isfinite(hits.t)
        if np.any(both):
            gap = np.abs(t_n - hits.t)[both] * np.linalg.norm(directions[both], axis=1)
            worst_naive_mm = max(worst_naive_mm, float(gap.max()))

    med = {k: statistics.median(v) for k, v in times.items()}
    total = steps * RAYS
    print(f"3D ray error, {RAYS} rays, {len(rig.triangles)} triangles, {steps} poses "
          f"1 % of each range apart")
    print(f"  ours (walk + certificates) {med['ours']:7.2f} ms   goal <= {GOAL_MS} ms: "
          f"{'met' if med['ours'] <= GOAL_MS else 'NOT met'}")
    print(f"  Embree (trimesh, rebuilt)  {med['embree']:7.2f} ms   ours / Embree "
          f"{med['ours'] / med['embree']:.2f}")
    print(f"  naive numpy walk           {med['naive']:7.2f} ms   ours / naive "
          f"{med['ours'] / med['naive']:.2f}")
    print(f"  brute force                {med['brute']:7.2f} ms   ours / brute "
          f"{med['ours'] / med['brute']:.3f}")
    print(f"  (rig evaluation, not in the error: {med['rig']:.2f} ms)")
    print(f"  certified by the crossing count {shortcut / total:.3%} of rays; |B| (triangles not "
          f"facing away from O) median {statistics.median(back):.0f}, range {min(back)} to "
          f"{max(back)} of {len(rig.triangles)}")
    print(f"  fallback share {fallback / total:.3%}, walks overturned by the certificates "
          f"{overturned / total:.3%}")
    print(f"  naive walk wrong on {naive_wrong / total:.3%} of rays (worst {worst_naive_mm:.1f} mm)"
          f"; Embree's first triangle differs on {embree_wrong / total:.3%} (float32, edges)")


if __name__ == "__main__":
    main()
