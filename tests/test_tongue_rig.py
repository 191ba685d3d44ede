"""The tongue rig definition: its parameter table and the checks on a definition read back."""

import copy
import json
from pathlib import Path

import numpy as np
import pytest

from glasshead.constants import TONGUE_CONTROL_FLOOR_MM
from glasshead.geometry.tongue_parameters import (
    CORONAL_CONTROLS,
    POLE_CONTROLS,
    SAGITTAL_POINTS,
    parameter_table,
)
from glasshead.geometry.tongue_rig import build_definition, validate_definition
from glasshead.geometry.tongue_surface import TongueRig

VECTORS = Path(__file__).parent / "vectors"


@pytest.fixture(scope="module")
def definition():
    return json.loads((VECTORS / "tongue-surface.json").read_text())["fixtures"]["rig"]


def moves_of(name):
    return next(p for p in parameter_table() if p["name"] == name)["moves"]


def test_there_are_fourteen_sagittal_parameters_three_times_seven_coronal_and_the_jaw():
    groups = [p["group"] for p in parameter_table()]
    assert groups.count("tongue sagittal") == 14
    for section in ("front", "middle", "back"):
        assert groups.count(f"tongue coronal {section}") == 7
    assert groups.count("jaw") == 1


def test_every_parameter_has_a_unit_a_range_around_its_neutral_value_and_a_description():
    for p in parameter_table():
        assert p["unit"] in ("mm", "deg", "ratio"), p["name"]
        assert p["min"] <= p["neutral"] <= p["max"] and p["min"] < p["max"], p["name"]
        assert p["description"], p["name"]
        assert p["moves"] or p["group"] == "jaw", p["name"]


def test_sagittal_control_points_are_lettered_from_the_tip_and_turn_round_the_hub_once():
    letters = [name for name, *_ in SAGITTAL_POINTS]
    assert letters == [chr(ord("A") + k) for k in range(len(letters))]
    angles = [angle for _n, _r, angle, _w, _b in SAGITTAL_POINTS]
    assert angles == sorted(angles) and angles[-1] - angles[0] < 360
    assert SAGITTAL_POINTS[1][1] == "tip"


def test_tip_advancement_moves_the_tip_pair_forward_together():
    moves = {m["point"]: m["by"] for m in moves_of("tip_advancement")}
    assert moves["A"] == moves["B"] == [1.0, 0.0]


def test_tip_thickness_moves_the_tip_pair_vertically_in_opposite_directions():
    moves = {m["point"]: m["by"] for m in moves_of("tip_thickness")}
    assert set(moves) == {"A", "B"}
    assert moves["A"][0] == moves["B"][0] == 0
    assert moves["A"][1] == -moves["B"][1] != 0


def test_edge_heights_move_one_side_only_and_mirror_each_other():
    left = {(m["section"], m["control"]): m["by"] for m in moves_of("front_left_edge_height")}
    right = {(m["section"], m["control"]): m["by"] for m in moves_of("front_right_edge_height")}
    assert all(control.startswith("left") for _s, control in left)
    assert {(s, c.replace("left", "right")): by for (s, c), by in left.items()} == right


def test_no_parameter_moves_a_pole_control():
    poles = {CORONAL_CONTROLS[k] for k in POLE_CONTROLS}
    for p in parameter_table():
        assert not any(m.get("control") in poles for m in p["moves"]), p["name"]


def test_the_shared_definition_passes_its_own_checks(definition):
    validate_definition(definition)
    assert definition["units"] == "mm" and definition["frame"]["name"] == "project"


@pytest.mark.parametrize("change, message", [
    (lambda d: d.update(format_version=99), "format_version"),
    (lambda d: d["parameters"].append(copy.deepcopy(d["parameters"][0])), "duplicate parameter"),
    (lambda d: d["parameters"][0].update(neutral=100.0), "min <= neutral <= max"),
    (lambda d: d["parameters"][0].update(unit="furlong"), "unit"),
    (lambda d: d["parameters"][0]["moves"].append({"point": "Z", "by": [1, 0]}),
     "bad sagittal move"),
    (lambda d: d["parameters"][0]["moves"].append({"point": "Z", "turn": 1.0}), "bad turn"),
    (lambda d: d["parameters"][0]["moves"].append({"point": "E", "turn": "far"}), "bad turn"),
    (lambda d: d["parameters"][0]["moves"].append({"point": "Z", "radial": -1.0}),
     "bad radial move"),
    (lambda d: d["parameters"][0]["moves"].append({"point": "E", "radial": None}),
     "bad radial move"),
    (lambda d: d["parameters"][12]["moves"].append(
        {"section": "front", "control": "left pole", "by": 1.0}), "pole controls cannot move"),
    (lambda d: d["sagittal"]["control_points"][0].update(section_weights=[0.5, 0.1, 0.1]),
     "summing to 1"),
    (lambda d: d["surface"].update(station_params=[0.5, 0.2, 0.7]), "station_params"),
    (lambda d: d["surface"].update(page_angles_deg=[-90.0, 0.0, 45.0]), "page_angles_deg"),
    (lambda d: d["coronal"].update(pole_half_width=0.0), "pole_half_width"),
    (lambda d: d.pop("jaw"), "'jaw'"),
])
def test_a_broken_definition_is_refused_with_a_message_naming_the_problem(definition, change,
                                                                           message):
    broken = copy.deepcopy(definition)
    change(broken)
    with pytest.raises(ValueError, match=message):
        validate_definition(broken)


def test_a_definition_survives_a_json_round_trip_unchanged_in_its_surface(definition):
    rig = TongueRig(definition)
    again = TongueRig(json.loads(json.dumps(definition)))
    values = rig.values_from({"tip_height": 3.0, "middle_width": -2.0, "jaw_opening": 8.0})
    # JSON keeps every float64 bit, so the same arithmetic gives the same bits.
    np.testing.assert_array_equal(rig.vertices(values), again.vertices(values))


def test_build_definition_checks_the_shapes_it_is_given(definition):
    rig = TongueRig(definition)
    common = {"section_weights": np.tile([1.0, 0.0, 0.0], (len(SAGITTAL_POINTS), 1)),
              "ratios": {s: np.ones(15) for s in ("front", "middle", "back")},
              "pole_half_width": 15.0, "station_params": rig.station_params,
              "page_angles_deg": definition["surface"]["page_angles_deg"],
              "jaw": definition["jaw"]}
    with pytest.raises(ValueError, match="sagittal_positions"):
        build_definition(sagittal_positions=np.zeros((5, 2)), **common)
    built = build_definition(sagittal_positions=rig.rest_points, **common)
    assert built["surface"]["vertex_count"] == rig.vertex_count
    front = built["coronal"]["ratios"]["front"]
    assert all(v == 0 for k, v in enumerate(front) if k in POLE_CONTROLS)


@pytest.mark.parametrize("name, value", [("back_dorsum_height", -16.0),
                                         ("back_dorsum_height", 20.0),
                                         ("root_advancement", 24.0),
                                         ("dorsum_front_height", 20.0)])
def test_the_dorsum_and_the_root_move_along_the_hubs_rays_so_no_point_turns(definition,
                                                                            name, value):
    rig = TongueRig(definition)
    values = rig.neutral.copy()
    values[rig.parameter_names.index(name)] = value
    rest, hub, _, _ = rig.control_points(rig.neutral)
    posed, _, _, _ = rig.control_points(values)
    moved = np.linalg.norm(posed - rest, axis=1) > 1.0
    assert moved.sum() >= 3, name
    turn = np.degrees(np.arctan2(*(posed - hub).T[::-1]) - np.arctan2(*(rest - hub).T[::-1]))
    np.testing.assert_allclose(turn, 0.0, atol=1e-4)
    inward = np.linalg.norm(posed - hub, axis=1) < np.linalg.norm(rest - hub, axis=1)
    # Raising the back or the front of the dorsum takes it away from the hub; the root comes
    # toward it.
    assert (inward[moved] == (value < 0 if "dorsum" in name else True)).all()


def test_the_raised_front_of_the_dorsum_goes_up_and_forward_and_only_up():
    front = {m["point"]: m["by"] for m in moves_of("dorsum_front_height")}
    assert set(front) == {"C", "D", "E", "F", "G"}
    assert all(by[1] > 0 for by in front.values())
    assert front["C"][0] > 0 and front["D"][0] > 0 and front["E"][0] > 0
    spec = next(p for p in parameter_table() if p["name"] == "dorsum_front_height")
    assert spec["min"] == spec["neutral"] == 0.0 and spec["max"] == 20.0


def test_the_retracted_tongue_turns_back_about_the_hub_keeping_each_points_distance(definition):
    rig = TongueRig(definition)
    values = rig.neutral.copy()
    values[rig.parameter_names.index("tongue_retraction")] = 20.0
    rest, hub, _, _ = rig.control_points(rig.neutral)
    posed, _, _, _ = rig.control_points(values)
    names = [p["name"] for p in definition["sagittal"]["control_points"]]
    turn = np.degrees(np.arctan2(*(posed - hub).T[::-1]) - np.arctan2(*(rest - hub).T[::-1]))
    turn = dict(zip(names, (turn + 180.0) % 360.0 - 180.0, strict=True))
    # D..M turn 20 degrees back (counterclockwise seen from the subject's left: the dorsum goes
    # back, the root down), tapering through the blade and along the floor; the tip stays.
    for name in "FGHIJKLM":
        assert turn[name] == pytest.approx(20.0, abs=1e-9), name
    assert 0 < turn["C"] < turn["D"] < turn["E"] < 20.0
    assert 0 < turn["O"] < turn["N"] < 20.0
    for name in "ABPQRS":
        assert turn[name] == pytest.approx(0.0, abs=1e-9), name
    np.testing.assert_allclose(np.linalg.norm(posed - hub, axis=1),
                               np.linalg.norm(rest - hub, axis=1), atol=1e-9)
    assert posed[names.index("G"), 0] < rest[names.index("G"), 0] - 5.0
    assert posed[names.index("K"), 1] < rest[names.index("K"), 1] - 5.0


def _directions_and_distances(rig, values):
    # Radial moves act about the hub at rest (the jaw closed here); the posed hub also follows
    # the root, by a share that the moved points change.
    points = rig.control_points(values)[0]
    away = points - rig.hub
    return np.arctan2(away[:, 1], away[:, 0]), np.linalg.norm(away, axis=1)


@pytest.mark.parametrize("name, value, moved", [
    ("dorsum_front_lowering", 6.0, {"D": 0.5, "E": 1.0, "F": 0.8, "G": 0.3}),
    ("root_base_advancement", 16.0, {"M": 1.0, "N": 0.6, "O": 0.2}),
])
def test_a_radial_move_draws_points_in_along_their_own_rays_after_the_straight_moves(
        definition, name, value, moved):
    # The dorsum forward and the blade back carry D..G off their rest rays; moved along those
    # rest rays they would cross the rays of their neighbours. A radial move keeps each point's
    # direction from the hub exactly, so it cannot turn one point past another.
    rig = TongueRig(definition)
    names = [p["name"] for p in definition["sagittal"]["control_points"]]
    before = rig.values_from({"dorsum_advancement": 6.0, "blade_advancement": -4.0,
                              "root_advancement": 12.0, "tip_height": 8.0})
    after = before.copy()
    after[rig.parameter_names.index(name)] = value
    angle0, distance0 = _directions_and_distances(rig, before)
    angle1, distance1 = _directions_and_distances(rig, after)
    np.testing.assert_allclose(angle1, angle0, atol=1e-12)
    drawn_in = dict(zip(names, distance0 - distance1, strict=True))
    for point in names:
        assert drawn_in[point] == pytest.approx(value * moved.get(point, 0.0), abs=1e-9), point


def test_a_radial_move_stops_at_the_floor_and_leaves_the_points_it_does_not_move(definition):
    broken = copy.deepcopy(definition)
    spec = next(p for p in broken["parameters"] if p["name"] == "root_base_advancement")
    spec["moves"] = [{"point": "M", "radial": -100.0}]
    rig = TongueRig(broken)
    values = rig.values_from({"root_base_advancement": 16.0})
    points, hub, _, _ = rig.control_points(values)
    rest, _, _, _ = rig.control_points(rig.neutral)
    distance = np.linalg.norm(points - hub, axis=1)
    m = [p["name"] for p in broken["sagittal"]["control_points"]].index("M")
    assert distance[m] == pytest.approx(TONGUE_CONTROL_FLOOR_MM, abs=1e-9)
    others = np.arange(len(points)) != m
    np.testing.assert_array_equal(points[others], rest[others])


def test_the_root_comes_forward_and_the_raised_back_of_the_dorsum_goes_up():
    root = {m["point"]: m["by"] for m in moves_of("root_advancement")}
    back = {m["point"]: m["by"] for m in moves_of("back_dorsum_height")}
    assert root["K"][0] > 0.95 and root["L"][0] > 0.95
    assert back["I"][1] > 0.7 and back["H"][1] > 0.4
