"""What every vector file shares: where the files live, the layout of a document, tolerances,
and the float32 encoding of inputs given bit for bit.

A document (``tests/vectors/*.json``) is::

    {"description": str, "generator": str, "format_version": int,
     "constants": {...}, "tolerance": {name: {"value", "unit", "reason"}},
     "fixtures": {...},                    # optional: bulky inputs shared by many cases
     "cases": [{"description", "input", "expected"}, ...]}

``glasshead.vectors.schema`` checks it; ``document()`` below builds one.
"""

import base64
import json
from pathlib import Path

import numpy as np

from glasshead.settings import REPO_ROOT

VECTORS_DIR = REPO_ROOT / "tests" / "vectors"
COMMAND = "glasshead vectors"
#: Documents larger than this (characters) are written without indentation.
COMPACT_ABOVE = 100_000


def tolerance(value, unit, reason):
    """One entry of a document's ``tolerance``: value (> 0), unit (see ``schema.UNITS``), reason."""
    return {"value": value, "unit": unit, "reason": reason}


def document(name, description, format_version, cases, constants=None, tolerances=None,
             fixtures=None):
    """A vector document in the shared layout (``fixtures`` only when given)."""
    out = {
        "description": description,
        "generator": f"{COMMAND} {name}",
        "format_version": format_version,
        "constants": constants or {},
        "tolerance": tolerances or {},
    }
    if fixtures is not None:
        out["fixtures"] = fixtures
    out["cases"] = cases
    return out


def case(description, input, expected):
    return {"description": description, "input": input, "expected": expected}


def dumps(doc):
    """The text of a vector file: indented when small, compact when large; one final newline."""
    text = json.dumps(doc, indent=1)
    if len(text) > COMPACT_ABOVE:
        text = json.dumps(doc, separators=(",", ":"))
    return text + "\n"


def read(name, vectors_dir=VECTORS_DIR):
    """A committed vector file: the parsed document for ``.json``, bytes otherwise."""
    path = Path(vectors_dir) / name
    return json.loads(path.read_text()) if name.endswith(".json") else path.read_bytes()


def rounded(values, decimals):
    """float64 values rounded to ``decimals``, as nested lists."""
    return np.round(np.asarray(values, dtype=np.float64), decimals).tolist()


def encode_f32(values) -> str:
    """Little-endian float32 bytes of ``values``, base64: inputs both sides read bit for bit."""
    return base64.b64encode(np.asarray(values, dtype="<f4").tobytes()).decode("ascii")


def decode_f32(text) -> np.ndarray:
    """The float32 values of ``encode_f32`` text, as float64 (exact)."""
    return np.frombuffer(base64.b64decode(text), dtype="<f4").astype(np.float64)
