"""The walked, certified first hits equal the exhaustive search's on the real rig."""

import json

import numpy as np
import pytest

from glasshead.fitting.first_hits import exhaustive_first_hits
from glasshead.fitting.objective3d import RayError3D
from glasshead.fitting.ray_walk import RayWalker
from glasshead.geometry.collision_exact import first_hits_from_origin
from glasshead.geometry.mesh_topology import triangle_adjacency
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.settings import get_settings

POSES = 20
RAYS = 1000


@pytest.fixture(scope="module")
def rig():
    path = get_settings().assets_dir / "tongue-rig.json"
    if not path.is_file():
        pytest.fail(f"built rig missing: expected {path} (run `glasshead build`)")
    return TongueRig(json.loads(path.read_text()))


@pytest.fixture(scope="module")
def setup(rig):
    rest = rig.vertices(rig.neutral)
    origin = np.r_[rig.hub, 0.0]
    rng = np.random.default_rng(20240611)
    # points spread over the rest surface, a little off it
    targets = rest[rng.choice(len(rest), RAYS, replace=False)] + rng.normal(0.0, 0.5, (RAYS, 3))
    return rest, origin, targets - origin, RayWalker(rig.triangles, rest)


def test_the_adjacency_of_the_closed_tongue_is_symmetric_and_complete(rig):
    adjacency = triangle_adjacency(rig.triangles)
    assert np.all(adjacency >= 0)
    rows = np.repeat(np.arange(len(adjacency)), 3)
    assert np.all(np.any(adjacency[adjacency.ravel()] == rows[:, None], axis=1))


def test_walking_from_the_previous_pose_gives_the_exhaustive_first_hit_on_random_poses(rig, setup):
    rest, origin, directions, walker = setup
    rng = np.random.default_rng(1998)
    previous = walker.first_hits(origin, directions, rest).triangle
    overturned = fallback = 0
    for _ in range(POSES):
        values = rng.uniform(rig.minimum, rig.maximum)
        vertices = rig.vertices(values)
        hits = walker.first_hits(origin, directions, vertices, previous)
        triangle, t = exhaustive_first_hits(origin, directions, vertices, rig.triangles)
        np.testing.assert_array_equal(hits.triangle, triangle)
        hit = triangle >= 0
        np.testing.assert_allclose(hits.t[hit], t[hit], rtol=1e-9, atol=0)
        assert np.all(np.isinf(hits.t[~hit]))
        # and the project's brute-force kernel agrees on where the first crossing is
        reference, _ = first_hits_from_origin(origin + directions, origin, vertices,
                                              rig.triangles)
        np.testing.assert_allclose(hits.t[hit], reference[hit], rtol=1e-9, atol=0)
        np.testing.assert_allclose(hits.point[hit], origin + t[hit, None] * directions[hit])
        overturned += int(hits.overturned.sum())
        fallback += int(hits.fallback.sum())
        previous = hits.triangle
    assert fallback < POSES * RAYS  # the walk, not the fallback, answers most rays


def test_small_steps_as_in_an_optimisation_stay_exact(rig, setup):
    rest, origin, directions, walker = setup
    rng = np.random.default_rng(7)
    values = rng.uniform(rig.minimum, rig.maximum)
    previous = walker.first_hits(origin, directions, rig.vertices(values)).triangle
    span = rig.maximum - rig.minimum
    for _ in range(10):
        values = np.clip(values + rng.normal(0.0, 0.01, values.shape) * span,
                         rig.minimum, rig.maximum)
        vertices = rig.vertices(values)
        hits = walker.first_hits(origin, directions, vertices, previous)
        triangle, _ = exhaustive_first_hits(origin, directions, vertices, rig.triangles)
        np.testing.assert_array_equal(hits.triangle, triangle)
        assert hits.fallback.mean() < 0.05
        previous = hits.triangle


def test_a_fold_in_front_of_the_previous_hit_is_found_where_a_naive_walk_keeps_the_far_one(
        rig, setup):
    rest, _, _, walker = setup
    # From outside the tongue every ray through it crosses two layers. Each ray's previous hit
    # is its far crossing (as if the near layer had just folded in front of it).
    origin = np.r_[rig.hub, 0.0] + np.array([0.0, 0.0, 80.0])
    rng = np.random.default_rng(3)
    directions = rest[rng.choice(len(rest), 200, replace=False)] - origin
    beyond = origin + 3.0 * directions
    far = np.array([exhaustive_first_hits(b, -d[None], rest, rig.triangles)[0][0]
                    for b, d in zip(beyond, directions, strict=True)])
    near, t_near = exhaustive_first_hits(origin, directions, rest, rig.triangles)
    through = (far >= 0) & (near >= 0) & (far != near)
    assert through.sum() > 100
    start = np.where(through, far, near)

    naive, t_naive = walker.naive_walk(origin, directions, rest, start)
    assert np.all(naive[through] == far[through])  # the naive walk stays on the far layer
    assert np.all(t_naive[through] > t_near[through])
    gap = (t_naive - t_near)[through] * np.linalg.norm(directions[through], axis=1)
    assert gap.max() > 10.0  # mm: the error a naive walk would make

    hits = walker.first_hits(origin, directions, rest, start)
    np.testing.assert_array_equal(hits.triangle, near)
    assert np.all(hits.overturned[through])


def test_the_3d_error_is_the_rms_distance_along_the_rays_and_keeps_its_hits(rig, setup):
    rest, origin, directions, _ = setup
    observed = origin + directions
    error = RayError3D(rig.triangles, rest, observed, origin)
    values = rig.values_from({"body_height": 3.0})
    vertices = rig.vertices(values)
    first = error(vertices)
    triangle, t = exhaustive_first_hits(origin, directions, vertices, rig.triangles)
    r = (t - 1.0) * np.linalg.norm(directions, axis=1)
    assert first == pytest.approx(np.sqrt(np.mean(r ** 2)), rel=1e-12)
    assert error.previous is not None
    again = error(rig.vertices(rig.values_from({"body_height": 3.2})))
    assert again != first and not error.hits.fallback.all()
    mask = np.arange(RAYS) % 2 == 0
    half = RayError3D(rig.triangles, rest, observed, origin, mask=mask)
    assert half(vertices) == pytest.approx(np.sqrt(np.mean(r[mask] ** 2)), rel=1e-12)
    assert error(rest) < 1.0  # the observed points lie within 0.5 mm-ish of the rest surface


def test_a_ray_that_misses_gets_the_documented_penalty(rig, setup):
    rest, origin, _, _ = setup
    outside = origin + np.array([0.0, 0.0, 80.0])
    observed = np.array([outside + [0.0, 0.0, 10.0], rest[100]])  # the first points away
    error = RayError3D(rig.triangles, rest, observed, outside, miss_penalty_mm=7.0)
    r = error.residuals(rest)
    assert r[0] == 7.0 and error.hits.triangle[0] == -1
    default = RayError3D(rig.triangles, rest, observed, outside)
    assert default.residuals(rest)[0] == pytest.approx(10.0)


def test_bad_input_is_refused_with_a_clear_message(rig, setup):
    rest, origin, directions, walker = setup
    nan = directions[:5].copy()
    nan[2, 1] = np.nan
    with pytest.raises(ValueError, match="directions must be finite: 1 rays.*ray 2"):
        walker.first_hits(origin, nan, rest, np.zeros(5, dtype=np.int64))
    with pytest.raises(ValueError, match=r"directions must have shape \(k, 3\)"):
        walker.first_hits(origin, directions[:, :2], rest)
    with pytest.raises(ValueError, match="non-zero"):
        walker.first_hits(origin, np.zeros((2, 3)), rest)
    with pytest.raises(ValueError, match=r"origin must have shape \(3,\)"):
        walker.first_hits(origin[:2], directions, rest)
    with pytest.raises(ValueError, match="vertices must have shape"):
        walker.first_hits(origin, directions, rest[:-1])
    with pytest.raises(ValueError, match="start must have shape"):
        walker.first_hits(origin, directions, rest, np.zeros(3, dtype=np.int64))
    with pytest.raises(ValueError, match="mask must be"):
        RayError3D(rig.triangles, rest, origin + directions, origin, mask=np.ones(3, bool))
    with pytest.raises(ValueError, match="triangles must have shape"):
        RayWalker(rig.triangles[:, :2], rest)


def _assert_exhaustive(hits, origin, directions, vertices, triangles):
    triangle, t = exhaustive_first_hits(origin, directions, vertices, triangles)
    np.testing.assert_array_equal(hits.triangle, triangle)
    hit = triangle >= 0
    np.testing.assert_array_equal(hits.t[hit], t[hit])
    assert np.all(np.isinf(hits.t[~hit]))


def test_the_crossing_count_certifies_most_rays_from_the_hub_in_small_steps(rig, setup):
    rest, origin, directions, walker = setup
    rng = np.random.default_rng(11)
    values = rng.uniform(rig.minimum, rig.maximum)
    previous = walker.first_hits(origin, directions, rig.vertices(values)).triangle
    span = rig.maximum - rig.minimum
    for _ in range(10):
        values = np.clip(values + rng.normal(0.0, 0.01, values.shape) * span,
                         rig.minimum, rig.maximum)
        vertices = rig.vertices(values)
        hits = walker.first_hits(origin, directions, vertices, previous)
        _assert_exhaustive(hits, origin, directions, vertices, rig.triangles)
        assert walker._w_max == 1 and walker._winding() == 1  # the hub is inside
        assert hits.shortcut.mean() > 0.95
        previous = hits.triangle


def test_rays_that_cross_back_facing_triangles_go_through_the_hierarchy_and_stay_exact(
        rig, setup):
    rest, _, _, walker = setup
    # an origin inside the tongue but close under its dorsum: many triangles face it
    top = rest[np.argmax(rest[:, 1])]
    hub = np.r_[rig.hub, 0.0]
    rng = np.random.default_rng(5)
    targets = rest[rng.choice(len(rest), RAYS, replace=False)]
    for share in (0.8, 0.9, 0.95):
        origin = hub + share * (top - hub)
        directions = targets - origin
        previous = walker.first_hits(origin, directions, rest).triangle
        vertices = rig.vertices(rig.values_from({"body_height": 1.0}))
        hits = walker.first_hits(origin, directions, vertices, previous)
        _assert_exhaustive(hits, origin, directions, vertices, rig.triangles)
        assert hits.back_facing > 0
        assert walker._winding() == 1
        certified = ~hits.shortcut
        assert 0 < certified.sum() < RAYS  # both paths are exercised
        # a shortcut ray crosses no back-facing triangle: its hit is the only one
        assert np.all(hits.triangle[hits.shortcut] >= 0)


def test_from_outside_the_tongue_a_ray_with_no_entry_crosses_nothing(rig, setup):
    rest, _, _, walker = setup
    origin = np.r_[rig.hub, 0.0] + np.array([0.0, 0.0, 80.0])
    rng = np.random.default_rng(9)
    through = rest[rng.choice(len(rest), 300, replace=False)] - origin
    away = rng.normal(0.0, 1.0, (300, 3))  # most of these miss the tongue
    directions = np.concatenate([through, away])
    previous = walker.first_hits(origin, directions, rest).triangle
    vertices = rig.vertices(rig.values_from({"tip_height": 2.0}))
    hits = walker.first_hits(origin, directions, vertices, previous)
    _assert_exhaustive(hits, origin, directions, vertices, rig.triangles)
    assert walker._winding() == 0
    assert hits.shortcut.sum() > 100
    assert np.all(hits.triangle[hits.shortcut] == -1)  # w(O) = 0: no crossing at all
    assert (hits.triangle[:300] >= 0).sum() > 250  # those through the tongue: certified


def test_rays_through_vertices_and_edges_take_the_smallest_tied_triangle(rig, setup):
    rest, origin, _, walker = setup
    vertices = rig.vertices(rig.values_from({"body_height": 2.0}))
    tri = rig.triangles
    rng = np.random.default_rng(17)
    pick = rng.choice(len(tri), 300, replace=False)
    corners = vertices[tri[pick, 0]]
    middles = 0.5 * (vertices[tri[pick, 1]] + vertices[tri[pick, 2]])
    directions = np.concatenate([corners, middles]) - origin
    # start each ray's walk on its picked triangle, which may not be the smallest of the ties
    start = np.r_[pick, pick]
    hits = walker.first_hits(origin, directions, vertices, start)
    _assert_exhaustive(hits, origin, directions, vertices, rig.triangles)
    assert hits.overturned.sum() > 50  # the walk's triangle lost the tie on many rays
    assert hits.shortcut.mean() > 0.9


def test_a_mesh_that_is_not_consistently_oriented_is_never_certified_by_counting(rig, setup):
    rest, origin, directions, _ = setup
    flipped = rig.triangles.copy()
    flipped[10] = flipped[10, ::-1]  # one triangle's normal inward: crossings no longer count
    walker = RayWalker(flipped, rest)
    assert not walker._oriented
    previous = walker.first_hits(origin, directions[:200], rest).triangle
    vertices = rig.vertices(rig.values_from({"body_height": 1.0}))
    hits = walker.first_hits(origin, directions[:200], vertices, previous)
    _assert_exhaustive(hits, origin, directions[:200], vertices, flipped)
    assert not hits.shortcut.any()


def test_the_hits_carry_the_enclosed_volume_of_the_pose_from_any_origin(rig, setup):
    rest, origin, directions, walker = setup
    rng = np.random.default_rng(11)
    start = None  # the first two poses search exhaustively, the others walk
    for k in range(10):
        values = rng.uniform(rig.minimum, rig.maximum)
        vertices = rig.vertices(values)
        # the origin inside (the hub) or well outside the tongue: a closed mesh's volume is
        # the same seen from anywhere
        o = origin if k % 2 == 0 else origin + np.array([90.0, 40.0, 25.0])
        hits = walker.first_hits(o, directions, vertices, start)
        assert hits.volume == pytest.approx(rig.volume(values), rel=1e-12)
        assert hits.volume > 0  # outward winding
        start = None if k < 1 else hits.triangle
