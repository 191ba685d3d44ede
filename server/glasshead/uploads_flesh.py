"""Flesh-point uploads (fit kind ``ema``): one frame of articulography, the sensors by name.

Two formats, told apart by the first character that is not a space:

- JSON: an object ``{"tongue_tip": [x, y, z], "lower_incisor": [x, y], ...}`` (one frame), or
  tracks ``{"tongue_tip": [[x, y, z], ...], ...}`` with a frame chosen by ``frame`` (0-based,
  default the first): the ``flesh_points`` of a ``POST /utterances`` answer, or that whole
  answer, read as they come;
- CSV: one sensor per line, ``point,x_mm,y_mm[,z_mm]`` (an optional header line, ``#``
  comments and blank lines allowed).

Points are named as the flesh points are (``geometry.flesh_points.FLESH_POINT_NAMES``) or by the
usual sensor codes (``ema.SENSOR_CODES``: TT, TB, TD or TR, LI or JAW, UL, LL, UI), in any case.
Coordinates are millimetres in the project frame (+x anterior, +y up, +z left). A point given
with two coordinates is compared in the mid-sagittal plane only (x and y), as 2D articulography
measures it. ``upper_incisor`` is the reference: when it is given, the fit first shifts every
point by what puts it on the head's upper incisor, so that sensors recorded relative to the
speaker's own upper incisor (as EMA data usually are) can be fitted as they are.

The result is (k, 4) float64 rows ``[index into FLESH_POINT_NAMES, x, y, z]``, z NaN for a 2D
point. Problems raise ``upload_text.ObservationError`` naming the line, the frame or the point.
"""

import json
import math

import numpy as np

from glasshead.ema.recording import SENSOR_CODES
from glasshead.geometry.flesh_points import FLESH_POINT_NAMES
from glasshead.upload_text import ObservationError, data_lines, decoded

#: A file's names (lower case) -> flesh point.
POINT_ALIASES = {**{code.lower(): name for code, name in SENSOR_CODES.items()
                    if name in FLESH_POINT_NAMES},
                 **{name: name for name in FLESH_POINT_NAMES}}
#: The one point every EMA head is referenced to; it is not fitted (the maxilla does not move).
REFERENCE = "upper_incisor"


def _point_name(raw: str, where: str) -> str:
    name = POINT_ALIASES.get(raw.strip().strip("\"'").lower())
    if name is None:
        raise ObservationError(f"{where}: {raw[:40]!r} is not a flesh point; name one of "
                               f"{', '.join(FLESH_POINT_NAMES)} (or TT, TB, TD, LI, UL, LL, UI)")
    return name


def _coordinates(values, where: str) -> list[float]:
    if not isinstance(values, list) or len(values) not in (2, 3) \
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        raise ObservationError(f"{where}: expected [x, y] or [x, y, z] in mm")
    numbers = [float(v) for v in values]
    if not all(math.isfinite(v) for v in numbers):
        raise ObservationError(f"{where}: a coordinate is not finite (NaN or infinity)")
    return numbers


def _from_json(text: str, frame: int | None) -> tuple[dict[str, list[float]], dict]:
    try:
        document = json.loads(text)
    except json.JSONDecodeError as error:
        raise ObservationError(f"field file: not valid JSON (line {error.lineno}: "
                               f"{error.msg})") from None
    if isinstance(document, dict) and isinstance(document.get("flesh_points"), dict):
        document = document["flesh_points"]  # a whole POST /utterances answer
    if not isinstance(document, dict) or not document:
        raise ObservationError("field file: expected an object of flesh points, "
                               "{\"tongue_tip\": [x, y, z], ...}")
    tracks = all(isinstance(v, list) and v and isinstance(v[0], list) for v in document.values())
    details: dict = {"format": "json"}
    if tracks:
        lengths = {len(v) for v in document.values()}
        frames = min(lengths)
        chosen = 0 if frame is None else frame
        if not 0 <= chosen < frames:
            raise ObservationError(f"field frame: {chosen} is not a frame index of these tracks "
                                   f"(0 to {frames - 1})")
        details.update(frames=frames, frame=chosen)
        document = {key: track[chosen] for key, track in document.items()}
    elif frame is not None:
        raise ObservationError("field frame: the file holds one frame, not tracks")
    points: dict[str, list[float]] = {}
    for key, values in document.items():
        name = _point_name(str(key), f"point {key!r}")
        if name in points:
            raise ObservationError(f"point {key!r}: {name} is given twice")
        points[name] = _coordinates(values, f"point {key!r}")
    return points, details


def _from_csv(text: str, frame: int | None) -> tuple[dict[str, list[float]], dict]:
    if frame is not None:
        raise ObservationError("field frame: a CSV of flesh points holds one frame")
    points: dict[str, list[float]] = {}
    header = False
    for number, line, fields in data_lines(text):
        if len(fields) not in (3, 4):
            raise ObservationError(f"line {number}: expected point,x_mm,y_mm[,z_mm], got "
                                   f"{len(fields)} columns")
        try:
            numbers = [float(f) for f in fields[1:]]
        except ValueError:
            if not points and not header:
                header = True  # a header line, allowed first
                continue
            raise ObservationError(f"line {number}: {line[:40]!r} has a coordinate that is not a "
                                   "number") from None
        if not all(math.isfinite(v) for v in numbers):
            raise ObservationError(f"line {number}: a coordinate is not finite (NaN or infinity)")
        name = _point_name(fields[0], f"line {number}")
        if name in points:
            raise ObservationError(f"line {number}: {name} is given twice")
        points[name] = numbers
    return points, {"format": "csv"}


def read_flesh_points(content: bytes, frame: int | None,
                      frame_limit_mm: float) -> tuple[np.ndarray, dict]:
    """((k, 4) float64 rows [point index, x, y, z or NaN], details) of a flesh-point file."""
    text = decoded(content, "CSV or JSON")
    stripped = text.lstrip()
    points, details = (_from_json if stripped[:1] in "{[" else _from_csv)(text, frame)
    moving = [name for name in points if name != REFERENCE]
    if not moving:
        raise ObservationError(
            "the file gives no flesh point that moves (only the upper incisor, the reference); "
            f"give at least one of {', '.join(n for n in FLESH_POINT_NAMES if n != REFERENCE)}")
    rows = np.full((len(points), 4), np.nan)
    for row, (name, values) in zip(rows, points.items(), strict=True):
        if max(abs(v) for v in values) > frame_limit_mm:
            raise ObservationError(f"point {name}: a coordinate beyond {frame_limit_mm:g} mm of "
                                   "the project frame's origin (the points must be in mm, in "
                                   "the project frame)")
        row[0] = FLESH_POINT_NAMES.index(name)
        row[1:1 + len(values)] = values
    details.update(points=[name for name in points],
                   dimensions=sorted({len(v) for v in points.values()}),
                   referenced=REFERENCE in points)
    return rows, details


def points_by_name(rows: np.ndarray) -> dict[str, np.ndarray]:
    """{flesh point: (2,) or (3,) float64} of the rows ``read_flesh_points`` made."""
    out = {}
    for row in np.asarray(rows, dtype=np.float64):
        name = FLESH_POINT_NAMES[int(row[0])]
        out[name] = row[1:3].copy() if math.isnan(row[3]) else row[1:4].copy()
    return out
