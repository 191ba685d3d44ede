"""Kernels the anatomical landmarks are found with: curves in the mid-sagittal plane.

The landmark rules (``glasshead.pipeline.landmarks``) cut meshes at z = 0 and read points off
the section curves: an extreme along a direction, the point of greatest curvature, a point at an
arc length, the closest pair of two curves. These functions do that on plain arrays.

Curvature is the signed curvature of a plane curve, k = (x' y'' - y' x'') / (x'^2 + y'^2)^(3/2)
(do Carmo, Differential Geometry of Curves and Surfaces, 1.5), with derivatives by central
differences of the curve resampled at equal arc length and smoothed by a Gaussian over arc
length (so that the facets of a mesh of 1-2 mm do not read as curvature).
"""

import numpy as np


def _points(points, dims=None) -> np.ndarray:
    p = np.asarray(points, dtype=np.float64)
    if p.ndim != 2 or len(p) == 0 or (dims is not None and p.shape[1] != dims):
        shape = f"(k, {dims})" if dims else "(k, d)"
        raise ValueError(f"points must have shape {shape} with k >= 1, got {p.shape}")
    if not np.all(np.isfinite(p)):
        raise ValueError("points must be finite")
    return p


def arc_lengths(points) -> np.ndarray:
    """(k,) float64 cumulative length along the polyline ``points`` (k, d), from its first point."""
    p = _points(points)
    return np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])


def point_at_arc(points, arc, s) -> np.ndarray:
    """(d,) float64 point of the polyline ``points`` (k, d) at arc length ``s`` (clamped to the
    curve), linear between its points; ``arc`` (k,) is ``arc_lengths(points)``."""
    p = _points(points)
    arc = np.asarray(arc, dtype=np.float64)
    if arc.shape != (len(p),):
        raise ValueError(f"arc must have shape ({len(p)},), got {arc.shape}")
    return np.array([np.interp(s, arc, p[:, i]) for i in range(p.shape[1])])


def resample(points, step) -> tuple[np.ndarray, np.ndarray]:
    """The polyline ``points`` (k, d) at equal arc-length ``step`` mm: (points (j, d), arc (j,))."""
    if not step > 0:
        raise ValueError(f"step must be positive, got {step}")
    p = _points(points)
    arc = arc_lengths(p)
    s = np.arange(0.0, arc[-1] + 0.5 * step, step)
    return np.stack([np.interp(s, arc, p[:, i]) for i in range(p.shape[1])], axis=1), s


def smooth(values, sigma_samples) -> np.ndarray:
    """``values`` (k,) or (k, d) convolved along axis 0 with a Gaussian of ``sigma_samples``
    samples, the ends extended by repeating the end values."""
    v = np.asarray(values, dtype=np.float64)
    if sigma_samples <= 0:
        return v.copy()
    half = int(np.ceil(3.0 * sigma_samples))
    x = np.arange(-half, half + 1)
    kernel = np.exp(-0.5 * (x / sigma_samples) ** 2)
    kernel /= kernel.sum()
    padded = np.concatenate([np.repeat(v[:1], half, axis=0), v, np.repeat(v[-1:], half, axis=0)])
    if v.ndim == 1:
        return np.convolve(padded, kernel, mode="valid")
    return np.stack([np.convolve(padded[:, i], kernel, mode="valid") for i in range(v.shape[1])],
                    axis=1)


def signed_curvature(points, step, sigma_mm) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Signed curvature (1/mm) along a plane polyline ``points`` (k, 2), resampled at ``step`` mm
    and smoothed over ``sigma_mm``. Returns (curvature (j,), resampled points (j, 2), arc (j,)).

    The sign is that of a turn to the left (counter-clockwise) as the curve runs forward: with
    the material on the right of the direction of travel, a negative curvature is a bulge of the
    material (convex), a positive one a hollow (concave).
    """
    p = _points(points, dims=2)
    if len(p) < 3:
        raise ValueError("a curvature needs at least 3 points")
    q, s = resample(p, step)
    q_smooth = smooth(q, sigma_mm / step)
    d1 = np.gradient(q_smooth, step, axis=0)
    d2 = np.gradient(d1, step, axis=0)
    speed = np.linalg.norm(d1, axis=1)
    speed = np.where(speed > 0.0, speed, np.inf)
    return (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / speed**3, q, s


def extreme_point(points, direction) -> int:
    """Index of the point of ``points`` (k, d) farthest along ``direction`` (d,)."""
    p = _points(points)
    return int(np.argmax(p @ np.asarray(direction, dtype=np.float64)))


def nearest_point(points, target) -> int:
    """Index of the point of ``points`` (k, d) nearest ``target`` (d,)."""
    p = _points(points)
    return int(np.argmin(np.linalg.norm(p - np.asarray(target, dtype=np.float64), axis=1)))


def farthest_point(points, target) -> int:
    """Index of the point of ``points`` (k, d) farthest from ``target`` (d,)."""
    p = _points(points)
    return int(np.argmax(np.linalg.norm(p - np.asarray(target, dtype=np.float64), axis=1)))


def closest_pair(a, b) -> tuple[int, int, float]:
    """(i, j, distance): the pair of points ``a[i]`` (of (k, d)) and ``b[j]`` (of (m, d)) closest
    to each other (brute force: k * m distances, for section curves of a few hundred points)."""
    a, b = _points(a), _points(b)
    if a.shape[1] != b.shape[1]:
        raise ValueError(f"a and b differ in dimension: {a.shape[1]} and {b.shape[1]}")
    distance = np.linalg.norm(a[:, None, :] - b[None, :, :], axis=2)
    i, j = np.unravel_index(int(np.argmin(distance)), distance.shape)
    return int(i), int(j), float(distance[i, j])


#: What each entry of a landmarks file must carry, and the kinds it may be.
LANDMARK_KEYS = ("name", "label", "kind", "position", "mesh", "feature", "rule", "meshes")
LANDMARK_KINDS = ("part", "place", "reference")


def validate_landmarks(document) -> dict:
    """Check a landmarks document (``pipeline.landmarks``); ValueError naming what is wrong.

    Returns the document. Refuses another format version, an entry without a field of
    ``LANDMARK_KEYS``, an unknown kind, a position that is not 3 finite numbers, a repeated name,
    and places whose ``order`` is not 0, 1, ... in the file's order.
    """
    from glasshead.constants import LANDMARKS_FORMAT_VERSION

    if not isinstance(document, dict):
        raise ValueError("a landmarks document must be a JSON object")
    version = document.get("format_version")
    if version != LANDMARKS_FORMAT_VERSION:
        raise ValueError(f"landmarks format_version {version!r} is not "
                         f"{LANDMARKS_FORMAT_VERSION}")
    entries = document.get("landmarks")
    if not isinstance(entries, list) or not entries:
        raise ValueError("the landmarks document lists no landmarks")
    names = set()
    orders = []
    for k, entry in enumerate(entries):
        missing = [key for key in LANDMARK_KEYS if not isinstance(entry, dict) or key not in entry]
        if missing:
            raise ValueError(f"landmark {k} lacks {', '.join(missing)}")
        if entry["kind"] not in LANDMARK_KINDS:
            raise ValueError(f"landmark {entry['name']!r} has unknown kind {entry['kind']!r}")
        position = entry["position"]
        if not (isinstance(position, list) and len(position) == 3
                and all(isinstance(c, int | float) and np.isfinite(c) for c in position)):
            raise ValueError(f"landmark {entry['name']!r} position must be 3 finite numbers")
        if entry["name"] in names:
            raise ValueError(f"landmark {entry['name']!r} is listed twice")
        names.add(entry["name"])
        if entry["kind"] == "place":
            orders.append(entry.get("order"))
    if orders != list(range(len(orders))):
        raise ValueError(f"places must be ordered 0, 1, ... front to back, got {orders}")
    return document
