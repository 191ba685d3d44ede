"""The shared velum vectors: reproduced by the Python reference within the file's tolerances, and
the refusals refused naming the parameter (node checks the same file in tests/js/velum.test.js)."""

import numpy as np
import pytest

from glasshead.constants import VELUM_PARAMETER
from glasshead.geometry.velum import nasal_port_area, port_cut_areas, pose_velum, prepare_velum
from vector_support import read_vectors, tol

pytestmark = pytest.mark.vectors
VECTORS = read_vectors("velum.json")
RIG = prepare_velum(VECTORS["fixtures"]["rig"])
PROBES = VECTORS["fixtures"]["probe_vertices"]
STORED = tol(VECTORS, "stored")


@pytest.mark.parametrize("case", VECTORS["cases"], ids=lambda c: c["description"])
def test_the_python_reference_reproduces_every_velum_case(case):
    opening = case["input"][VELUM_PARAMETER]
    expected = case["expected"]
    if "error" in expected:
        with pytest.raises(ValueError, match=VELUM_PARAMETER) as refusal:
            pose_velum(RIG, opening)
        assert expected["error"] in str(refusal.value)
        return
    posed = pose_velum(RIG, opening)
    np.testing.assert_allclose(posed[PROBES].ravel(), expected["probe_positions"], rtol=0,
                               atol=STORED)
    assert nasal_port_area(RIG, opening) == pytest.approx(expected["port_area_mm2"], abs=STORED)
    np.testing.assert_allclose(port_cut_areas(RIG, opening), expected["cut_areas_mm2"], rtol=0,
                               atol=STORED)


def test_the_vector_rig_is_the_built_one(built_assets):
    import json

    built = json.loads((built_assets / "velum-rig.json").read_text())
    assert built["poses"] == VECTORS["fixtures"]["rig"]["poses"]
    assert built["port"] == VECTORS["fixtures"]["rig"]["port"]
