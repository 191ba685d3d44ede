"""GET /epg/layout and POST /epg/contacts over HTTP, on the assets of the shared contact vectors."""

import json

import pytest
from fastapi.testclient import TestClient

from glasshead.api.app import create_app
from glasshead.pipeline.collision_tables import TABLES_FILE
from glasshead.pipeline.epg_layout import BUILDER_VERSION, LAYOUT_FILE
from glasshead.settings import get_settings
from vector_support import decode_f32, read_vectors

API = "/api/v1"
VECTORS = read_vectors("epg-contacts.json")
FIXTURES = VECTORS["fixtures"]
POSES = [c for c in VECTORS["cases"] if "params" in c["input"]]
KERNEL_CASES = [c for c in VECTORS["cases"] if "vertices" in c["input"]]


def _assets(tmp_path, layout=True):
    assets = tmp_path / "assets"
    assets.mkdir()
    (assets / TABLES_FILE).write_bytes(read_vectors(FIXTURES["tables"]["file"]))
    (assets / "tongue-rig.json").write_text(json.dumps(FIXTURES["rig"]))
    if layout:
        (assets / LAYOUT_FILE).write_text(json.dumps(dict(FIXTURES["layout"],
                                                          builder=BUILDER_VERSION)))
    return assets


@pytest.fixture
def client(tmp_path, monkeypatch):
    monkeypatch.setenv("GLASSHEAD_ASSETS_DIR", str(_assets(tmp_path)))
    monkeypatch.setenv("GLASSHEAD_WEB_DIST_DIR", str(tmp_path / "no-web"))
    get_settings.cache_clear()
    yield TestClient(create_app())
    get_settings.cache_clear()


def test_the_layout_serves_the_reading_palate_by_default(client):
    response = client.get(f"{API}/epg/layout")
    assert response.status_code == 200
    body = response.json()
    assert body["grid"] == "reading62" and body["rows"] == 8 and len(body["electrodes"]) == 62
    assert body["missing_cells"] == [0, 7]
    # Served as read from the layout file: the same numbers, not computed ones.
    assert body["electrodes"] == FIXTURES["layout"]["grids"]["reading62"]["electrodes"]
    assert body["contact"] == {"tolerance_mm": 1.0, "behind_mm": 0.5}


def test_the_layout_serves_the_dense_grid_and_refuses_an_unknown_one(client):
    dense = client.get(f"{API}/epg/layout", params={"grid": "dense96"}).json()
    assert dense["rows"] == 12 and len(dense["electrodes"]) == 96
    bad = client.get(f"{API}/epg/layout", params={"grid": "reading64"})
    assert bad.status_code == 422
    assert "grid" in bad.json()["detail"] and "reading62" in bad.json()["detail"]


@pytest.mark.vectors
def test_contacts_from_params_are_the_vectors_contacts_with_their_indices(client):
    case = max(POSES, key=lambda c: c["expected"]["reading62"]["contacted"])
    response = client.post(f"{API}/epg/contacts", json={"params": case["input"]["params"]})
    assert response.status_code == 200
    body = response.json()
    assert body["rows"] == case["expected"]["reading62"]["rows"]
    assert sum(body["contacts"]) == case["expected"]["reading62"]["contacted"]
    assert len(body["cells"]) == 64 and body["cells"][0] == 0 and body["cells"][7] == 0
    assert len(body["electrodes"]) == 62 and body["electrodes"][0] == "R1C2"
    assert body["contacted"] == [i for i, c in zip(body["electrodes"], body["contacts"],
                                                   strict=True) if c]
    assert body["indices"]["contacts"] == sum(body["contacts"])
    # One division of integers, computed the same way: a relative 1e-12 allows printing only.
    assert body["indices"]["percent"] == pytest.approx(100 * sum(body["contacts"]) / 62,
                                                       rel=1e-12)
    assert body["collision"] == case["expected"]["collision"]


@pytest.mark.vectors
def test_contacts_on_the_dense_grid_come_without_the_reading_indices(client):
    case = POSES[-1]
    body = client.post(f"{API}/epg/contacts", json={"params": case["input"]["params"],
                                                    "grid": "dense96"}).json()
    assert body["rows"] == case["expected"]["dense96"]["rows"]
    assert body["indices"] is None and len(body["cells"]) == 96


@pytest.mark.vectors
def test_contacts_from_vertices_use_the_rig_triangles_or_those_sent(client):
    tongue = next(c for c in KERNEL_CASES if c["input"]["triangles"] == "rig"
                  and c["expected"]["reading62"]["contacted"] > 0)
    vertices = decode_f32(tongue["input"]["vertices"]).reshape(-1, 3).tolist()
    body = client.post(f"{API}/epg/contacts", json={"vertices": vertices}).json()
    assert body["rows"] == tongue["expected"]["reading62"]["rows"]
    assert body["collision"] is None
    small = next(c for c in KERNEL_CASES if isinstance(c["input"]["triangles"], list)
                 and c["expected"]["contacted"])
    response = client.post(f"{API}/epg/contacts", json={
        "vertices": decode_f32(small["input"]["vertices"]).reshape(-1, 3).tolist(),
        "triangles": [small["input"]["triangles"][i:i + 3]
                      for i in range(0, len(small["input"]["triangles"]), 3)]})
    assert response.json()["contacted"] == small["expected"]["contacted"]


@pytest.mark.parametrize("body, message", [
    ({}, "exactly one of params, vertices"),
    ({"params": {}, "vertices": [[0, 0, 0]]}, "exactly one of params, vertices"),
    ({"params": {"tip_heigth": 1.0}}, "params.tip_heigth: unknown parameter"),
    ({"params": {"tip_height": 99.0}}, "outside its range"),
    ({"vertices": [[0, 0, 0]] * 5}, "the tongue has"),
    ({"vertices": [[0, 0, 0]] * 3, "triangles": [[0, 1, 3]]}, "vertex 3 does not exist"),
    ({"vertices": [[0, 0]]}, "vertices"),
    ({"params": {}, "grid": "reading64"}, "grid"),
    ({"params": {}, "triangles": [[0, 1, 2]]}, "triangles go with vertices"),
])
def test_bad_contact_requests_get_422_naming_the_problem(client, body, message):
    response = client.post(f"{API}/epg/contacts", json=body)
    assert response.status_code == 422
    assert message in response.json()["detail"]


def test_without_a_built_layout_the_epg_routes_say_what_to_run(tmp_path, monkeypatch):
    monkeypatch.setenv("GLASSHEAD_ASSETS_DIR", str(_assets(tmp_path, layout=False)))
    monkeypatch.setenv("GLASSHEAD_WEB_DIST_DIR", str(tmp_path / "no-web"))
    get_settings.cache_clear()
    try:
        client = TestClient(create_app())
        for response in (client.get(f"{API}/epg/layout"),
                         client.post(f"{API}/epg/contacts", json={"params": {}})):
            assert response.status_code == 503
            assert "glasshead build" in response.json()["detail"]
    finally:
        get_settings.cache_clear()


def test_the_openapi_document_names_the_epg_operations(client):
    paths = client.get(f"{API}/openapi.json").json()["paths"]
    assert paths["/api/v1/epg/layout"]["get"]["operationId"] == "getEpgLayout"
    assert paths["/api/v1/epg/contacts"]["post"]["operationId"] == "computeEpgContacts"
