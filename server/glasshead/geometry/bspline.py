"""B-spline basis functions and knot vectors (twin of ``web/src/core/bspline.js``).

The tongue rig evaluates its curves at parameters fixed when the rig is loaded, so the kernels here
turn (knots, degree, parameters) into basis tables once; evaluation is then a small weighted sum.

Knot vectors:
- clamped: the curve starts at the first and ends at the last control point;
- periodic (closed): uniform knots over [0, 1) with the first ``degree`` control points repeated
  at the end ("wrapped"), so the curve closes with full continuity.
"""

import numpy as np
import numpy.typing as npt

Floats = npt.NDArray[np.float64]


def clamped_knots(inner: npt.ArrayLike, degree: int, start: float = 0.0,
                  end: float = 1.0) -> Floats:
    """Clamped knot vector: ``start`` and ``end`` repeated ``degree + 1`` times around ``inner``.

    inner : (k,) float, strictly inside (start, end), non-decreasing.
    Returns (k + 2 * degree + 2,) float64; the curve has ``k + degree + 1`` control points.
    """
    inner = np.asarray(inner, dtype=np.float64).reshape(-1)
    _check_degree(degree)
    if np.any(np.diff(inner) < 0):
        raise ValueError("inner knots must be non-decreasing")
    if inner.size and (inner[0] <= start or inner[-1] >= end):
        raise ValueError(f"inner knots must lie strictly inside ({start}, {end})")
    return np.concatenate([np.full(degree + 1, start), inner, np.full(degree + 1, end)])


def periodic_knots(count: int, degree: int) -> Floats:
    """Uniform knots of a closed curve with ``count`` distinct control points, domain [0, 1).

    The curve uses ``count + degree`` wrapped control points (see ``wrap_periodic``).
    Returns (count + 2 * degree + 1,) float64: knot i is (i - degree) / count.
    """
    _check_degree(degree)
    if count <= degree:
        raise ValueError(f"a closed curve of degree {degree} needs more than {degree} points")
    return (np.arange(count + 2 * degree + 1, dtype=np.float64) - degree) / count


def wrap_periodic(points: npt.ArrayLike, degree: int) -> Floats:
    """Repeat the first ``degree`` control points at the end: (n, d) -> (n + degree, d)."""
    points = np.asarray(points, dtype=np.float64)
    return np.concatenate([points, points[:degree]], axis=0)


# The NURBS Book (Piegl and Tiller, 2nd ed.), algorithm A2.1 FindSpan.
def find_span(knots: npt.NDArray[np.float64], degree: int, u: float) -> int:
    """Index i of the knot span with knots[i] <= u < knots[i + 1], within the curve's domain.

    knots : (m + 1,) float; the curve has n + 1 = m - degree control points.
    u is clamped into the domain [knots[degree], knots[n + 1]]; the right end maps to the last
    span.
    """
    n = len(knots) - degree - 2
    if u >= knots[n + 1]:
        return n
    if u <= knots[degree]:
        return degree
    low, high = degree, n + 1
    mid = (low + high) // 2
    while u < knots[mid] or u >= knots[mid + 1]:
        if u < knots[mid]:
            high = mid
        else:
            low = mid
        mid = (low + high) // 2
    return mid


# The NURBS Book (Piegl and Tiller, 2nd ed.), algorithm A2.2 BasisFuns.
def basis_funs(knots: Floats, degree: int, span: int, u: float) -> Floats:
    """The degree + 1 non-zero basis functions N[span - degree .. span] at u, as (degree + 1,)
    float64."""
    values = np.zeros(degree + 1)
    left = np.zeros(degree + 1)
    right = np.zeros(degree + 1)
    values[0] = 1.0
    for j in range(1, degree + 1):
        left[j] = u - knots[span + 1 - j]
        right[j] = knots[span + j] - u
        saved = 0.0
        for r in range(j):
            temp = values[r] / (right[r + 1] + left[j - r])
            values[r] = saved + right[r + 1] * temp
            saved = left[j - r] * temp
        values[j] = saved
    return values


def basis_table(knots: npt.ArrayLike, degree: int,
                params: npt.ArrayLike) -> tuple[npt.NDArray[np.int64], Floats]:
    """Spans and non-zero basis values at each parameter.

    knots : (m + 1,) float; params : (k,) float.
    Returns ``(first, values)``: first (k,) int64, index of the first control point each row
    weights (span - degree); values (k, degree + 1) float64.
    """
    checked = _check_knots(knots, degree)
    u_all = np.asarray(params, dtype=np.float64).reshape(-1)
    first = np.empty(u_all.size, dtype=np.int64)
    values = np.empty((u_all.size, degree + 1))
    for row, u in enumerate(u_all):
        span = find_span(checked, degree, float(u))
        first[row] = span - degree
        values[row] = basis_funs(checked, degree, span, float(u))
    return first, values


def basis_matrix(knots: npt.ArrayLike, degree: int, params: npt.ArrayLike,
                 count: int | None = None) -> Floats:
    """Dense (k, n) matrix B with curve(params) = B @ control_points.

    ``count`` folds the columns of a wrapped periodic curve back onto its ``count`` distinct
    control points (column j of the wrapped curve goes to j % count).
    """
    checked = _check_knots(knots, degree)
    first, values = basis_table(checked, degree, params)
    columns = len(checked) - degree - 1
    width = columns if count is None else count
    matrix = np.zeros((first.size, width))
    rows = np.repeat(np.arange(first.size), degree + 1)
    cols = (first[:, None] + np.arange(degree + 1)).reshape(-1) % width
    np.add.at(matrix, (rows, cols), values.reshape(-1))
    return matrix


def greville_abscissae(knots: npt.ArrayLike, degree: int) -> Floats:
    """Parameter where each control point has the most influence: the mean of its ``degree``
    inner knots."""
    checked = _check_knots(knots, degree)
    count = len(checked) - degree - 1
    return np.array([checked[i + 1 : i + degree + 1].mean() for i in range(count)])


def _check_degree(degree: int) -> None:
    if int(degree) != degree or degree < 1:
        raise ValueError(f"degree must be a positive integer, got {degree!r}")


def _check_knots(knots: npt.ArrayLike, degree: int) -> Floats:
    _check_degree(degree)
    checked = np.asarray(knots, dtype=np.float64).reshape(-1)
    if checked.size < 2 * degree + 2:
        raise ValueError(f"{checked.size} knots are too few for degree {degree}")
    if np.any(np.diff(checked) < 0):
        raise ValueError("knots must be non-decreasing")
    if not np.all(np.isfinite(checked)):
        raise ValueError("knots must be finite")
    return checked
