"""Ray-triangle intersection parameters: the project's one Python copy of the kernel.

Two-sided Moller and Trumbore (1997), "Fast, minimum storage ray-triangle intersection", written
operation by operation as in ``web/src/core/collision.js`` and ``epgContacts.js``, so that the
Python and JavaScript twins round alike. The collision correction and its tables, the exact
references (``collision_exact.ray_triangle_hits``), the EPG contacts, the EPG error and the 3D
ray walk all call it.
"""

from typing import overload

import numpy as np
import numpy.typing as npt

Floats = npt.NDArray[np.float64]
#: A coordinate: one float, or an (m,) float64 array of them.
Coordinate = float | Floats


@overload
def ray_triangle(sx: float, sy: float, sz: float, dx: float, dy: float, dz: float,
                 e1x: float, e1y: float, e1z: float, e2x: float, e2y: float, e2z: float,
                 ) -> tuple[float, float, float, float]: ...
@overload
def ray_triangle(sx: Floats, sy: Coordinate, sz: Coordinate,
                 dx: Coordinate, dy: Coordinate, dz: Coordinate,
                 e1x: Coordinate, e1y: Coordinate, e1z: Coordinate,
                 e2x: Coordinate, e2y: Coordinate, e2z: Coordinate,
                 ) -> tuple[Floats, Floats, Floats, Floats]: ...
def ray_triangle(sx: Coordinate, sy: Coordinate, sz: Coordinate,
                 dx: Coordinate, dy: Coordinate, dz: Coordinate,
                 e1x: Coordinate, e1y: Coordinate, e1z: Coordinate,
                 e2x: Coordinate, e2y: Coordinate, e2z: Coordinate,
                 ) -> tuple[Coordinate, Coordinate, Coordinate, Coordinate]:
    """Barycentric (u, v), ray parameter t and determinant of rays against triangles.

    s = ray origin minus the triangle's first corner a; d = ray direction; e1 = b - a, e2 = c - a.
    Each argument is a float or an (m,) float64 array (broadcast together).
    Returns (det, u, v, t), each (m,) float64; u, v and t are inf or nan where det == 0 (Python
    floats raise ZeroDivisionError there instead).
    """
    hx = dy * e2z - dz * e2y
    hy = dz * e2x - dx * e2z
    hz = dx * e2y - dy * e2x
    det = e1x * hx + e1y * hy + e1z * hz
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / det
        u = (sx * hx + sy * hy + sz * hz) * inv
        qx = sy * e1z - sz * e1y
        qy = sz * e1x - sx * e1z
        qz = sx * e1y - sy * e1x
        v = (dx * qx + dy * qy + dz * qz) * inv
        t = (e2x * qx + e2y * qy + e2z * qz) * inv
    return det, u, v, t


@overload
def inside_triangle(det: float, u: float, v: float, slack: float) -> bool: ...
@overload
def inside_triangle(det: Floats, u: Coordinate, v: Coordinate,
                    slack: float) -> npt.NDArray[np.bool_]: ...
def inside_triangle(det: Coordinate, u: Coordinate, v: Coordinate,
                    slack: float) -> bool | npt.NDArray[np.bool_]:
    """(m,) bool (a bool for float inputs): a non-degenerate triangle contains the hit, with
    ``slack`` on its edges."""
    return (det != 0.0) & (u >= -slack) & (v >= -slack) & (u + v <= 1.0 + slack)
