"""Collision correction: the shared vectors, and exactness on real tongue poses.

Exactness is measured against the definition of inside: P is inside the palate or teeth when the
ray from O toward P crosses the maxilla before P, computed here by Embree (trimesh) over the full
scene maxilla, independently of the tables.
"""

import numpy as np
import pytest

from collision_support import (
    ExactRays,
    badin_mesh,
    check_exact_correction,
    scene_maxilla,
    scene_tables,
    tongue_rig,
)
from glasshead.constants import COLLISION_TOL, FLAG_CORRECTED, FLAG_SCREENED, FLAG_TESTED
from glasshead.geometry.collision import correct_vertices
from glasshead.geometry.collision_format import CollisionTablesError, decode_collision_tables
from glasshead.vectors.collision import (
    CASES_NAME,
    TABLES_NAME,
    build_vector_tables,
    cases_document,
)
from vector_support import assert_same_document, read_vectors, tol

VECTORS = read_vectors(CASES_NAME)
TABLES_BYTES = read_vectors(TABLES_NAME)
VECTOR_TABLES = decode_collision_tables(TABLES_BYTES)
CORRECTIONS = [c for c in VECTORS["cases"] if "error" not in c["expected"]]
REFUSALS = [c for c in VECTORS["cases"] if "error" in c["expected"]]
#: mm. Python against its own float64 answers (the file states the reason).
REFERENCE_MM = tol(VECTORS, "reference_mm")
#: Table values are float32: a float64 result a last bit away on another CPU can round to the
#: neighbouring float32, one unit in the last place (2**-23 relative) apart.
FLOAT32_RTOL = 2.0**-23
#: Seeded random poses checked here (about a second); bench/collision_exactness.py prints the
#: figures for the same kind of run.
POSES = 1000
SEED = 1998


@pytest.mark.vectors
def test_vector_cases_are_well_formed():
    assert len(REFUSALS) >= 4
    for case in CORRECTIONS:
        n = len(case["input"]["vertices"])
        assert n > 0 and len(case["expected"]["flags"]) == n, case["description"]
        assert case["expected"]["counts"]["screened"] == n, case["description"]


@pytest.mark.vectors
def test_vector_tables_are_up_to_date_with_the_builder():
    fresh = decode_collision_tables(build_vector_tables())
    header = {k: v for k, v in fresh.header.items() if k != "payload_crc32"}
    stored = {k: v for k, v in VECTOR_TABLES.header.items() if k != "payload_crc32"}
    message = f"run glasshead vectors {TABLES_NAME}"
    assert_same_document(header, stored, rtol=FLOAT32_RTOL, path=f"{TABLES_NAME} header")
    for name, array in VECTOR_TABLES.arrays.items():
        got = fresh[name]
        assert got.dtype == array.dtype and got.shape == array.shape, f"{name}: {message}"
        if np.issubdtype(array.dtype, np.floating):
            np.testing.assert_allclose(got, array, rtol=FLOAT32_RTOL, atol=1e-6,
                                       err_msg=f"{name}: {message}")
        else:
            np.testing.assert_array_equal(got, array, err_msg=f"{name}: {message}")


@pytest.mark.vectors
def test_vector_cases_are_up_to_date_with_the_python_reference():
    fresh = cases_document(TABLES_BYTES, VECTOR_TABLES)
    assert_same_document(fresh, VECTORS, atol=REFERENCE_MM)


@pytest.mark.vectors
@pytest.mark.parametrize("case", CORRECTIONS, ids=lambda c: c["description"])
def test_python_twin_answers_each_vector(case):
    out, flags, counts = correct_vertices(case["input"]["vertices"], VECTOR_TABLES)
    # Flags and counts exactly: every input stays clear of the decision boundaries.
    assert flags.tolist() == case["expected"]["flags"]
    assert counts == case["expected"]["counts"]
    np.testing.assert_allclose(out, case["expected"]["vertices"], rtol=0, atol=REFERENCE_MM)


@pytest.mark.vectors
@pytest.mark.parametrize("case", REFUSALS, ids=lambda c: c["description"])
def test_python_twin_refuses_each_damaged_table(case):
    data = bytearray(TABLES_BYTES)
    patch = case["input"].get("patch")
    if patch:
        offset = patch["offset"] % len(data)
        data[offset:offset + len(patch["bytes"])] = bytes(patch["bytes"])
    if "truncate" in case["input"]:
        data = data[:case["input"]["truncate"]]
    with pytest.raises(CollisionTablesError, match=case["expected"]["error"]):
        decode_collision_tables(bytes(data))


@pytest.mark.vectors
def test_vectors_cover_every_flag_and_a_whole_tongue():
    flags = {f for c in CORRECTIONS for f in c["expected"]["flags"]}
    assert flags == {FLAG_SCREENED, FLAG_TESTED, FLAG_CORRECTED}
    assert max(len(c["input"]["vertices"]) for c in CORRECTIONS) > 300


def test_untouched_vertices_are_returned_bit_for_bit():
    tongue, _ = badin_mesh("tongue")
    points = tongue + [6.0, 14.0, 1.5]
    out, flags, _ = correct_vertices(points, VECTOR_TABLES)
    keep = flags != FLAG_CORRECTED
    assert keep.any() and (~keep).any()
    # Not computed: the input's own bits, handed back.
    assert np.array_equal(out[keep], points[keep])


@pytest.mark.parametrize("bad, message", [
    (np.zeros((4, 2)), r"shape \(n, 3\)"),
    (np.zeros(3), r"shape \(n, 3\)"),
    (np.array([[0.0, np.nan, 0.0]]), "finite"),
    (np.array([[0.0, np.inf, 0.0]]), "finite"),
])
def test_malformed_vertices_are_refused(bad, message):
    with pytest.raises(ValueError, match=message):
        correct_vertices(bad, VECTOR_TABLES)


@pytest.fixture(scope="module")
def scene():
    tables = scene_tables()
    v, f = scene_maxilla()
    return {"tables": tables, "rays": ExactRays(v, f, tables.header["origin"]), "rig": tongue_rig()}


def test_the_tables_were_built_from_the_maxilla_the_scene_shows(scene):
    v, f = scene_maxilla()
    source = scene["tables"].header["source"]
    assert (source["vertices"], source["faces"]) == (len(v), len(f))


def test_random_tongue_poses_end_no_deeper_than_a_tenth_of_a_millimetre_and_spare_the_innocent(
        scene):
    worst, corrected = check_exact_correction(scene["tables"], scene["rays"], scene["rig"],
                                              POSES, SEED)
    assert worst <= COLLISION_TOL.depth
    assert corrected > POSES, "the poses must actually press into the palate"
