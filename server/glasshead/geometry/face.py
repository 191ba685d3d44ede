"""The face rig definition: its checks.

- ``geometry.face_rig``: the reference evaluator (skin and lips on the jaw, the lip parameters);
- ``pipeline.face_rig``: the build step that writes ``<assets_dir>/face-rig.json``;
- ``glasshead.asset_store``: where the application reads the built file, once per version.
"""

import json
import math
from pathlib import Path

from glasshead.constants import FACE_RIG_FORMAT_VERSION
from glasshead.geometry.face_rig import LIP_MESHES, LIP_PARAMETER_NAMES, MESH_NAMES

TABLE_KEYS = ("y0", "z0", "step_y", "step_z", "rows", "cols", "x", "recession", "depth", "steps")


def _finite(value):
    return isinstance(value, (int, float)) and math.isfinite(value)


def validate_face_rig(rig):
    """Check a face rig read from JSON; raise ValueError naming the first problem."""
    if not isinstance(rig, dict):
        raise TypeError("a face rig must be a JSON object")
    version = rig.get("format_version")
    if version != FACE_RIG_FORMAT_VERSION:
        raise ValueError(f"face rig format_version {version!r} is not {FACE_RIG_FORMAT_VERSION}")
    for key in ("parameters", "field", "teeth", "meshes"):
        if key not in rig:
            raise ValueError(f"face rig has no '{key}'")
    names = tuple(p.get("name") for p in rig["parameters"])
    if names != LIP_PARAMETER_NAMES:
        raise ValueError(f"face rig parameters are {names}, expected {LIP_PARAMETER_NAMES}")
    for p in rig["parameters"]:
        if not all(_finite(p.get(k)) for k in ("min", "max", "neutral")) \
                or not p["min"] <= p["neutral"] <= p["max"]:
            raise ValueError(f"parameter {p['name']}: needs finite min <= neutral <= max")
    for row in ("upper", "lower"):
        table = rig["teeth"].get(row, {})
        missing = [k for k in TABLE_KEYS if k not in table]
        if missing:
            raise ValueError(f"teeth.{row} lacks {missing}")
        cells = table["rows"] * table["cols"]
        if table["rows"] < 2 or table["cols"] < 2 or len(table["x"]) != cells:
            raise ValueError(f"teeth.{row} needs rows * cols (both >= 2) values")
    for name in MESH_NAMES:
        mesh = rig["meshes"].get(name)
        if mesh is None:
            raise ValueError(f"face rig has no mesh '{name}'")
        count = mesh.get("vertex_count")
        weights = mesh.get("jaw_weights", [])
        if len(weights) != count or not all(_finite(w) and 0.0 <= w <= 1.0 for w in weights):
            raise ValueError(f"mesh {name}: needs vertex_count jaw_weights in [0, 1]")
        if name in LIP_MESHES:
            edges = mesh.get("midline_edges", [])
            if not edges or not all(0 <= i < count for e in edges for i in e):
                raise ValueError(f"mesh {name}: midline_edges missing or out of range")
    return rig


def read_face_rig(path):
    """Read and validate a face rig file; ValueError naming the file if it is not one."""
    path = Path(path)
    try:
        return validate_face_rig(json.loads(path.read_text()))
    except (json.JSONDecodeError, KeyError, TypeError, ValueError) as exc:
        raise ValueError(f"{path}: not a face rig ({exc})") from None
