"""The jaw pose the tongue rides on: rotation about the temporomandibular axis plus a slide."""

import math

import numpy as np
import pytest

from glasshead.geometry.jaw import apply_jaw_pose, estimate_condyle, jaw_definition, jaw_pose
from glasshead.pipeline.tongue_rig import load_badin_mesh
from glasshead.settings import get_settings
from vector_support import read_vectors, tol

JAW = jaw_definition([-55.0, 40.0], translation_per_degree=(0.2, -0.08))


def test_a_closed_jaw_is_the_identity():
    np.testing.assert_allclose(jaw_pose(0.0, JAW), np.eye(3, 4), atol=1e-15)


def test_without_a_slide_the_pivot_stays_put_and_distances_to_it_are_kept():
    still = jaw_definition([-55.0, 40.0], translation_per_degree=(0.0, 0.0))
    pose = jaw_pose(17.0, still)
    np.testing.assert_allclose(apply_jaw_pose([[-55.0, 40.0]], pose), [[-55.0, 40.0]], atol=1e-12)
    chin = np.array([[25.0, -30.0, 4.0]])
    moved = apply_jaw_pose(chin, pose)
    # mm, about 100 mm from the pivot: a rotation keeps it up to rounding
    assert np.linalg.norm(moved[0, :2] - [-55, 40]) == pytest.approx(
        np.linalg.norm(chin[0, :2] - [-55, 40]), abs=1e-9)
    assert moved[0, 2] == pytest.approx(chin[0, 2], abs=1e-12)  # the jaw turns about z


def test_opening_turns_the_chin_down_by_the_opening_angle_and_slides_the_condyle_forward():
    pose = jaw_pose(20.0, JAW)
    chin = np.array([[25.0, -30.0]])
    moved = apply_jaw_pose(chin, pose)
    assert moved[0, 1] < chin[0, 1] - 20
    before = math.atan2(chin[0, 1] - 40.0, chin[0, 0] + 55.0)
    slid = moved[0] - np.array([0.2, -0.08]) * 20  # undo the slide
    after = math.atan2(slid[1] - 40.0, slid[0] + 55.0)
    assert math.degrees(before - after) == pytest.approx(20.0, abs=1e-9)  # degrees
    np.testing.assert_allclose(apply_jaw_pose([[-55.0, 40.0]], pose), [[-51.0, 38.4]], atol=1e-12)


def test_weights_blend_between_staying_and_riding_fully():
    pose = jaw_pose(12.0, JAW)
    points = np.array([[10.0, -20.0], [10.0, -20.0], [10.0, -20.0]])
    moved = apply_jaw_pose(points, pose, [0.0, 0.5, 1.0])
    # mm: blends of points tens of millimetres out, equal up to rounding
    np.testing.assert_allclose(moved[0], points[0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(moved[1], 0.5 * (moved[0] + moved[2]), rtol=0, atol=1e-12)
    np.testing.assert_allclose(moved[2], apply_jaw_pose(points[:1], pose)[0], rtol=0, atol=1e-12)


def test_bad_input_is_refused():
    with pytest.raises(ValueError, match="finite"):
        jaw_pose(float("nan"), JAW)
    with pytest.raises(ValueError, match=r"\(n, 2\) or \(n, 3\)"):
        apply_jaw_pose(np.zeros(4), jaw_pose(1.0, JAW))
    with pytest.raises(ValueError, match="one value per point"):
        apply_jaw_pose(np.zeros((3, 2)), jaw_pose(1.0, JAW), [1.0])
    with pytest.raises(ValueError, match="2 finite numbers"):
        jaw_definition([1.0, 2.0, 3.0])


def test_the_condyle_estimate_is_the_top_of_the_back_half_of_a_mandible():
    # A toy mandible: a chin block at the front, a lower coronoid and a higher condyle behind.
    chin = np.array([[x, y, z] for x in (0, 20) for y in (-40, -20) for z in (-30, 30)], float)
    coronoid = np.array([[-30, 30, 40], [-30, 30, -40]], float)
    condyle = np.array([[-60, 44, 50], [-62, 42, 50], [-60, 44, -50], [-62, 42, -50]], float)
    pivot = estimate_condyle(np.vstack([chin, coronoid, condyle]))
    np.testing.assert_allclose(pivot, [-61.0, 43.0], rtol=0, atol=1e-9)  # means of vertices, mm


def test_the_badin_condyles_are_at_the_top_back_of_the_ramus_behind_and_above_the_tongue():
    jaw_vertices, _ = load_badin_mesh(get_settings().data_dir, "jaw")
    tongue_vertices, _ = load_badin_mesh(get_settings().data_dir, "tongue")
    pivot = estimate_condyle(jaw_vertices)
    assert pivot[0] < tongue_vertices[:, 0].min()  # behind the tongue root
    assert pivot[1] > tongue_vertices[:, 1].max() + 20  # well above the dorsum
    assert jaw_vertices[:, 1].max() - 5 <= pivot[1] <= jaw_vertices[:, 1].max()


@pytest.mark.vectors
def test_the_jaw_vectors_reproduce_in_python():
    document = read_vectors("tongue-jaw.json")
    # Row-major 3 x 4: the last entry of each row is the translation (mm), the rest rotation.
    translation = np.zeros((3, 4), dtype=bool)
    translation[:, 3] = True
    for case in document["cases"]:
        pose = jaw_pose(case["input"]["opening_deg"], document["fixtures"]["jaw"]).reshape(-1)
        expected = np.asarray(case["expected"]["pose"])
        where = translation.reshape(-1)
        np.testing.assert_allclose(pose[~where], expected[~where], rtol=0,
                                   atol=tol(document, "rotation"), err_msg=case["description"])
        np.testing.assert_allclose(pose[where], expected[where], rtol=0,
                                   atol=tol(document, "translation_mm"),
                                   err_msg=case["description"])
        moved = apply_jaw_pose(case["input"]["points"], pose.reshape(3, 4),
                               case["input"]["weights"])
        np.testing.assert_allclose(moved, case["expected"]["points"], rtol=0,
                                   atol=tol(document, "point_mm"), err_msg=case["description"])
