"""The browser's copy of the shared constants: ``web/src/core/shared.generated.js``.

``glasshead.constants`` is where every constant the two sides share is written; this module turns
each of its upper-case names into a frozen export of an ES module, with the constant's ``#:``
comment as its JSDoc, and ``web/src/core/constants.js`` re-exports them. Run after changing
constants.py::

    .venv/bin/python -m glasshead.shared_constants

``tests/test_shared_constants.py`` fails, naming that command, while the committed file differs
from what this writes.
"""

import ast
import inspect
import json
import math
import re
import sys
import textwrap
from pathlib import Path

import numpy as np

from glasshead import constants


def shared_names() -> list[str]:
    """The constants both sides read: every upper-case name of constants.py that is not a class
    or a module, in the order of that file."""
    return [name for name, value in vars(constants).items()
            if name.isupper() and not inspect.isclass(value) and not inspect.ismodule(value)]


#: Where the module is written, from the repository root.
OUTPUT = Path("web/src/core/shared.generated.js")
#: The command that writes it.
COMMAND = ".venv/bin/python -m glasshead.shared_constants"
#: Longest line before a value is spread over several lines.
LINE_LENGTH = 100

_IDENTIFIER = re.compile(r"^[A-Za-z_$][A-Za-z0-9_$]*$")


def repository_root() -> Path:
    """The repository (the directory holding ``server/`` and ``web/``)."""
    return Path(__file__).resolve().parents[2]


def doc_comments() -> dict[str, str]:
    """name -> its ``#:`` comment in constants.py (joined lines), for module-level assignments."""
    source = inspect.getsource(constants)
    lines = source.splitlines()
    docs = {}
    for node in ast.parse(source).body:
        if isinstance(node, ast.Assign):
            targets = node.targets
        elif isinstance(node, ast.AnnAssign):
            targets = [node.target]
        else:
            continue
        names = [n.id for t in targets for n in ast.walk(t) if isinstance(n, ast.Name)]
        comment: list[str] = []
        k = node.lineno - 2
        while k >= 0 and lines[k].lstrip().startswith("#:"):
            comment.insert(0, lines[k].lstrip()[2:].strip())
            k -= 1
        for name in names:
            docs[name] = " ".join(comment)
    return docs


def plain(value):
    """A constant as JSON-like data: tuples and arrays become lists, bytes ASCII text, and a
    tolerance object (``CollisionTolerance``) a dict of its public class attributes."""
    if isinstance(value, np.ndarray):
        return plain(value.tolist())
    if isinstance(value, (tuple, list)):
        return [plain(v) for v in value]
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, bytes):
        return value.decode("ascii")
    if isinstance(value, (bool, int, float, str)) or value is None:
        return value
    attributes = {k: v for k, v in vars(type(value)).items() if not k.startswith("_")}
    if attributes and all(isinstance(v, (int, float)) for v in attributes.values()):
        return attributes
    raise TypeError(f"cannot share a {type(value).__name__} with the browser")


def literal(value, indent: int = 0, lead: int = 0) -> str:
    """The JavaScript literal of a plain value, frozen; spread over lines (tab-indented at
    ``indent``) when it would not fit on one after ``lead`` characters."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if value is None:
        return "null"
    if isinstance(value, (int, float)):
        if isinstance(value, float) and not math.isfinite(value):
            raise ValueError(f"{value} has no JSON form")
        text = re.sub(r"e([+-])0*(\d)", lambda m: f"e{m[1].replace('+', '')}{m[2]}", repr(value))
        return f"- {text[1:]}" if text.startswith("-") else text
    if isinstance(value, str):
        return "'" + json.dumps(value)[1:-1].replace("'", "\\'") + "'"
    inner = indent + 1
    if isinstance(value, (list, tuple)):
        keys = [""] * len(value)
        values = value
        opener, closer = "[", "]"
    else:
        keys = [f"{k if _IDENTIFIER.match(k) else literal(k)}: " for k in value]
        values = list(value.values())
        opener, closer = "{", "}"
    flat = [k + literal(v) for k, v in zip(keys, values, strict=True)]
    one = f"Object.freeze( {opener} {', '.join(flat)} {closer} )" if flat else \
        f"Object.freeze( {opener}{closer} )"
    if "\n" not in one and lead + len(one) + 1 <= LINE_LENGTH:
        return one
    items = [k + literal(v, inner, 4 * inner + len(k)) for k, v in zip(keys, values, strict=True)]
    tabs = "\t" * inner
    return (f"Object.freeze( {opener}\n" + "".join(f"{tabs}{item},\n" for item in items)
            + "\t" * indent + f"{closer} )")


def jsdoc(text: str) -> list[str]:
    """A JSDoc comment of ``text``: one line when it fits, else wrapped."""
    if len(text) + 7 <= LINE_LENGTH:
        return [f"/** {text} */"]
    return ["/**", *(f" * {line}" for line in textwrap.wrap(text, LINE_LENGTH - 3)), " */"]


def module_text() -> str:
    """The whole generated ES module."""
    docs = doc_comments()
    out = [
        "// Generated from server/glasshead/constants.py by server/glasshead/shared_constants.py:",
        "// do not edit. After changing constants.py, regenerate it from the repository root with",
        f"//   {COMMAND}",
        "// (tests/test_shared_constants.py fails while it is stale). Import from ./constants.js.",
        "",
    ]
    last_doc = None
    for name in shared_names():
        value = plain(getattr(constants, name))
        doc = docs.get(name) or ""
        if name == "COLLISION_TOL":
            doc = inspect.getdoc(type(constants.COLLISION_TOL)) or doc
        if doc and doc != last_doc:
            out.extend(jsdoc(doc))
        last_doc = doc
        lead = len(f"export const {name} = ")
        out.append(f"export const {name} = {literal(value, 0, lead)};")
    return "\n".join(out) + "\n"


def write(root: Path | None = None) -> Path:
    """Write the module under ``root`` (the repository by default); returns its path."""
    path = (root or repository_root()) / OUTPUT
    path.write_text(module_text(), encoding="utf-8")
    return path


if __name__ == "__main__":
    print(f"wrote {write(Path(sys.argv[1]) if len(sys.argv) > 1 else None)}")
