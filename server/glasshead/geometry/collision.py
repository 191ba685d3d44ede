"""Tongue-palate collision correction: the Python twin of ``web/src/core/collision.js``.

Cohen, Beskow and Massaro (1998), part 4: a voxel table screens points, a liner found from the
point's spherical coordinates about O tests the rest, and a failing point is moved along the line
toward O onto the surface. Here the liner cells carry exact bounds and triangles
(``geometry.liner``), so the answer is that of an exact raycast from O:

1. Screen: a point at or below ``floor_y`` (no part of the maxilla is lower, and O is on that
   plane) or in an ok voxel is outside, at no cost (flag FLAG_SCREENED).
2. Test: find the liner cell from longitude atan2(dx, dy) and latitude atan2(dz, hypot(dx, dy)).
   Outside the grid, in an empty cell, or nearer than the cell's ``rmin``: outside (FLAG_TESTED).
   A not-ok voxel skips the rmin comparison and goes straight to correction.
3. Correct: in a PLANE cell the surface is one plane n . x = c (the paper's dot product with the
   normal): the point is inside when s = n . (P - O) > c, and moves to O + (P - O) c / s. In a
   LIST cell, two-sided Moller-Trumbore (1997) against the cell's few triangles gives the first
   hit t along O -> P; the point is inside when t < 1 and moves to O + t (P - O) (FLAG_CORRECTED).

Every operation is written as the JS twin writes it (same order, float64 on float32 table
values), so both return the same flags and positions; ``tests/vectors/collision-*.json`` hold
the cases that prove it.
"""

import numpy as np
import numpy.typing as npt

from glasshead.constants import (
    CELL_LIST,
    CELL_PLANE,
    COLLISION_TOL,
    FLAG_CORRECTED,
    FLAG_SCREENED,
    FLAG_TESTED,
    VOXEL_BORDER,
    VOXEL_NOT_OK,
    VOXEL_OK,
)
from glasshead.geometry.collision_format import CollisionTables
from glasshead.geometry.ray_triangle import inside_triangle, ray_triangle


def screen(points: npt.NDArray[np.float64], tables: CollisionTables) -> npt.NDArray[np.uint8]:
    """Voxel class of each point (VOXEL_OK below the floor; VOXEL_BORDER outside the grid).

    points : (n, 3) float64, project frame. Returns (n,) uint8.
    """
    h = tables.header
    vox = tables["voxels"]
    shape = np.array(vox.shape)
    bmin = np.array(h["voxels"]["bounds"]["min"], dtype=np.float64)
    bmax = np.array(h["voxels"]["bounds"]["max"], dtype=np.float64)
    inv = shape / (bmax - bmin)
    # Clipped before the cast so that far-away points cannot wrap around into the grid.
    idx = np.clip(np.floor((points - bmin) * inv), -1, shape).astype(np.int64)
    inside = np.all((idx >= 0) & (idx < shape), axis=1)
    classes = np.full(len(points), VOXEL_BORDER, dtype=np.uint8)
    ii = idx[inside]
    classes[inside] = vox[ii[:, 0], ii[:, 1], ii[:, 2]]
    classes[points[:, 1] <= h["floor_y"]] = VOXEL_OK
    return classes


def correct_vertices(vertices: npt.ArrayLike, tables: CollisionTables,
                     ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.uint8], dict[str, int]]:
    """Correct tongue vertices against the collision tables.

    vertices : (n, 3) float, project frame (mm). tables : ``collision_format.CollisionTables``.
    Returns (corrected (n, 3) float64, flags (n,) uint8, counts dict with ``screened``,
    ``tested`` and ``corrected``). Vertices that were outside are returned unchanged, bit for bit.
    """
    points = np.asarray(vertices, dtype=np.float64)
    if points.ndim != 2 or points.shape[1] != 3:
        raise ValueError(f"vertices must have shape (n, 3), got {points.shape}")
    if not np.all(np.isfinite(points)):
        raise ValueError("vertices must be finite numbers")
    h = tables.header
    origin = np.array(h["origin"], dtype=np.float64)
    out = points.copy()
    flags = np.full(len(points), FLAG_SCREENED, dtype=np.uint8)
    classes = screen(points, tables)
    todo = np.flatnonzero(classes != VOXEL_OK)
    flags[todo] = FLAG_TESTED

    px = points[todo, 0] - origin[0]
    py = points[todo, 1] - origin[1]
    pz = points[todo, 2] - origin[2]
    rho2 = px * px + py * py
    theta = np.arctan2(px, py)
    phi = np.arctan2(pz, np.sqrt(rho2))
    liner = h["liner"]
    inv_step = 1.0 / liner["step"]
    i = np.floor((theta - liner["lon0"]) * inv_step).astype(np.int64)
    j = np.floor((phi - liner["lat0"]) * inv_step).astype(np.int64)
    in_grid = (i >= 0) & (i < liner["nlon"]) & (j >= 0) & (j < liner["nlat"])
    cell = np.where(in_grid, j * liner["nlon"] + i, 0)
    r2 = rho2 + pz * pz
    rmin = tables["cell_rmin"].ravel()[cell].astype(np.float64)
    kind = tables["cell_kind"].ravel()[cell]
    live = in_grid & ((classes[todo] == VOXEL_NOT_OK) | ~(r2 < rmin * rmin))

    t = np.full(len(todo), np.inf)
    first = tables["cell_offsets"][cell].astype(np.int64)
    plane = live & (kind == CELL_PLANE)
    if plane.any():
        nc = tables["planes"][tables["cell_triangles"][first[plane]]].astype(np.float64)
        s = nc[:, 0] * px[plane] + nc[:, 1] * py[plane] + nc[:, 2] * pz[plane]
        with np.errstate(divide="ignore", invalid="ignore"):
            t[plane] = np.where(s > nc[:, 3], nc[:, 3] / s, np.inf)
    listed = np.flatnonzero(live & (kind == CELL_LIST))
    if len(listed):
        t[listed] = _first_hits(px[listed], py[listed], pz[listed], cell[listed], tables)

    hit = t < 1.0
    rows = todo[hit]
    th = t[hit]
    out[rows, 0] = origin[0] + px[hit] * th
    out[rows, 1] = origin[1] + py[hit] * th
    out[rows, 2] = origin[2] + pz[hit] * th
    flags[rows] = FLAG_CORRECTED
    counts = {"screened": len(points), "tested": len(todo), "corrected": len(rows)}
    return out, flags, counts


def _first_hits(px: np.ndarray, py: np.ndarray, pz: np.ndarray, cell: np.ndarray,
                tables: CollisionTables) -> npt.NDArray[np.float64]:
    """Smallest Moller-Trumbore t > 0 over each point's cell list (+inf when none)."""
    offsets = tables["cell_offsets"]
    start = offsets[cell].astype(np.int64)
    count = offsets[cell + 1].astype(np.int64) - start
    owner = np.repeat(np.arange(len(cell)), count)
    entry = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count) + start[owner]
    tri = tables["triangles"][tables["cell_triangles"][entry]].astype(np.float64)
    t = np.full(len(cell), np.inf)
    np.minimum.at(t, owner, moller_trumbore(px[owner], py[owner], pz[owner], tri))
    return t


def moller_trumbore(dx: np.ndarray, dy: np.ndarray, dz: np.ndarray,
                    tri: np.ndarray) -> npt.NDArray[np.float64]:
    """Two-sided Moller-Trumbore from O along (dx, dy, dz), written operation by operation as in
    ``collision.js`` so that both twins round alike.

    tri : (k, 9) float, rows (a, e1, e2) relative to O. Returns (k,) t, +inf on a miss.
    """
    ax, ay, az, e1x, e1y, e1z, e2x, e2y, e2z = tri.T
    det, u, v, t = ray_triangle(-ax, -ay, -az, dx, dy, dz, e1x, e1y, e1z, e2x, e2y, e2z)
    hit = inside_triangle(det, u, v, COLLISION_TOL.barycentric) & (t > 0.0)
    return np.where(hit, t, np.inf)
