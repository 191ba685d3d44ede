"""Build the collision tables (liner and voxel table) from the maxilla the scene shows.

The origin O (the paper's "fixed origin inside the mouth") is chosen from the maxilla itself:

- z = 0, the mid-sagittal plane, so the liner is symmetric like the palate;
- x at the middle of the maxilla's antero-posterior extent (about the premolars), so that from O
  the palate vault, the alveolar ridge and the lingual faces of all the upper teeth are seen
  head-on rather than grazing;
- y at the maxilla's lowest point (the incisal edges), the floor of the tables: nothing of the
  maxilla lies below O's horizontal plane, so no ray from O into the lower half-space can meet it
  and every tongue vertex at or below that plane is outside for one comparison. A tongue below
  the upper incisal edge is under the teeth, not in them, so this is also the physical answer.

O must see the palate: the ray straight up from it has to hit the maxilla, and O must keep a few
millimetres from every triangle; otherwise the build stops with a message.

Resolution: the liner steps 0.5 degrees in longitude and latitude (``COLLISION_LINER_STEP_DEG``),
about 0.2 mm between rays on the palate 20 to 30 mm from O. At that step the bilinear liner is
within 0.2 mm of the surface wherever it is continuous (see bench/collision_exactness.py for the
figures over tongue contacts); where it is not (teeth edges, rays switching between hitting and
missing) the cells' exact triangle tests take over, so the correction is exact everywhere.
"""

import hashlib
import time
from pathlib import Path

import numpy as np

from glasshead.constants import (
    CELL_EMPTY,
    CELL_LIST,
    CELL_PLANE,
    COLLISION_LINER_STEP_DEG,
    COLLISION_TABLES_FILE,
    COLLISION_VOXELS,
    VOXEL_BORDER,
    VOXEL_NOT_OK,
    VOXEL_OK,
)
from glasshead.geometry.collision_exact import closest_points_on_triangles, ray_triangle_hits
from glasshead.geometry.collision_format import (
    CollisionTablesError,
    decode_collision_header,
    encode_collision_tables,
)
from glasshead.geometry.liner import build_liner, plane_of_triangles
from glasshead.geometry.spherical import angles_to_direction
from glasshead.geometry.voxels import classify_voxels
from glasshead.pipeline.outputs import load_built_meshes

TABLES_FILE = COLLISION_TABLES_FILE
#: Bumped whenever the builder's output changes for the same maxilla, so stale tables rebuild.
BUILDER_VERSION = 1
#: Nearest O may be to the maxilla, mm.
MIN_CLEARANCE_MM = 3.0
#: Margin around the visible surface for the voxel box, mm.
VOXEL_MARGIN_MM = 1.0
#: The voxel box reaches this fraction of the palate's length behind the visible surface.
VOXEL_BACK_REACH = 0.5
#: Refinement levels for voxels that neither test settles (each level halves the size).
VOXEL_REFINE_DEPTH = 2


def collision_origin(vertices):
    """O for a maxilla (see the module docstring). vertices : (n, 3) float, mm. Returns (3,)."""
    v = np.asarray(vertices, dtype=np.float64)
    return np.array([0.5 * (v[:, 0].min() + v[:, 0].max()), v[:, 1].min(), 0.0])


def _validate(vertices, faces):
    v = np.asarray(vertices, dtype=np.float64)
    f = np.asarray(faces)
    if v.ndim != 2 or v.shape[1] != 3 or len(v) < 3:
        raise ValueError(f"maxilla_vertices must have shape (n, 3), got {v.shape}")
    if not np.all(np.isfinite(v)):
        raise ValueError("maxilla_vertices must be finite")
    if f.ndim != 2 or f.shape[1] != 3 or len(f) == 0 or not np.issubdtype(f.dtype, np.integer):
        raise ValueError(f"maxilla_faces must be (m, 3) integers, got {f.shape} {f.dtype}")
    if f.min() < 0 or f.max() >= len(v):
        raise ValueError("maxilla_faces refer to vertices that do not exist")
    return v, f.astype(np.int64)


def _check_origin(origin, tri):
    """Refuse an O that is not inside the oral cavity looking at the oral side of the maxilla.

    Rays from O over the upper half-space must mostly hit, and hit triangles whose normals face
    O (the frame conversion leaves the maxilla wound with normals toward the oral cavity); O must
    keep ``MIN_CLEARANCE_MM`` from every triangle.
    """
    rel = tri - origin
    a, e1, e2 = rel[:, 0], rel[:, 1] - rel[:, 0], rel[:, 2] - rel[:, 0]
    theta, phi = np.meshgrid(np.radians(np.arange(-75.0, 76.0, 15.0)),
                             np.radians(np.arange(-60.0, 61.0, 15.0)))
    d = angles_to_direction(theta.ravel(), phi.ravel())
    t = ray_triangle_hits(d[:, None], a[None], e1[None], e2[None])
    first = np.argmin(t, axis=1)
    hit = np.isfinite(t[np.arange(len(d)), first])
    normals = np.cross(e1, e2)[first[hit]]
    facing = np.einsum("ij,ij->i", normals, d[hit]) < 0
    if hit.mean() < 0.5 or facing.mean() < 0.9:
        raise ValueError(
            f"collision origin {origin.round(2).tolist()} does not see the palate from the oral "
            f"cavity ({hit.mean():.0%} of upward rays hit, {facing.mean() if hit.any() else 0:.0%}"
            " of them the oral side); is the maxilla upside down or wound inside out?")
    gap = np.linalg.norm(closest_points_on_triangles(origin, tri[:, 0], tri[:, 1], tri[:, 2])
                         - origin, axis=1).min()
    if gap < MIN_CLEARANCE_MM:
        raise ValueError(f"collision origin is {gap:.2f} mm from the maxilla; it must be at "
                         f"least {MIN_CLEARANCE_MM} mm inside the oral cavity")


def build_collision_tables(maxilla_vertices, maxilla_faces, out_dir,
                           step_deg=COLLISION_LINER_STEP_DEG, voxels=COLLISION_VOXELS):
    """Build the liner and voxel tables and write ``out_dir/collision-tables.bin``.

    maxilla_vertices : (n, 3) float, project frame, mm (the scene's maxilla: palate and teeth).
    maxilla_faces : (m, 3) int. out_dir : path. step_deg : liner step. voxels : cells per axis.
    Returns a summary dict: ``file``, ``bytes``, ``sha256``, ``origin``, ``header`` (the JSON
    header without its array table) and ``stats``.
    """
    started = time.perf_counter()
    v, f = _validate(maxilla_vertices, maxilla_faces)
    origin = collision_origin(v)
    tri64 = v[f]
    area2 = np.linalg.norm(np.cross(tri64[:, 1] - tri64[:, 0], tri64[:, 2] - tri64[:, 0]), axis=1)
    tri64 = tri64[area2 > 0.0]
    _check_origin(origin, tri64)
    # Tables hold float32 triangles relative to O; every bound is computed from those values.
    tri = (tri64 - origin).astype(np.float32).astype(np.float64)
    liner = build_liner(tri, np.radians(step_deg))
    g = liner.grid

    jj, ii = np.meshgrid(np.arange(g.nlat + 1), np.arange(g.nlon + 1), indexing="ij")
    seen = np.isfinite(liner.node_radius)
    dirs = angles_to_direction(g.lon0 + ii * g.step, g.lat0 + jj * g.step)[seen]
    surface = origin + dirs * liner.node_radius[seen][:, None]
    bounds_min = np.minimum(surface.min(axis=0), origin) - VOXEL_MARGIN_MM
    bounds_max = np.maximum(surface.max(axis=0), origin) + VOXEL_MARGIN_MM
    bounds_min[1] = origin[1]  # below the floor nothing needs a voxel
    # The back of the tongue rises behind the hard palate; cover it so it is screened cheaply.
    bounds_min[0] -= VOXEL_BACK_REACH * (bounds_max[0] - bounds_min[0])
    shape = (voxels, voxels, voxels)
    voxel_classes = classify_voxels(liner, origin, bounds_min, bounds_max, shape,
                                    depth=VOXEL_REFINE_DEPTH)

    normals, offsets_c = plane_of_triangles(tri)
    arrays = {
        "node_radius": liner.node_radius.astype(np.float32),
        "cell_kind": liner.kind,
        # Radius bounds rounded outward to float32: rmin down, rmax up.
        "cell_rmin": np.nextafter(liner.rmin.astype(np.float32), np.float32(0)),
        "cell_rmax": np.nextafter(liner.rmax.astype(np.float32), np.float32(np.inf)),
        "cell_offsets": liner.offsets,
        "cell_triangles": liner.cell_triangles,
        "triangles": np.concatenate([tri[:, 0], tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]],
                                    axis=1).astype(np.float32),
        "planes": np.concatenate([normals, offsets_c[:, None]], axis=1).astype(np.float32),
        "voxels": voxel_classes,
    }
    kinds = np.bincount(liner.kind.ravel(), minlength=3)
    counts = np.diff(liner.offsets.astype(np.int64))
    classes = np.bincount(voxel_classes.ravel(), minlength=3)
    stats = {
        "triangles": len(tri),
        "cells": int(liner.kind.size),
        "cells_empty": int(kinds[CELL_EMPTY]),
        "cells_plane": int(kinds[CELL_PLANE]),
        "cells_list": int(kinds[CELL_LIST]),
        "list_length_mean": float(counts[liner.kind.ravel() == CELL_LIST].mean()),
        "list_length_max": int(counts.max()),
        "nodes_missed": int((~seen).sum()),
        "voxels_ok": int(classes[VOXEL_OK]),
        "voxels_borderline": int(classes[VOXEL_BORDER]),
        "voxels_not_ok": int(classes[VOXEL_NOT_OK]),
    }
    header = {
        "frame": {"name": "project", "units": "mm",
                  "axes": {"x": "anterior", "y": "superior", "z": "left"}},
        "origin": origin.tolist(),
        "floor_y": float(origin[1]),
        "liner": {"lon0": g.lon0, "lat0": g.lat0, "step": g.step, "step_deg": float(step_deg),
                  "nlon": g.nlon, "nlat": g.nlat, "longitude": "atan2(dx, dy)",
                  "latitude": "atan2(dz, hypot(dx, dy))", "node_miss": "+inf"},
        "voxels": {"shape": list(shape),
                   "bounds": {"min": bounds_min.tolist(), "max": bounds_max.tolist()},
                   "order": "C order over (x, y, z): index = (ix * ny + iy) * nz + iz",
                   "classes": {"ok": VOXEL_OK, "borderline": VOXEL_BORDER,
                               "not_ok": VOXEL_NOT_OK}},
        "cell_kinds": {"empty": CELL_EMPTY, "plane": CELL_PLANE, "list": CELL_LIST},
        "triangles_layout": "a, b - a, c - a relative to O (9 float32)",
        "planes_layout": "unit normal n, c = n . a >= 0 relative to O (4 float32)",
        "source": {"vertices": len(v), "faces": len(f),
                   "sha256": hashlib.sha256(v.tobytes() + f.tobytes()).hexdigest()},
        "builder": BUILDER_VERSION,
        "stats": stats,
    }
    data = encode_collision_tables(header, arrays)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    (out / TABLES_FILE).write_bytes(data)
    stats["build_seconds"] = round(time.perf_counter() - started, 2)
    return {"file": TABLES_FILE, "bytes": len(data), "sha256": hashlib.sha256(data).hexdigest(),
            "origin": origin.tolist(), "header": header, "stats": stats}


def load_scene_maxilla(assets_dir):
    """(vertices (n, 3) float64, faces (m, 3) int64) of the maxilla the scene shows: the
    ``maxilla`` entry with ``scene: true`` in ``assets_dir/manifest.json``."""
    vertices, faces, _ = load_built_meshes(assets_dir, ["maxilla"], scene_only=True)["maxilla"]
    return vertices, faces


def build_step(assets_dir):
    """The `glasshead build` step: tables from the scene maxilla, skipped when up to date.

    Returns {"step": "collision-tables", "file", "skipped", "bytes", "stats"}.
    """
    v, f = load_scene_maxilla(assets_dir)
    out = Path(assets_dir) / TABLES_FILE
    digest = hashlib.sha256(np.ascontiguousarray(v).tobytes()
                            + np.ascontiguousarray(f).tobytes()).hexdigest()
    if out.is_file():
        try:
            header = decode_collision_header(out.read_bytes())
        except CollisionTablesError:
            header = None
        if header and header.get("source", {}).get("sha256") == digest \
                and header.get("builder") == BUILDER_VERSION:
            return {"step": "collision-tables", "file": str(out), "skipped": True,
                    "bytes": out.stat().st_size, "stats": header.get("stats", {})}
    summary = build_collision_tables(v, f, assets_dir)
    return {"step": "collision-tables", "file": str(out), "skipped": False,
            "bytes": summary["bytes"], "stats": summary["stats"]}
