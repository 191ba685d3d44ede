"""The labial faces of the incisors, tabulated for the face rig (a part of its build).

Each row of incisors is a height field x = F(y, z): the first surface a ray cast along -x from in
front of the face meets, on a regular grid over the incisor band. The lips may not go behind it
(``geometry.face_teeth``). The upper row is tabulated on the maxilla as the scene shows it, the
lower on the mandible at rest (the rig carries it with the jaw).
"""

import numpy as np
import trimesh

from glasshead.geometry.face_teeth import teeth_bound

#: Grid steps of the tables, mm: finer in height, where the faces curve into the biting edge.
TEETH_STEP_Y_MM = 0.25
TEETH_STEP_Z_MM = 0.5
#: Half-width of the tables about the midline, mm: the incisors and the canines' front (past
#: them the arch turns back, and the corners of the mouth rest on it).
TEETH_HALF_WIDTH_MM = 16.0
#: Heights tabulated, mm (project frame, mandible at rest).
TEETH_UPPER_Y_MM = (-4.0, 20.0)
TEETH_LOWER_Y_MM = (-26.0, 2.0)
#: A hit this far behind the one before it (walking from the root) is past the biting edge: the
#: ray grazed the edge and struck bone behind it, so it counts as a miss.
TEETH_STEP_BACK_MM = 3.0
#: Past the biting edge, or beyond the table, a face recedes by this times the squared distance
#: (mm^-1): 1 mm at 0.5 mm out, as an incisor's edge rounds off.
TEETH_RECESSION = 4.0
#: How far behind a face a point still counts as in the teeth (about an incisor's thickness near
#: the gum, mm); deeper points are behind the teeth, inside the mouth.
TEETH_DEPTH_MM = 6.0
#: Projections of a point onto the face's tangent plane (each lands nearer the curved face).
TEETH_PUSH_STEPS = 2
#: Room left between the rest pose and the faces where the sources overlap them, mm.
TEETH_REST_CLEARANCE_MM = 0.01


def incisor_surface(vertices, faces, y_window, edge_below):
    """Tabulate the labial face x = F(y, z) of a row of incisors by casting rays along -x.

    vertices, faces : the bone mesh (maxilla, or mandible at rest; project frame).
    y_window : (lo, hi) heights tabulated.  edge_below : True for the upper teeth (their biting
    edge is the bottom of the face), False for the lower.  Each column is walked from the root
    toward the biting edge; cells past the edge (from the first miss, or the first hit
    TEETH_STEP_BACK_MM behind the previous one) continue the face receding by
    TEETH_RECESSION * distance^2; cells nearer the root than the first hit take its value.
    Returns (surface dict for ``geometry.face_teeth.teeth_bound``, stats dict).
    """
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    ys = np.arange(y_window[0], y_window[1] + 1e-9, TEETH_STEP_Y_MM)
    zs = np.arange(-TEETH_HALF_WIDTH_MM, TEETH_HALF_WIDTH_MM + 1e-9, TEETH_STEP_Z_MM)
    yy, zz = np.meshgrid(ys, zs, indexing="ij")
    front = float(np.max(vertices[:, 0])) + 10.0
    origins = np.stack([np.full(yy.size, front), yy.ravel(), zz.ravel()], axis=1)
    directions = np.tile([-1.0, 0.0, 0.0], (len(origins), 1))
    locations, ray, _ = mesh.ray.intersects_location(origins, directions, multiple_hits=False)
    x = np.full(len(origins), np.nan)
    x[ray] = locations[:, 0]
    x = x.reshape(yy.shape)
    order = np.arange(len(ys))[::-1] if edge_below else np.arange(len(ys))
    filled = x.copy()
    past_edge = np.zeros(x.shape, dtype=bool)
    for col in range(len(zs)):
        hits = [k for k in order if not np.isnan(x[k, col])]
        if not hits:
            raise ValueError(f"no ray hit the teeth at z = {zs[col]:.1f} mm")
        position = list(order)
        first = position.index(hits[0])
        filled[order[:first], col] = x[hits[0], col]  # above the first hit: the root's value
        edge = hits[0]
        for k in order[first + 1:]:
            if np.isnan(x[k, col]) or x[k, col] < x[edge, col] - TEETH_STEP_BACK_MM:
                break
            edge = k
        beyond = order[position.index(edge) + 1:]
        gone = np.abs(ys[beyond] - ys[edge])
        filled[beyond, col] = x[edge, col] - TEETH_RECESSION * gone * gone
        past_edge[beyond, col] = True
    surface = {"y0": float(ys[0]), "z0": float(zs[0]), "step_y": TEETH_STEP_Y_MM,
               "step_z": TEETH_STEP_Z_MM, "rows": len(ys), "cols": len(zs),
               "x": [round(float(v), 4) for v in filled.ravel()], "recession": TEETH_RECESSION,
               "depth": TEETH_DEPTH_MM, "steps": TEETH_PUSH_STEPS}
    middle = len(zs) // 2
    on_tooth = ys[~past_edge[:, middle]]
    stats = {"cells": int(filled.size), "cells_past_edge": int(past_edge.sum()),
             "midline_edge_y_mm": float(on_tooth.min() if edge_below else on_tooth.max())}
    return surface, stats


def make_room(surface, rest_points):
    """Lower the table locally until no rest point lies behind it (in place).

    Where the sources' lips or skin already dip into the teeth (their own modelling error; the
    inner corners of the mouth lie on the canines), the four table values around each such point
    are moved back by its depth plus twice TEETH_REST_CLEARANCE_MM: bilinear weights sum to 1, so
    the face then passes behind it, and the rest pose needs no correction. Far from such points the
    faces keep their measured place. Returns (points moved past, largest depth) for the report.
    """
    rows, cols = surface["rows"], surface["cols"]
    table = np.asarray(surface["x"], dtype=np.float64).reshape(rows, cols)
    worst, count = 0.0, 0
    for _ in range(8):  # lowering a cell can only help its other points; a few rounds settle
        current = {**surface, "x": table.ravel()}
        depth = teeth_bound(rest_points[:, 1], rest_points[:, 2], current) - rest_points[:, 0]
        behind = np.flatnonzero((depth > -TEETH_REST_CLEARANCE_MM) & (depth < TEETH_DEPTH_MM))
        if len(behind) == 0:
            break
        if count == 0:
            count, worst = len(behind), float(depth[behind].max())
        iy = np.clip(np.floor((rest_points[behind, 1] - surface["y0"]) / surface["step_y"]),
                     0, rows - 2).astype(int)
        iz = np.clip(np.floor((rest_points[behind, 2] - surface["z0"]) / surface["step_z"]),
                     0, cols - 2).astype(int)
        need = depth[behind] + 2.0 * TEETH_REST_CLEARANCE_MM
        for dy in (0, 1):
            for dz in (0, 1):
                lowered = table[iy + dy, iz + dz] - need
                np.minimum.at(table, (iy + dy, iz + dz), lowered)
    surface["x"] = [round(float(v), 4) for v in table.ravel()]
    return count, round(worst, 3)


def incisor_surfaces(maxilla, mandible, rest_meshes):
    """Both rows' tables, made room for every rest vertex of ``rest_meshes`` (list of (n, 3)
    arrays; the lower row's in the rest mandible's frame, which is the project frame at rest)
    by ``make_room``. Returns (dict "upper"/"lower" -> surface, stats dict)."""
    points = np.concatenate(rest_meshes)
    surfaces, stats = {}, {}
    for row, bone, window in (("upper", maxilla, TEETH_UPPER_Y_MM),
                              ("lower", mandible, TEETH_LOWER_Y_MM)):
        vertices, faces = bone
        surface, row_stats = incisor_surface(vertices, faces, window, edge_below=row == "upper")
        count, worst = make_room(surface, points)
        row_stats["rest_points_behind"] = count
        row_stats["rest_depth_mm"] = worst
        surfaces[row], stats[row] = surface, row_stats
    return surfaces, stats
