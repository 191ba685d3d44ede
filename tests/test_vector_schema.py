"""Every shared vector file follows the one schema (glasshead.vectors.schema), and a file that
breaks it is reported with its name and the case (index and description)."""

import json
from pathlib import Path

import pytest

from glasshead.vectors import VECTOR_FILES
from glasshead.vectors.schema import VectorSchemaError, check, problems

pytestmark = pytest.mark.vectors

VECTORS = Path(__file__).parent / "vectors"
JSON_FILES = sorted(path.name for path in VECTORS.glob("*.json"))


def good_document():
    return {
        "description": "a small valid document",
        "generator": "glasshead vectors example.json",
        "format_version": 1,
        "constants": {"seed": 1},
        "tolerance": {"vertex_mm": {"value": 1e-4, "unit": "mm", "reason": "float32 in JS"}},
        "fixtures": {"rig": {}},
        "cases": [
            {"description": "one", "input": {"x": 1.0}, "expected": {"y": 2.0}},
            {"description": "a refusal", "input": {"x": -1.0}, "expected": {"error": "negative"}},
        ],
    }


def test_the_generator_writes_every_vector_file_there_is_and_no_other():
    present = sorted(path.name for path in VECTORS.iterdir() if path.is_file())
    assert present == sorted(VECTOR_FILES)


@pytest.mark.parametrize("name", JSON_FILES)
def test_the_vector_file_follows_the_schema(name):
    check(json.loads((VECTORS / name).read_text()), name)


def test_a_valid_document_passes():
    assert problems(good_document()) == []


def test_a_broken_case_is_reported_with_the_file_its_index_and_its_description():
    document = good_document()
    document["cases"][1]["expected"] = {"error": "negative", "also": 1}
    document["cases"].append({"description": "one", "input": [], "expected": {}})
    with pytest.raises(VectorSchemaError) as raised:
        check(document, "broken.json")
    message = str(raised.value)
    assert "broken.json: case 1 ('a refusal'): a refusal's expected must be exactly" in message
    assert "broken.json: case 2 ('one'): description repeats case 0" in message
    assert "broken.json: case 2 ('one'): input must be an object" in message


@pytest.mark.parametrize("change, fragment", [
    (lambda d: d.pop("constants"), "top level: missing constants"),
    (lambda d: d.update(seed=3), "top level: unknown keys seed"),
    (lambda d: d.update(format_version="2"), "format_version must be an integer"),
    (lambda d: d.update(generator="python -m glasshead.geometry.vectors"), "generator must be"),
    (lambda d: d["tolerance"].update(x={"value": 0, "unit": "mm", "reason": "r"}), "value must"),
    (lambda d: d["tolerance"].update(x={"value": 1, "unit": "inch", "reason": "r"}), "unit 'inch'"),
    (lambda d: d["tolerance"].update(x=1e-3), "tolerance 'x': must be exactly"),
    (lambda d: d["cases"][0].pop("expected"), "case 0 ('one'): missing expected"),
    (lambda d: d["cases"][0].update(note="n"), "case 0 ('one'): unknown keys note"),
    (lambda d: d["cases"][0].update(description=""), "case 0: description must be"),
])
def test_each_rule_names_what_is_wrong(change, fragment):
    document = good_document()
    change(document)
    with pytest.raises(VectorSchemaError, match="broken.json") as raised:
        check(document, "broken.json")
    assert fragment in str(raised.value)
