"""Every request body in the OpenAPI document has an example, and every example is valid.

An example is the first thing a reader of /api/v1/docs copies, so each media type of each
request body documents one: on the media type (``example``/``examples``, as the multipart forms
do through ``openapi_extra``) or on the body's schema (``examples`` from the Pydantic model's
``json_schema_extra``). Each example is checked against the body's schema, with its ``$ref``s
resolved against the document's components (JSON Schema 2020-12, OpenAPI 3.1's dialect), by
jsonschema_rs, which schemathesis brings.
"""

import jsonschema_rs
import pytest

from glasshead.api.app import create_app


@pytest.fixture(scope="module")
def document() -> dict:
    return create_app().openapi()


def request_bodies(document: dict):
    """(label, media type object) of every media type of every operation's request body."""
    for path, operations in document["paths"].items():
        for method, operation in operations.items():
            body = operation.get("requestBody") if isinstance(operation, dict) else None
            for media_type, content in (body or {}).get("content", {}).items():
                yield f"{method.upper()} {path} {media_type}", content


def body_schema(document: dict, content: dict) -> dict:
    """The media type's schema, its own ``$ref`` followed once."""
    schema = content.get("schema", {})
    if "$ref" in schema:
        name = schema["$ref"].removeprefix("#/components/schemas/")
        return document["components"]["schemas"][name]
    return schema


def examples_of(document: dict, content: dict) -> list:
    found = [content["example"]] if "example" in content else []
    found += [entry["value"] for entry in content.get("examples", {}).values()]
    return found + list(body_schema(document, content).get("examples", []))


def schema_errors(document: dict, content: dict, instance) -> list[str]:
    """Where and why ``instance`` breaks the media type's schema; empty when it is valid."""
    schema = {**content.get("schema", {}), "components": document["components"]}
    validator = jsonschema_rs.Draft202012Validator(schema)
    return [f"{'/'.join(map(str, error.instance_path)) or '(body)'}: {error.message}"
            for error in validator.iter_errors(instance)]


def test_every_request_body_media_type_documents_an_example(document):
    bodies = dict(request_bodies(document))
    assert len(bodies) >= 34, f"only {len(bodies)} request bodies found"
    missing = [label for label, content in bodies.items() if not examples_of(document, content)]
    assert missing == [], f"request bodies without an example: {missing}"


def test_every_example_validates_against_its_request_body_schema(document):
    checked, invalid = 0, {}
    for label, content in request_bodies(document):
        for number, example in enumerate(examples_of(document, content)):
            checked += 1
            if errors := schema_errors(document, content, example):
                invalid[f"{label} example {number}"] = errors
    assert invalid == {}
    assert checked >= 34


def test_the_check_finds_an_example_that_breaks_a_referenced_schema(document):
    # Nested $refs (LessonPatch -> Item -> Target) are followed: an item with an unknown key is
    # refused as the server refuses it, and so is a vertex of two coordinates.
    bodies = dict(request_bodies(document))
    lesson = bodies["PATCH /api/v1/lessons/{lesson_id} application/json"]
    assert schema_errors(document, lesson, {"items": [{"target": {"kind": "word",
                                                                  "text": "ship"}}]}) == []
    assert schema_errors(document, lesson, {"items": [{"target": {"kind": "word", "text": "ship"},
                                                       "tempo": 0.5}]}) != []
    collision = bodies["POST /api/v1/collision/correct application/json"]
    assert schema_errors(document, collision, {"vertices": [[10.97, 17.92]]}) != []
    assert schema_errors(document, collision, {"vertices": [[10.97, 17.92, 0.0]],
                                               "velum_opening": 1.5}) != []
