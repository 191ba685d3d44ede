"""POST /epg/contacts with a triangle whose vertex index no request could reach is a 422, not a 500.

Found by schemathesis (bench/fuzz_api.py, fuzzing phase, no token): ``"triangles": [[0, 1,
2**63]]`` passed validation (an index had only to be >= 0), then failed in the compute worker
while it made the index array ("Python int too large to convert to C long"), and the request was
answered 500. An index is now below COLLISION_MAX_VERTICES, the most vertices a request may send,
so the document says so and the request is refused before any work; an index below that but past
the vertices sent keeps its own 422.
"""

import pytest

from glasshead.constants import COLLISION_MAX_VERTICES

API = "/api/v1"
THREE_VERTICES = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]


@pytest.fixture
def client(start_app, built_assets, monkeypatch):
    monkeypatch.setenv("GLASSHEAD_COMPUTE_WORKERS", "1")
    return start_app()[1]


@pytest.mark.parametrize("index", [2**63, 2**64, COLLISION_MAX_VERTICES])
def test_an_index_no_request_could_reach_is_a_422_naming_the_triangle(client, index):
    response = client.post(f"{API}/epg/contacts",
                           json={"vertices": THREE_VERTICES, "triangles": [[0, 1, index]]})
    assert response.status_code == 422, response.text
    assert response.json()["detail"].startswith("body.triangles.0.2")


def test_an_index_past_the_vertices_sent_is_still_a_422_naming_the_vertex(client):
    response = client.post(f"{API}/epg/contacts",
                           json={"vertices": THREE_VERTICES, "triangles": [[0, 1, 3]]})
    assert response.status_code == 422, response.text
    assert "vertex 3 does not exist" in response.json()["detail"]


def test_the_document_gives_the_bound(client):
    document = client.get(f"{API}/openapi.json").json()
    triangle = document["components"]["schemas"]["ContactsRequest"]["properties"]["triangles"]
    index = triangle["anyOf"][0]["items"]["items"]
    assert index["minimum"] == 0 and index["exclusiveMaximum"] == COLLISION_MAX_VERTICES
