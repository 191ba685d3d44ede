"""Authors' observations as uploaded files, read and checked whole before anything is stored.

Four kinds of file, each read into one float64 array in the project frame (mm):

- ``contour``: a mid-sagittal tongue contour as CSV, two columns ``x_mm,y_mm`` (an optional
  header line, ``#`` comments and blank lines allowed), root to tip, at least
  ``MIN_CONTOUR_POINTS`` points -> (n, 2);
- ``surface``: a tongue surface as Wavefront OBJ (its ``v`` lines; faces are not needed) or PLY
  (ASCII or binary, read by trimesh), at least ``MIN_SURFACE_VERTICES`` vertices -> (k, 3);
- ``epg``: EPG frames in one of the recording formats (``glasshead.epg.formats``: emuR JSON, CSV,
  SSFF). The goal is the majority pattern of every frame of the file
  (``epg.classes.majority_pattern``), each electrode weighted by how clear its majority is
  (|2 p - 1|, p the share of frames that touch it, as the phoneme targets weigh a class), or one
  frame chosen by its index (every electrode weighted 1) -> (2, 8, 8): wanted, weights;
- ``ema``: one frame of flesh-point (EMA sensor) positions, CSV or JSON (``uploads_flesh``)
  -> (k, 4) rows [point index, x, y, z or NaN].

A ``combined`` observation is two or more of ``contour``, ``epg`` and ``ema`` together
(``read_combined``), kept as a dict of their arrays by kind.

Every problem raises ``ObservationError`` with the HTTP status the API answers (413 too large,
415 not the kind's format, 422 a readable file with bad content) and a message that names it:
the line for CSV and OBJ, the frame and field for EPG. Coordinates are checked against the
project frame (every anatomical point lies within ``FRAME_LIMIT_MM`` of its origin), which
catches a file in metres or in another frame before a fit is spent on it.
"""

import io
import math
import re
from dataclasses import dataclass, field

import numpy as np

from glasshead.epg import formats
from glasshead.epg.classes import ELECTRODES, majority_pattern
from glasshead.epg.sequence import EpgFormatError
from glasshead.fitting.fit3d import MIN_RAYS
from glasshead.upload_text import ObservationError, data_lines, decoded
from glasshead.uploads_flesh import read_flesh_points

KINDS = ("contour", "surface", "epg", "ema")
#: The kinds a ``combined`` fit takes together.
COMBINED_PARTS = ("contour", "epg", "ema")
#: Largest weight a combined fit's part may have (a weight of 100 already silences the others).
MAX_PART_WEIGHT = 100.0
MIB = 1024 * 1024
#: Largest upload of each kind, bytes: a surface of about 200,000 vertices as OBJ; a contour or
#: EPG file far larger than any real one (2 MiB of EPG CSV is about 14,000 frames).
MAX_BYTES = {"contour": 2 * MIB, "surface": 8 * MIB, "epg": 2 * MIB, "ema": 2 * MIB}
MAX_BYTES["combined"] = sum(MAX_BYTES[part] for part in COMBINED_PARTS)
MIN_CONTOUR_POINTS = 5
#: mm. A contour shorter than this leaves too few rays for the 2D error (1 mm apart).
MIN_CONTOUR_LENGTH_MM = 10.0
#: The 3D fit's own minimum of compared vertices (fewer cannot determine its 31 parameters).
MIN_SURFACE_VERTICES = MIN_RAYS
#: mm. The project frame's origin is inside the mouth; every anatomical point is within this.
FRAME_LIMIT_MM = 150.0

@dataclass
class Observation:
    """What a fit is given: ``points`` (see the module docstring for each kind's shape) and
    ``source``: what else the file said (file name, format, counts)."""

    kind: str
    points: np.ndarray | dict[str, np.ndarray]
    source: dict = field(default_factory=dict)


def size_limit_message(kind: str) -> str:
    article = "an" if kind[0] in "aeiou" else "a"
    return (f"field file: larger than the {MAX_BYTES[kind] // MIB} MiB limit for {article} "
            f"{kind} upload")


def read_observation(kind: str, content: bytes, filename: str | None = None, *,
                     frame: int | None = None) -> Observation:
    """Read and check one uploaded file of ``kind`` (raises ``ObservationError``)."""
    if kind not in KINDS:
        raise ObservationError(f"field kind: {kind!r} is not one of {', '.join(KINDS)}")
    if len(content) > MAX_BYTES[kind]:
        raise ObservationError(size_limit_message(kind), status=413)
    if not content.strip():
        raise ObservationError("field file: the file is empty")
    if frame is not None and kind not in ("epg", "ema"):
        raise ObservationError("field frame: only an epg or ema upload has frames")
    source = {"filename": filename or None, "bytes": len(content)}
    if kind == "contour":
        points = read_contour(content)
        source.update(format="csv", points=len(points))
    elif kind == "surface":
        points, fmt = read_surface(content, filename)
        source.update(format=fmt, vertices=len(points))
    elif kind == "epg":
        points, details = read_epg(content, filename, frame)
        source.update(details)
    else:
        points, details = read_flesh_points(content, frame, FRAME_LIMIT_MM)
        source.update(details)
    return Observation(kind, points, source)


def read_combined(parts: dict[str, tuple[bytes, str | None]], *, frame: int | None = None,
                  ema_frame: int | None = None) -> Observation:
    """Read two or more observations fitted together: ``parts`` {kind: (content, file name)}
    of ``COMBINED_PARTS``; ``frame`` chooses the EPG frame, ``ema_frame`` the flesh points'.
    Each part's problem is named with its field (``epg_file: ...``)."""
    unknown = [kind for kind in parts if kind not in COMBINED_PARTS]
    if unknown:
        raise ObservationError(f"a combined fit takes {', '.join(COMBINED_PARTS)}, not "
                               f"{', '.join(unknown)}")
    if len(parts) < 2:
        raise ObservationError("a combined fit needs at least two of contour_file, epg_file "
                               "and ema_file (one alone is a fit of its own kind)")
    if frame is not None and "epg" not in parts:
        raise ObservationError("field frame: it chooses an EPG frame, and there is no epg_file")
    if ema_frame is not None and "ema" not in parts:
        raise ObservationError("field ema_frame: there is no ema_file")
    points: dict[str, np.ndarray] = {}
    source: dict = {"parts": {}}
    for kind in COMBINED_PARTS:
        if kind not in parts:
            continue
        content, filename = parts[kind]
        try:
            part = read_observation(kind, content, filename,
                                    frame=frame if kind == "epg" else
                                    ema_frame if kind == "ema" else None)
        except ObservationError as error:
            problem = str(error).removeprefix("field file: ")
            raise ObservationError(f"{kind}_file: {problem}", error.status) from None
        points[kind] = np.asarray(part.points, dtype=np.float64)
        source["parts"][kind] = part.source
    return Observation("combined", points, source)


def _check_frame(points: np.ndarray, lines: list[int], unit_hint: str) -> None:
    far = np.abs(points).max(axis=1) > FRAME_LIMIT_MM
    if far.any():
        k = int(np.flatnonzero(far)[0])
        raise ObservationError(f"line {lines[k]}: a coordinate beyond {FRAME_LIMIT_MM:g} mm of "
                               f"the project frame's origin{unit_hint}")


def read_contour(content: bytes) -> np.ndarray:
    """(n, 2) float64 mm from CSV text: ``x_mm,y_mm`` per line, root to tip."""
    rows: list[tuple[float, float]] = []
    lines: list[int] = []
    header = False
    for number, line, fields in data_lines(decoded(content, "CSV")):
        if len(fields) != 2:
            raise ObservationError(f"line {number}: expected two columns x_mm,y_mm, got "
                                   f"{len(fields)}")
        try:
            x, y = float(fields[0]), float(fields[1])
        except ValueError:
            if not rows and not header and all(re.match(r"^[A-Za-z_\"']", f) for f in fields):
                header = True  # a header line, allowed first
                continue
            raise ObservationError(f"line {number}: {line[:40]!r} is not two numbers "
                                   "x_mm,y_mm") from None
        if not (math.isfinite(x) and math.isfinite(y)):
            raise ObservationError(f"line {number}: {line[:40]!r} is not finite (NaN or "
                                   "infinity)")
        rows.append((x, y))
        lines.append(number)
    if len(rows) < MIN_CONTOUR_POINTS:
        raise ObservationError(f"the contour has {len(rows)} points; at least "
                               f"{MIN_CONTOUR_POINTS} are needed")
    points = np.array(rows, dtype=np.float64)
    _check_frame(points, lines, " (the contour must be in mm, in the project frame)")
    length = float(np.linalg.norm(np.diff(points, axis=0), axis=1).sum())
    if length < MIN_CONTOUR_LENGTH_MM:
        raise ObservationError(f"the contour is {length:.1f} mm long; at least "
                               f"{MIN_CONTOUR_LENGTH_MM:g} mm are needed")
    return points


def _surface_format(content: bytes, filename: str | None) -> str:
    suffix = filename.lower().rsplit(".", 1)[-1] if filename and "." in filename else ""
    if suffix in ("obj", "ply"):
        return suffix
    if content[:3] == b"ply":
        return "ply"
    if re.search(rb"^\s*v\s", content[:4096], flags=re.MULTILINE):
        return "obj"
    raise ObservationError("field file: not an OBJ or PLY surface (name it .obj or .ply)",
                           status=415)


def read_surface(content: bytes, filename: str | None) -> tuple[np.ndarray, str]:
    """((k, 3) float64 vertices in mm, "obj" | "ply") of a surface file."""
    fmt = _surface_format(content, filename)
    if fmt == "obj":
        vertices, lines = _obj_vertices(decoded(content, "OBJ"))
    else:
        vertices = _ply_vertices(content)
        lines = [k + 1 for k in range(len(vertices))]
    if len(vertices) < MIN_SURFACE_VERTICES:
        raise ObservationError(f"the surface has {len(vertices)} vertices; at least "
                               f"{MIN_SURFACE_VERTICES} are needed")
    bad = ~np.all(np.isfinite(vertices), axis=1)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        where = f"line {lines[k]}" if fmt == "obj" else f"vertex {k + 1}"
        raise ObservationError(f"{where}: a vertex is not finite (NaN or infinity)")
    hint = " (the surface must be in mm, in the project frame)"
    if fmt == "obj":
        _check_frame(vertices, lines, hint)
    elif np.abs(vertices).max() > FRAME_LIMIT_MM:
        k = int(np.flatnonzero(np.abs(vertices).max(axis=1) > FRAME_LIMIT_MM)[0])
        raise ObservationError(f"vertex {k + 1}: a coordinate beyond {FRAME_LIMIT_MM:g} mm of "
                               f"the project frame's origin{hint}")
    return vertices, fmt


def _obj_vertices(text: str) -> tuple[np.ndarray, list[int]]:
    vertices: list[list[float]] = []
    lines: list[int] = []
    for number, line in enumerate(text.splitlines(), start=1):
        fields = line.split()
        if not fields or fields[0] != "v":
            continue
        try:
            if len(fields) < 4:
                raise ValueError
            vertices.append([float(f) for f in fields[1:4]])
        except ValueError:
            raise ObservationError(f"line {number}: {line.strip()[:40]!r} is not a vertex "
                                   "'v x y z'") from None
        lines.append(number)
    return np.array(vertices, dtype=np.float64).reshape(-1, 3), lines


def _ply_vertices(content: bytes) -> np.ndarray:
    import trimesh

    try:
        loaded = trimesh.load(io.BytesIO(content), file_type="ply", process=False)
    except Exception as error:  # trimesh raises many kinds for a corrupt file
        raise ObservationError(f"field file: cannot be read as PLY ({error.__class__.__name__}: "
                               f"{str(error)[:80]})") from None
    if isinstance(loaded, trimesh.Scene):
        parts = [np.asarray(g.vertices) for g in loaded.geometry.values()
                 if hasattr(g, "vertices")]
        return np.concatenate(parts).astype(np.float64) if parts else np.zeros((0, 3))
    if not isinstance(loaded, (trimesh.Trimesh, trimesh.PointCloud)):
        raise ObservationError("field file: the PLY holds neither a mesh nor a point cloud")
    return np.asarray(loaded.vertices, dtype=np.float64).reshape(-1, 3)


def read_epg(content: bytes, filename: str | None,
             frame: int | None) -> tuple[np.ndarray, dict]:
    """((2, 8, 8) float64: wanted pattern and weights, details) of an EPG recording file."""
    try:
        fmt = formats.detect_format(content, filename)
    except EpgFormatError as error:
        raise ObservationError(f"field file: not an EPG recording ({error})", status=415) from None
    try:
        sequences = formats.parse(content, fmt)
    except EpgFormatError as error:
        raise ObservationError(str(error)) from None
    frames = np.concatenate([s.frames for s in sequences]) if sequences \
        else np.zeros((0, 8, 8), dtype=np.uint8)
    if not len(frames):
        raise ObservationError("the recording has no frames")
    details = {"format": fmt, "recordings": len(sequences), "frames": int(len(frames))}
    if frame is None:
        wanted = majority_pattern(frames)
        weights = np.abs(2.0 * frames.mean(axis=0) - 1.0) * ELECTRODES
        details["goal"] = f"majority of {len(frames)} frames"
    else:
        if not 0 <= frame < len(frames):
            raise ObservationError(f"field frame: {frame} is not a frame index of this "
                                   f"recording (0 to {len(frames) - 1})")
        wanted = (frames[frame].astype(bool) & ELECTRODES).astype(np.uint8)
        weights = ELECTRODES.astype(np.float64)
        details["goal"] = f"frame {frame}"
        details["frame"] = frame
    return np.stack([wanted.astype(np.float64), weights]), details
