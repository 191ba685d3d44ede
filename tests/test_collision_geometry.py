"""The exact pieces under the collision tables, each against a brute-force reference.

Seeded random cases; the seed is in each test so a failure can be replayed.
"""

from pathlib import Path

import numpy as np
import pytest
import trimesh

from glasshead.geometry.collision_exact import (
    closest_points_on_segments,
    closest_points_on_triangles,
    first_hits_from_origin,
    project_onto_closest,
    ray_triangle_hits,
)
from glasshead.geometry.spherical import (
    angles_to_direction,
    cone_edge_normals,
    direction_angles,
    linear_extremes,
    triangle_cone_bounds,
)
from glasshead.geometry.voxels import RangeExtreme2D, box_direction_span


def _random_cells(rng, count):
    ta = rng.uniform(-np.pi, np.pi - 0.3, count)
    pa = rng.uniform(-np.pi / 2, np.pi / 2 - 0.3, count)
    return ta, ta + rng.uniform(0.0, 0.3, count), pa, pa + rng.uniform(0.0, 0.3, count)


def test_extremes_of_a_linear_function_over_cells_bound_and_reach_dense_samples():
    seed = 11
    rng = np.random.default_rng(seed)
    m = rng.normal(size=(300, 3))
    ta, tb, pa, pb = _random_cells(rng, 300)
    fmin, fmax = linear_extremes(m, ta, tb, pa, pb)
    s = np.linspace(0.0, 1.0, 41)
    theta = ta[:, None, None] + (tb - ta)[:, None, None] * s[None, :, None]
    phi = pa[:, None, None] + (pb - pa)[:, None, None] * s[None, None, :]
    values = np.einsum("kabi,ki->kab", angles_to_direction(theta, phi), m)
    sampled_min, sampled_max = values.min(axis=(1, 2)), values.max(axis=(1, 2))
    assert np.all(fmin <= sampled_min + 1e-12), f"seed {seed}"
    assert np.all(fmax >= sampled_max - 1e-12), f"seed {seed}"
    # The closed form is tight: dense sampling gets within the sampling error of it.
    np.testing.assert_allclose(fmin, sampled_min, atol=2e-3)
    np.testing.assert_allclose(fmax, sampled_max, atol=2e-3)


def test_extremes_include_the_interior_maximum_when_the_cell_holds_the_direction_itself():
    m = np.array([[0.0, 2.0, 0.0]])  # maximal straight up: theta 0, phi 0
    fmin, fmax = linear_extremes(m, [-0.1], [0.1], [-0.1], [0.1])
    np.testing.assert_allclose(fmax, [2.0], rtol=1e-12)  # float64 trigonometry: a few ulp
    np.testing.assert_allclose(fmin, [2.0 * np.cos(0.1) ** 2], rtol=1e-12)


def test_extremes_refuse_inverted_cells():
    with pytest.raises(ValueError, match="theta_a <= theta_b"):
        linear_extremes(np.ones((1, 3)), [0.2], [0.1], [0.0], [0.1])


def test_direction_angles_invert_angles_to_direction():
    rng = np.random.default_rng(3)
    theta = rng.uniform(-np.pi, np.pi, 100)
    phi = rng.uniform(-1.5, 1.5, 100)
    t2, p2 = direction_angles(angles_to_direction(theta, phi) * 7.0)
    np.testing.assert_allclose(t2, theta, atol=1e-12)
    np.testing.assert_allclose(p2, phi, atol=1e-12)


def test_cone_bounds_of_triangles_hold_every_direction_through_them():
    seed = 5
    rng = np.random.default_rng(seed)
    centre = rng.normal(size=(400, 3)) * 20.0
    tri = centre[:, None, :] + rng.normal(size=(400, 3, 3)) * 6.0
    lo_t, hi_t, lo_p, hi_p = triangle_cone_bounds(tri[:, 0], tri[:, 1], tri[:, 2])
    w = rng.dirichlet(np.ones(3), size=(400, 200))
    points = np.einsum("kcj,ksc->ksj", tri, w).reshape(-1, 3)
    theta, phi = direction_angles(points)
    owner = np.repeat(np.arange(400), 200)
    assert np.all(theta >= lo_t[owner] - 1e-12) and np.all(theta <= hi_t[owner] + 1e-12), seed
    assert np.all(phi >= lo_p[owner] - 1e-12) and np.all(phi <= hi_p[owner] + 1e-12), seed


def test_edge_normals_put_points_of_the_triangle_inside_and_others_outside():
    tri = np.array([[[10.0, 0.0, 0.0], [10.0, 5.0, 0.0], [10.0, 0.0, 5.0]]])
    n = cone_edge_normals(tri[:, 0], tri[:, 1], tri[:, 2])[0]
    assert np.all(n @ np.array([10.0, 1.0, 1.0]) > 0)
    assert np.any(n @ np.array([10.0, -1.0, 1.0]) < 0)


def test_box_direction_span_holds_the_directions_of_points_in_the_box():
    seed = 8
    rng = np.random.default_rng(seed)
    lo = rng.uniform(-30, 30, size=(300, 3))
    hi = lo + rng.uniform(0.1, 8.0, size=(300, 3))
    t_lo, t_hi, p_lo, p_hi = box_direction_span(lo, hi)
    pts = lo[:, None] + (hi - lo)[:, None] * rng.uniform(size=(300, 100, 3))
    theta, phi = direction_angles(pts.reshape(-1, 3))
    owner = np.repeat(np.arange(300), 100)
    assert np.all((theta >= t_lo[owner]) & (theta <= t_hi[owner])), seed
    assert np.all((phi >= p_lo[owner] - 1e-12) & (phi <= p_hi[owner] + 1e-12)), seed


def test_range_table_answers_rectangle_minima_like_brute_force():
    rng = np.random.default_rng(2)
    values = rng.uniform(size=(37, 53))
    table = RangeExtreme2D(values, np.minimum)
    j0 = rng.integers(0, 37, 200)
    j1 = np.minimum(j0 + rng.integers(0, 37, 200), 36)
    i0 = rng.integers(0, 53, 200)
    i1 = np.minimum(i0 + rng.integers(0, 53, 200), 52)
    brute = [values[a:b + 1, c:d + 1].min() for a, b, c, d in zip(j0, j1, i0, i1, strict=True)]
    # A minimum picks one of the stored values, computing none: exact.
    np.testing.assert_array_equal(table.query(j0, j1, i0, i1), brute)


def test_closest_point_on_triangle_matches_trimesh_in_every_voronoi_region():
    seed = 13
    rng = np.random.default_rng(seed)
    tri = rng.normal(size=(1, 3, 3)) * 5.0
    p = rng.normal(size=(2000, 3)) * 12.0
    ours = closest_points_on_triangles(p, tri[:, 0], tri[:, 1], tri[:, 2])
    theirs = trimesh.triangles.closest_point(np.repeat(tri, len(p), axis=0), p)
    np.testing.assert_allclose(ours, theirs, atol=1e-9)


@pytest.mark.parametrize("collapse", ["b on a", "c on b", "c on ab's line", "all on a"])
def test_a_degenerate_triangle_answers_the_closest_point_of_its_edges(collapse):
    seed = 29
    rng = np.random.default_rng(seed)
    n = 5000
    a, b, c = rng.normal(size=(3, n, 3)) * 5.0
    if collapse == "b on a":
        b = a.copy()
    elif collapse == "c on b":
        c = b.copy()
    elif collapse == "c on ab's line":
        c = a + rng.uniform(-1.0, 2.0, (n, 1)) * (b - a)
    else:
        b, c = a.copy(), a.copy()
    p = rng.normal(size=(n, 3)) * 12.0
    ours = closest_points_on_triangles(p, a, b, c)
    edges = np.stack([closest_points_on_segments(p, a, b), closest_points_on_segments(p, b, c),
                      closest_points_on_segments(p, c, a)])
    # 1e-9 mm: float64 rounding on coordinates of tens of millimetres.
    assert np.all(np.isfinite(ours))
    np.testing.assert_allclose(np.linalg.norm(ours - p, axis=1),
                               np.linalg.norm(edges - p, axis=2).min(axis=0), atol=1e-9)


def test_the_build_surface_distances_use_the_one_closest_point_kernel():
    from glasshead.geometry import surface_distance

    assert surface_distance.closest_points_on_triangles is closest_points_on_triangles


def test_the_moller_trumbore_kernel_is_written_once_and_the_ray_queries_call_it():
    from glasshead.fitting import ray_walk
    from glasshead.geometry import collision_exact, ray_triangle

    package = Path(ray_triangle.__file__).parents[1]
    written = sorted(str(path.relative_to(package)) for path in package.rglob("*.py")
                     if "dy * e2z - dz * e2y" in path.read_text())
    assert written == ["geometry/ray_triangle.py"]
    assert collision_exact.ray_triangle is ray_walk.ray_triangle is ray_triangle.ray_triangle


def test_moller_trumbore_hits_inside_and_misses_outside_and_parallel():
    a = np.array([5.0, -1.0, -1.0])
    e1 = np.array([0.0, 3.0, 0.0])
    e2 = np.array([0.0, 0.0, 3.0])
    d = np.array([[1.0, 0.0, 0.0], [2.0, 0.2, 0.2], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0],
                  [-1.0, 0.0, 0.0]])
    t = ray_triangle_hits(d, a, e1, e2)
    np.testing.assert_allclose(t[:2], [5.0, 2.5], rtol=1e-12)  # a few float64 operations
    assert np.all(np.isinf(t[2:]))  # beside the triangle, parallel to it, pointing away


def test_first_hits_agree_with_embree_raycasts_on_a_real_shape():
    seed = 17
    mesh = trimesh.creation.icosphere(subdivisions=3, radius=20.0)
    rng = np.random.default_rng(seed)
    points = rng.normal(size=(500, 3)) * 15.0
    origin = np.array([1.0, 2.0, 0.5])
    t, radius = first_hits_from_origin(points, origin, mesh.vertices, mesh.faces)
    d = points - origin
    hit, ray_idx, _ = mesh.ray.intersects_location(np.tile(origin, (500, 1)),
                                                   d / np.linalg.norm(d, axis=1)[:, None],
                                                   multiple_hits=False)
    ref = np.full(500, np.inf)
    ref[ray_idx] = np.linalg.norm(hit - origin, axis=1)
    # mm: Embree intersects in float32 (about 2e-6 mm of rounding at 20 mm).
    np.testing.assert_allclose(radius, ref, rtol=0, atol=1e-4)
    # Inside or outside: compared where the point is more than 1e-3 mm from the surface, so that
    # float32 Embree and float64 rounding cannot disagree on which side it is.
    r = np.linalg.norm(d, axis=1)
    clear = ~(np.abs(r - ref) <= 1e-3)
    assert clear.sum() >= 490, f"seed {seed}: only {clear.sum()} points clear of the surface"
    np.testing.assert_array_equal((t < 1)[clear], (r > ref)[clear])


def test_projection_onto_the_closest_triangle_moves_only_points_behind_the_surface():
    # A square floor facing +y: points below it are behind and move straight up onto it.
    v = np.array([[-10.0, 0, -10], [10, 0, -10], [10, 0, 10], [-10, 0, 10]])
    f = np.array([[0, 2, 1], [0, 3, 2]])
    points = np.array([[1.0, -2.0, 3.0], [1.0, 2.0, 3.0]])
    out, moved = project_onto_closest(points, v, f)
    np.testing.assert_array_equal(moved, [True, False])  # 2 mm behind and 2 mm in front
    np.testing.assert_allclose(out, [[1.0, 0.0, 3.0], [1.0, 2.0, 3.0]], rtol=0, atol=1e-12)
