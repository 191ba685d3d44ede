"""The application shell: health, JSON errors, OpenAPI, the anatomy manifest and cached assets."""

import hashlib
import json

import pytest
from fastapi.testclient import TestClient

from glasshead.api.app import create_app
from glasshead.settings import get_settings

#: A small GLB-like file; an asset URL is immutable only when its v is the file's hash.
GLB = b"glTF" + bytes(60)
GLB_SHA256 = hashlib.sha256(GLB).hexdigest()


@pytest.fixture
def client_with_assets(tmp_path, monkeypatch):
    """An app whose assets directory holds one small GLB-like file and its manifest."""
    assets = tmp_path / "assets"
    assets.mkdir()
    (assets / "maxilla.glb").write_bytes(GLB)
    manifest = {
        "format_version": 1,
        "frame": {"units": "mm"},
        "meshes": [{"name": "maxilla", "file": "maxilla.glb", "sha256": GLB_SHA256,
                    "triangles": 12, "vertices": 8, "lod": "full", "scene": True, "role": "bone"}],
    }
    (assets / "manifest.json").write_text(json.dumps(manifest))
    monkeypatch.setenv("GLASSHEAD_ASSETS_DIR", str(assets))
    monkeypatch.setenv("GLASSHEAD_WEB_DIST_DIR", str(tmp_path / "no-web"))
    get_settings.cache_clear()
    yield TestClient(create_app())
    get_settings.cache_clear()


def test_health_answers_and_names_the_assets_that_are_not_built(client_with_assets):
    response = client_with_assets.get("/api/v1/health")
    assert response.status_code == 200
    body = response.json()
    assert body["status"] == "degraded" and body["assets_built"] is False
    assert body["assets"]["manifest"]["status"] == "ok"
    assert body["assets"]["tongue_rig"]["status"] == "missing"
    assert "glasshead build" in body["assets"]["tongue_rig"]["detail"]


def test_an_unknown_api_path_gets_a_json_404_naming_the_path(client_with_assets):
    response = client_with_assets.get("/api/v1/no-such-thing")
    assert response.status_code == 404
    assert response.headers["content-type"].startswith("application/json")
    assert "/api/v1/no-such-thing" in response.json()["detail"]


def test_the_openapi_document_lists_the_public_operations(client_with_assets):
    document = client_with_assets.get("/api/v1/openapi.json").json()
    operation_ids = {op["operationId"] for path in document["paths"].values()
                     for op in path.values()}
    assert {"getHealth", "getAnatomy"} <= operation_ids
    assert client_with_assets.get("/api/v1/docs").status_code == 200


def test_anatomy_lists_meshes_with_versioned_urls(client_with_assets):
    meshes = client_with_assets.get("/api/v1/anatomy").json()["meshes"]
    assert meshes[0]["name"] == "maxilla"
    assert meshes[0]["triangles"] == 12
    assert meshes[0]["url"] == "/assets/build/maxilla.glb?v=" + GLB_SHA256[:16]


def test_versioned_assets_are_cached_for_good_and_revalidate_by_etag(client_with_assets):
    url = client_with_assets.get("/api/v1/anatomy").json()["meshes"][0]["url"]
    response = client_with_assets.get(url)
    assert response.status_code == 200
    assert response.headers["content-type"] == "model/gltf-binary"
    assert "immutable" in response.headers["cache-control"]
    again = client_with_assets.get(url, headers={"If-None-Match": response.headers["etag"]})
    assert again.status_code == 304


def test_asset_paths_cannot_escape_the_assets_directory(client_with_assets):
    assert client_with_assets.get("/assets/build/%2e%2e/%2e%2e/etc/passwd").status_code == 404
    assert client_with_assets.get("/assets/build/missing.glb").status_code == 404


def test_anatomy_answers_503_with_a_hint_when_not_built(tmp_path, monkeypatch):
    monkeypatch.setenv("GLASSHEAD_ASSETS_DIR", str(tmp_path / "empty"))
    get_settings.cache_clear()
    try:
        response = TestClient(create_app()).get("/api/v1/anatomy")
    finally:
        get_settings.cache_clear()
    assert response.status_code == 503
    assert "glasshead build" in response.json()["detail"]


def test_host_and_port_come_from_the_environment(monkeypatch):
    monkeypatch.setenv("HOST", "0.0.0.0")
    monkeypatch.setenv("PORT", "8123")
    get_settings.cache_clear()
    try:
        settings = get_settings()
    finally:
        get_settings.cache_clear()
    assert (settings.host, settings.port) == ("0.0.0.0", 8123)
