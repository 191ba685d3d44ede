"""The rest shape fitted to the MRI tongue (Badin et al.), and the build step that writes it."""

import json

import numpy as np
import pytest
import trimesh

from glasshead.geometry.tongue_parameters import HUB_MM
from glasshead.geometry.tongue_rig import validate_definition
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.pipeline import tongue_rig as step
from glasshead.settings import get_settings


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    out = tmp_path_factory.mktemp("build")
    report = step.build_tongue_rig(get_settings().data_dir, out)
    return out, report, json.loads((out / step.OUTPUT_NAME).read_text())


@pytest.fixture(scope="module")
def mri():
    return step.load_badin_mesh(get_settings().data_dir, "tongue")


def test_the_rest_shape_is_within_a_millimetre_of_the_mri_tongue_on_average(built):
    _out, report, definition = built
    distance = definition["fit"]["distance_mm"]
    assert distance["mean_both_ways"] <= 1.0
    assert distance["rig_to_mri"]["mean"] <= 1.0 and distance["mri_to_rig"]["mean"] <= 1.0
    assert distance["rig_to_mri"]["max"] < 6.0 and distance["mri_to_rig"]["max"] < 6.0
    assert report["fit"] == definition["fit"]


def test_the_reported_distances_are_what_an_independent_measurement_finds(built, mri):
    _out, _report, definition = built
    rig = TongueRig(definition)
    rest = trimesh.Trimesh(rig.vertices(rig.neutral), rig.triangles, process=False)
    target = trimesh.Trimesh(*mri, process=False)
    points, _ = trimesh.sample.sample_surface(target, 5000, seed=1)
    distance = np.abs(trimesh.proximity.signed_distance(rest, points))
    reported = definition["fit"]["distance_mm"]["mri_to_rig"]["mean"]
    assert distance.mean() == pytest.approx(reported, rel=0.15)


def test_the_rest_volume_matches_the_mri_volume_within_two_percent(built, mri):
    _out, _report, definition = built
    volume = definition["fit"]["volume_mm3"]
    assert volume["mri"] == pytest.approx(trimesh.Trimesh(*mri, process=False).volume, rel=1e-9)
    assert volume["rig"] == pytest.approx(volume["mri"], rel=0.02)


def test_the_written_definition_is_valid_and_its_rest_shape_does_not_fold(built):
    out, report, definition = built
    validate_definition(definition)
    rig = TongueRig(definition)
    assert rig.pages_in_order(rig.neutral)
    assert report["vertices"] == rig.vertex_count >= 2000
    assert report["file"] == str(out / step.OUTPUT_NAME) and report["skipped"] is False


def test_named_control_points_keep_their_section(built):
    points = {p["name"]: p for p in built[2]["sagittal"]["control_points"]}
    # fitted blends: within 1e-6 of the whole of one section
    assert points["B"]["section_weights"] == pytest.approx([1.0, 0.0, 0.0], abs=1e-6)  # tip: front
    assert points["G"]["section_weights"] == pytest.approx([0.0, 1.0, 0.0], abs=1e-6)  # dorsum
    assert points["K"]["section_weights"] == pytest.approx([0.0, 0.0, 1.0], abs=1e-6)  # root: back


def test_a_second_build_with_the_same_inputs_is_skipped(built):
    out, _report, definition = built
    again = step.build_tongue_rig(get_settings().data_dir, out)
    assert again["skipped"] is True
    assert json.loads((out / step.OUTPUT_NAME).read_text()) == definition


def test_a_build_whose_inputs_changed_runs_again(built, tmp_path, monkeypatch):
    _out, _report, definition = built
    stale = dict(definition, source=dict(definition["source"], inputs={"tongue.obj": "old"}))
    (tmp_path / step.OUTPUT_NAME).write_text(json.dumps(stale))
    calls = []
    monkeypatch.setattr(step, "fit_definition",
                        lambda data_dir: calls.append(data_dir) or definition)
    report = step.build_tongue_rig(get_settings().data_dir, tmp_path)
    assert report["skipped"] is False and len(calls) == 1
    assert json.loads((tmp_path / step.OUTPUT_NAME).read_text()) == definition


def test_the_hub_sees_the_mri_tongue_as_star_shaped(mri):
    # The radial rig can only represent what is visible from its hub: nearly every direction
    # from the hub must cross the MRI surface exactly once.
    mesh = trimesh.Trimesh(*mri, process=False)
    theta, phi = np.meshgrid(np.radians(np.arange(0, 360, 3)), np.radians(np.arange(-88, 89, 4)))
    directions = np.stack([np.cos(phi) * np.cos(theta), np.cos(phi) * np.sin(theta),
                           np.sin(phi)], -1).reshape(-1, 3)
    origins = np.tile([HUB_MM[0], HUB_MM[1], 0.0], (len(directions), 1))
    _hits, ray, _face = mesh.ray.intersects_location(origins, directions, multiple_hits=True)
    crossings = np.bincount(ray, minlength=len(directions))
    assert np.all(crossings >= 1)
    assert np.mean(crossings == 1) > 0.99


def test_missing_reference_data_stops_the_build_with_the_file_named(tmp_path):
    with pytest.raises(FileNotFoundError, match="tongue.obj"):
        step.build_tongue_rig(tmp_path / "no-data", tmp_path / "out")
