"""The voxel table: a 32 x 32 x 32 grid around the palate, each voxel ok, not ok or borderline.

In front of the liner, the paper (Cohen, Beskow and Massaro 1998, part 4) screens tongue points
with a precomputed voxel table so that most need no test at all. Here each voxel is classified
exactly against the liner's cell bounds (``geometry.liner``):

- ok: every point of the voxel is nearer to O than the first hit in its direction. The voxel's
  farthest corner is nearer than the smallest ``rmin`` over every cell its directions span.
- not ok: every point of the voxel is beyond the first hit. Its nearest point is farther than the
  largest ``rmax`` over the cells it spans, and every ray through it hits; or every cell it spans
  is a plane cell and the voxel lies beyond each of their planes.
- borderline: neither can be proven. A voxel that fails both tests is split in eight, up to
  ``depth`` times, and is ok (not ok) when all its parts are; what stays borderline straddles the
  surface or lies within 1/2**depth of a voxel of it.

Boxes are widened by ``COLLISION_TOL.length`` so a point on a voxel face is covered by both.
"""

import numpy as np

from glasshead.constants import CELL_PLANE, COLLISION_TOL, VOXEL_BORDER, VOXEL_NOT_OK, VOXEL_OK


def box_direction_span(lo, hi):
    """Longitude and latitude ranges spanned by boxes seen from O (boxes relative to O).

    lo, hi : (k, 3) float corners. Returns (theta_lo, theta_hi, phi_lo, phi_hi), (k,) float64;
    a box around the polar axis, or across the inferior seam, spans the full longitude range.
    """
    lo, hi = np.asarray(lo, dtype=np.float64), np.asarray(hi, dtype=np.float64)
    x0, y0, z0 = lo.T
    x1, y1, z1 = hi.T
    corners_x = np.stack([x0, x0, x1, x1], axis=1)
    corners_y = np.stack([y0, y1, y0, y1], axis=1)
    angles = np.arctan2(corners_x, corners_y)
    holds_axis = (x0 <= 0) & (x1 >= 0) & (y0 <= 0) & (y1 >= 0)
    crosses_seam = (x0 <= 0) & (x1 >= 0) & (y1 < 0)
    full = holds_axis | crosses_seam
    theta_lo = np.where(full, -np.pi, angles.min(axis=1))
    theta_hi = np.where(full, np.pi, angles.max(axis=1))
    # Distance from the polar axis: nearest and farthest points of the xy rectangle.
    rho_min = np.hypot(np.clip(0.0, x0, x1), np.clip(0.0, y0, y1))
    rho_max = np.hypot(np.maximum(-x0, x1), np.maximum(-y0, y1))
    phi_hi = np.where(z1 >= 0, np.arctan2(z1, rho_min), np.arctan2(z1, rho_max))
    phi_lo = np.where(z0 >= 0, np.arctan2(z0, rho_max), np.arctan2(z0, rho_min))
    return theta_lo, theta_hi, phi_lo, phi_hi


class RangeExtreme2D:
    """Minimum (or maximum) over any rectangle of a 2D array in O(1): a 2D sparse table whose
    levels (2**kj x 2**ki blocks) are built on first use."""

    def __init__(self, values, op):
        self.op = op
        self.levels = {(0, 0): np.asarray(values, dtype=np.float64)}

    def level(self, kj, ki):
        key = (kj, ki)
        if key not in self.levels:
            if ki > 0:
                base, s = self.level(kj, ki - 1), 1 << (ki - 1)
                self.levels[key] = self.op(base[:, :-s], base[:, s:])
            else:
                base, s = self.level(kj - 1, 0), 1 << (kj - 1)
                self.levels[key] = self.op(base[:-s], base[s:])
        return self.levels[key]

    def query(self, j0, j1, i0, i1):
        """Extreme over rows j0..j1 and columns i0..i1 (inclusive), (k,) int arrays."""
        kj = np.floor(np.log2(j1 - j0 + 1)).astype(np.int64)
        ki = np.floor(np.log2(i1 - i0 + 1)).astype(np.int64)
        out = np.empty(len(j0))
        for a, b in set(zip(kj.tolist(), ki.tolist(), strict=True)):
            sel = np.flatnonzero((kj == a) & (ki == b))
            table = self.level(a, b)
            ja, jb = j0[sel], j1[sel] - (1 << a) + 1
            ia, ib = i0[sel], i1[sel] - (1 << b) + 1
            out[sel] = self.op(self.op(table[ja, ia], table[ja, ib]),
                               self.op(table[jb, ia], table[jb, ib]))
        return out


def _classify_boxes(lo, hi, liner, rmin_table, rmax_table):
    """Classes of boxes (relative to O) from the liner's cell bounds, without refinement."""
    g = liner.grid
    t_lo, t_hi, p_lo, p_hi = box_direction_span(lo, hi)
    w = COLLISION_TOL.angle
    i0 = np.floor((t_lo - w - g.lon0) / g.step).astype(np.int64)
    i1 = np.floor((t_hi + w - g.lon0) / g.step).astype(np.int64)
    j0 = np.floor((p_lo - w - g.lat0) / g.step).astype(np.int64)
    j1 = np.floor((p_hi + w - g.lat0) / g.step).astype(np.int64)
    leaves_grid = (i0 < 0) | (i1 >= g.nlon) | (j0 < 0) | (j1 >= g.nlat)
    misses_grid = (i1 < 0) | (i0 >= g.nlon) | (j1 < 0) | (j0 >= g.nlat)
    i0, i1 = np.clip(i0, 0, g.nlon - 1), np.clip(i1, 0, g.nlon - 1)
    j0, j1 = np.clip(j0, 0, g.nlat - 1), np.clip(j1, 0, g.nlat - 1)
    far = np.linalg.norm(np.maximum(np.abs(lo), np.abs(hi)), axis=1)
    near = np.linalg.norm(np.clip(0.0, lo, hi), axis=1)
    rmin = np.where(misses_grid, np.inf, rmin_table.query(j0, j1, i0, i1))
    rmax = rmax_table.query(j0, j1, i0, i1)
    classes = np.full(len(lo), VOXEL_BORDER, dtype=np.uint8)
    classes[far < rmin] = VOXEL_OK
    classes[(classes == VOXEL_BORDER) & ~leaves_grid & (near > rmax)] = VOXEL_NOT_OK
    # A box whose directions see only plane cells is inside when it lies beyond every one of
    # those planes: the exact test of each cell holds for all its points at once.
    candidates = np.flatnonzero((classes == VOXEL_BORDER) & ~leaves_grid & np.isfinite(rmax))
    corners = np.stack([np.where(np.array([(k >> a) & 1 for a in range(3)], dtype=bool),
                                 hi[candidates], lo[candidates]) for k in range(8)], axis=1)
    for row, box in zip(candidates, corners, strict=True):
        cells = (slice(j0[row], j1[row] + 1), slice(i0[row], i1[row] + 1))
        if not np.all(liner.kind[cells] == CELL_PLANE):
            continue
        first = liner.offsets[:-1].reshape(liner.kind.shape)[cells]
        tri = np.unique(liner.cell_triangles[first])
        n, c = liner.normals[tri], liner.plane_offsets[tri]
        if np.all(box @ n.T - c > COLLISION_TOL.length):
            classes[row] = VOXEL_NOT_OK
    return classes


def classify_voxels(liner, origin, bounds_min, bounds_max, shape, depth=2):
    """Classify a voxel grid against the liner.

    liner : geometry.liner.Liner; origin : (3,) float, O in the project frame.
    bounds_min, bounds_max : (3,) float, the grid's box in the project frame.
    shape : (nx, ny, nz) int. depth : int, refinement levels for undecided voxels.
    Returns (nx, ny, nz) uint8 of VOXEL_OK / VOXEL_BORDER / VOXEL_NOT_OK; voxel (ix, iy, iz)
    spans bounds_min + (ix, iy, iz) * size to bounds_min + (ix + 1, iy + 1, iz + 1) * size.
    """
    origin = np.asarray(origin, dtype=np.float64).reshape(3)
    bmin = np.asarray(bounds_min, dtype=np.float64).reshape(3)
    bmax = np.asarray(bounds_max, dtype=np.float64).reshape(3)
    shape = tuple(int(s) for s in shape)
    if len(shape) != 3 or min(shape) < 1 or not np.all(bmax > bmin):
        raise ValueError("voxel grid needs a positive shape and bounds_max > bounds_min")
    size = (bmax - bmin) / np.array(shape)
    index = np.stack(np.meshgrid(*(np.arange(s) for s in shape), indexing="ij"), axis=-1)
    index = index.reshape(-1, 3)
    lo = bmin + index * size - origin - COLLISION_TOL.length
    hi = bmin + (index + 1) * size - origin + COLLISION_TOL.length
    tables = (RangeExtreme2D(liner.rmin, np.minimum), RangeExtreme2D(liner.rmax, np.maximum))
    return _refine(lo, hi, liner, tables, depth).reshape(shape)


def _refine(lo, hi, liner, tables, depth):
    classes = _classify_boxes(lo, hi, liner, *tables)
    undecided = np.flatnonzero(classes == VOXEL_BORDER)
    if depth == 0 or len(undecided) == 0:
        return classes
    lo_u, hi_u = lo[undecided], hi[undecided]
    mid = 0.5 * (lo_u + hi_u)
    octant = np.array([[(k >> a) & 1 for a in range(3)] for k in range(8)], dtype=bool)
    child_lo = np.where(octant[None], mid[:, None], lo_u[:, None]).reshape(-1, 3)
    child_hi = np.where(octant[None], hi_u[:, None], mid[:, None]).reshape(-1, 3)
    children = _refine(child_lo, child_hi, liner, tables, depth - 1).reshape(-1, 8)
    all_ok = np.all(children == VOXEL_OK, axis=1)
    all_in = np.all(children == VOXEL_NOT_OK, axis=1)
    classes[undecided[all_ok]] = VOXEL_OK
    classes[undecided[all_in]] = VOXEL_NOT_OK
    return classes
