"""Tongue collision with the velum and the pharyngeal wall (geometry.tract_collision), on the
built meshes: exact against a brute-force raycast, no innocent vertex moved, the velum met at
every opening, and bad input refused. The shared vectors are checked in
test_tract_collision_vectors.py (and by node in tests/js/tractCollision.test.js)."""

import json

import numpy as np
import pytest

from glasshead.constants import (
    COLLISION_TOL,
    FLAG_CORRECTED,
    PHARYNX_GLB,
    TRACT_ORIGIN_AHEAD_MM,
    VELUM_REST_GLB,
)
from glasshead.geometry.collision import correct_vertices
from glasshead.geometry.collision_exact import first_hits_from_origin
from glasshead.geometry.collision_format import decode_collision_tables
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.geometry.tract_collision import (
    TractCollisionError,
    correct_tract,
    prepare_tract,
    tract_pose,
)
from glasshead.geometry.velum import prepare_velum
from glasshead.pipeline.outputs import load_built_meshes

POSES = 12
SEED = 31


@pytest.fixture(scope="module")
def parts(built_assets):
    rig = prepare_velum(json.loads((built_assets / "velum-rig.json").read_text()))
    meshes = load_built_meshes(built_assets, ["velum_rest", "pharynx"])
    return rig, meshes["velum_rest"][1], meshes["pharynx"][0], meshes["pharynx"][1]


@pytest.fixture(scope="module")
def collider(parts):
    return prepare_tract(*parts)


@pytest.fixture(scope="module")
def tongue_poses(built_assets):
    """Seeded random tongue poses (every parameter uniform over its range), palate corrected."""
    rig = TongueRig(json.loads((built_assets / "tongue-rig.json").read_text()))
    tables = decode_collision_tables((built_assets / "collision-tables.bin").read_bytes())
    low = np.array([p["min"] for p in rig.definition["parameters"]])
    high = np.array([p["max"] for p in rig.definition["parameters"]])
    rng = np.random.default_rng(SEED)
    out = []
    for _ in range(POSES):
        values = low + (high - low) * rng.random(len(low))
        out.append((correct_vertices(rig.vertices(values), tables)[0], float(rng.random())))
    return out


def test_the_origin_lies_in_front_of_the_velum_at_its_lowest_height(collider, parts):
    poses = parts[0].poses
    assert collider.origin[2] == 0.0
    np.testing.assert_allclose(collider.origin[0], poses[..., 0].max() + TRACT_ORIGIN_AHEAD_MM,
                               rtol=0, atol=1e-5)  # float32 poses
    np.testing.assert_allclose(collider.origin[1], poses[..., 1].min(), rtol=0, atol=1e-5)
    assert collider.origin[0] > collider.screen_x


def test_corrected_tongues_lie_on_or_in_front_of_the_tract_and_nothing_else_moves(
        collider, tongue_poses):
    corrected_total = 0
    for vertices, opening in tongue_poses:
        out, flags, counts = correct_tract(vertices, collider, opening)
        moved = flags == FLAG_CORRECTED
        # Outside vertices come back bit for bit.
        assert np.array_equal(out[~moved], vertices[~moved])
        # No vertex is left beyond the first crossing of its ray by more than the budget.
        for mesh, (positions, _, _) in zip(collider.meshes, tract_pose(collider, opening),
                                           strict=True):
            _, radius = first_hits_from_origin(out, collider.origin, positions, mesh.faces)
            depth = np.linalg.norm(out - collider.origin, axis=1) - radius
            assert np.nanmax(np.where(np.isfinite(radius), depth, -np.inf)) \
                <= COLLISION_TOL.depth
        corrected_total += counts["corrected"]
    assert corrected_total > 200, "the random poses must reach the velum and the wall"


def test_the_corrected_set_is_the_brute_force_inside_set(collider, tongue_poses):
    vertices, opening = tongue_poses[0]
    _, flags, _ = correct_tract(vertices, collider, opening)
    inside = np.zeros(len(vertices), dtype=bool)
    for mesh, (positions, _, _) in zip(collider.meshes, tract_pose(collider, opening),
                                       strict=True):
        t, _ = first_hits_from_origin(vertices, collider.origin, positions, mesh.faces)
        inside |= t < 1.0
    np.testing.assert_array_equal(flags == FLAG_CORRECTED, inside)


def test_a_lowered_velum_meets_a_tongue_that_a_raised_one_clears(collider, tongue_poses):
    counts = {}
    for opening in (0.0, 1.0):
        counts[opening] = sum(correct_tract(v, collider, opening)[2]["corrected"]
                              for v, _ in tongue_poses)
    assert counts[1.0] > counts[0.0]


@pytest.mark.parametrize("opening", [1.5, -0.1, float("nan"), "0.5"])
def test_an_opening_out_of_range_is_refused_naming_the_parameter(collider, opening):
    with pytest.raises(ValueError, match="velum_opening"):
        correct_tract(np.zeros((1, 3)), collider, opening)


def test_bad_vertices_are_refused(collider):
    with pytest.raises(ValueError, match=r"shape \(n, 3\)"):
        correct_tract(np.zeros((4, 2)), collider, 0.5)
    with pytest.raises(ValueError, match="finite"):
        correct_tract(np.full((2, 3), np.nan), collider, 0.5)


def test_meshes_that_do_not_fit_are_refused(parts):
    rig, velum_faces, pharynx, pharynx_faces = parts
    with pytest.raises(TractCollisionError, match="velum faces refer to vertices"):
        prepare_tract(rig, velum_faces + 10_000, pharynx, pharynx_faces)
    # A wall moved in front of the origin: the screen would be wrong.
    with pytest.raises(TractCollisionError, match="lies behind a tract mesh"):
        prepare_tract(rig, velum_faces, pharynx + [60.0, 0.0, 0.0], pharynx_faces)


def test_the_build_reports_the_origin_and_its_clearances(built_assets):
    report = json.loads((built_assets / "build-report.json").read_text())["tract-collision"]
    assert report["origin_mm"][2] == 0.0
    assert report["screen_x_mm"] < report["origin_mm"][0]
    assert min(report["clearance_mm"].values()) >= 3.0
    assert report["triangles"] == {"velum": 7570, "pharynx": 2630}


def test_a_build_whose_velum_rig_is_damaged_stops_naming_the_files(built_assets, tmp_path):
    import shutil
    from types import SimpleNamespace

    from glasshead.pipeline.tract_collision_check import TractCollisionBuildError, build_step

    for name in ("manifest.json", VELUM_REST_GLB, PHARYNX_GLB):
        shutil.copy(built_assets / name, tmp_path / name)
    (tmp_path / "velum-rig.json").write_text('{"format_version": 1}')
    with pytest.raises(TractCollisionBuildError, match="velum-rig.json, velum_rest.glb and "
                                                       "pharynx.glb"):
        build_step(SimpleNamespace(assets_dir=tmp_path))


def test_the_api_corrects_against_the_velum_and_the_wall_when_given_an_opening(
        start_app, built_assets, collider, tongue_poses):
    _, client = start_app(built_assets)
    # The first seeded pose that the tract corrects at this opening.
    vertices = next(v for v, _ in tongue_poses if correct_tract(v, collider, 1.0)[2]["corrected"])
    body = {"vertices": vertices.tolist(), "velum_opening": 1.0}
    answer = client.post("/api/v1/collision/correct", json=body)
    assert answer.status_code == 200, answer.text
    result = answer.json()
    expected, flags, counts = correct_tract(vertices, collider, 1.0)
    assert result["tract_counts"] == counts and counts["corrected"] > 0
    assert result["tract_flags"] == flags.tolist()
    np.testing.assert_allclose(result["vertices"], expected, rtol=0, atol=1e-9)  # JSON floats
    # Without an opening the palate alone, as before.
    plain = client.post("/api/v1/collision/correct", json={"vertices": vertices.tolist()})
    assert plain.json()["tract_counts"] is None


@pytest.mark.parametrize("opening", [1.5, -0.2, "open"])
def test_the_api_refuses_an_opening_out_of_range_naming_it(start_app, built_assets, opening):
    _, client = start_app(built_assets)
    answer = client.post("/api/v1/collision/correct",
                         json={"vertices": [[0.0, 0.0, 0.0]], "velum_opening": opening})
    assert answer.status_code == 422
    assert "velum_opening" in answer.text
