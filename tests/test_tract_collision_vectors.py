"""The shared tract collision vectors: reproduced by the Python reference (node checks the same
file in tests/js/tractCollision.test.js)."""

import numpy as np
import pytest

from glasshead.constants import FLAG_CORRECTED, VELUM_PARAMETER
from glasshead.geometry.tract_collision import correct_tract, prepare_tract
from glasshead.geometry.velum import prepare_velum
from vector_support import decode_f32, read_vectors, tol

pytestmark = pytest.mark.vectors
VECTORS = read_vectors("tract-collision.json")
FIXTURES = VECTORS["fixtures"]
RIG = prepare_velum(read_vectors("velum.json")["fixtures"]["rig"])
COLLIDER = prepare_tract(RIG, np.reshape(FIXTURES["velum_faces"], (-1, 3)),
                         decode_f32(FIXTURES["pharynx_vertices_f32"]).reshape(-1, 3),
                         np.reshape(FIXTURES["pharynx_faces"], (-1, 3)))
POSITION_MM = tol(VECTORS, "position_mm")


@pytest.mark.parametrize("case", VECTORS["cases"], ids=lambda c: c["description"])
def test_the_python_reference_reproduces_every_tract_case(case):
    opening = case["input"][VELUM_PARAMETER]
    vertices = decode_f32(case["input"]["vertices_f32"]).reshape(-1, 3)
    expected = case["expected"]
    if "error" in expected:
        with pytest.raises(ValueError, match=VELUM_PARAMETER) as refusal:
            correct_tract(vertices, COLLIDER, opening)
        assert expected["error"] in str(refusal.value)
        return
    out, flags, counts = correct_tract(vertices, COLLIDER, opening)
    assert flags.tolist() == expected["flags"]
    assert counts == expected["counts"]
    moved = np.flatnonzero(flags == FLAG_CORRECTED)
    assert moved.tolist() == expected["corrected"]
    np.testing.assert_allclose(out[moved].ravel(), expected["corrected_positions"], rtol=0,
                               atol=POSITION_MM)


def test_the_origin_is_the_one_the_file_states():
    np.testing.assert_allclose(COLLIDER.origin, VECTORS["constants"]["origin"], rtol=0,
                               atol=1e-9)
