"""The quantised GLB writer: a real mesh read back (by trimesh, applying the node's transform) at
its vertices within half a grid step, its faces unchanged, in about half the bytes."""

import gzip

import numpy as np
import pytest
import trimesh

from glasshead.asset_store import read_glb_mesh
from glasshead.pipeline.quantized_glb import GRID_MAX, quantized_glb
from glasshead.settings import get_settings


@pytest.fixture(scope="module")
def airway():
    """The largest mesh of the head view, as the build wrote it (float32, uint32 indices)."""
    path = get_settings().assets_dir / "airway.glb"
    if not path.is_file():
        pytest.fail(f"built asset missing: {path} (run `glasshead build`)")
    data = path.read_bytes()
    return data, *read_glb_mesh(data)


def test_a_quantised_mesh_reads_back_within_half_a_grid_step_with_the_same_faces(airway):
    data, vertices, faces = airway
    normals = trimesh.Trimesh(vertices, faces, process=False).vertex_normals
    glb, error = quantized_glb(vertices, faces, normals)
    step = (vertices.max(axis=0) - vertices.min(axis=0)).max() / GRID_MAX
    back, back_faces = read_glb_mesh(glb)
    np.testing.assert_allclose(back, vertices, rtol=0, atol=0.5 * step + 1e-6)
    assert error <= 0.5 * step + 1e-9
    np.testing.assert_array_equal(back_faces, faces)
    assert len(glb) < 0.55 * len(data)
    assert len(gzip.compress(glb)) < 0.7 * len(gzip.compress(data))


def test_a_large_mesh_keeps_32_bit_indices_and_bad_input_is_refused():
    vertices = np.random.default_rng(7).uniform(-50, 50, (70_000, 3))
    faces = np.array([[0, 1, 69_999]])
    normals = np.tile([0.0, 0.0, 1.0], (len(vertices), 1))
    back, back_faces = read_glb_mesh(quantized_glb(vertices, faces, normals)[0])
    np.testing.assert_array_equal(back_faces, faces)
    np.testing.assert_allclose(back[69_999], vertices[69_999], atol=100 / GRID_MAX)
    with pytest.raises(ValueError, match="faces index vertices"):
        quantized_glb(vertices[:3], faces, normals[:3])
    with pytest.raises(ValueError, match="normals must be"):
        quantized_glb(vertices, faces, normals[:5])
