"""Shared test vectors: the JSON files in tests/vectors/ that pytest and node both check.

Run ``python -m glasshead.geometry.vectors`` to regenerate every registered file, or name some:
``python -m glasshead.geometry.vectors tongue-surface.json``; ``--list`` lists them.

Each file is produced by a function that returns a JSON-ready document, registered in
``VECTOR_FILES`` as ``"module:function"`` (imported only when that file is generated, so a
module with heavy imports costs nothing to the others). To add a file, add one line there.
Documents follow the JSON-Schema-Test-Suite habit: a ``description``, then ``cases`` of
``{description, input, expected}`` with unique descriptions.
"""

import argparse
import importlib
import inspect
import json
import sys
from pathlib import Path

import numpy as np

from glasshead import constants
from glasshead.settings import REPO_ROOT

VECTORS_DIR = REPO_ROOT / "tests" / "vectors"

#: File name -> "module:function" returning the document.
VECTOR_FILES = {
    "constants.json": "glasshead.geometry.vectors:constants_document",
    "tongue-surface.json": "glasshead.geometry.tongue_vectors:surface_document",
    "tongue-jaw.json": "glasshead.geometry.tongue_vectors:jaw_document",
    "tongue-bspline.json": "glasshead.geometry.tongue_vectors:bspline_document",
    "face-rig.json": "glasshead.geometry.face_vectors:face_document",
}


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
    return {name: to_json_value(value) for name, value in vars(constants).items()
            if name.isupper() and not inspect.isclass(value) and not inspect.ismodule(value)}


def constants_document():
    return {
        "description": "The Python constants (glasshead.constants); web/src/core/constants.js "
                       "must export the same names with the same values",
        "generator": "python -m glasshead.geometry.vectors constants.json",
        "constants": python_constants(),
    }


def generate(names=None, out_dir=VECTORS_DIR):
    """Write the named vector files (all when None); returns the paths written."""
    names = list(VECTOR_FILES) if not names else list(names)
    unknown = [n for n in names if n not in VECTOR_FILES]
    if unknown:
        raise ValueError(f"unknown vector file(s) {unknown}; known: {sorted(VECTOR_FILES)}")
    written = []
    for name in names:
        module_name, function_name = VECTOR_FILES[name].split(":")
        document = getattr(importlib.import_module(module_name), function_name)()
        descriptions = [case["description"] for case in document.get("cases", [])]
        if len(descriptions) != len(set(descriptions)):
            raise ValueError(f"{name}: case descriptions are not unique")
        path = Path(out_dir) / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(document, indent=None, separators=(",", ":")) + "\n")
        written.append(path)
    return written


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m glasshead.geometry.vectors",
                                     description="Regenerate the shared test vectors.")
    parser.add_argument("names", nargs="*", help="vector files to write (default: all)")
    parser.add_argument("--out", default=str(VECTORS_DIR), help="output directory")
    parser.add_argument("--list", action="store_true", help="list the registered files")
    args = parser.parse_args(argv)
    if args.list:
        print("\n".join(sorted(VECTOR_FILES)))
        return 0
    try:
        for path in generate(args.names, args.out):
            print(f"wrote {path}")
    except ValueError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
