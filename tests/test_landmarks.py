"""The teaching landmarks, checked on the anatomy they are found on, and served by the API."""

import json

import numpy as np
import pytest
import trimesh

from assets_support import copy_built_assets
from glasshead.constants import LANDMARKS_FILE
from glasshead.geometry.landmarks import (
    closest_pair,
    point_at_arc,
    signed_curvature,
    validate_landmarks,
)
from glasshead.pipeline.landmarks import PARTS, PLACES

#: mm. A landmark found on a mesh's mid-sagittal section lies on that mesh to rounding (positions
#: are written to 1 micrometre); one placed between meshes (lips, port, pharynx) lies within the
#: gap it bridges.
ON_MESH_MM = 0.01


@pytest.fixture(scope="module")
def document(built_assets):
    return json.loads((built_assets / LANDMARKS_FILE).read_text())


@pytest.fixture(scope="module")
def at(document):
    return {e["name"]: np.array(e["position"]) for e in document["landmarks"]}


def _mesh(assets, name):
    return trimesh.load(assets / f"{name}.glb", force="mesh", process=False)


def _distance(assets, name, point):
    _, distance, _ = trimesh.proximity.closest_point(_mesh(assets, name), [point])
    return float(distance[0])


def test_the_file_names_every_part_and_place_of_the_issue(document):
    validate_landmarks(document)
    kinds = {e["name"]: e["kind"] for e in document["landmarks"]}
    for name, *_ in PARTS:
        assert kinds[name] == "part"
    assert [n for n, _ in PLACES] == ["bilabial", "labiodental", "dental", "alveolar",
                                      "postalveolar", "palatal", "velar", "uvular", "glottal"]
    assert all(kinds[n] == "place" for n, _ in PLACES)
    for entry in document["landmarks"]:
        assert entry["rule"] and entry["mesh"] and entry["feature"]


def test_the_places_run_front_to_back_along_the_roof_and_glottal_is_lowest(document, at):
    places = sorted((e for e in document["landmarks"] if e["kind"] == "place"),
                    key=lambda e: e["order"])
    x = [at[e["name"]][0] for e in places]
    # From bilabial to uvular each place lies behind the one before (strictly, by 0.5 mm or
    # more); glottal lies lowest of all and behind the alveolar ridge.
    roof = x[:8]
    assert all(a - b >= 0.5 for a, b in zip(roof, roof[1:], strict=False)), roof
    y = {e["name"]: at[e["name"]][1] for e in places}
    assert y["glottal"] == min(y.values())
    assert at["glottal"][0] < at["alveolar"][0]


def test_the_alveolar_ridge_lies_behind_and_above_the_upper_incisor_edge(document, at):
    edge, ridge = at["upper_incisor_edge"], at["alveolar_ridge"]
    behind = edge[0] - ridge[0]
    above = ridge[1] - edge[1]
    # An adult's alveolar crest lies some 5-30 mm behind the incisal edge and 8-25 mm above it
    # (a central incisor crown is about 10.5 mm long; the ridge rises behind it). Measured on
    # the Badin maxilla: 25.0 mm behind, 18.6 mm above.
    assert 5.0 <= behind <= 30.0, behind
    assert 8.0 <= above <= 25.0, above
    assert document["measures"]["alveolar_ridge_behind_upper_incisor_edge_mm"] == \
        pytest.approx(behind, abs=0.01)
    # It lies behind the dental place and in front of the postalveolar one.
    assert at["dental"][0] > ridge[0] > at["postalveolar"][0]


def test_the_uvula_is_the_tip_of_the_rest_velum(built_assets, at):
    velum = _mesh(built_assets, "velum_rest")
    vertices = np.asarray(velum.vertices)
    vertices = vertices[np.abs(vertices[:, 2]) < 2.0]
    junction = at["hard_soft_junction"]
    # The tip is the velum point near the midline (|z| < 2 mm) farthest from the hard palate's
    # back edge, to within the mesh's spacing (1.5 mm), and it lies on the velum.
    farthest = np.max(np.linalg.norm(vertices - junction, axis=1))
    assert np.linalg.norm(at["uvula"] - junction) == pytest.approx(farthest, abs=1.5)
    assert _distance(built_assets, "velum_rest", at["uvula"]) < ON_MESH_MM
    assert at["uvula"][1] < at["velum"][1] and at["uvula"][0] < at["velum"][0]


@pytest.mark.parametrize("name, mesh", [
    ("upper_incisor_edge", "maxilla"), ("alveolar_ridge", "maxilla"),
    ("hard_palate", "maxilla"), ("hard_soft_junction", "maxilla"), ("dental", "maxilla"),
    ("lower_incisor_edge", "mandible"), ("upper_lip", "upper_lip"), ("lower_lip", "lower_lip"),
    ("velar", "velum_rest"), ("uvula", "velum_rest"), ("tongue_tip", "tongue_rest"),
    ("tongue_blade", "tongue_rest"), ("tongue_front", "tongue_rest"),
    ("tongue_back", "tongue_rest"), ("tongue_root", "tongue_rest"),
])
def test_a_landmark_found_on_a_mesh_lies_on_it(built_assets, at, name, mesh):
    assert _distance(built_assets, mesh, at[name]) < ON_MESH_MM


def test_landmarks_between_meshes_lie_within_the_gap_they_name(built_assets, at, document):
    # The nasal port is halfway across its gap: half its width from the velum and the wall
    # (within 0.05 mm: the gap is measured between section points).
    half = 0.5 * document["measures"]["nasal_port_rest_gap_mm"]
    for mesh in ("velum_rest", "pharynx"):
        assert _distance(built_assets, mesh, at["nasal_port"]) <= half + 0.05
    # The larynx point is on the thyroid; the glottis within 10 mm of an arytenoid.
    assert _distance(built_assets, "thyroid", at["larynx"]) < ON_MESH_MM
    assert min(_distance(built_assets, m, at["glottis"])
               for m in ("arytenoid_left", "arytenoid_right")) < 10.0
    # Tongue parts run tip to root, front to back.
    tongue = [at[f"tongue_{p}"][0] for p in ("tip", "blade", "front", "back", "root")]
    assert tongue == sorted(tongue, reverse=True)


def test_the_build_report_gives_every_position_and_rule(build_report, document):
    section = build_report["landmarks"]
    for entry in document["landmarks"]:
        np.testing.assert_allclose(section["positions_mm"][entry["name"]], entry["position"],
                                   atol=1e-9)
        assert entry["rule"] in section["rules"][entry["name"]]


def test_a_curvature_kernel_finds_a_circle_s_radius():
    # A quarter circle of radius 10 mm run counter-clockwise turns left: +1/10 per mm (within
    # 1 % away from the smoothed ends); run backwards it turns right.
    t = np.linspace(0.0, np.pi / 2, 200)
    arc = np.stack([10 * np.cos(t), 10 * np.sin(t)], axis=1)
    k, _, s = signed_curvature(arc, 0.1, 0.5)
    middle = (s > 3.0) & (s < s[-1] - 3.0)
    np.testing.assert_allclose(k[middle], 0.1, rtol=0.01)
    k_back, _, _ = signed_curvature(arc[::-1], 0.1, 0.5)
    np.testing.assert_allclose(k_back[middle[::-1]], -0.1, rtol=0.01)


def test_the_small_kernels_on_exact_inputs():
    line = np.array([[0.0, 0.0], [3.0, 4.0], [3.0, 10.0]])
    np.testing.assert_allclose(point_at_arc(line, [0.0, 5.0, 11.0], 8.0), [3.0, 7.0], atol=1e-12)
    i, j, d = closest_pair([[0.0, 0.0], [5.0, 0.0]], [[9.0, 3.0], [6.0, 1.0]])
    assert (i, j) == (1, 1) and d == pytest.approx(np.sqrt(2.0), abs=1e-12)


@pytest.mark.parametrize("damage, message", [
    (lambda d: d.update(format_version=99), "format_version"),
    (lambda d: d["landmarks"][0].update(position=[0.0, "x", 0.0]), "position"),
    (lambda d: d["landmarks"][0].pop("rule"), "lacks rule"),
    (lambda d: d["landmarks"].append(dict(d["landmarks"][0])), "listed twice"),
])
def test_the_reader_refuses_a_damaged_document(document, damage, message):
    copy = json.loads(json.dumps(document))
    damage(copy)
    with pytest.raises(ValueError, match=message):
        validate_landmarks(copy)


def test_the_route_serves_the_built_landmarks(built_assets, document, start_app):
    response = start_app(built_assets)[1].get("/api/v1/anatomy/landmarks")
    assert response.status_code == 200
    body = response.json()
    assert body["format_version"] == document["format_version"]
    assert [e["name"] for e in body["landmarks"]] == [e["name"] for e in document["landmarks"]]
    assert body["landmarks"][0]["position"] == document["landmarks"][0]["position"]


def test_without_built_landmarks_the_route_answers_503_naming_the_command(
        tmp_path, built_assets, start_app):
    assets = tmp_path / "assets"
    copy_built_assets(built_assets, assets)
    (assets / LANDMARKS_FILE).unlink()
    response = start_app(assets)[1].get("/api/v1/anatomy/landmarks")
    assert response.status_code == 503
    body = response.json()
    assert body["asset"] == "landmarks" and body["file"] == LANDMARKS_FILE
    assert "glasshead build" in body["detail"]
