"""A closed scalp, back of the head and under-jaw shell that joins the open rim of the face skin.

The Badin face is a mask: it ends at the hairline, in front of the ears and under the chin. The
shell closes the head so that it reads as a head from every side. It is built like this:

1. Target surface. Two axis-aligned ellipsoids, symmetric about z = 0, fitted by least squares:
   the *cranium* ellipsoid to the Badin cranium band pushed out by ``SCALP_MM`` along the ray
   from the band's centre (its vertical semi-axis bounded to 0.85..1.15 of the mean horizontal
   one, since the band stops above the brows and below the vertex), widened if needed so it is
   at least as wide as the face rim; the *lower* ellipsoid to the rim points more than
   ``LOWER_RIM_DROP_MM`` below the cranium centre (jaw line and under the chin), so that it
   closes under the jaw; and the *neck* (``pipeline.neck``), a tube fitted round the larynx,
   the hyoid and the upper spine. The target radius along a ray from the centre H (the cranium
   ellipsoid's centre) is the smooth maximum (p-norm, ``UNION_POWER``) of the three far
   intersections.
2. Parameterisation. Directions from H are written in spherical coordinates about a pole b in
   the mid-sagittal plane, behind and above H: alpha (angle from b) and psi (azimuth about b).
   The rim, seen from H, is a closed curve going once around b; each rim vertex i starts a
   meridian from (alpha_i, psi_i) to the pole, sampled at ``RINGS`` rings. The pole's tilt above
   -x (searched over ``POLE_TILT_DEG``) is the one whose meridians cross the rim most steeply:
   with b = -x the hairline, which runs from the forehead back past the temples at about the
   height of H, lay almost along the meridians, so the first strips were slivers that folded
   over (a crease across the forehead). Where the rim's azimuth still turns back, later rings
   use its running maximum, so no ring folds.
3. Radius. Ring 0 is the rim vertices themselves, so shell and skin share their border vertices
   exactly (no gap, no overlap). Along a meridian the radius is the target plus an offset
   delta(beta) = (delta0 + delta0' beta) * (1 - s)^2 (1 + 2 s), s = beta / BLEND_RAD, beta the
   angle travelled from the rim: delta0 makes the shell start on the rim, delta0' makes its slope
   there match the skin's (from the skin's vertex normal), and the Hermite factor fades both out
   by BLEND_RAD, after which the shell is the target surface. delta0 and delta0' hand over, over
   ``RIM_HANDOVER_RINGS`` rings, to their averages over ``RIM_SMOOTHING`` rim neighbours each
   side, so the rim's small jags fade out within a few rings instead of running down the
   meridians as ridges or standing as a step next to the rim.
4. Triangles: quads between rings (split in two), a fan at the pole; wound so normals point
   away from H.
"""

from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

#: Soft tissue over the skull, mm (scalp thickness is about 5-7 mm).
SCALP_MM = 6.0
#: Rim points this far below the cranium centre drive the lower (jaw and neck) ellipsoid, mm.
LOWER_RIM_DROP_MM = 40.0
#: Exponent of the smooth maximum of the two ellipsoid radii (higher = sharper junction).
UNION_POWER = 6.0
#: Angle over which the shell turns from the skin's rim to the target surface.
BLEND_RAD = np.radians(30.0)
#: The same where the neck reaches more than NECK_STEP_MM beyond the rim.
NECK_BLEND_RAD, NECK_STEP_MM = np.radians(6.0), 5.0
#: Rim vertices on each side averaged when the rim offsets are carried along the meridians.
RIM_SMOOTHING = 3
#: Rings of vertices from the rim to the pole.
RINGS = 40
#: Rings over which the rim's own offsets hand over to their smoothed values.
RIM_HANDOVER_RINGS = 4
#: Range searched for the pole's tilt above -x in the mid-sagittal plane, degrees.
POLE_TILT_DEG = (0.0, 75.0)


@dataclass
class HeadShell:
    """vertices (n, 3) float64 mm; faces (m, 3) int64; rim (k,) int64 skin vertex ids of ring 0;
    params: the fitted surfaces and the method, for the build report."""

    vertices: np.ndarray
    faces: np.ndarray
    rim: np.ndarray
    params: dict


def boundary_loops(faces):
    """Closed boundary loops of a triangle mesh, longest first; list of (k,) int64 vertex ids."""
    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    key = np.sort(edges, axis=1)
    _, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    border = edges[counts[inverse.ravel()] == 1]
    following = {int(a): int(b) for a, b in border}
    if len(following) != len(border):
        raise ValueError("the skin's border is not a set of simple loops")
    loops, seen = [], set()
    for start in following:
        if start in seen:
            continue
        loop, v = [], start
        while v not in seen:
            seen.add(v)
            loop.append(v)
            v = following[v]
        loops.append(np.asarray(loop, dtype=np.int64))
    return sorted(loops, key=len, reverse=True)


def _fit_ellipsoid(points, start, lower, upper):
    """Least-squares axis-aligned ellipsoid centred on z = 0; params (cx, cy, ax, ay, az)."""

    def residual(q):
        centre = np.array([q[0], q[1], 0.0])
        return (np.linalg.norm((points - centre) / q[2:5], axis=1) - 1.0) * np.mean(q[2:5])

    fit = least_squares(residual, np.clip(start, lower, upper), bounds=(lower, upper))
    rms = float(np.sqrt(np.mean(fit.fun**2)))
    return np.array([fit.x[0], fit.x[1], 0.0]), fit.x[2:5], rms


def _far_radius(origin, dirs, centre, axes):
    """Distance from origin along unit dirs (k, 3) to the far side of an ellipsoid (0 if missed)."""
    o = (origin - centre) / axes
    d = dirs / axes
    a = np.einsum("ij,ij->i", d, d)
    b = 2.0 * d @ o
    c = o @ o - 1.0
    root = np.sqrt(np.maximum(b * b - 4.0 * a * c, 0.0))
    return np.maximum((-b + root) / (2.0 * a), 0.0)


def _pole_axes(tilt):
    """Rows: the pole b = (-cos t, sin t, 0), behind and above the centre for tilt t > 0, and
    two unit axes u, w = +z completing an orthonormal frame; u is +y when t = 0. (3, 3)."""
    c, s = np.cos(tilt), np.sin(tilt)
    return np.array([[-c, s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _directions(alpha, psi, axes):
    """Unit vectors at angle alpha from the pole axes[0] and azimuth psi about it; (k, 3)."""
    s = np.sin(alpha)
    return np.stack([np.cos(alpha), s * np.cos(psi), s * np.sin(psi)], axis=1) @ axes


def _spherical(rays, axes):
    """(alpha, psi) of unit rays (k, 3) about the pole axes[0]; psi unwrapped along the rim."""
    local = rays @ axes.T
    alpha = np.arccos(np.clip(local[:, 0], -1.0, 1.0))
    return alpha, np.unwrap(np.arctan2(local[:, 2], local[:, 1]))


def _rim_crossing_deg(rays, axes):
    """Smallest angle, degrees, between a rim edge and the meridian through it (negative where
    the rim's azimuth turns back); meridians must cross the rim, not run along it."""
    alpha, psi = _spherical(rays, axes)
    if psi[-1] < psi[0]:
        psi = -psi
    d_psi = np.diff(np.append(psi, psi[0] + 2.0 * np.pi))
    d_alpha = np.diff(np.append(alpha, alpha[0]))
    mid = (alpha + np.roll(alpha, -1)) / 2.0
    return float(np.degrees(np.arctan2(np.sin(mid) * d_psi, np.abs(d_alpha))).min())


def _choose_pole(rays):
    """Pole tilt (radians, in the mid-sagittal plane) whose meridians cross the rim most steeply."""
    tilts = np.radians(np.arange(POLE_TILT_DEG[0], POLE_TILT_DEG[1] + 0.5, 1.0))
    crossing = [_rim_crossing_deg(rays, _pole_axes(t)) for t in tilts]
    best = int(np.argmax(crossing))
    return tilts[best], crossing[best]


def build_head_shell(skin_vertices, skin_faces, cranium_vertices, neck=None):
    """Shell closing the head behind and below the face skin's outer rim.

    skin_vertices (n, 3) float, skin_faces (m, 3) int: the outer skin, project frame mm.
    cranium_vertices (k, 3) float, project frame mm. neck: a ``pipeline.neck.Neck`` the shell
    takes into its outline (its third shape), or None. Returns a ``HeadShell``.
    """
    skin_vertices = np.asarray(skin_vertices, dtype=np.float64)
    cranium = np.asarray(cranium_vertices, dtype=np.float64)
    rim_ids = boundary_loops(np.asarray(skin_faces))[0]
    rim = skin_vertices[rim_ids]

    band_centre = np.array([(cranium[:, 0].min() + cranium[:, 0].max()) / 2,
                            cranium[:, 1].min(), 0])
    out = cranium - band_centre
    scalp = cranium + SCALP_MM * out / np.linalg.norm(out, axis=1)[:, None]
    half = (cranium.max(axis=0) - cranium.min(axis=0)) / 2
    mean_h = (half[0] + half[2]) / 2
    c_up, a_up, rms_up = _fit_ellipsoid(
        scalp,
        [band_centre[0], band_centre[1], half[0], mean_h, half[2]],
        [band_centre[0] - 40, band_centre[1] - 60, 0.5 * half[0], 0.85 * mean_h, 0.5 * half[2]],
        [band_centre[0] + 40, band_centre[1] + 40, 2.0 * half[0], 1.15 * mean_h, 2.0 * half[2]],
    )
    a_up[2] = max(a_up[2], np.abs(rim[:, 2]).max() + 2.0)
    low = rim[rim[:, 1] < c_up[1] - LOWER_RIM_DROP_MM]
    c_lo, a_lo, rms_lo = _fit_ellipsoid(
        low,
        [c_up[0] + 20, low[:, 1].min() + 40, 60, 50, a_up[2] * 0.8],
        [c_up[0] - 40, -300, 30, 30, 30],
        [c_up[0] + 60, c_up[1], 150, 90, a_up[2]],
    )
    centre = c_up

    def target(dirs):
        p = UNION_POWER
        r1 = _far_radius(centre, dirs, c_up, a_up)
        r2 = _far_radius(centre, dirs, c_lo, a_lo)
        r3 = neck.far_radius(centre, dirs) if neck is not None else 0.0
        return (r1**p + r2**p + r3**p) ** (1.0 / p)

    ray = rim - centre
    r0 = np.linalg.norm(ray, axis=1)
    ray /= r0[:, None]
    tilt, crossing = _choose_pole(ray)
    axes = _pole_axes(tilt)
    alpha, psi = _spherical(ray, axes)
    if psi[-1] < psi[0]:  # walk the rim with increasing azimuth
        rim_ids, rim, ray, r0 = rim_ids[::-1], rim[::-1], ray[::-1], r0[::-1]
        alpha, psi = _spherical(ray, axes)
    if abs(psi[-1] - psi[0]) < np.pi:
        raise ValueError("the face rim does not go around the head centre; cannot close the head")
    psi_mono = np.maximum.accumulate(psi)

    # Slope of the skin across the rim, from its normal: dr/dbeta = -r (n.e) / (n.ray), with e
    # the unit tangent toward the pole along the meridian.
    normals = vertex_normals(skin_vertices, np.asarray(skin_faces))[rim_ids]
    toward_pole = np.stack(
        [np.sin(alpha), -np.cos(alpha) * np.cos(psi), -np.cos(alpha) * np.sin(psi)], axis=1
    ) @ axes
    facing = np.maximum(np.einsum("ij,ij->i", normals, ray), 0.2)
    skin_slope = np.clip(-r0 * np.einsum("ij,ij->i", normals, toward_pole) / facing, -r0, r0)
    step = 1e-3
    t0 = target(_directions(alpha, psi, axes))
    target_slope = (target(_directions(alpha - step, psi, axes)) - t0) / step
    delta0, delta_slope = r0 - t0, skin_slope - target_slope
    # Away from the rim the offsets are smoothed along it, so its jags do not run down the
    # meridians as ridges; the hand-over over a few rings keeps them from standing as a step.
    smooth0, smooth_slope = _smooth_loop(delta0), _smooth_loop(delta_slope)

    # Where the neck takes the outline far beyond the rim (the throat under the chin), the shell
    # turns from the rim within NECK_BLEND_RAD: the angle between chin and neck.
    blend = np.full(len(rim), BLEND_RAD)
    if neck is not None:
        blend[neck.far_radius(centre, ray) > r0 + NECK_STEP_MM] = NECK_BLEND_RAD
    rings = [rim]
    for k in range(1, RINGS):
        a = alpha * (1.0 - k / RINGS)
        beta = alpha - a
        ring_psi = psi + (psi_mono - psi) * min(1.0, k / 3.0)
        dirs = _directions(a, ring_psi, axes)
        s = np.clip(beta / blend, 0.0, 1.0)
        w = min(1.0, k / RIM_HANDOVER_RINGS)
        d0 = (1.0 - w) * delta0 + w * smooth0
        d1 = (1.0 - w) * delta_slope + w * smooth_slope
        offset = (d0 + d1 * np.minimum(beta, blend)) * (1 - s) ** 2 * (1 + 2 * s)
        rings.append(centre + dirs * (target(dirs) + offset)[:, None])
    pole_dir = axes[:1]
    vertices = np.vstack(rings + [centre + pole_dir * target(pole_dir)[:, None]])

    n = len(rim)
    i = np.arange(n)
    j = (i + 1) % n
    quads = np.vstack([
        np.stack([k * n + i, k * n + j, (k + 1) * n + j, (k + 1) * n + i], axis=1)
        for k in range(RINGS - 1)
    ])
    pole = len(vertices) - 1
    faces = np.vstack(
        [quads[:, [0, 1, 2]], quads[:, [0, 2, 3]],
         np.stack([(RINGS - 1) * n + i, (RINGS - 1) * n + j, np.full(n, pole)], axis=1)]
    ).astype(np.int64)
    tri = vertices[faces]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    if np.einsum("ij,ij->i", normal, tri.mean(axis=1) - centre).sum() < 0:
        faces = faces[:, ::-1].copy()

    params = {
        "method": (
            "radial shell about the cranium ellipsoid centre: meridians from each face-rim vertex "
            "to a pole tilted to cross the rim steeply, radius = smooth max of a cranium "
            "ellipsoid (scalp "
            f"{SCALP_MM} mm) and a lower jaw/neck ellipsoid fitted to the rim below the cheeks, "
            f"plus a Hermite offset matching the rim's position and slope, faded over "
            f"{np.degrees(BLEND_RAD):.0f} degrees; ring 0 is the rim itself (shared vertices)"
        ),
        "centre_mm": centre.round(3).tolist(),
        "cranium_ellipsoid": {"centre_mm": c_up.round(3).tolist(),
                              "semi_axes_mm": a_up.round(3).tolist(),
                              "fit_rms_mm": round(rms_up, 3)},
        "lower_ellipsoid": {"centre_mm": c_lo.round(3).tolist(),
                            "semi_axes_mm": a_lo.round(3).tolist(),
                            "fit_rms_mm": round(rms_lo, 3)},
        "neck": neck.report() if neck is not None else None,
        "rim_vertices": int(n),
        "rings": RINGS,
        "pole_direction": axes[0].round(4).tolist(),
        "rim_meridian_crossing_min_deg": round(crossing, 2),
        "rim_azimuth_turnbacks": int(np.sum(np.diff(psi) < 0)),
    }
    return HeadShell(vertices, faces, rim_ids, params)


def _smooth_loop(values, width=RIM_SMOOTHING):
    """Circular moving average of (n,) values over 2 * width + 1 neighbours."""
    padded = np.concatenate([values[-width:], values, values[:width]])
    kernel = np.ones(2 * width + 1) / (2 * width + 1)
    return np.convolve(padded, kernel, mode="valid")


def vertex_normals(vertices, faces):
    """Area-weighted unit vertex normals; (n, 3) float64."""
    tri = vertices[faces]
    face_normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normals = np.zeros_like(vertices)
    for corner in range(3):
        np.add.at(normals, faces[:, corner], face_normal)
    length = np.linalg.norm(normals, axis=1)
    return normals / np.where(length > 0, length, 1.0)[:, None]
