"""Exactness report of the collision correction over 1,000 seeded random tongue poses.

Every parameter of the tongue rig, the jaw included, is drawn uniformly over its range. Each pose
is corrected by the Python twin (``glasshead.geometry.collision``) against the built tables, and
every vertex is judged against the exact scene maxilla with Embree raycasts from O (trimesh):
"inside" means the ray from O toward the vertex crosses the maxilla before reaching it. The
built files are read by the server's own readers (``glasshead.asset_store``: the quantised GLB
dequantised with its node transform), and the maxilla is first checked against the liner's node
radii, so that the reference is the surface the tables were built from.

Prints: the worst depth left inside after correction, innocent vertices moved (outside before,
changed after), vertices left inside, the vertices corrected per pose, and the accuracy of the
paper's bilinear liner against the real surface at every direction where the tongue touched it
(the resolution requirement: within 0.2 mm).

    .venv/bin/python bench/collision_exactness.py [poses] [seed]
    GLASSHEAD_BENCH_QUICK=1: 60 poses, a seventh of the liner's nodes.
"""

import os
import sys
import time
from pathlib import Path

import numpy as np
import trimesh

from glasshead.asset_store import read_glb_mesh, read_manifest, read_tongue_rig
from glasshead.constants import CELL_EMPTY, CELL_PLANE, COLLISION_TOL
from glasshead.geometry.collision import correct_vertices
from glasshead.geometry.collision_format import decode_collision_tables
from glasshead.pipeline.collision_tables import TABLES_FILE
from glasshead.settings import get_settings

LINER_GOAL_MM = 0.2
#: Corner radii of one cell further apart than this mark a jump of the surface inside the cell.
JUMP_MM = 1.0
QUICK = os.environ.get("GLASSHEAD_BENCH_QUICK") == "1"


def built(name):
    path = Path(get_settings().assets_dir) / name
    if not path.is_file():
        sys.exit(f"{path} is missing: run `glasshead build` first")
    return path


def scene_maxilla():
    manifest = read_manifest(built("manifest.json").read_bytes())
    entry = next(m for m in manifest["meshes"] if m["name"] == "maxilla" and m.get("scene", True))
    vertices, faces = read_glb_mesh(built(entry["file"]).read_bytes())
    return trimesh.Trimesh(vertices, faces, process=False)


def node_agreement(tables, mesh, origin, stride):
    """Every ``stride``-th liner node's ray against the mesh: (rays, how many first hits differ
    from the node's radius by more than COLLISION_TOL.surface, the worst finite difference)."""
    liner = tables.header["liner"]
    radius = tables["node_radius"].astype(np.float64)
    j, i = np.divmod(np.arange(0, radius.size, stride), radius.shape[1])
    lon, lat = liner["lon0"] + i * liner["step"], liner["lat0"] + j * liner["step"]
    directions = np.stack([np.sin(lon) * np.cos(lat), np.cos(lon) * np.cos(lat), np.sin(lat)],
                          axis=1)
    hit = first_hit_radius(mesh, origin, origin + directions)
    expected = radius[j, i]
    with np.errstate(invalid="ignore"):  # inf - inf where both rays miss
        gap = np.abs(hit - expected)
    same = (hit == expected) | (gap <= COLLISION_TOL.surface)
    finite = np.isfinite(gap)
    worst = float(np.max(gap[finite])) if finite.any() else 0.0
    return len(hit), int(np.sum(~same)), worst


def first_hit_radius(mesh, origin, points):
    d = points - origin
    r = np.linalg.norm(d, axis=1)
    hit, ray, _ = mesh.ray.intersects_location(np.tile(origin, (len(d), 1)), d / r[:, None],
                                               multiple_hits=False)
    out = np.full(len(d), np.inf)
    out[ray] = np.linalg.norm(hit - origin, axis=1)
    return out


def liner_accuracy(tables, origin, directions, exact):
    """Bilinear liner radius minus the exact radius at directions (n, 3) with exact hits, and
    whether each direction's cell is smooth (a plane cell whose four corner rays all hit)."""
    liner = tables.header["liner"]
    theta = np.arctan2(directions[:, 0], directions[:, 1])
    phi = np.arctan2(directions[:, 2], np.hypot(directions[:, 0], directions[:, 1]))
    u = (theta - liner["lon0"]) / liner["step"]
    w = (phi - liner["lat0"]) / liner["step"]
    i, j = np.floor(u).astype(int), np.floor(w).astype(int)
    fu, fw = u - i, w - j
    r = tables["node_radius"].astype(np.float64)
    corners = np.stack([r[j, i], r[j, i + 1], r[j + 1, i], r[j + 1, i + 1]], axis=1)
    with np.errstate(invalid="ignore"):
        value = ((1 - fw) * ((1 - fu) * corners[:, 0] + fu * corners[:, 1])
                 + fw * ((1 - fu) * corners[:, 2] + fu * corners[:, 3]))
    # A cell is continuous when its four corner rays hit and their radii differ by less than
    # a millimetre; otherwise the surface jumps inside it (a silhouette or a ray that misses).
    with np.errstate(invalid="ignore"):
        spread = corners.max(axis=1) - corners.min(axis=1)
    continuous = np.all(np.isfinite(corners), axis=1) & (spread < JUMP_MM)
    return value - exact, continuous, tables["cell_kind"][j, i]


def main(argv):
    poses = int(argv[0]) if argv else (60 if QUICK else 1000)
    seed = int(argv[1]) if len(argv) > 1 else 1998
    tables = decode_collision_tables(built(TABLES_FILE).read_bytes())
    rig = read_tongue_rig(built("tongue-rig.json").read_bytes())
    mesh = scene_maxilla()
    origin = np.array(tables.header["origin"])
    rays, disagree, node_worst = node_agreement(tables, mesh, origin, 7 if QUICK else 1)
    print(f"scene maxilla against the liner's node radii: {rays} rays, {disagree} differ by "
          f"more than {COLLISION_TOL.surface} mm, worst finite difference {node_worst:.2e} mm")
    rng = np.random.default_rng(seed)
    values = rng.uniform(rig.minimum, rig.maximum, size=(poses, len(rig.minimum)))

    worst, innocent, missed = 0.0, 0, 0
    corrected, tested, seconds = [], [], []
    liner_error, liner_smooth, liner_kind = [], [], []
    for k in range(poses):
        points = rig.vertices(values[k])
        started = time.perf_counter()
        out, _, counts = correct_vertices(points, tables)
        seconds.append(time.perf_counter() - started)
        first = first_hit_radius(mesh, origin, points)
        r = np.linalg.norm(points - origin, axis=1)
        moved = np.any(out != points, axis=1)
        innocent += int(np.sum(moved & (r < first - COLLISION_TOL.surface)))
        missed += int(np.sum(~moved & (r > first + COLLISION_TOL.surface)))
        after = np.where(moved, np.linalg.norm(out - origin, axis=1), r)
        worst = max(worst, float(np.max(after - first)))
        corrected.append(counts["corrected"])
        tested.append(counts["tested"])
        if moved.any():
            d = points[moved] - origin
            error, smooth, kind = liner_accuracy(tables, origin, d, first[moved])
            liner_error.append(error)
            liner_smooth.append(smooth)
            liner_kind.append(kind)

    corrected = np.array(corrected)
    n = rig.vertex_count
    print(f"Collision exactness: {poses} seeded tongue poses (seed {seed}), {n} vertices each, "
          f"every parameter uniform over its range, jaw included; scene maxilla "
          f"{len(mesh.faces)} triangles; reference: Embree raycasts from O over the mesh")
    print(f"worst depth inside after correction: {worst:.2e} mm (limit {COLLISION_TOL.depth} mm)")
    print(f"innocent vertices moved: {innocent}; vertices left inside: {missed}")
    print(f"vertices corrected per pose: median {np.median(corrected):.0f}, mean "
          f"{corrected.mean():.1f}, max {corrected.max()}; poses with contact "
          f"{np.sum(corrected > 0)} of {poses}; tested per pose: median {np.median(tested):.0f}, "
          f"max {max(tested)}")
    for q in (50, 90, 99):
        print(f"  corrected per pose, {q}th percentile: {np.percentile(corrected, q):.0f}")
    if liner_error:
        err = np.abs(np.concatenate(liner_error))
        smooth = np.concatenate(liner_smooth)
        kind = np.concatenate(liner_kind)
        print(f"paper's bilinear liner at the {len(err)} contact directions: within "
              f"{LINER_GOAL_MM} mm at {np.mean(err <= LINER_GOAL_MM):.2%}")
        print(f"  in cells where the surface is continuous ({np.mean(smooth):.2%} of contacts): "
              f"max {err[smooth].max():.3f} mm, 99th percentile "
              f"{np.percentile(err[smooth], 99):.3f} mm, within {LINER_GOAL_MM} mm at "
              f"{np.mean(err[smooth] <= LINER_GOAL_MM):.2%}")
        print(f"  in cells where it jumps by over {JUMP_MM} mm or a corner ray misses "
              f"({np.mean(~smooth):.2%} of contacts): no sampled liner can follow it there; "
              "the exact cell test decides")
        print(f"  contact cells: plane {np.mean(kind == CELL_PLANE):.1%}, list "
              f"{np.mean((kind != CELL_PLANE) & (kind != CELL_EMPTY)):.1%}")
    print(f"Python twin: median {1000 * np.median(seconds):.2f} ms per pose (reference, not "
          "the real-time path)")
    exact = worst <= COLLISION_TOL.depth and innocent == 0 and missed == 0
    print("exact: " + ("yes" if exact else "NO"))
    print(f"check: the reference maxilla is the tables' surface: "
          f"{'ok' if disagree == 0 else 'FAILED'}")
    print(f"check: the Python twin is exact against Embree: {'ok' if exact else 'FAILED'}")
    return 0 if exact and disagree == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
