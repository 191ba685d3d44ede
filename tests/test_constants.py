"""The two constants modules are mirrors: glasshead/constants.py and web/src/core/constants.js."""

import json
import shutil
import subprocess

import numpy as np
import pytest

from glasshead.settings import REPO_ROOT
from glasshead.vectors.constants import constants_document, python_constants
from vector_support import assert_same_document, read_vectors, tol

pytestmark = pytest.mark.vectors
STORED = read_vectors("constants.json")
#: Relative tolerance of constants written in two languages (the file states its reason).
RTOL = tol(STORED, "value")

# Prints every upper-case export of the JS constants module as plain JSON.
NODE_SCRIPT = """
import * as constants from './web/src/core/constants.js';
const plain = Object.fromEntries( Object.entries( constants )
	.filter( ( [ name ] ) => name === name.toUpperCase() ) );
const unwrap = ( _k, v ) => ( ArrayBuffer.isView( v ) ? Array.from( v ) : v );
console.log( JSON.stringify( plain, unwrap ) );
"""


def assert_same(js, py, path):
    if isinstance(py, (bool, str)) or py is None:
        assert js == py, f"{path}: JS {js!r}, Python {py!r}"
    elif isinstance(py, (int, float)):
        assert isinstance(js, (int, float)) and not isinstance(js, bool), f"{path}: {js!r}"
        np.testing.assert_allclose(js, py, rtol=RTOL, atol=0, err_msg=path)
    elif isinstance(py, list):
        assert isinstance(js, list) and len(js) == len(py), f"{path}: JS {js!r}, Python {py!r}"
        for k, (a, b) in enumerate(zip(js, py, strict=True)):
            assert_same(a, b, f"{path}[{k}]")
    else:
        assert isinstance(js, dict) and sorted(js) == sorted(py), \
            f"{path}: JS {js!r}, Python {py!r}"
        for key in py:
            assert_same(js[key], py[key], f"{path}.{key}")


def test_the_constants_vector_file_is_up_to_date_with_python():
    fresh = json.loads(json.dumps(constants_document()))
    try:
        assert_same_document(fresh, STORED, rtol=RTOL)
    except AssertionError as exc:
        raise AssertionError(f"tests/vectors/constants.json is stale ({exc}): run glasshead "
                             "vectors constants.json") from None


def test_javascript_exports_the_same_constants_with_the_same_values():
    node = shutil.which("node")
    assert node, "node is needed to read web/src/core/constants.js"
    result = subprocess.run([node, "--input-type=module", "-e", NODE_SCRIPT], cwd=REPO_ROOT,
                            capture_output=True, text=True, check=True)
    js = json.loads(result.stdout)
    py = json.loads(json.dumps(python_constants()))
    missing_in_js = sorted(set(py) - set(js))
    missing_in_python = sorted(set(js) - set(py))
    assert not missing_in_js and not missing_in_python, (
        f"only in Python: {missing_in_js}; only in JS: {missing_in_python}")
    for name in py:
        assert_same(js[name], py[name], name)
