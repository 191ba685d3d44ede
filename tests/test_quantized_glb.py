"""The quantised GLB writer: a real mesh read back (by trimesh, applying the node's transform) at
its vertices within half a lattice step, its faces unchanged, in about half the bytes; every
built mesh on the one lattice, so that points two meshes share stay one point."""

import gzip
import json

import numpy as np
import pytest
import trimesh
from scipy.spatial import cKDTree

from glasshead.asset_store import read_glb_mesh
from glasshead.pipeline import sources
from glasshead.pipeline.quantized_glb import GRID_MAX, STEP_MM, quantized_glb

#: The largest position error the docs state (docs/api.md, page weight): half a lattice step.
MAX_ERROR_MM = 0.00196


@pytest.fixture(scope="module")
def mandible(data_dir):
    """The Badin mandible from the sources, in the project frame (float64, mm)."""
    return sources.read_badin_mesh(data_dir, "jaw")


def built_mesh(assets, name):
    mesh = trimesh.load(assets / f"{name}.glb", force="mesh", process=False)
    return np.asarray(mesh.vertices, dtype=np.float64), np.asarray(mesh.faces, dtype=np.int64)


def test_a_quantised_mesh_reads_back_within_half_a_lattice_step_with_the_same_faces(mandible):
    vertices, faces = mandible
    normals = trimesh.Trimesh(vertices, faces, process=False).vertex_normals
    glb, error = quantized_glb(vertices, faces, normals)
    back, back_faces = read_glb_mesh(glb)
    np.testing.assert_allclose(back, vertices, rtol=0, atol=0.5 * STEP_MM + 1e-12)
    assert 0 < error <= MAX_ERROR_MM
    assert np.abs(back - vertices).max() == pytest.approx(error, abs=1e-12)
    np.testing.assert_array_equal(back_faces, faces)
    plain = trimesh.Trimesh(vertices, faces, process=False).export(file_type="glb",
                                                                    include_normals=True)
    assert len(glb) < 0.55 * len(plain)
    assert len(gzip.compress(glb)) < 0.8 * len(gzip.compress(plain))


def test_every_built_mesh_lies_on_the_shared_lattice_within_the_stated_error(built_assets,
                                                                              mandible):
    manifest = json.loads((built_assets / "manifest.json").read_text())
    for entry in manifest["meshes"]:
        vertices, _ = built_mesh(built_assets, entry["name"])
        steps = vertices / STEP_MM
        np.testing.assert_array_equal(steps, np.rint(steps), err_msg=entry["name"])
    # The built mandible is the source's, moved onto the lattice and no further.
    built, _ = built_mesh(built_assets, "mandible")
    assert built.shape == mandible[0].shape
    assert 0 < np.abs(built - mandible[0]).max() <= MAX_ERROR_MM


def test_points_the_skin_shares_with_the_head_shell_and_the_lips_are_still_one_point(
        built_assets):
    skin, _ = built_mesh(built_assets, "face_skin")
    for other, least in (("head_shell", 100), ("upper_lip", 5), ("lower_lip", 5)):
        points, _ = built_mesh(built_assets, other)
        distance, _ = cKDTree(points).query(skin)
        near = distance < 0.01
        assert near.sum() >= least, f"only {near.sum()} skin points on the {other}"
        assert distance[near].max() == 0.0, other


def test_a_large_mesh_keeps_32_bit_indices_and_bad_input_is_refused():
    vertices = np.random.default_rng(7).uniform(-50, 50, (70_000, 3))
    faces = np.array([[0, 1, 69_999]])
    normals = np.tile([0.0, 0.0, 1.0], (len(vertices), 1))
    back, back_faces = read_glb_mesh(quantized_glb(vertices, faces, normals)[0])
    np.testing.assert_array_equal(back_faces, faces)
    np.testing.assert_allclose(back, vertices, rtol=0, atol=0.5 * STEP_MM + 1e-12)
    with pytest.raises(ValueError, match="faces index vertices"):
        quantized_glb(vertices[:3], faces, normals[:3])
    with pytest.raises(ValueError, match="normals must be"):
        quantized_glb(vertices, faces, normals[:5])


def test_a_mesh_wider_than_the_lattice_takes_the_next_power_of_two_step():
    vertices = np.array([[0.0, 0.0, 0.0], [400.0, 1.0, 0.0], [0.3, 2.0, 1.0]])
    glb, error = quantized_glb(vertices, np.array([[0, 1, 2]]),
                               np.tile([0.0, 0.0, 1.0], (3, 1)))
    back, _ = read_glb_mesh(glb)
    step = 2 * STEP_MM  # 400 mm is 102,400 steps of 2^-8 mm, 51,200 of 2^-7 mm
    assert 400.0 / (step / 2) > GRID_MAX >= 400.0 / step
    np.testing.assert_allclose(back, vertices, rtol=0, atol=0.5 * step + 1e-12)
    assert error <= 0.5 * step
