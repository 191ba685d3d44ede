"""Synthetic EPG contact: which electrodes the corrected tongue surface touches.

Twin of ``web/src/core/epgContacts.js``; ``tests/vectors/epg-contacts.json`` proves that both give
the same contacts.

Each electrode has a **probe**: the segment along its normal n (toward the tongue) from
``behind`` mm behind it to ``tolerance`` mm in front of it. The electrode is contacted when the
tongue surface crosses its probe: when some tongue triangle is hit by the line E + t n at a
t with -behind <= t <= tolerance (two-sided Moller-Trumbore 1997, with the barycentric slack of
the collision kernels, so a probe through an edge shared by two triangles cannot slip between
them). The tongue has been corrected against the palate first, so a touching tongue lies on the
palate's surface, where the electrodes are (Cohen, Beskow and Massaro 1998, part 6: "an
electrode is contacted when the tongue reaches it").

Both twins test a probe only against triangles whose bounding boxes meet its own (a test that
can only skip triangles the probe cannot hit), and do the same float64 operations in the same
order on the same values, so they agree bit for bit on the same vertices.
"""

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from glasshead.constants import (
    COLLISION_TOL,
    EPG_CONTACT_BEHIND_MM,
    EPG_CONTACT_TOLERANCE_MM,
)
from glasshead.geometry.ray_triangle import inside_triangle, ray_triangle

#: Barycentric slack of the probe test (shared with the collision kernels, for the same reason).
BARYCENTRIC_SLACK = COLLISION_TOL.barycentric
#: mm. Boxes are widened by this before the box test, so it never drops a hit the slack accepts.
PAD_MM = 1e-6


@dataclass
class Probes:
    """The electrodes of one grid, ready for contact tests.

    origins (k, 3) float64 electrode positions; directions (k, 3) float64 unit normals toward the
    tongue; cells (k,) int64 flat grid cell of each electrode (row * columns + column); ids (k,)
    str; rows, columns: grid size; tolerance, behind: the probe's reach in front and behind, mm.
    """

    grid: str
    origins: np.ndarray
    directions: np.ndarray
    cells: np.ndarray
    ids: list[str]
    rows: int
    columns: int
    tolerance: float = EPG_CONTACT_TOLERANCE_MM
    behind: float = EPG_CONTACT_BEHIND_MM

    @property
    def count(self) -> int:
        return len(self.origins)


def probes_from_layout(grid_layout: dict, tolerance: float = EPG_CONTACT_TOLERANCE_MM,
                       behind: float = EPG_CONTACT_BEHIND_MM) -> Probes:
    """Probes of one grid of a layout document (``layout["grids"][name]``)."""
    electrodes = grid_layout["electrodes"]
    if not electrodes:
        raise ValueError("the layout grid has no electrodes")
    origins = np.array([e["position"] for e in electrodes], dtype=np.float64)
    directions = np.array([e["normal"] for e in electrodes], dtype=np.float64)
    if origins.shape != (len(electrodes), 3) or directions.shape != origins.shape:
        raise ValueError("electrode positions and normals must be [x, y, z]")
    if not (np.all(np.isfinite(origins)) and np.all(np.isfinite(directions))):
        raise ValueError("electrode positions and normals must be finite")
    lengths = np.linalg.norm(directions, axis=1)
    if np.any(np.abs(lengths - 1.0) > 1e-6):
        raise ValueError("electrode normals must be unit vectors")
    if not (tolerance > 0 and behind >= 0):
        raise ValueError("the probe needs tolerance > 0 and behind >= 0")
    cells = np.array([e["cell"] for e in electrodes], dtype=np.int64)
    rows, columns = int(grid_layout["rows"]), int(grid_layout["columns"])
    if cells.min() < 0 or cells.max() >= rows * columns or len(set(cells.tolist())) != len(cells):
        raise ValueError("electrode cells must be distinct and inside the grid")
    return Probes(grid_layout["grid"], origins, directions, cells,
                  [e["id"] for e in electrodes], rows, columns, float(tolerance), float(behind))


def _check_mesh(vertices: npt.ArrayLike,
                triangles: npt.ArrayLike) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    v = np.asarray(vertices, dtype=np.float64)
    t = np.asarray(triangles)
    if v.ndim != 2 or v.shape[1] != 3:
        raise ValueError(f"vertices must have shape (n, 3), got {v.shape}")
    if not np.all(np.isfinite(v)):
        raise ValueError("vertices must be finite numbers")
    if t.ndim != 2 or t.shape[1] != 3 or not np.issubdtype(t.dtype, np.integer):
        raise ValueError(f"triangles must be (m, 3) integers, got {t.shape} {t.dtype}")
    if len(t) and (t.min() < 0 or t.max() >= len(v)):
        raise ValueError("triangles refer to vertices that do not exist")
    return v, t.astype(np.int64)


def probe_hits(origin: np.ndarray, direction: np.ndarray, a: np.ndarray, b: np.ndarray,
               c: np.ndarray, tolerance: float, behind: float) -> npt.NDArray[np.bool_]:
    """Which triangles (a, b, c each (m, 3) float64) the probe crosses: (m,) bool.

    Two-sided Moller-Trumbore (1997) from ``origin`` along ``direction`` (``ray_triangle``).
    """
    dx, dy, dz = direction
    ax, ay, az = a.T
    e1x, e1y, e1z = b[:, 0] - ax, b[:, 1] - ay, b[:, 2] - az
    e2x, e2y, e2z = c[:, 0] - ax, c[:, 1] - ay, c[:, 2] - az
    det, u, v, t = ray_triangle(origin[0] - ax, origin[1] - ay, origin[2] - az, dx, dy, dz,
                                e1x, e1y, e1z, e2x, e2y, e2z)
    return inside_triangle(det, u, v, BARYCENTRIC_SLACK) & (t >= -behind) & (t <= tolerance)


def electrode_contacts(vertices: npt.ArrayLike, triangles: npt.ArrayLike,
                       probes: Probes) -> npt.NDArray[np.uint8]:
    """Contact (1) or not (0) of each electrode: (k,) uint8.

    vertices : (n, 3) float, the corrected tongue, project frame (mm). triangles : (m, 3) int.
    Each probe is tested against the triangles whose boxes meet its own (widened by ``PAD_MM``,
    so no triangle the test would accept is left out): the same answer as every triangle.
    """
    v, t = _check_mesh(vertices, triangles)
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    low = np.minimum(np.minimum(a, b), c)
    high = np.maximum(np.maximum(a, b), c)
    near = probes.origins - probes.behind * probes.directions
    far = probes.origins + probes.tolerance * probes.directions
    box_low = np.minimum(near, far) - PAD_MM
    box_high = np.maximum(near, far) + PAD_MM
    out = np.zeros(probes.count, dtype=np.uint8)
    for k in range(probes.count):
        m = np.flatnonzero(np.all((high >= box_low[k]) & (low <= box_high[k]), axis=1))
        if len(m):
            out[k] = probe_hits(probes.origins[k], probes.directions[k], a[m], b[m], c[m],
                                probes.tolerance, probes.behind).any()
    return out


def contact_grid(contacts: npt.ArrayLike, probes: Probes) -> npt.NDArray[np.uint8]:
    """Electrode contacts (k,) laid out on the grid: (rows, columns) uint8, 0 where a cell has
    no electrode (the R1 corners of the Reading palate)."""
    contacts = np.asarray(contacts, dtype=np.uint8)
    if contacts.shape != (probes.count,):
        raise ValueError(f"expected {probes.count} contacts, got shape {contacts.shape}")
    grid = np.zeros(probes.rows * probes.columns, dtype=np.uint8)
    grid[probes.cells] = contacts
    return grid.reshape(probes.rows, probes.columns)
