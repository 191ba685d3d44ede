"""GET /api/v1/tongue/rig and POST /api/v1/tongue/surface."""

import json
import os
from pathlib import Path

import numpy as np
import pytest
from fastapi.testclient import TestClient

from glasshead.api.app import create_app
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.settings import get_settings

VECTORS = Path(__file__).parent / "vectors"


@pytest.fixture(scope="module")
def definition():
    return json.loads((VECTORS / "tongue-surface.json").read_text())["fixtures"]["rig"]


@pytest.fixture
def client(tmp_path, monkeypatch, definition):
    """An app whose assets directory holds the rig of the shared vectors."""
    (tmp_path / "tongue-rig.json").write_text(json.dumps(definition))
    monkeypatch.setenv("GLASSHEAD_ASSETS_DIR", str(tmp_path))
    monkeypatch.setenv("GLASSHEAD_WEB_DIST_DIR", str(tmp_path / "no-web"))
    get_settings.cache_clear()
    yield TestClient(create_app())
    get_settings.cache_clear()


def test_the_rig_route_returns_the_definition_with_its_parameter_table(client, definition):
    response = client.get("/api/v1/tongue/rig")
    assert response.status_code == 200
    body = response.json()
    assert body == definition
    names = [p["name"] for p in body["parameters"]]
    assert "tip_height" in names and "middle_groove_depth" in names and "jaw_opening" in names


def test_the_surface_route_returns_vertices_and_triangles_of_the_reference_evaluator(client,
                                                                                    definition):
    params = {"tip_height": 5.0, "jaw_opening": 10.0, "back_width": -2.5}
    response = client.post("/api/v1/tongue/surface", json={"params": params})
    assert response.status_code == 200
    body = response.json()
    rig = TongueRig(definition)
    expected = rig.evaluate(rig.values_from(params))
    assert body["vertex_count"] == len(expected.vertices) >= 2000
    assert body["triangle_count"] == len(expected.triangles)
    np.testing.assert_allclose(body["vertices"], expected.vertices, atol=1e-9)
    np.testing.assert_array_equal(body["triangles"], expected.triangles)
    np.testing.assert_allclose(body["normals"], expected.normals, atol=1e-9)
    # The same float64 evaluator on both sides of the request: equal up to rounding.
    assert body["volume_mm3"] == pytest.approx(expected.volume, rel=1e-12)
    # the values sent, and a neutral value, echoed: not computed
    assert body["params"]["tip_height"] == 5.0 and body["params"]["tip_advancement"] == 0.0
    assert body["units"] == "mm" and body["frame"] == "project"


def test_an_empty_request_gives_the_rest_shape(client, definition):
    body = client.post("/api/v1/tongue/surface", json={}).json()
    rig = TongueRig(definition)
    np.testing.assert_allclose(body["vertices"], rig.evaluate(rig.neutral).vertices, atol=1e-9)


def test_an_unknown_parameter_gets_a_422_naming_it_and_the_known_ones(client):
    response = client.post("/api/v1/tongue/surface", json={"params": {"tip_heigth": 1.0}})
    assert response.status_code == 422
    detail = response.json()["detail"]
    assert detail.startswith("unknown parameter 'tip_heigth'; known: tip_advancement, tip_height")


def test_a_value_outside_its_range_gets_a_422_with_the_range_and_unit(client, definition):
    tip = next(p for p in definition["parameters"] if p["name"] == "tip_height")
    response = client.post("/api/v1/tongue/surface", json={"params": {"tip_height": 40}})
    assert response.status_code == 422
    assert response.json()["detail"] == (
        f"tip_height = 40 is outside its range [{tip['min']:g}, {tip['max']:g}] mm")


def test_a_value_that_is_not_a_number_gets_a_422(client):
    response = client.post("/api/v1/tongue/surface", json={"params": {"tip_height": "high"}})
    assert response.status_code == 422
    assert "params.tip_height" in response.json()["detail"]


def test_the_openapi_document_names_both_tongue_operations(client):
    document = client.get("/api/v1/openapi.json").json()
    operations = {op["operationId"]: path for path, item in document["paths"].items()
                  for op in item.values()}
    assert operations["getTongueRig"] == "/api/v1/tongue/rig"
    assert operations["evaluateTongueSurface"] == "/api/v1/tongue/surface"


def test_a_rebuilt_rig_file_is_served_without_a_restart(client, tmp_path, definition):
    assert client.get("/api/v1/tongue/rig").json()["coronal"]["pole_half_width"] == \
        definition["coronal"]["pole_half_width"]
    changed = json.loads(json.dumps(definition))
    changed["coronal"]["pole_half_width"] += 1.0
    path = tmp_path / "tongue-rig.json"
    path.write_text(json.dumps(changed))
    stat = path.stat()
    os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns + 10**9))
    assert client.get("/api/v1/tongue/rig").json()["coronal"]["pole_half_width"] == \
        changed["coronal"]["pole_half_width"]


def test_without_a_built_file_the_rig_routes_answer_503_and_fit_nothing(tmp_path, monkeypatch):
    monkeypatch.setenv("GLASSHEAD_ASSETS_DIR", str(tmp_path / "empty"))
    monkeypatch.setenv("GLASSHEAD_WEB_DIST_DIR", str(tmp_path / "no-web"))
    get_settings.cache_clear()
    try:
        client = TestClient(create_app())
        for response in (client.get("/api/v1/tongue/rig"),
                         client.post("/api/v1/tongue/surface", json={"params": {}})):
            assert response.status_code == 503
            assert response.json()["asset"] == "tongue_rig"
            assert "tongue-rig.json" in response.json()["detail"]
            assert "glasshead build" in response.json()["detail"]
        assert not (tmp_path / "empty").exists()  # serving never writes the build's output
    finally:
        get_settings.cache_clear()
