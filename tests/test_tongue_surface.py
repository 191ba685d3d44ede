"""The reference tongue evaluator: a closed surface of fixed topology that the parameters shape."""

import itertools
import json
from pathlib import Path

import numpy as np
import pytest

from glasshead.constants import TONGUE_CONTROL_FLOOR_MM
from glasshead.geometry.jaw import apply_jaw_pose, jaw_pose
from glasshead.geometry.mesh_volume import is_closed_manifold
from glasshead.geometry.tongue_surface import ParameterError, TongueRig, surface_triangles

VECTORS = Path(__file__).parent / "vectors"


@pytest.fixture(scope="module")
def rig():
    return TongueRig(json.loads((VECTORS / "tongue-surface.json").read_text())["fixtures"]["rig"])


def test_the_surface_has_at_least_2000_vertices_and_is_closed_and_consistently_wound(rig):
    surface = rig.evaluate(rig.neutral)
    assert len(surface.vertices) >= 2000
    assert is_closed_manifold(surface.triangles)
    edges = len(surface.triangles) * 3 // 2
    assert len(surface.vertices) - edges + len(surface.triangles) == 2  # a sphere
    assert surface.volume > 0


def test_normals_are_unit_vectors_pointing_away_from_the_hub(rig):
    surface = rig.evaluate(rig.values_from({"jaw_opening": 10.0, "back_width": 4.0}))
    hub = rig.control_points(rig.values_from({"jaw_opening": 10.0}))[1]
    np.testing.assert_allclose(np.linalg.norm(surface.normals, axis=1), 1.0, atol=1e-12)
    outward = surface.vertices - np.r_[hub, 0.0]
    assert np.all(np.einsum("ij,ij->i", outward, surface.normals) > 0)


def test_the_triangles_never_change_only_the_vertices_do(rig):
    a = rig.evaluate(rig.neutral)
    b = rig.evaluate(rig.values_from({"dorsum_height": 6.0, "front_groove_depth": 3.0}))
    np.testing.assert_array_equal(a.triangles, b.triangles)
    np.testing.assert_array_equal(a.triangles, surface_triangles(rig.stations, rig.page_samples))
    assert np.abs(a.vertices - b.vertices).max() > 3


def test_missing_parameters_take_their_neutral_values(rig):
    np.testing.assert_array_equal(rig.values_from({}), rig.neutral)  # copied, not computed
    # the same computation twice in one process: the same bits
    np.testing.assert_array_equal(rig.evaluate(rig.neutral).vertices, rig.vertices(rig.neutral))


def test_an_unknown_parameter_is_refused_by_name_with_the_known_names(rig):
    with pytest.raises(ParameterError, match=r"unknown parameter 'tip_heigth'; known: "
                                             r"tip_advancement, tip_height") as error:
        rig.values_from({"tip_heigth": 1.0})
    assert error.value.parameter == "tip_heigth"


def test_a_value_outside_its_range_is_refused_with_the_range_and_unit(rig):
    p = rig.parameters["tip_height"]
    with pytest.raises(ParameterError, match=rf"tip_height = 40 is outside its range "
                                             rf"\[{p['min']:g}, {p['max']:g}\] mm"):
        rig.values_from({"tip_height": 40})
    with pytest.raises(ParameterError, match="not a finite number"):
        rig.values_from({"jaw_opening": float("nan")})


def test_the_rest_shape_is_left_right_symmetric(rig):
    v = rig.evaluate(rig.neutral).vertices
    mirrored = v * [1, 1, -1]
    nearest = np.min(np.linalg.norm(mirrored[:, None, :] - v[None, ::7, :], axis=2), axis=1)
    # every vertex has a mirror image on the surface (within the sample spacing)
    assert np.median(nearest) < 2.5
    np.testing.assert_allclose(v[:, 2].min(), -v[:, 2].max(), atol=1e-9)


def test_parameter_sets_within_range_keep_the_pages_in_order_so_the_surface_cannot_fold(rig):
    seed = 5
    rng = np.random.default_rng(seed)
    for values in rng.uniform(rig.minimum, rig.maximum, (400, len(rig.neutral))):
        named = dict(zip(rig.parameter_names, values, strict=True))
        assert rig.pages_in_order(values), f"seed {seed}: {named}"


def test_every_corner_of_the_sagittal_and_jaw_ranges_keeps_the_pages_in_order(rig):
    names = [n for n, p in rig.parameters.items() if p["group"] in ("tongue sagittal", "jaw")]
    index = [rig.parameter_names.index(n) for n in names]
    for corner in itertools.product(*[(rig.minimum[k], rig.maximum[k]) for k in index]):
        values = rig.neutral.copy()
        values[index] = corner
        assert rig.pages_in_order(values), dict(zip(names, corner, strict=True))


def test_no_radius_goes_through_the_hub_with_the_deepest_grooves_at_any_corner(rig):
    # The root forward with the back of the dorsum down brings stations within 6 mm of the hub;
    # there a deep groove took the midline through it (1,024 of these corners did) until no
    # radial control could come nearer the hub than the floor.
    names = [n for n, p in rig.parameters.items() if p["group"] in ("tongue sagittal", "jaw")]
    index = [rig.parameter_names.index(n) for n in names]
    deepest = rig.neutral.copy()
    for section in ("middle", "back"):
        for name, end in (("groove_depth", rig.maximum), ("groove_width", rig.maximum),
                          ("left_edge_height", rig.minimum),
                          ("right_edge_height", rig.minimum)):
            k = rig.parameter_names.index(f"{section}_{name}")
            deepest[k] = end[k]
    smallest = np.inf
    for corner in itertools.product(*[(rig.minimum[k], rig.maximum[k]) for k in index]):
        values = deepest.copy()
        values[index] = corner
        smallest = min(smallest, rig.page_radii(values)[3].min())
    assert smallest >= TONGUE_CONTROL_FLOOR_MM - 1e-9


def _station_crosses(rig, values, hub):
    stations = rig.station_basis @ rig.control_points(values)[0] - hub
    following = np.roll(stations, -1, axis=0)
    return stations[:, 0] * following[:, 1] - stations[:, 1] * following[:, 0]


def test_the_hub_comes_forward_and_up_with_the_root_where_the_pages_allow(rig):
    by = dict((f["parameter"], f["by"]) for f in rig.definition["hub"]["follows"])
    assert by["root_advancement"][0] > 0 and by["root_advancement"][1] > 0
    values = rig.values_from({"root_advancement": 10.0})
    hub = rig.control_points(values)[1]
    np.testing.assert_allclose(hub, rig.hub + 10.0 * np.asarray(by["root_advancement"]),
                               atol=1e-12)
    np.testing.assert_array_equal(rig.control_points(rig.neutral)[1], rig.hub)


def test_a_hub_that_would_close_the_turn_between_two_stations_stops_at_its_share(rig):
    # The root drawn in as far as it goes with the back of the dorsum down brings the root's
    # stations within a few mm of the hub: there the whole move would fold the pages.
    values = rig.values_from({"root_advancement": rig.parameters["root_advancement"]["max"],
                              "back_dorsum_height": rig.parameters["back_dorsum_height"]["min"],
                              "jaw_opening": 8.0})
    unmoved = rig.control_points(rig.values_from({"jaw_opening": 8.0}))[1]
    hub = rig.control_points(values)[1]
    follows = np.asarray(rig.definition["hub"]["follows"][0]["by"])
    full = np.linalg.norm(follows) * rig.parameters["root_advancement"]["max"]
    assert 0 < np.linalg.norm(hub - unmoved) < 0.9 * full
    kept = _station_crosses(rig, values, hub) / _station_crosses(rig, values, unmoved)
    assert kept.min() == pytest.approx(rig.hub_keep, abs=1e-9)
    assert rig.pages_in_order(values)


def test_a_rig_whose_hub_follows_an_unknown_parameter_is_refused(rig):
    broken = json.loads(json.dumps(rig.definition))
    broken["hub"]["follows"] = [{"parameter": "root_advance", "by": [0.5, 0.5]}]
    with pytest.raises(ValueError, match="the hub follows 'root_advance', which is not in"):
        TongueRig(broken)
    broken["hub"]["follows"] = []
    broken["hub"]["keep"] = 1.0
    with pytest.raises(ValueError, match=r"keep must lie in \[0, 1\)"):
        TongueRig(broken)


def test_pages_out_of_order_are_detected(rig):
    values = rig.neutral.copy()
    moved = rig.rest_points.copy()
    rig.rest_points[1] = rig.rest_points[4]  # tip B thrown behind the blade
    try:
        assert not rig.pages_in_order(values)
    finally:
        rig.rest_points[:] = moved


def test_tip_advancement_moves_the_tip_forward_and_leaves_the_root(rig):
    rest = rig.evaluate(rig.neutral).vertices
    moved = rig.evaluate(rig.values_from({"tip_advancement": 6.0})).vertices
    assert moved[:, 0].max() - rest[:, 0].max() > 5
    np.testing.assert_allclose(moved[:, 0].min(), rest[:, 0].min(), atol=1e-9)


def test_dorsum_height_raises_the_top_of_the_tongue(rig):
    rest = rig.evaluate(rig.neutral).vertices
    raised = rig.evaluate(rig.values_from({"dorsum_height": 5.0})).vertices
    assert 4 < raised[:, 1].max() - rest[:, 1].max() < 6


def test_front_width_widens_the_front_of_the_tongue_about_a_millimetre_per_millimetre(rig):
    def width_near_tip(v):
        front = v[v[:, 0] > v[:, 0].max() - 12]
        return np.ptp(front[:, 2])

    rest = rig.evaluate(rig.neutral).vertices
    wide = rig.evaluate(rig.values_from({"front_width": 4.0})).vertices
    assert 2.5 < width_near_tip(wide) - width_near_tip(rest) < 5.5


def test_left_edge_height_raises_the_left_side_only(rig):
    rest = rig.evaluate(rig.neutral).vertices
    raised = rig.evaluate(rig.values_from({"middle_left_edge_height": 5.0})).vertices
    moved = np.linalg.norm(raised - rest, axis=1) > 0.5
    assert moved.any()
    assert np.all(rest[moved, 2] > 0)  # +z is the subject's left


def test_groove_depth_lowers_the_midline_of_the_dorsum(rig):
    rest = rig.evaluate(rig.neutral).vertices
    grooved = rig.evaluate(rig.values_from({"middle_groove_depth": 4.0})).vertices
    middle = np.argmax(rig.station_blend[:, 1])
    top = 2 + middle * rig.page_samples + rig.page_samples // 2  # the midline sample
    assert abs(rest[top, 2]) < 1e-9 and rest[top, 1] > 5
    hub = np.r_[rig.hub, 0.0]
    lowered = np.linalg.norm(rest[top] - hub) - np.linalg.norm(grooved[top] - hub)
    # 1 mm per mm where the middle section applies fully; here it applies in part
    np.testing.assert_allclose(lowered, 4.0 * rig.station_blend[middle, 1], atol=0.05)
    side = np.argmin(np.linalg.norm(rest - (rest[top] + [0, 0, 15]), axis=1))
    assert abs(grooved[side, 1] - rest[side, 1]) < 1  # the sides of the dorsum stay


def test_the_tongue_rides_on_the_jaw_its_floor_points_move_with_the_mandible(rig):
    values = rig.values_from({"jaw_opening": 10.0})
    points, hub, _offsets, _stretch = rig.control_points(values)
    pose = jaw_pose(10.0, rig.jaw)
    fully = rig.point_jaw_weights == 1.0
    np.testing.assert_allclose(points[fully], apply_jaw_pose(rig.rest_points[fully], pose),
                               atol=1e-12)
    np.testing.assert_allclose(hub, apply_jaw_pose(rig.hub[None], pose, [rig.hub_jaw_weight])[0],
                               rtol=0, atol=1e-12)  # mm, the same pose by two routes
    rest, opened = rig.evaluate(rig.neutral).vertices, rig.vertices(values)
    assert opened[:, 1].min() < rest[:, 1].min() - 5  # 8.5 mm lower at 10 degrees


def test_width_stretches_sideways_and_never_moves_the_poles(rig):
    rest = rig.evaluate(rig.neutral).vertices
    wide = rig.evaluate(rig.values_from({"middle_width": 6.0, "back_width": 6.0})).vertices
    # Width enters z alone: x and y (and the poles) are the same arithmetic on the same numbers.
    np.testing.assert_array_equal(wide[:2], rest[:2])
    np.testing.assert_array_equal(wide[:, :2], rest[:, :2])
    assert np.all(np.abs(wide[:, 2]) >= np.abs(rest[:, 2]) - 1e-12)
