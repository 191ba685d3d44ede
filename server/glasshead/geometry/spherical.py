"""Longitude and latitude about the collision origin O, and exact bounds over lon/lat cells.

The liner (Cohen, Beskow and Massaro 1998, part 4) indexes directions from O by longitude and
latitude. Here the polar axis is the project +z axis (toward the subject's left), so the
mid-sagittal plane is the equator and the palate, seen from O, never sits on a pole:

    longitude  theta = atan2(dx, dy)              0 = superior, +pi/2 = anterior, seam = inferior
    latitude   phi   = atan2(dz, hypot(dx, dy))   0 = mid-sagittal plane, +pi/2 = left

and the unit direction is d(theta, phi) = (cos phi sin theta, cos phi cos theta, sin phi).

A cell is the closed rectangle [theta_a, theta_b] x [phi_a, phi_b]. Everything the tables
promise about a cell rests on one exact computation: the minimum and maximum over the cell of a
linear function m . d. The function is smooth on the rectangle, so its extremes lie at a corner, at
a critical point of an edge, or at the interior critical points d = +-m/|m|; all are in closed form.
"""

import numpy as np

#: Candidate points per cell for the extremes of m . d: 4 corners, 2 per latitude edge,
#: 2 per longitude edge and the two interior critical points.
_CANDIDATES = 4 + 2 * 2 + 2 * 2 + 2


def direction_angles(p):
    """Longitude and latitude of the directions ``p`` (relative to O).

    p : (n, 3) float. Returns (theta, phi), each (n,) float64, radians.
    """
    p = np.asarray(p, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] != 3:
        raise ValueError(f"p must have shape (n, 3), got {p.shape}")
    rho = np.hypot(p[:, 0], p[:, 1])
    return np.arctan2(p[:, 0], p[:, 1]), np.arctan2(p[:, 2], rho)


def angles_to_direction(theta, phi):
    """Unit directions for longitudes ``theta`` and latitudes ``phi`` (radians, broadcast).

    Returns (..., 3) float64.
    """
    theta, phi = np.broadcast_arrays(np.asarray(theta, dtype=np.float64),
                                     np.asarray(phi, dtype=np.float64))
    cos_phi = np.cos(phi)
    return np.stack([cos_phi * np.sin(theta), cos_phi * np.cos(theta), np.sin(phi)], axis=-1)


def _wrap(angle):
    """Angles mapped into (-pi, pi]."""
    return np.pi - np.mod(np.pi - angle, 2.0 * np.pi)


def linear_extremes(m, theta_a, theta_b, phi_a, phi_b):
    """Exact minimum and maximum of ``m . d`` over lon/lat cells.

    m : (k, 3) float, one linear function per cell.
    theta_a, theta_b, phi_a, phi_b : (k,) float, cell bounds in radians, with
        -pi <= theta_a <= theta_b <= pi and -pi/2 <= phi_a <= phi_b <= pi/2.
    Returns (fmin, fmax), each (k,) float64.
    """
    m = np.asarray(m, dtype=np.float64)
    if m.ndim != 2 or m.shape[1] != 3:
        raise ValueError(f"m must have shape (k, 3), got {m.shape}")
    bounds = [np.broadcast_to(np.asarray(b, dtype=np.float64), (len(m),))
              for b in (theta_a, theta_b, phi_a, phi_b)]
    ta, tb, pa, pb = bounds
    if np.any(tb < ta) or np.any(pb < pa):
        raise ValueError("cell bounds must satisfy theta_a <= theta_b and phi_a <= phi_b")
    mx, my, mz = m[:, 0], m[:, 1], m[:, 2]
    # m . d = cos(phi) * A * cos(theta - alpha) + mz * sin(phi), A sin(alpha) = mx, A cos = my.
    amp = np.hypot(mx, my)
    alpha = np.arctan2(mx, my)
    alpha_opposite = _wrap(alpha + np.pi)

    theta = np.empty((len(m), _CANDIDATES))
    phi = np.empty_like(theta)
    valid = np.ones_like(theta, dtype=bool)
    # Corners.
    theta[:, 0:4] = np.stack([ta, ta, tb, tb], axis=1)
    phi[:, 0:4] = np.stack([pa, pb, pa, pb], axis=1)
    # Latitude edges: stationary in theta at alpha and alpha + pi.
    for col, (t, p) in enumerate([(alpha, pa), (alpha_opposite, pa),
                                  (alpha, pb), (alpha_opposite, pb)], start=4):
        theta[:, col], phi[:, col] = t, p
        valid[:, col] = (t >= ta) & (t <= tb)
    # Longitude edges: B cos(phi) + mz sin(phi) is stationary at atan2(mz, B), atan2(-mz, -B).
    col = 8
    for t in (ta, tb):
        b = amp * np.cos(t - alpha)
        for p in (np.arctan2(mz, b), np.arctan2(-mz, -b)):
            theta[:, col], phi[:, col] = t, p
            valid[:, col] = (p >= pa) & (p <= pb)
            col += 1
    # Interior critical points: the directions +m and -m.
    lat_plus = np.arctan2(mz, amp)
    for t, p in ((alpha, lat_plus), (alpha_opposite, -lat_plus)):
        theta[:, col], phi[:, col] = t, p
        valid[:, col] = (t >= ta) & (t <= tb) & (p >= pa) & (p <= pb)
        col += 1

    cos_phi = np.cos(phi)
    values = (cos_phi * (mx[:, None] * np.sin(theta) + my[:, None] * np.cos(theta))
              + mz[:, None] * np.sin(phi))
    fmin = np.where(valid, values, np.inf).min(axis=1)
    fmax = np.where(valid, values, -np.inf).max(axis=1)
    return fmin, fmax


def triangle_cone_bounds(a, b, c):
    """Longitude and latitude ranges of the cones from O through triangles (a, b, c).

    a, b, c : (m, 3) float, vertices relative to O.
    Returns (theta_lo, theta_hi, phi_lo, phi_hi), each (m,) float64. A cone that contains a pole
    or spans half a turn of longitude gets the full range [-pi, pi]; the ranges are exact
    otherwise (latitude extremes of an edge may lie inside the edge's great-circle arc).
    """
    verts = np.stack([np.asarray(v, dtype=np.float64) for v in (a, b, c)], axis=1)
    if verts.ndim != 3 or verts.shape[2] != 3:
        raise ValueError(f"triangle vertices must have shape (m, 3), got {verts.shape[::2]}")
    unit = verts / np.linalg.norm(verts, axis=2, keepdims=True)
    orientation = np.sign(np.einsum("ij,ij->i", np.cross(unit[:, 0], unit[:, 1]), unit[:, 2]))
    # Inward normals of the three planes through O and an edge.
    edge_normals = np.stack([np.cross(unit[:, k], unit[:, (k + 1) % 3]) for k in range(3)], axis=1)
    edge_normals *= orientation[:, None, None]
    holds_north = np.all(edge_normals[:, :, 2] >= 0.0, axis=1)
    holds_south = np.all(edge_normals[:, :, 2] <= 0.0, axis=1)

    lat = np.arcsin(np.clip(unit[:, :, 2], -1.0, 1.0))
    phi_lo, phi_hi = lat.min(axis=1), lat.max(axis=1)
    for k in range(3):
        u, v = unit[:, k], unit[:, (k + 1) % 3]
        n = np.cross(u, v)
        n_len = np.linalg.norm(n, axis=1)
        ok = n_len > 0.0
        n_hat = n / np.where(ok, n_len, 1.0)[:, None]
        # Highest point of the great circle: e_z with its n component removed.
        top = np.array([0.0, 0.0, 1.0]) - n_hat[:, 2:3] * n_hat
        top_len = np.linalg.norm(top, axis=1)
        ok &= top_len > 0.0
        top = top / np.where(top_len > 0.0, top_len, 1.0)[:, None]
        for extreme in (top, -top):
            inside = (ok & (np.einsum("ij,ij->i", np.cross(u, extreme), n) >= 0.0)
                      & (np.einsum("ij,ij->i", np.cross(extreme, v), n) >= 0.0))
            z = np.arcsin(np.clip(extreme[:, 2], -1.0, 1.0))
            phi_hi = np.where(inside, np.maximum(phi_hi, z), phi_hi)
            phi_lo = np.where(inside, np.minimum(phi_lo, z), phi_lo)
    phi_hi = np.where(holds_north, np.pi / 2, phi_hi)
    phi_lo = np.where(holds_south, -np.pi / 2, phi_lo)

    # Longitude: the cone projects onto the xy-plane as the 2D cone of the projected vertices;
    # its span is the circle minus the widest gap between the vertex longitudes.
    lon = np.sort(np.arctan2(verts[:, :, 0], verts[:, :, 1]), axis=1)
    gaps = np.concatenate([np.diff(lon, axis=1), (lon[:, :1] + 2 * np.pi) - lon[:, 2:]], axis=1)
    widest = np.argmax(gaps, axis=1)
    rows = np.arange(len(lon))
    theta_lo = lon[rows, (widest + 1) % 3]
    theta_hi = lon[rows, widest]
    on_axis = np.any(np.hypot(verts[:, :, 0], verts[:, :, 1]) == 0.0, axis=1)
    full = (holds_north | holds_south | on_axis | (gaps.max(axis=1) <= np.pi)
            | (theta_hi < theta_lo))  # a span across the seam is widened to the full circle
    theta_lo = np.where(full, -np.pi, theta_lo)
    theta_hi = np.where(full, np.pi, theta_hi)
    return theta_lo, theta_hi, phi_lo, phi_hi


def cone_edge_normals(a, b, c):
    """Inward normals of the planes through O and each edge of triangles (a, b, c).

    a, b, c : (m, 3) float, relative to O. Returns (m, 3, 3) float64: a direction d lies in the
    triangle's cone exactly when ``normals[i, k] . d >= 0`` for k = 0, 1, 2.
    """
    verts = np.stack([np.asarray(v, dtype=np.float64) for v in (a, b, c)], axis=1)
    orientation = np.sign(np.einsum("ij,ij->i", np.cross(verts[:, 0], verts[:, 1]), verts[:, 2]))
    normals = np.stack([np.cross(verts[:, k], verts[:, (k + 1) % 3]) for k in range(3)], axis=1)
    lengths = np.linalg.norm(normals, axis=2, keepdims=True)
    normals = normals / np.where(lengths > 0.0, lengths, 1.0)
    return normals * orientation[:, None, None]
