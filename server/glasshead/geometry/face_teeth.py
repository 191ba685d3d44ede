"""The lips against the incisors: the labial faces as height fields, and the correction.

Twin of the teeth part of ``web/src/core/faceRig.js``. Each row of incisors is tabulated (by
``glasshead.pipeline.face_rig_teeth``) as x = F(y, z), the front-most surface along -x on a
regular grid; a point with x < F(y, z) is behind the teeth and is moved out onto them along the
face's normal. Only points less than the table's ``depth`` behind the face count: deeper ones
are behind the teeth altogether (inside the mouth, or the back of the head in the same band of y
and z), not in them. The upper row is fixed to the maxilla, so F is read at the point itself; the
lower row is tabulated on the mandible at rest, so the point is first taken into the rest
mandible's frame (R^T (p - t)), corrected there, and brought back.
"""

from collections.abc import Mapping
from typing import Any

import numpy as np
import numpy.typing as npt


def teeth_tables(teeth: Mapping[str, Any]) -> dict[str, Any]:
    """The rig's ``teeth`` with each row's table ``x`` read as an array once: ``teeth_bound``
    takes a JSON list too, but converts it at every call, and a pose calls it for every step of
    both rows (a caller that poses many frames prepares them with this)."""
    return {name: dict(row, x=np.asarray(row["x"], dtype=np.float64))
            for name, row in teeth.items()}


def teeth_bound(y: npt.ArrayLike, z: npt.ArrayLike, surface: Mapping[str, Any],
                gradient: bool = False) -> Any:
    """The labial face x = F(y, z) of a row of incisors, receding outside its table.

    ``surface`` tabulates F on a regular grid (``y0``, ``z0``, ``step_y``, ``step_z``, ``rows``
    x ``cols`` values ``x``, row-major by y), read bilinearly; beyond the table (in y or z) the
    face recedes by ``recession`` * (distance outside, mm)^2 from the nearest edge value, so the
    constraint fades out continuously rather than stopping at a line.
    y, z : (n,) float, in the surface's own frame.  Returns (n,) float64, or with ``gradient``
    the tuple (F, dF/dy, dF/dz).
    """
    rows, cols = int(surface["rows"]), int(surface["cols"])
    step_y, step_z = float(surface["step_y"]), float(surface["step_z"])
    recession = float(surface["recession"])
    table = np.asarray(surface["x"], dtype=np.float64).reshape(rows, cols)
    fy = (np.asarray(y, dtype=np.float64) - float(surface["y0"])) / step_y
    fz = (np.asarray(z, dtype=np.float64) - float(surface["z0"])) / step_z
    cy = np.clip(fy, 0.0, rows - 1.0)
    cz = np.clip(fz, 0.0, cols - 1.0)
    iy = np.minimum(np.floor(cy).astype(np.int64), rows - 2)
    iz = np.minimum(np.floor(cz).astype(np.int64), cols - 2)
    ty, tz = cy - iy, cz - iz
    low = (1.0 - tz) * table[iy, iz] + tz * table[iy, iz + 1]
    high = (1.0 - tz) * table[iy + 1, iz] + tz * table[iy + 1, iz + 1]
    out_y, out_z = (fy - cy) * step_y, (fz - cz) * step_z
    value = (1.0 - ty) * low + ty * high - recession * (out_y * out_y + out_z * out_z)
    if not gradient:
        return value
    left = (1.0 - ty) * table[iy, iz] + ty * table[iy + 1, iz]
    right = (1.0 - ty) * table[iy, iz + 1] + ty * table[iy + 1, iz + 1]
    # Inside the table in an axis the bilinear slope applies; outside it, only the recession's.
    dy = np.where(out_y == 0.0, (high - low) / step_y, 0.0) - 2.0 * recession * out_y
    dz = np.where(out_z == 0.0, (right - left) / step_z, 0.0) - 2.0 * recession * out_z
    return value, dy, dz


def push_out(points: npt.NDArray[np.float64],
             surface: Mapping[str, Any]) -> npt.NDArray[np.bool_]:
    """Move the points lying behind a face (by less than ``depth``) onto it, in place.

    Each is moved along the face's normal (1, -F_y, -F_z) onto its tangent plane, ``steps``
    times (each lands nearer the curved face): where the face is turned (the sides of the arch,
    the rounded biting edge) a point slides off sideways or downward instead of being shoved far
    forward, which would fold the lip.
    points : (n, 3) float64 in the surface's frame.  Returns a (n,) bool mask of points moved.
    """
    depth = float(surface["depth"])
    moved = np.zeros(len(points), dtype=bool)
    for _ in range(int(surface["steps"])):
        bound, dy, dz = teeth_bound(points[:, 1], points[:, 2], surface, gradient=True)
        behind = bound - points[:, 0]
        hit = (behind > 0.0) & (behind < depth)
        s = np.where(hit, behind / (1.0 + dy * dy + dz * dz), 0.0)
        points[:, 0] += s
        points[:, 1] -= s * dy
        points[:, 2] -= s * dz
        moved |= hit
    return moved


def clamp_to_teeth(points: npt.NDArray[np.float64], teeth: Mapping[str, Any],
                   rotation: npt.NDArray[np.float64], translation: npt.NDArray[np.float64]) -> int:
    """Push points out of both incisor rows, in place (see ``push_out``).

    points : (n, 3) float64 array, posed.  teeth : the rig's ``teeth`` dict (``upper`` in the
    project frame, ``lower`` in the rest mandible's frame).  rotation (3, 3), translation (3,):
    the jaw pose.  The lower row is applied first, then the upper.
    Returns the number of points moved.
    """
    r, t = rotation, translation
    local = (points - t) @ r  # rest mandible frame: R^T (p - t)
    lower = push_out(local, teeth["lower"])
    points[lower] = local[lower] @ r.T + t
    upper = push_out(points, teeth["upper"])
    return int(lower.sum() + upper.sum())
