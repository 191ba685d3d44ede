"""The screen of the tract collision: the twin of ``web/src/core/tractScreen.js``.

Every tract point X lies behind the origin T (x < T.x). Seen from T, a direction is the point
(a, b) = ((y - T.y) / d, (z - T.z) / d) of the central (gnomonic) projection, d = T.x - x the
depth. A central projection maps a segment to a segment, so the convex hull of some points
projects into the hull of their projections, and the segment T -> P projects to P's point alone.
The screen is a grid over (a, b) whose cells hold the smallest depth of any tract hull whose
projection's box covers the cell: a vertex shallower than its cell's value cannot reach a tract
triangle, and neither can one outside the grid.

Between two measured poses the velum's vertices move on straight lines, so a triangle over a
share interval [u0, u1] lies in the hull of its six corners at u0 and u1. Each segment between
measured poses is cut into ``SCREEN_SUBDIVISIONS`` intervals with a table each; the still wall
enters every table. The operations are the JS twin's, in its order, so both build the same
tables.
"""

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from glasshead.constants import COLLISION_TOL

Floats = npt.NDArray[np.float64]

#: Intervals per segment between two measured velum poses, each with its own depth table.
SCREEN_SUBDIVISIONS = 4
#: Cell size of the depth tables, in projected units (mm across per mm of depth).
SCREEN_CELL = 0.025
#: Widening of each hull's projected box: float32 posing moves a point by about 1e-7.
WIDEN = 1e-6
#: Lowering of each depth bound, mm: float32 posing and storage are off by a few 1e-6 mm.
LOWER = 100 * COLLISION_TOL.length


@dataclass(frozen=True)
class DepthScreen:
    """Grid origin (a0, b0), inverse cell size, na x nb cells, tables (k, nb * na) float32 (one
    per share interval of the moving mesh, or one), and the moving mesh's index (-1 for none)."""

    a0: float
    b0: float
    inv: float
    na: int
    nb: int
    tables: npt.NDArray[np.float32]
    moving: int


def _project(origin: Floats, points: Floats) -> tuple[Floats, Floats, Floats]:
    d = origin[0] - points[..., 0]
    return (points[..., 1] - origin[1]) / d, (points[..., 2] - origin[2]) / d, d


def _mark(screen_grid: tuple[float, float, float, int], table: npt.NDArray[np.float32],
          origin: Floats, corners: Floats) -> None:
    """Lower the cells under each hull's projected box to its smallest depth.
    corners : (h, c, 3), the c corners of h hulls."""
    a0, b0, inv, na = screen_grid
    a, b, d = _project(origin, corners)
    i0 = np.floor((a.min(axis=1) - WIDEN - a0) * inv).astype(np.int64)
    i1 = np.floor((a.max(axis=1) + WIDEN - a0) * inv).astype(np.int64)
    j0 = np.floor((b.min(axis=1) - WIDEN - b0) * inv).astype(np.int64)
    j1 = np.floor((b.max(axis=1) + WIDEN - b0) * inv).astype(np.int64)
    bound = (d.min(axis=1) - LOWER).astype(np.float32)
    ni, nj = i1 - i0 + 1, j1 - j0 + 1
    counts = ni * nj
    owner = np.repeat(np.arange(len(corners)), counts)
    local = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
    cells = (j0[owner] + local // ni[owner]) * na + i0[owner] + local % ni[owner]
    np.minimum.at(table, cells, bound[owner])


def create_depth_screen(origin: npt.ArrayLike, meshes: list[tuple[Floats, npt.ArrayLike]],
                        ) -> DepthScreen:
    """The depth tables of tract meshes seen from T.

    origin : T (3,). meshes : (poses (p, n, 3) float64 of float32 values, faces (m, 3)) each, at
    most one with several poses; every vertex behind T. ValueError otherwise.
    """
    origin = np.asarray(origin, dtype=np.float64)
    moving_meshes = [k for k, (poses, _) in enumerate(meshes) if len(poses) > 1]
    if len(moving_meshes) > 1:
        raise ValueError("the tract screen takes one moving mesh")
    moving = moving_meshes[0] if moving_meshes else -1
    every = np.concatenate([poses.reshape(-1, 3) for poses, _ in meshes])
    if not np.all(origin[0] - every[:, 0] > 0):
        raise ValueError("a tract vertex lies at or in front of the origin")
    a, b, _ = _project(origin, every)
    inv = 1.0 / SCREEN_CELL
    a0, b0 = float(a.min()) - 2 * SCREEN_CELL, float(b.min()) - 2 * SCREEN_CELL
    na = int(np.ceil((a.max() - a0) * inv)) + 2
    nb = int(np.ceil((b.max() - b0) * inv)) + 2
    grid = (a0, b0, inv, na)
    still = np.full(na * nb, np.inf, dtype=np.float32)
    for k, (poses, faces) in enumerate(meshes):
        if k != moving:
            _mark(grid, still, origin, poses[0][np.asarray(faces)])
    tables = []
    if moving < 0:
        tables.append(still)
    else:
        poses, faces = meshes[moving]
        faces = np.asarray(faces)
        for interval in range((len(poses) - 1) * SCREEN_SUBDIVISIONS):
            first, step = divmod(interval, SCREEN_SUBDIVISIONS)
            u0, u1 = step / SCREEN_SUBDIVISIONS, (step + 1) / SCREEN_SUBDIVISIONS
            a_pose, b_pose = poses[first][faces], poses[first + 1][faces]
            corners = np.concatenate([a_pose * (1 - u0) + b_pose * u0,
                                      a_pose * (1 - u1) + b_pose * u1], axis=1)
            table = still.copy()
            _mark(grid, table, origin, corners)
            tables.append(table)
    return DepthScreen(a0, b0, inv, na, nb, np.stack(tables), moving)


def screen_table(screen: DepthScreen, first: int, share: float) -> npt.NDArray[np.float32]:
    """The depth table for the moving mesh at ``share`` after measured pose ``first``."""
    if screen.moving < 0:
        return screen.tables[0]
    step = min(int(np.floor(share * SCREEN_SUBDIVISIONS)), SCREEN_SUBDIVISIONS - 1)
    return screen.tables[first * SCREEN_SUBDIVISIONS + step]


def screened(screen: DepthScreen, origin: Floats, points: Floats, table) -> npt.NDArray[np.bool_]:
    """(n,) True where a point (behind T) is shallower than its cell or outside the grid."""
    px = points[:, 0] - origin[0]
    depth = -px
    i = np.floor(((points[:, 1] - origin[1]) / depth - screen.a0) * screen.inv)
    j = np.floor(((points[:, 2] - origin[2]) / depth - screen.b0) * screen.inv)
    inside = (i >= 0) & (i < screen.na) & (j >= 0) & (j < screen.nb)
    cell = np.where(inside, j * screen.na + i, 0).astype(np.int64)
    return ~inside | (depth < table[cell])
