"""GET /collision/tables and POST /collision/correct over HTTP, on the shared vector tables."""

import shutil

import numpy as np
import pytest
from fastapi.testclient import TestClient

from glasshead.api.app import create_app
from glasshead.constants import COLLISION_MAX_VERTICES, COLLISION_TABLES_FORMAT_VERSION
from glasshead.pipeline.collision_tables import TABLES_FILE
from glasshead.settings import get_settings
from vector_support import VECTORS_DIR, read_vectors, tol

VECTORS = read_vectors("collision-correct.json")
TABLES_PATH = VECTORS_DIR / VECTORS["fixtures"]["tables"]["file"]


def _client(tmp_path, monkeypatch, tables=True):
    assets = tmp_path / "assets"
    assets.mkdir()
    if tables:
        shutil.copy(TABLES_PATH, assets / TABLES_FILE)
    monkeypatch.setenv("GLASSHEAD_ASSETS_DIR", str(assets))
    monkeypatch.setenv("GLASSHEAD_WEB_DIST_DIR", str(tmp_path / "no-web"))
    get_settings.cache_clear()
    return TestClient(create_app()), assets


@pytest.fixture
def client(tmp_path, monkeypatch):
    yield _client(tmp_path, monkeypatch)[0]
    get_settings.cache_clear()


def test_tables_answer_with_their_header_and_a_url_that_serves_the_binary(client):
    response = client.get("/api/v1/collision/tables")
    assert response.status_code == 200
    body = response.json()
    assert body["format_version"] == COLLISION_TABLES_FORMAT_VERSION
    assert body["header"]["voxels"]["shape"] == [16, 16, 16]
    assert len(body["header"]["origin"]) == 3
    binary = client.get(body["url"])
    assert binary.status_code == 200
    assert binary.content == TABLES_PATH.read_bytes()
    assert body["bytes"] == len(binary.content)


@pytest.mark.vectors
def test_correct_returns_the_reference_vertices_flags_and_counts(client):
    case = max((c for c in VECTORS["cases"] if "vertices" in c["input"]),
               key=lambda c: len(c["input"]["vertices"]))
    response = client.post("/api/v1/collision/correct", json=case["input"])
    assert response.status_code == 200
    body = response.json()
    assert body["flags"] == case["expected"]["flags"]
    assert body["counts"] == case["expected"]["counts"]
    np.testing.assert_allclose(body["vertices"], case["expected"]["vertices"], rtol=0,
                               atol=tol(VECTORS, "reference_mm"))


def test_correct_accepts_an_empty_vertex_list(client):
    response = client.post("/api/v1/collision/correct", json={"vertices": []})
    assert response.status_code == 200
    assert response.json()["counts"] == {"screened": 0, "tested": 0, "corrected": 0}


@pytest.mark.parametrize("body, fragment", [
    ({"vertices": [[1.0, 2.0]]}, "vertices.0"),
    ({"vertices": [[1.0, 2.0, 3.0, 4.0]]}, "vertices.0"),
    ({"vertices": [[1.0, "2", 3.0]]}, "vertices.0.1"),
    ({"vertices": "many"}, "vertices"),
    ({"points": [[1.0, 2.0, 3.0]]}, "vertices"),
    ({"vertices": [[0.0, 0.0, 0.0]] * (COLLISION_MAX_VERTICES + 1)}, "at most 20000"),
])
def test_malformed_or_oversized_vertex_arrays_get_a_422_that_says_what_is_wrong(client, body,
                                                                               fragment):
    response = client.post("/api/v1/collision/correct", json=body)
    assert response.status_code == 422
    assert fragment in response.json()["detail"]


@pytest.mark.parametrize("token", ["NaN", "Infinity", "-Infinity"])
def test_non_finite_coordinates_get_a_422_naming_the_coordinate(client, token):
    raw = '{"vertices": [[1.0, 2.0, 3.0], [4.0, ' + token + ', 6.0]]}'
    response = client.post("/api/v1/collision/correct", content=raw,
                           headers={"content-type": "application/json"})
    assert response.status_code == 422
    detail = response.json()["detail"]
    assert "vertices.1.1" in detail and "finite" in detail


def test_missing_tables_answer_503_with_the_command_to_build_them(tmp_path, monkeypatch):
    client, _ = _client(tmp_path, monkeypatch, tables=False)
    for response in (client.get("/api/v1/collision/tables"),
                     client.post("/api/v1/collision/correct", json={"vertices": [[0, 0, 0]]})):
        assert response.status_code == 503
        assert "glasshead build" in response.json()["detail"]
    get_settings.cache_clear()


def test_tables_of_another_format_version_are_refused_not_misread(tmp_path, monkeypatch):
    client, assets = _client(tmp_path, monkeypatch)
    data = bytearray((assets / TABLES_FILE).read_bytes())
    data[8:12] = (COLLISION_TABLES_FORMAT_VERSION + 1).to_bytes(4, "little")
    (assets / TABLES_FILE).write_bytes(bytes(data))
    response = client.get("/api/v1/collision/tables")
    assert response.status_code == 503
    assert "format version" in response.json()["detail"]
    get_settings.cache_clear()


def test_the_openapi_document_names_both_operations(client):
    paths = client.get("/api/v1/openapi.json").json()["paths"]
    assert paths["/api/v1/collision/tables"]["get"]["operationId"] == "getCollisionTables"
    assert paths["/api/v1/collision/correct"]["post"]["operationId"] == "correctCollision"
