"""B-spline basis functions (The NURBS Book A2.1, A2.2) against the Cox-de Boor recursion."""

import numpy as np
import pytest

from glasshead.geometry.bspline import (
    basis_funs,
    basis_matrix,
    basis_table,
    clamped_knots,
    find_span,
    greville_abscissae,
    periodic_knots,
    wrap_periodic,
)


def cox_de_boor(knots, i, degree, u):
    """N_{i,degree}(u) from the recursive definition (the last knot closes the last span)."""
    if degree == 0:
        if u == knots[-1]:
            return 1.0 if knots[i] < u == knots[i + 1] else 0.0
        return 1.0 if knots[i] <= u < knots[i + 1] else 0.0
    value = 0.0
    if knots[i + degree] > knots[i]:
        value += ((u - knots[i]) / (knots[i + degree] - knots[i])
                  * cox_de_boor(knots, i, degree - 1, u))
    if knots[i + degree + 1] > knots[i + 1]:
        value += ((knots[i + degree + 1] - u) / (knots[i + degree + 1] - knots[i + 1])
                  * cox_de_boor(knots, i + 1, degree - 1, u))
    return value


def test_basis_functions_match_the_cox_de_boor_recursion_on_seeded_random_knots():
    seed = 11
    rng = np.random.default_rng(seed)
    for _trial in range(40):
        degree = int(rng.integers(1, 5))
        knots = clamped_knots(np.sort(rng.uniform(0.02, 0.98, rng.integers(1, 7))), degree)
        for u in np.r_[0.0, 1.0, rng.uniform(0, 1, 8)]:
            span = find_span(knots, degree, u)
            values = basis_funs(knots, degree, span, u)
            reference = [cox_de_boor(knots, span - degree + i, degree, u)
                         for i in range(degree + 1)]
            # Two float64 evaluations of the same weights in [0, 1]: the last bits differ.
            np.testing.assert_allclose(values, reference, rtol=0, atol=1e-12,
                                       err_msg=f"seed {seed}, u {u}")


def test_uniform_cubic_basis_at_a_knot_of_a_closed_curve_is_one_sixth_four_sixths_one_sixth():
    first, values = basis_table(periodic_knots(8, 3), 3, [0.25])
    assert first[0] == 2
    np.testing.assert_allclose(values[0], [1 / 6, 4 / 6, 1 / 6, 0], rtol=0, atol=1e-15)  # ~ulp


def test_a_closed_curve_is_continuous_where_it_wraps_round():
    rng = np.random.default_rng(3)
    points = rng.uniform(-10, 10, (7, 2))
    knots = periodic_knots(7, 3)
    near_end = basis_matrix(knots, 3, [1 - 1e-9], count=7) @ points
    start = basis_matrix(knots, 3, [0.0], count=7) @ points
    # 1e-9 before the end, on points within 10 of the origin: the curve moves about 1e-8.
    np.testing.assert_allclose(near_end, start, rtol=0, atol=1e-6)
    # folding the wrapped columns is the same as evaluating the wrapped control points (the
    # sums are taken in another order: a few ulp of values up to 10)
    wrapped = basis_matrix(knots, 3, [0.3, 0.9]) @ wrap_periodic(points, 3)
    np.testing.assert_allclose(basis_matrix(knots, 3, [0.3, 0.9], count=7) @ points, wrapped,
                               rtol=0, atol=1e-12)


def test_basis_rows_sum_to_one_and_are_never_negative():
    knots = clamped_knots([-66, -46, -32, -22, -12, 0, 12, 22, 32, 46, 66], 3, -90, 90)
    matrix = basis_matrix(knots, 3, np.linspace(-90, 90, 181))
    assert matrix.min() >= 0
    np.testing.assert_allclose(matrix.sum(axis=1), 1.0, rtol=0, atol=1e-14)  # a few ulp of 1


def test_a_clamped_curve_starts_and_ends_on_its_end_control_points():
    knots = clamped_knots([0.3, 0.6], 3)
    np.testing.assert_allclose(basis_matrix(knots, 3, [0.0, 1.0]),
                               [[1, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 1]], rtol=0, atol=1e-15)


def test_greville_abscissae_are_the_means_of_inner_knots():
    knots = clamped_knots([0.5], 2)
    np.testing.assert_allclose(greville_abscissae(knots, 2), [0, 0.25, 0.75, 1.0], rtol=0,
                               atol=1e-15)  # means of a few knots in [0, 1]


@pytest.mark.parametrize("knots, degree, message", [
    ([0, 1, 0.5, 1], 1, "non-decreasing"),
    ([0, 1], 1, "too few"),
    ([0, 0, 1, 1], 0, "positive integer"),
])
def test_bad_knot_vectors_are_refused_with_a_message(knots, degree, message):
    with pytest.raises(ValueError, match=message):
        basis_table(knots, degree, [0.2])


def test_clamped_knots_refuse_inner_knots_outside_the_domain():
    with pytest.raises(ValueError, match="strictly inside"):
        clamped_knots([0.0, 0.5], 3)
