"""The velum rig: the built file, the blend of the three measured poses, and the nasal port."""

import json

import numpy as np
import pytest
import trimesh

from glasshead.constants import VELUM_PARAMETER, VELUM_RIG_FILE
from glasshead.geometry.velum import (
    VelumRigError,
    nasal_port_area,
    port_cut_areas,
    pose_velum,
    prepare_velum,
)

#: mm. Stored positions are rounded to 5 decimals; the GLBs hold float32 (4e-6 mm at 60 mm).
STORED_MM = 1e-5
#: mm^2. Areas of the same rig from the same float64 arithmetic.
AREA_MM2 = 1e-9


@pytest.fixture(scope="module")
def definition(built_assets):
    return json.loads((built_assets / VELUM_RIG_FILE).read_text())


@pytest.fixture(scope="module")
def rig(definition):
    return prepare_velum(definition)


@pytest.fixture(scope="module")
def glb_poses(built_assets):
    return {name: np.asarray(trimesh.load(built_assets / f"velum_{name}.glb", force="mesh",
                                          process=False).vertices, dtype=np.float64)
            for name in ("raised", "rest", "lowered")}


def test_the_rig_file_has_the_parameter_in_the_tongue_rigs_table_format(definition):
    (parameter,) = definition["parameters"]
    assert {k: parameter[k] for k in ("name", "unit", "min", "max", "group")} == \
        {"name": VELUM_PARAMETER, "unit": "ratio", "min": 0.0, "max": 1.0, "group": "velum"}
    assert parameter["neutral"] == definition["poses"]["at"][1]
    assert parameter["description"] and definition["description"]
    assert definition["frame"]["units"] == "mm"
    assert definition["poses"]["names"] == ["raised", "rest", "lowered"]
    assert definition["poses"]["vertex_count"] == 3787


def test_the_rest_share_is_the_rest_poses_share_of_the_path_by_mean_displacement(definition,
                                                                                glb_poses):
    raised, rest, lowered = glb_poses["raised"], glb_poses["rest"], glb_poses["lowered"]
    first = np.linalg.norm(rest - raised, axis=1).mean()
    second = np.linalg.norm(lowered - rest, axis=1).mean()
    assert definition["poses"]["at"][1] == pytest.approx(first / (first + second), abs=1e-6)
    assert 0.7 < definition["poses"]["at"][1] < 0.8


def test_openings_0_r_and_1_give_the_measured_poses(rig, glb_poses):
    for opening, name in ((0.0, "raised"), (rig.rest_share, "rest"), (1.0, "lowered")):
        np.testing.assert_allclose(pose_velum(rig, opening), glb_poses[name], rtol=0,
                                   atol=STORED_MM, err_msg=name)


def test_between_two_poses_every_vertex_lies_on_the_segment_between_them(rig):
    raised, rest, lowered = rig.poses
    for opening, (a, b, share) in ((0.3, (raised, rest, 0.3 / rig.rest_share)),
                                   (0.9, (rest, lowered, (0.9 - rig.rest_share)
                                          / (1 - rig.rest_share)))):
        posed = pose_velum(rig, opening)
        np.testing.assert_allclose(posed, a + (b - a) * share, rtol=0, atol=1e-9)
        low, high = np.minimum(a, b), np.maximum(a, b)
        assert np.all(posed >= low - 1e-9) and np.all(posed <= high + 1e-9)


def test_pose_velum_writes_into_out_and_refuses_an_opening_out_of_range(rig):
    out = np.empty((rig.vertex_count, 3))
    assert pose_velum(rig, 0.5, out=out) is out
    for bad in (-0.01, 1.5, float("nan")):
        with pytest.raises(ValueError, match=VELUM_PARAMETER):
            pose_velum(rig, bad)


def test_the_port_is_exactly_closed_when_the_velum_is_raised(rig):
    assert nasal_port_area(rig, 0.0) == 0.0
    assert np.all(port_cut_areas(rig, 0.0) == 0.0)


def test_the_port_never_narrows_as_the_velum_lowers_and_is_wider_lowered_than_at_rest(rig):
    openings = np.linspace(0.0, 1.0, 1001)
    areas = np.array([nasal_port_area(rig, o) for o in openings])
    assert np.all(np.diff(areas) >= -AREA_MM2)
    assert areas[1] > 0.0
    assert nasal_port_area(rig, 1.0) > nasal_port_area(rig, rig.rest_share) + 1.0


def test_the_lowered_port_is_of_the_size_published_for_nasals(rig):
    # Velopharyngeal port areas for nasal consonants are in the order of 10 to 100 mm^2; the
    # fully lowered measured pose gives about 102 mm^2 (docs/velum.md).
    assert 50.0 < nasal_port_area(rig, 1.0) < 150.0
    assert 10.0 < nasal_port_area(rig, 0.25) < nasal_port_area(rig, 0.5)


def test_the_stored_areas_are_those_the_evaluator_gives(definition, rig):
    stored = definition["port"]["areas_mm2"]
    assert stored["0"] == 0.0
    assert stored["1"] == pytest.approx(nasal_port_area(rig, 1.0), abs=1e-3)
    assert stored["r"] == pytest.approx(nasal_port_area(rig, rig.rest_share), abs=1e-3)


@pytest.mark.parametrize("change, message", [
    (lambda d: d.update(format_version=99), "format_version"),
    (lambda d: d["parameters"][0].update(name="velum"), VELUM_PARAMETER),
    (lambda d: d["poses"]["positions"].update(rest=[0.0] * 9), "pose rest"),
    (lambda d: d["poses"].update(at=[0.0, 1.5, 1.0]), "rest share"),
    (lambda d: d["port"].update(rows=[0]), "one entry per sample"),
])
def test_a_damaged_definition_is_refused_naming_what_is_wrong(definition, change, message):
    damaged = json.loads(json.dumps(definition))
    change(damaged)
    with pytest.raises(VelumRigError, match=message):
        prepare_velum(damaged)
