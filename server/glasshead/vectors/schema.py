"""The one schema of every shared vector file (``tests/vectors/*.json``), checked on both sides.

Twin of ``tests/js/support/vectorSchema.js``; ``tests/test_vector_schema.py`` and
``tests/js/vectorSchema.test.js`` run them over every file. The rules:

- top level: exactly ``description`` (text), ``generator`` (the command that writes the file),
  ``format_version`` (integer >= 1), ``constants`` (object), ``tolerance`` (object), ``cases``
  (array), and optionally ``fixtures`` (object: bulky inputs that many cases share);
- each tolerance: ``{"value": number > 0, "unit": one of UNITS, "reason": text}``; a file whose
  results are all integers, flags or text has ``"tolerance": {}``;
- each case: exactly ``description`` (text, unique within the file), ``input`` (object) and
  ``expected`` (object); a refusal is a case whose ``expected`` is ``{"error": text}``.

A problem is reported with the file and, inside a case, its index and description.
"""

import math

TOP_LEVEL = ("description", "generator", "format_version", "constants", "tolerance", "cases")
OPTIONAL = ("fixtures",)
CASE_KEYS = ("description", "input", "expected")
TOLERANCE_KEYS = ("value", "unit", "reason")
#: Units a tolerance may have: millimetres, cubic millimetres, relative (a fraction of the
#: expected magnitude), "1" (absolute, for dimensionless numbers), radians, degrees.
UNITS = ("mm", "mm2", "mm3", "relative", "1", "rad", "deg", "Hz")
GENERATOR_PREFIX = "glasshead vectors"


class VectorSchemaError(ValueError):
    """A vector document breaks the schema; the message lists every problem found."""


def _text(value):
    return isinstance(value, str) and value.strip() != ""


def _object(value):
    return isinstance(value, dict)


def _where(index, case):
    description = case.get("description") if isinstance(case, dict) else None
    return f"case {index} ({description!r})" if _text(description) else f"case {index}"


def _case_problems(index, case, seen):
    where = _where(index, case)
    if not _object(case):
        return [f"{where}: a case must be an object"]
    problems = []
    keys = set(case)
    missing = [k for k in CASE_KEYS if k not in keys]
    unknown = sorted(keys - set(CASE_KEYS))
    if missing:
        problems.append(f"{where}: missing {', '.join(missing)}")
    if unknown:
        problems.append(f"{where}: unknown keys {', '.join(unknown)}")
    description = case.get("description")
    if not _text(description):
        problems.append(f"{where}: description must be non-empty text")
    elif description in seen:
        problems.append(f"{where}: description repeats case {seen[description]}")
    else:
        seen[description] = index
    if "input" in case and not _object(case["input"]):
        problems.append(f"{where}: input must be an object")
    expected = case.get("expected")
    if "expected" in case and not _object(expected):
        problems.append(f"{where}: expected must be an object")
    elif _object(expected) and "error" in expected:
        if not _text(expected["error"]) or len(expected) != 1:
            problems.append(f"{where}: a refusal's expected must be exactly {{\"error\": text}}")
    return problems


def _tolerance_problems(tolerance):
    problems = []
    for name, entry in tolerance.items():
        where = f"tolerance {name!r}"
        if not _object(entry) or set(entry) != set(TOLERANCE_KEYS):
            problems.append(f"{where}: must be exactly {{value, unit, reason}}")
            continue
        value = entry["value"]
        if isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not math.isfinite(value) or value <= 0:
            problems.append(f"{where}: value must be a finite number > 0")
        if entry["unit"] not in UNITS:
            problems.append(f"{where}: unit {entry['unit']!r} is not one of {', '.join(UNITS)}")
        if not _text(entry["reason"]):
            problems.append(f"{where}: reason must be non-empty text")
    return problems


def problems(document):
    """Every way ``document`` breaks the schema, as messages (empty when it follows it)."""
    if not _object(document):
        return ["top level: a vector file must hold a JSON object"]
    found = []
    keys = set(document)
    missing = [k for k in TOP_LEVEL if k not in keys]
    unknown = sorted(keys - set(TOP_LEVEL) - set(OPTIONAL))
    if missing:
        found.append(f"top level: missing {', '.join(missing)}")
    if unknown:
        found.append(f"top level: unknown keys {', '.join(unknown)} (shared inputs go in "
                     "fixtures, fixed numbers in constants)")
    if "description" in keys and not _text(document["description"]):
        found.append("top level: description must be non-empty text")
    generator = document.get("generator")
    if "generator" in keys and not (_text(generator) and generator.startswith(GENERATOR_PREFIX)):
        found.append(f"top level: generator must be the command, {GENERATOR_PREFIX} ...")
    version = document.get("format_version")
    if "format_version" in keys and (isinstance(version, bool) or not isinstance(version, int)
                                     or version < 1):
        found.append("top level: format_version must be an integer >= 1")
    for key in ("constants", "fixtures"):
        if key in keys and not _object(document[key]):
            found.append(f"top level: {key} must be an object")
    if "tolerance" in keys:
        if _object(document["tolerance"]):
            found += _tolerance_problems(document["tolerance"])
        else:
            found.append("top level: tolerance must be an object ({} when every result is exact)")
    cases = document.get("cases")
    if "cases" in keys and not isinstance(cases, list):
        found.append("top level: cases must be an array")
    elif isinstance(cases, list):
        seen: dict[str, int] = {}
        for index, case in enumerate(cases):
            found += _case_problems(index, case, seen)
    return found


def check(document, name):
    """Raise ``VectorSchemaError`` naming the file ``name`` and each problem, if there is any."""
    found = problems(document)
    if found:
        shown = found[:20] + ([f"... and {len(found) - 20} more"] if len(found) > 20 else [])
        raise VectorSchemaError(f"{name} breaks the vector schema:\n"
                                + "\n".join(f"  {name}: {p}" for p in shown))
    return document
