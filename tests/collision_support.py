"""Shared helpers for the collision tests: real meshes, built assets and exact raycasts.

Everything here reads real data (../shared/data) or what `glasshead build` wrote; when either is
missing the calling test fails with a message saying what to run, it is never skipped.
"""

import json
from pathlib import Path

import numpy as np
import trimesh

from glasshead.constants import BADIN_TO_PROJECT_AXES, COLLISION_TOL, FLAG_CORRECTED
from glasshead.geometry.collision import correct_vertices
from glasshead.geometry.collision_format import decode_collision_tables
from glasshead.geometry.frame import badin_to_project, fix_winding
from glasshead.geometry.meshio import read_obj
from glasshead.pipeline.collision_tables import TABLES_FILE
from glasshead.settings import get_settings


def badin_mesh(name):
    """(vertices, faces) of a Badin mesh in the project frame."""
    path = Path(get_settings().data_dir) / "anatomy" / "artisynth-badin" / f"{name}.obj"
    assert path.is_file(), f"reference data missing: {path} (set GLASSHEAD_DATA_DIR)"
    v, f = read_obj(path)
    return badin_to_project(v), fix_winding(f, BADIN_TO_PROJECT_AXES)


def built(name):
    path = Path(get_settings().assets_dir) / name
    assert path.is_file(), f"{path} is missing: run `glasshead build` first"
    return path


def scene_maxilla():
    """(vertices, faces) of the maxilla the scene shows, from the build manifest's GLB."""
    manifest = json.loads(built("manifest.json").read_text())
    entries = [m for m in manifest["meshes"] if m["name"] == "maxilla" and m.get("scene", True)]
    assert entries, "the build manifest lists no scene maxilla"
    mesh = trimesh.load(built(entries[0]["file"]), force="mesh", process=False)
    return np.asarray(mesh.vertices, dtype=np.float64), np.asarray(mesh.faces, dtype=np.int64)


def scene_tables():
    """The collision tables `glasshead build` wrote."""
    return decode_collision_tables(built(TABLES_FILE).read_bytes())


def tongue_rig():
    """The tongue rig `glasshead build` wrote, loaded by the reference evaluator."""
    from glasshead.geometry.tongue_surface import TongueRig

    return TongueRig(json.loads(built("tongue-rig.json").read_text()))


def random_poses(rig, count, seed):
    """(count, P) parameter values drawn uniformly over every range, jaw included."""
    rng = np.random.default_rng(seed)
    return rng.uniform(rig.minimum, rig.maximum, size=(count, len(rig.minimum)))


class ExactRays:
    """First-hit radius from O along the ray through each point, by Embree (trimesh)."""

    def __init__(self, vertices, faces, origin):
        self.mesh = trimesh.Trimesh(vertices, faces, process=False)
        self.origin = np.asarray(origin, dtype=np.float64)

    def radius(self, points):
        """(n,) distance from O to the first crossing along O -> P's ray (+inf: none)."""
        d = np.asarray(points, dtype=np.float64) - self.origin
        r = np.linalg.norm(d, axis=1)
        ok = r > 0
        unit = d[ok] / r[ok, None]
        hit, ray, _ = self.mesh.ray.intersects_location(np.tile(self.origin, (len(unit), 1)),
                                                        unit, multiple_hits=False)
        out = np.full(len(d), np.inf)
        rows = np.flatnonzero(ok)[ray]
        out[rows] = np.linalg.norm(hit - self.origin, axis=1)
        return out


def check_exact_correction(tables, rays, rig, poses, seed):
    """Random tongue poses corrected by ``tables``, against exact first hits (``rays``, an
    ExactRays of the same palate): no vertex outside the palate moves, none inside stays, and
    each corrected one lies on the first surface along its own ray from O (1e-4 mm: the tables'
    float32 triangles against Embree's float32 hits). Returns (the deepest corrected vertex
    below that surface, mm; the corrected vertices over all poses)."""
    origin = np.array(tables.header["origin"])
    tol = COLLISION_TOL
    corrected, worst = 0, 0.0
    for k, values in enumerate(random_poses(rig, poses, seed)):
        points = rig.vertices(values)
        out, flags, counts = correct_vertices(points, tables)
        first = rays.radius(points)
        r = np.linalg.norm(points - origin, axis=1)
        outside = r < first - tol.surface
        inside = r > first + tol.surface
        moved = np.any(out != points, axis=1)
        where = f"seed {seed}, pose {k}"
        assert not np.any(moved & outside), f"{where}: an innocent vertex was moved"
        assert not np.any(inside & ~moved), f"{where}: a vertex inside was left there"
        np.testing.assert_array_equal(moved, flags == FLAG_CORRECTED)
        after = np.linalg.norm(out[moved] - origin, axis=1)
        worst = max(worst, float((after - rays.radius(out[moved])).max(initial=0.0)))
        np.testing.assert_allclose(after, first[moved], rtol=0, atol=1e-4, err_msg=where)
        corrected += counts["corrected"]
    return worst, corrected
