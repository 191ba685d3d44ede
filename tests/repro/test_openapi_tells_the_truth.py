"""The OpenAPI document declares what the server sends, and a wrong method is a 405.

Every 422 ``detail`` was a string while the document declared an array (FastAPI's
HTTPValidationError) on 19 operations; 404, 409, 413 and 415 were not documented at all; and
any method on a known path answered 404. schemathesis checks the whole document against the
server (tests/test_api_openapi_conformance.py); these are the cases it was built from.
"""

import pytest

from accounts_support import signed_in

API = "/api/v1"
ERROR_REF = "#/components/schemas/Error"


@pytest.fixture(scope="module")
def document(built_assets):
    from glasshead.api.app import create_app

    return create_app().openapi()


@pytest.fixture
def client(start_app):
    return signed_in(start_app()[1], "admin")


def operations(document):
    for path, methods in document["paths"].items():
        for method, operation in methods.items():
            yield path, method, operation


def test_no_operation_declares_fastapis_array_of_validation_errors(document):
    schemas = document["components"]["schemas"]
    assert "HTTPValidationError" not in schemas and "ValidationError" not in schemas
    assert schemas["Error"]["properties"]["detail"]["type"] == "string"
    assert schemas["Error"]["required"] == ["detail"]


def test_every_documented_error_is_the_one_error_schema(document):
    errors = 0
    for _, _, operation in operations(document):
        for status, response in operation["responses"].items():
            if status[0] in "45":
                errors += 1
                assert response["content"]["application/json"]["schema"] == {"$ref": ERROR_REF}
    assert errors > 100


@pytest.mark.parametrize("path, method, statuses", [
    ("/poses", "post", {"400", "403", "409", "413", "422", "503"}),
    ("/poses/{pose_id}", "get", {"404", "422"}),
    ("/poses/{pose_id}", "put", {"400", "404", "409", "412", "413", "422", "503"}),
    ("/poses/{pose_id}", "patch", {"404", "409", "412"}),
    ("/epg/recordings", "post", {"400", "413", "415", "422"}),
    ("/epg/recordings/{recording_id}/export", "get", {"404", "409", "422"}),
    ("/epg/recordings/{recording_id}", "delete", {"404", "412", "422"}),
    ("/fits", "post", {"413", "415", "422", "503"}),
    ("/anatomy", "get", {"503"}),
    ("/tongue/surface", "post", {"413", "422", "503"}),
])
def test_the_errors_an_operation_can_answer_are_documented(document, path, method, statuses):
    documented = set(document["paths"][API + path][method]["responses"])
    assert statuses <= documented


def test_an_operation_with_no_input_documents_no_422(document):
    assert set(document["paths"][f"{API}/health"]["get"]["responses"]) == {"200", "400"}
    assert "404" not in document["paths"][f"{API}/poses"]["get"]["responses"]


def test_a_validation_error_is_sent_as_the_string_the_document_declares(client):
    response = client.post(f"{API}/tongue/surface", json={"params": {"tip_height": "high"}})
    assert response.status_code == 422
    assert isinstance(response.json()["detail"], str)


@pytest.mark.parametrize("method, path, allow", [
    ("DELETE", "/health", "GET"),
    ("PUT", "/epg/recordings", "GET, POST"),
    ("POST", "/poses/1", "DELETE, GET, PATCH, PUT"),
    ("GET", "/tongue/surface", "POST"),
    ("PATCH", "/fits/3", "DELETE, GET"),
])
def test_a_known_path_with_a_method_it_does_not_take_is_405_with_allow(client, method, path,
                                                                       allow):
    response = client.request(method, API + path)
    assert response.status_code == 405
    assert response.headers["Allow"] == allow
    assert method in response.json()["detail"] and allow in response.json()["detail"]


def test_an_unknown_api_path_is_still_404_for_any_method(client):
    for method in ("GET", "POST", "DELETE"):
        response = client.request(method, f"{API}/no/such/thing")
        assert response.status_code == 404
        assert "Allow" not in response.headers
