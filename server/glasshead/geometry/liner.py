"""The liner: the maxilla seen from O, cell by cell in longitude and latitude, made exact.

The paper (Cohen, Beskow and Massaro 1998, part 4) casts rays from an origin O at regular
longitude and latitude steps; the first hits with the palate or teeth form a regular quadrilateral
mesh of radii, and a tongue point whose distance from O exceeds the (bilinear) liner radius in its
direction is moved along the line toward O onto the liner. Sampled at a fixed step that test is
not exact: the surface turns between samples, and rays switch between hitting and missing.

So each liner cell also carries what the maxilla really is inside it, bounded exactly:

- ``rmin``: a radius below the first hit of every ray in the cell (Ericson 5.1.5 distance and the
  triangle's plane over the cell, both exact lower bounds). A point nearer than rmin is outside.
- ``rmax``: a radius beyond the first hit of every ray in the cell, finite only when one triangle
  covers the whole cell. A point farther than rmax is inside.
- the triangles whose cone from O meets the cell and that can be the first hit there. When a
  single triangle covers the cell and nothing can be in front of it, the cell is a PLANE cell:
  the exact test is the paper's dot product with the surface normal, n . (P - O) > c.

"Inside" is defined from O: P is inside the palate or teeth when the ray from O toward P crosses
the maxilla before reaching P (two-sided triangles). Rays that hit nothing never make a point
inside.
"""

from dataclasses import dataclass

import numpy as np

from glasshead.constants import CELL_EMPTY, CELL_LIST, CELL_PLANE, COLLISION_TOL
from glasshead.geometry.collision_exact import closest_points_on_triangles, ray_triangle_hits
from glasshead.geometry.spherical import (
    angles_to_direction,
    cone_edge_normals,
    linear_extremes,
    triangle_cone_bounds,
)


@dataclass
class LinerGrid:
    """A regular longitude x latitude grid: cell (j, i) spans
    [lon0 + i step, lon0 + (i + 1) step] x [lat0 + j step, lat0 + (j + 1) step] (radians)."""

    lon0: float
    lat0: float
    step: float
    nlon: int
    nlat: int

    def cell_bounds(self, i, j, widen=0.0):
        """Bounds (theta_a, theta_b, phi_a, phi_b) of cells (i, j), widened by ``widen`` rad."""
        ta = self.lon0 + i * self.step - widen
        pa = self.lat0 + j * self.step - widen
        return (np.maximum(ta, -np.pi), np.minimum(ta + self.step + 2 * widen, np.pi),
                np.maximum(pa, -np.pi / 2), np.minimum(pa + self.step + 2 * widen, np.pi / 2))


@dataclass
class Liner:
    """Liner tables, all float64 / int in memory (stored as float32 / uint32 / uint8).

    node_radius : (nlat + 1, nlon + 1) first-hit radius of the ray through each grid node, +inf
        where it hits nothing (the paper's liner).
    kind : (nlat, nlon) uint8, CELL_EMPTY / CELL_PLANE / CELL_LIST.
    rmin, rmax : (nlat, nlon) bounds of the first-hit radius over each cell (+inf when none).
    offsets : (nlat * nlon + 1,) uint32, CSR offsets of each cell's triangles in ``cell_triangles``.
    cell_triangles : (k,) uint32 triangle indices, nearest possible hit first.
    normals, plane_offsets : (m, 3), (m,) triangle planes n . x = c relative to O, c >= 0.
    """

    grid: LinerGrid
    node_radius: np.ndarray
    kind: np.ndarray
    rmin: np.ndarray
    rmax: np.ndarray
    offsets: np.ndarray
    cell_triangles: np.ndarray
    normals: np.ndarray
    plane_offsets: np.ndarray


def plane_of_triangles(tri):
    """Unit normals n and offsets c of triangle planes, oriented so that c = n . a >= 0.

    tri : (m, 3, 3) float, vertices relative to O. Returns (n (m, 3), c (m,)) float64.
    """
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    c = np.einsum("ij,ij->i", n, tri[:, 0])
    flip = np.where(c < 0, -1.0, 1.0)
    return n * flip[:, None], c * flip


def grid_for_triangles(tri, step):
    """The smallest grid of the given step (radians) that holds every triangle's cone."""
    lo_t, hi_t, lo_p, hi_p = triangle_cone_bounds(tri[:, 0], tri[:, 1], tri[:, 2])
    i0 = np.floor((lo_t.min() + np.pi) / step)
    i1 = np.ceil((hi_t.max() + np.pi) / step)
    j0 = np.floor((lo_p.min() + np.pi / 2) / step)
    j1 = np.ceil((hi_p.max() + np.pi / 2) / step)
    return LinerGrid(lon0=-np.pi + i0 * step, lat0=-np.pi / 2 + j0 * step, step=step,
                     nlon=int(i1 - i0), nlat=int(j1 - j0))


def _candidate_pairs(tri, grid):
    """(triangle, i, j) for every cell in each triangle's longitude/latitude box."""
    lo_t, hi_t, lo_p, hi_p = triangle_cone_bounds(tri[:, 0], tri[:, 1], tri[:, 2])
    w = COLLISION_TOL.angle
    i0 = np.clip(np.floor((lo_t - w - grid.lon0) / grid.step), 0, grid.nlon - 1).astype(np.int64)
    i1 = np.clip(np.floor((hi_t + w - grid.lon0) / grid.step), 0, grid.nlon - 1).astype(np.int64)
    j0 = np.clip(np.floor((lo_p - w - grid.lat0) / grid.step), 0, grid.nlat - 1).astype(np.int64)
    j1 = np.clip(np.floor((hi_p + w - grid.lat0) / grid.step), 0, grid.nlat - 1).astype(np.int64)
    ni, nj = i1 - i0 + 1, j1 - j0 + 1
    counts = ni * nj
    owner = np.repeat(np.arange(len(tri)), counts)
    local = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
    return owner, i0[owner] + local % ni[owner], j0[owner] + local // ni[owner]


def build_liner(tri, step):
    """Build the liner of triangles ``tri`` ((m, 3, 3) float, relative to O) at ``step`` radians.

    Triangles whose plane passes through O (no ray from O crosses them) are left out.
    Returns a ``Liner``.
    """
    tri = np.asarray(tri, dtype=np.float64)
    if tri.ndim != 3 or tri.shape[1:] != (3, 3):
        raise ValueError(f"tri must have shape (m, 3, 3), got {tri.shape}")
    normals, offsets_c = plane_of_triangles(tri)
    if not np.all(offsets_c > COLLISION_TOL.length):
        raise ValueError("O lies on the plane of a triangle; move O away from the maxilla")
    grid = grid_for_triangles(tri, step)
    owner, ci, cj = _candidate_pairs(tri, grid)
    ta, tb, pa, pb = grid.cell_bounds(ci, cj, widen=COLLISION_TOL.angle)

    # The cone of a triangle meets a cell unless the cell lies beyond one of its edge planes;
    # it covers the cell when the cell lies inside all three.
    edge_n = cone_edge_normals(tri[:, 0], tri[:, 1], tri[:, 2])
    meets = np.ones(len(owner), dtype=bool)
    covers = np.ones(len(owner), dtype=bool)
    for k in range(3):
        fmin, fmax = linear_extremes(edge_n[owner, k], ta, tb, pa, pb)
        meets &= fmax >= 0.0
        covers &= fmin >= 0.0
    pmin, pmax = linear_extremes(normals[owner], ta, tb, pa, pb)
    meets &= pmax > 0.0
    keep = np.flatnonzero(meets)
    owner, ci, cj, covers, pmin, pmax = (x[keep] for x in (owner, ci, cj, covers, pmin, pmax))

    # Radius bounds of each triangle over each cell it meets.
    dist = np.linalg.norm(closest_points_on_triangles(np.zeros(3), tri[:, 0], tri[:, 1],
                                                      tri[:, 2]), axis=1)
    lower = np.maximum(offsets_c[owner] / pmax, dist[owner]) - COLLISION_TOL.length
    with np.errstate(divide="ignore"):
        upper = np.where(covers & (pmin > 0.0), offsets_c[owner] / pmin, np.inf)
    upper = upper + COLLISION_TOL.length

    ncell = grid.nlat * grid.nlon
    cell = cj * grid.nlon + ci
    rmin = np.full(ncell, np.inf)
    np.minimum.at(rmin, cell, lower)
    rmax = np.full(ncell, np.inf)
    np.minimum.at(rmax, cell, upper)
    # A triangle that starts beyond rmax can never be the first hit in that cell.
    useful = lower <= rmax[cell]
    owner, cell, lower, covers = owner[useful], cell[useful], lower[useful], covers[useful]
    order = np.lexsort((lower, cell))
    owner, cell, covers = owner[order], cell[order], covers[order]
    counts = np.bincount(cell, minlength=ncell)
    offsets = np.concatenate([[0], np.cumsum(counts)]).astype(np.uint32)
    kind = np.full(ncell, CELL_EMPTY, dtype=np.uint8)
    kind[counts > 0] = CELL_LIST
    single = np.flatnonzero(counts == 1)
    kind[single[covers[offsets[single]]]] = CELL_PLANE

    shape = (grid.nlat, grid.nlon)
    cell_triangles = owner.astype(np.uint32)
    return Liner(grid=grid, node_radius=node_radii(grid, offsets, cell_triangles, tri),
                 kind=kind.reshape(shape), rmin=rmin.reshape(shape), rmax=rmax.reshape(shape),
                 offsets=offsets, cell_triangles=cell_triangles, normals=normals,
                 plane_offsets=offsets_c)


def node_radii(grid: LinerGrid, offsets: np.ndarray, cell_triangles: np.ndarray,
               tri: np.ndarray) -> np.ndarray:
    """First-hit radius of the ray through every grid node (+inf on a miss): the paper's liner.

    offsets, cell_triangles : the liner's CSR cell lists; tri : (m, 3, 3) triangles relative to O.
    Returns (nlat + 1, nlon + 1) float64. A node lies on the closed boundary of its neighbouring
    cells, so the triangle list of any one of them holds every triangle its ray can hit first.
    """
    g = grid
    jj, ii = np.meshgrid(np.arange(g.nlat + 1), np.arange(g.nlon + 1), indexing="ij")
    d = angles_to_direction(g.lon0 + ii * g.step, g.lat0 + jj * g.step).reshape(-1, 3)
    cell = (np.minimum(jj, g.nlat - 1) * g.nlon + np.minimum(ii, g.nlon - 1)).ravel()
    start = offsets[cell].astype(np.int64)
    count = offsets[cell + 1].astype(np.int64) - start
    node = np.repeat(np.arange(len(cell)), count)
    entry = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count) + start[node]
    t_idx = cell_triangles[entry]
    t = ray_triangle_hits(d[node], tri[t_idx, 0], tri[t_idx, 1] - tri[t_idx, 0],
                          tri[t_idx, 2] - tri[t_idx, 0])
    radius = np.full(len(cell), np.inf)
    np.minimum.at(radius, node, t)
    return radius.reshape(g.nlat + 1, g.nlon + 1)


def cell_of_angles(grid, theta, phi):
    """Cell indices (i, j) of directions, and whether they fall inside the grid."""
    i = np.floor((theta - grid.lon0) / grid.step).astype(np.int64)
    j = np.floor((phi - grid.lat0) / grid.step).astype(np.int64)
    inside = (i >= 0) & (i < grid.nlon) & (j >= 0) & (j < grid.nlat)
    return i, j, inside


def bilinear_radius(liner, theta, phi):
    """The paper's liner radius in directions (theta, phi): bilinear in the cell's node radii.

    Returns (n,) float64, +inf outside the grid or where a corner ray missed (a marked cell).
    """
    g = liner.grid
    i, j, inside = cell_of_angles(g, theta, phi)
    i, j = np.clip(i, 0, g.nlon - 1), np.clip(j, 0, g.nlat - 1)
    fu = (theta - g.lon0) / g.step - i
    fv = (phi - g.lat0) / g.step - j
    r = liner.node_radius
    with np.errstate(invalid="ignore"):
        value = ((1 - fv) * ((1 - fu) * r[j, i] + fu * r[j, i + 1])
                 + fv * ((1 - fu) * r[j + 1, i] + fu * r[j + 1, i + 1]))
    value[~inside | ~np.isfinite(value)] = np.inf
    return value
