"""constants.json and collision-constants.json: the constants both sides must share.

``web/src/core/constants.js`` must export every upper-case name of ``glasshead.constants`` with
the same value; tests/test_constants.py and tests/js/constants.test.js check it against these
files (tests/js/collision.test.js checks the collision subset).
"""

import inspect

import numpy as np

from glasshead import constants as project
from glasshead.vectors.common import document, tolerance

FORMAT_VERSION = 2
#: Constants are decimal literals or short arithmetic on them; both languages parse a literal to
#: the same double, and the arithmetic may round its last bit differently.
RELATIVE = tolerance(1e-12, "relative", "decimal literals read by two languages, and short "
                                        "arithmetic on them, differ at most in the last bits")
COLLISION_NAMES = (
    "COLLISION_TABLES_FORMAT_VERSION", "COLLISION_TABLES_MAGIC", "COLLISION_LINER_STEP_DEG",
    "COLLISION_VOXELS", "VOXEL_OK", "VOXEL_BORDER", "VOXEL_NOT_OK", "CELL_EMPTY", "CELL_PLANE",
    "CELL_LIST", "FLAG_SCREENED", "FLAG_TESTED", "FLAG_CORRECTED", "COLLISION_MAX_VERTICES",
    "COLLISION_TOL",
)
COLLISION_TOL_FIELDS = ("angle", "length", "barycentric", "surface", "depth")


def to_json_value(value):
    """A constant as plain JSON: arrays and tuples as lists, bytes as ASCII text, a tolerance
    object as the dict of its public attributes."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, (tuple, list)):
        return [to_json_value(v) for v in value]
    if isinstance(value, dict):
        return {str(k): to_json_value(v) for k, v in value.items()}
    if isinstance(value, bytes):
        return value.decode("ascii")
    if isinstance(value, (np.integer, np.floating)):
        return value.item()
    if isinstance(value, (bool, int, float, str)) or value is None:
        return value
    attributes = {name: getattr(value, name) for name in dir(value)
                  if not name.startswith("_") and not callable(getattr(value, name))}
    return {name: to_json_value(v) for name, v in attributes.items()}


def python_constants():
    """Every upper-case, non-class name of ``glasshead.constants`` as plain JSON values."""
    return {name: to_json_value(value) for name, value in vars(project).items()
            if name.isupper() and not inspect.isclass(value) and not inspect.ismodule(value)}


def constants_document():
    return document(
        "constants.json",
        "The Python constants (glasshead.constants); web/src/core/constants.js must export the "
        "same names with the same values",
        FORMAT_VERSION, cases=[], constants=python_constants(), tolerances={"value": RELATIVE})


def collision_constants_document():
    values = python_constants()
    chosen = {name: values[name] for name in COLLISION_NAMES}
    chosen["COLLISION_TOL"] = {k: chosen["COLLISION_TOL"][k] for k in COLLISION_TOL_FIELDS}
    return document(
        "collision-constants.json",
        "The collision constants shared by constants.py and constants.js",
        FORMAT_VERSION, cases=[], constants=chosen, tolerances={"value": RELATIVE})


def files():
    return {"constants.json": constants_document(),
            "collision-constants.json": collision_constants_document()}
