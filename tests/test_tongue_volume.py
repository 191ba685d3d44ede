"""Mesh volume (divergence theorem) and normals; the tongue's volume responds to its parameters,
so a volume constraint in fitting has something to hold."""

import json
from pathlib import Path

import numpy as np
import pytest
import trimesh

from glasshead.geometry.mesh_volume import is_closed_manifold, mesh_volume, vertex_normals
from glasshead.geometry.tongue_surface import TongueRig

VECTORS = Path(__file__).parent / "vectors"

CUBE = trimesh.creation.box(extents=(2.0, 3.0, 5.0))


@pytest.fixture(scope="module")
def rig():
    return TongueRig(json.loads((VECTORS / "tongue-surface.json").read_text())["fixtures"]["rig"])


def test_the_volume_of_a_box_is_the_product_of_its_sides_wherever_it_is():
    assert mesh_volume(CUBE.vertices, CUBE.faces) == pytest.approx(30.0, rel=1e-12)
    moved = CUBE.vertices + [100.0, -40.0, 7.0]
    assert mesh_volume(moved, CUBE.faces) == pytest.approx(30.0, rel=1e-12)


def test_reversed_winding_gives_a_negative_volume():
    assert mesh_volume(CUBE.vertices, CUBE.faces[:, ::-1]) == pytest.approx(-30.0, rel=1e-12)


def test_the_volume_of_a_fine_sphere_approaches_four_thirds_pi_r_cubed():
    sphere = trimesh.creation.icosphere(subdivisions=5, radius=10.0)
    assert mesh_volume(sphere.vertices, sphere.faces) == pytest.approx(4 / 3 * np.pi * 1000,
                                                                       rel=2e-3)


def test_vertex_normals_of_a_sphere_point_along_the_radius():
    sphere = trimesh.creation.icosphere(subdivisions=3, radius=4.0)
    normals = vertex_normals(sphere.vertices, sphere.faces)
    np.testing.assert_allclose(normals, sphere.vertices / 4.0, atol=2e-2)


def test_bad_meshes_are_refused():
    with pytest.raises(ValueError, match="vertices must be"):
        mesh_volume(np.zeros((4, 2)), [[0, 1, 2]])
    with pytest.raises(ValueError, match="out of range"):
        mesh_volume(np.zeros((3, 3)), [[0, 1, 3]])


def test_a_box_is_closed_and_an_open_box_is_not():
    assert is_closed_manifold(CUBE.faces)
    assert not is_closed_manifold(CUBE.faces[1:])


def test_the_tongue_volume_equals_trimesh_on_the_same_mesh(rig):
    surface = rig.evaluate(rig.values_from({"jaw_opening": 9.0, "tip_advancement": 3.0}))
    reference = trimesh.Trimesh(surface.vertices, surface.triangles, process=False).volume
    assert surface.volume == pytest.approx(reference, rel=1e-10)


@pytest.mark.parametrize("name", ["body_height", "dorsum_height", "back_dorsum_height",
                                  "root_advancement"])
def test_body_and_dorsum_height_and_root_advancement_change_the_volume_by_over_five_percent(
        rig, name):
    p = rig.parameters[name]
    low = rig.evaluate(rig.values_from({name: p["min"]})).volume
    high = rig.evaluate(rig.values_from({name: p["max"]})).volume
    assert max(low, high) / min(low, high) > 1.05


@pytest.mark.parametrize("section", ["front", "middle", "back"])
def test_a_wider_section_holds_more_volume(rig, section):
    name = f"{section}_width"
    rest = rig.evaluate(rig.neutral).volume
    low = rig.evaluate(rig.values_from({name: rig.parameters[name]["min"]})).volume
    high = rig.evaluate(rig.values_from({name: rig.parameters[name]["max"]})).volume
    assert low < 0.98 * rest and high > 1.02 * rest


def test_every_tongue_parameter_but_asymmetry_and_the_turn_changes_the_volume(rig):
    # A volume penalty in a fit steers through the parameters that change the volume.
    for k, name in enumerate(rig.parameter_names):
        if name.endswith("asymmetry") or name == "tongue_retraction":
            continue  # left in, right out: the two sides cancel to first order
        step = 0.05 * (rig.maximum[k] - rig.minimum[k])
        values = rig.neutral.copy()
        values[k] = min(values[k] + step, rig.maximum[k])
        change = rig.volume(values) - rig.volume(rig.neutral)
        assert abs(change) > 10.0, f"{name}: volume changed by {change:.2f} mm^3"


def test_turning_the_tongue_back_keeps_its_volume_within_one_percent(rig):
    # The turn moves D to M rigidly about the hub; only the taper through the blade and along
    # the floor changes the volume.
    rest = rig.volume(rig.neutral)
    turned = rig.volume(rig.values_from({"tongue_retraction": 25.0}))
    assert 0.0 < abs(turned / rest - 1.0) < 0.01


def test_a_volume_penalty_tells_apart_shapes_that_a_contour_fit_confuses(rig):
    # Two sets with the same mid-sagittal contour (only coronal widths differ) have different
    # volumes: only a volume term can choose between them in a 2D fit.
    a = rig.evaluate(rig.values_from({"middle_width": -4.0}))
    b = rig.evaluate(rig.values_from({"middle_width": 4.0}))
    midline = np.abs(a.vertices[:, 2]) < 1e-9
    np.testing.assert_allclose(a.vertices[midline], b.vertices[midline], atol=1e-12)
    assert b.volume - a.volume > 0.03 * a.volume
