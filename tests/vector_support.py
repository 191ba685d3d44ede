"""Reading the shared vectors (tests/vectors) in pytest, and comparing with their tolerances.

Every JSON file is checked against the schema as it is read. ``tol(document, name)`` is the value
of one of the file's stated tolerances (each has its unit and reason in the file).
"""

import math
from pathlib import Path

from glasshead.vectors.common import decode_f32, read
from glasshead.vectors.schema import check

VECTORS_DIR = Path(__file__).parent / "vectors"
__all__ = ["VECTORS_DIR", "assert_generated", "assert_same_document", "decode_f32",
           "read_vectors", "tol"]


def read_vectors(name):
    """A vector file: a JSON document (checked against the schema), or the bytes of another."""
    content = read(name, VECTORS_DIR)
    return check(content, name) if name.endswith(".json") else content


def tol(document, name):
    """The value of the document's tolerance ``name``."""
    return document["tolerance"][name]["value"]


def _where(path, value):
    return f"{path} ({value.get('description')!r})" if isinstance(value, dict) \
        and "description" in value and path else path


def assert_same_document(actual, expected, atol=0.0, rtol=0.0, path=""):
    """``actual`` equals ``expected`` in structure, text, flags and integers exactly, and in
    floats within ``atol + rtol * |expected|``; a difference is reported with its path."""
    if isinstance(expected, bool) or isinstance(actual, bool) or expected is None \
            or isinstance(expected, str):
        assert actual == expected, f"{path or 'document'}: {actual!r} != {expected!r}"
    elif isinstance(expected, int) and isinstance(actual, int):
        assert actual == expected, f"{path}: {actual} != {expected} (integers are exact)"
    elif isinstance(expected, (int, float)):
        assert isinstance(actual, (int, float)), f"{path}: {actual!r} is not a number"
        assert math.isfinite(actual) == math.isfinite(expected) and (
            not math.isfinite(expected) or abs(actual - expected) <= atol + rtol * abs(expected)
        ), f"{path}: {actual!r} != {expected!r} (atol {atol}, rtol {rtol})"
    elif isinstance(expected, list):
        assert isinstance(actual, list) and len(actual) == len(expected), \
            f"{path}: lengths {len(actual) if isinstance(actual, list) else actual!r} != " \
            f"{len(expected)}"
        for k, (a, e) in enumerate(zip(actual, expected, strict=True)):
            assert_same_document(a, e, atol, rtol, _where(f"{path}[{k}]", e))
    else:
        keys = sorted(actual) if isinstance(actual, dict) else actual
        assert keys == sorted(expected), f"{path or 'document'}: keys {keys!r} != " \
                                         f"{sorted(expected)}"
        for key in expected:
            assert_same_document(actual[key], expected[key], atol, rtol, f"{path}.{key}")


def assert_generated(name, document, vectors, atol=0.0, rtol=0.0):
    """``document``, as the generator makes it now, is the committed vector file ``vectors``
    (``name``); a difference names the command that writes the file again."""
    try:
        assert_same_document(document, vectors, atol=atol, rtol=rtol)
    except AssertionError as exc:
        raise AssertionError(f"{exc}: run `glasshead vectors {name}`") from None
