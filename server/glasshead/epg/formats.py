"""Read and write EPG recordings in three formats.

``emur-json``: the JSON form of the emuR reference data (``../shared/data/epg/emur-engassim.json``):
    ``{"segments": [{"label", "utt", "word", "start_ms", "end_ms", "frames": [{"t_ms", "raw",
    "rows"}]}]}``; ``rows`` are 8 strings of '0'/'1', R1 first, character c = column c + 1;
    ``raw`` is the same frame as 8 bytes in emuR's compressed layout (see ``sequence``). A frame
    needs ``rows`` or ``raw``; when it has both they must agree. One recording per segment.

``csv``: Glasshead's documented CSV (``docs/epg-recordings.md``), one recording per file::

    # glasshead-epg-csv 1
    # name: sp1bescan s->k          optional "# key: value" lines (name, frame_rate_hz, others)
    t_s,R1C2,R1C3,...,R1C7,R2C1,...,R8C8
    155.965,0,0,...

    A header row of ``t_s`` and the 62 electrodes (row-major, R1 first, R1's columns 2-7 only),
    then one row per frame: the time in seconds and 62 values 0 or 1.

``ssff``: the Simple Signal File Format of the EMU speech database system, which stores EPG as
    an ``epg`` column of 8 BYTEs per frame in emuR's compressed layout (see ``glasshead.epg.ssff``
    for the specification and its source).

Every reader raises ``EpgFormatError`` naming the frame (0-based) and the field at fault.
"""

import csv
import io
import json
import math

import numpy as np

from glasshead.epg.sequence import (
    MAX_FRAMES,
    EpgFormatError,
    EpgSequence,
    frames_to_raw,
    make_sequence,
    raw_to_frames,
    rows_to_strings,
)
from glasshead.epg.ssff import SSFF_MAGIC, check_frame_rate, parse_ssff, write_ssff

FORMATS = ("emur-json", "csv", "ssff")
MEDIA_TYPES = {"emur-json": "application/json", "csv": "text/csv",
               "ssff": "application/octet-stream"}
EXTENSIONS = {"emur-json": ".json", "csv": ".csv", "ssff": ".epg"}

CSV_MAGIC = "# glasshead-epg-csv 1"
#: CSV electrode columns, row-major, R1 first; R1 has only columns 2-7.
CSV_ELECTRODES = [f"R{r}C{c}" for r in range(1, 9) for c in range(1, 9)
                  if not (r == 1 and c in (1, 8))]
#: Flat (row * 8 + column) cell of each CSV electrode column.
_CSV_CELLS = np.array([(int(n[1]) - 1) * 8 + int(n[3]) - 1 for n in CSV_ELECTRODES])



def detect_format(content: bytes, filename: str | None = None) -> str:
    """Guess the format from the file name's extension, else from the first bytes."""
    suffix = (filename or "").lower().rsplit(".", 1)[-1] if filename and "." in filename else ""
    by_suffix = {"json": "emur-json", "csv": "csv", "ssff": "ssff", "epg": "ssff"}
    if suffix in by_suffix:
        return by_suffix[suffix]
    head = content[:32].lstrip()
    if head.startswith(SSFF_MAGIC.encode()):
        return "ssff"
    if head[:1] in (b"{", b"["):
        return "emur-json"
    if head.startswith(b"#") or head.lower().startswith(b"t_s"):
        return "csv"
    raise EpgFormatError("cannot tell the format; give format=emur-json, csv or ssff",
                         field="format")


def parse(content: bytes, fmt: str, name: str | None = None) -> list[EpgSequence]:
    """Read recordings from a file's bytes in format ``fmt``; ``name`` overrides their names."""
    readers = {"emur-json": parse_emur_json, "csv": parse_csv, "ssff": parse_ssff}
    if fmt not in readers:
        raise EpgFormatError(f"unknown format {fmt!r}; use one of {', '.join(FORMATS)}",
                             field="format")
    sequences = readers[fmt](content)
    if name:
        for i, sequence in enumerate(sequences):
            sequence.name = name if len(sequences) == 1 else f"{name} {i + 1}"
    return sequences


def serialise(sequences: list[EpgSequence], fmt: str) -> bytes:
    """Write recordings in format ``fmt`` (csv and ssff hold exactly one recording)."""
    if fmt == "emur-json":
        return write_emur_json(sequences)
    if len(sequences) != 1:
        raise ValueError(f"{fmt} holds one recording; got {len(sequences)}")
    if fmt == "csv":
        return write_csv(sequences[0])
    if fmt == "ssff":
        return write_ssff(sequences[0])
    raise ValueError(f"unknown format {fmt!r}")


# --- emuR JSON ---------------------------------------------------------------------------------

def parse_emur_json(content: bytes) -> list[EpgSequence]:
    try:
        document = json.loads(content)
    except (UnicodeDecodeError, json.JSONDecodeError) as error:
        raise EpgFormatError(f"not valid JSON ({error})", field="body") from None
    except RecursionError:
        raise EpgFormatError("JSON nested too deeply for an emuR EPG document",
                             field="body") from None
    if isinstance(document, dict) and "segments" in document:
        segments = document["segments"]
    elif isinstance(document, dict) and "frames" in document:
        segments = [document]
    else:
        segments = document
    if not isinstance(segments, list) or not segments:
        raise EpgFormatError("expected a non-empty list of segments with frames",
                             field="segments")
    total = sum(len(s["frames"]) for s in segments
                if isinstance(s, dict) and isinstance(s.get("frames"), list))
    if total > MAX_FRAMES:
        raise EpgFormatError(f"{total} frames is more than the limit of {MAX_FRAMES}",
                             field="frames")
    sequences = []
    for index, segment in enumerate(segments):
        try:
            sequences.append(_emur_segment(segment))
        except EpgFormatError as error:
            raise (error.in_segment(index) if len(segments) > 1 else error) from None
    return sequences


def _emur_segment(segment) -> EpgSequence:
    if not isinstance(segment, dict) or not isinstance(segment.get("frames"), list):
        raise EpgFormatError("a segment is an object with a list of frames", field="frames")
    frames = np.zeros((len(segment["frames"]), 8, 8), dtype=np.uint8)
    t_s = np.zeros(len(frames))
    for i, frame in enumerate(segment["frames"]):
        if not isinstance(frame, dict):
            raise EpgFormatError("a frame is an object with t_ms and rows or raw",
                                 field="frames", frame=i)
        t_s[i] = _number(frame.get("t_ms"), "t_ms", i) / 1000.0
        from_rows = rows_to_frame(frame["rows"], i) if "rows" in frame else None
        from_raw = _emur_raw(frame["raw"], i) if "raw" in frame else None
        if from_rows is None and from_raw is None:
            raise EpgFormatError("the frame has neither rows nor raw", field="rows", frame=i)
        if from_rows is not None and from_raw is not None and (from_rows != from_raw).any():
            raise EpgFormatError("rows and raw describe different contacts", field="raw",
                                 frame=i)
        if from_rows is not None:
            frames[i] = from_rows
        elif from_raw is not None:
            frames[i] = from_raw
    meta = {key: segment[key] for key in ("label", "word") if isinstance(segment.get(key), str)}
    if isinstance(segment.get("utt"), str):
        meta["utterance"] = segment["utt"]
    for key in ("start_ms", "end_ms"):
        if segment.get(key) is not None:
            meta[key.replace("_ms", "_s")] = _number(segment[key], key, None) / 1000.0
    name = " ".join(meta[k] for k in ("utterance", "label") if k in meta) or "emuR segment"
    return make_sequence(frames, t_s, segment.get("name") or name, meta=meta)


def rows_to_frame(rows, frame: int) -> np.ndarray:
    """8 strings of 8 '0'/'1' (R1 first) -> an (8, 8) uint8 frame; EpgFormatError names the
    fault."""
    if not isinstance(rows, list) or len(rows) != 8:
        count = len(rows) if isinstance(rows, list) else "not a list"
        raise EpgFormatError(f"expected 8 rows of 8 contacts, got {count}", field="rows",
                             frame=frame)
    grid = np.zeros((8, 8), dtype=np.uint8)
    for r, row in enumerate(rows):
        if not isinstance(row, str) or len(row) != 8:
            size = len(row) if isinstance(row, str) else type(row).__name__
            raise EpgFormatError(f"expected 8 contacts, got {size}", field=f"rows[{r}]",
                                 frame=frame)
        for c, char in enumerate(row):
            if char not in "01":
                raise EpgFormatError(f"contact {char!r} at column {c + 1} is not 0 or 1",
                                     field=f"rows[{r}]", frame=frame)
            grid[r, c] = char == "1"
    if grid[0, 0] or grid[0, 7]:
        column = 1 if grid[0, 0] else 8
        raise EpgFormatError(f"R1 has no electrode in column {column}; it must be 0",
                             field="rows[0]", frame=frame)
    return grid


def _emur_raw(raw, frame: int) -> np.ndarray:
    if not isinstance(raw, list) or len(raw) != 8:
        raise EpgFormatError("expected 8 bytes, R8 first", field="raw", frame=frame)
    for b, value in enumerate(raw):
        if not isinstance(value, int) or isinstance(value, bool) or not 0 <= value <= 255:
            raise EpgFormatError(f"{value!r} is not a byte 0-255", field=f"raw[{b}]",
                                 frame=frame)
    if raw[7] & 0b10000001:
        raise EpgFormatError("R1 has no electrode in columns 1 and 8; bits 0 and 7 must be 0",
                             field="raw[7]", frame=frame)
    return raw_to_frames(np.array([raw], dtype=np.uint8))[0]


def _number(value, field: str, frame: int | None) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise EpgFormatError(f"{value!r} is not a number", field=field, frame=frame)
    return float(value)


def write_emur_json(sequences: list[EpgSequence]) -> bytes:
    segments = []
    for seq in sequences:
        raw = frames_to_raw(seq.frames)
        segment: dict[str, object] = {"name": seq.name}
        for key, out in (("label", "label"), ("utterance", "utt"), ("word", "word")):
            if key in seq.meta:
                segment[out] = seq.meta[key]
        for key in ("start_s", "end_s"):
            if key in seq.meta:
                segment[key.replace("_s", "_ms")] = _ms(seq.meta[key])
        segment["frames"] = [
            {"t_ms": _ms(t), "raw": [int(b) for b in raw[i]], "rows": rows_to_strings(frame)}
            for i, (t, frame) in enumerate(zip(seq.t_s, seq.frames, strict=True))
        ]
        segments.append(segment)
    return json.dumps({"source": "Glasshead EPG export", "segments": segments}).encode()


def _ms(seconds: float) -> float:
    """Seconds -> milliseconds, rounded to 1 ns so that ms -> s -> ms gives the same number."""
    return round(float(seconds) * 1000.0, 6)


# --- CSV ---------------------------------------------------------------------------------------

def parse_csv(content: bytes) -> list[EpgSequence]:
    try:
        text = content.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        raise EpgFormatError(f"not UTF-8 text ({error.reason})", field="body") from None
    lines = text.splitlines()
    meta: dict[str, str | float] = {}
    frame_rate, header_at = None, None
    for number, line in enumerate(lines, start=1):
        stripped = line.strip()
        if not stripped or stripped == CSV_MAGIC:
            continue
        if stripped.startswith("#"):
            key, sep, value = stripped.lstrip("#").partition(":")
            if sep:
                meta[key.strip()] = value.strip()
            continue
        header_at = number
        break
    if header_at is None:
        raise EpgFormatError("no header row (t_s and the 62 electrodes)", field="header")
    header = [h.strip() for h in next(csv.reader([lines[header_at - 1]]))]
    expected = ["t_s", *CSV_ELECTRODES]
    if len(header) != len(expected):
        raise EpgFormatError(f"line {header_at}: expected {len(expected)} columns (t_s and 62 "
                             f"electrodes), got {len(header)}", field="header")
    for got, want in zip(header, expected, strict=True):
        if got.upper() != want.upper():
            raise EpgFormatError(f"line {header_at}: column {got!r} where {want!r} belongs",
                                 field="header")
    rows = [(n, r) for n, r in enumerate(csv.reader(lines[header_at:]), start=header_at + 1)
            if r and any(cell.strip() for cell in r)]
    if len(rows) > MAX_FRAMES:
        raise EpgFormatError(f"{len(rows)} frames is more than the limit of {MAX_FRAMES}",
                             field="frames")
    frames = np.zeros((len(rows), 64), dtype=np.uint8)
    t_s = np.zeros(len(rows))
    for i, (number, row) in enumerate(rows):
        if len(row) != len(expected):
            raise EpgFormatError(f"line {number}: expected 62 electrodes, got {len(row) - 1}",
                                 field="electrodes", frame=i)
        try:
            t_s[i] = float(row[0])
        except ValueError:
            raise EpgFormatError(f"line {number}: {row[0]!r} is not a time in seconds",
                                 field="t_s", frame=i) from None
        for name, cell, value in zip(CSV_ELECTRODES, _CSV_CELLS, row[1:], strict=True):
            value = value.strip()
            if value not in ("0", "1"):
                raise EpgFormatError(f"line {number}: value {value!r} is not 0 or 1",
                                     field=name, frame=i)
            frames[i, cell] = value == "1"
    if "frame_rate_hz" in meta:
        frame_rate = _csv_number(meta.pop("frame_rate_hz"), "frame_rate_hz")
        check_frame_rate(frame_rate, "frame_rate_hz")
    for key in ("start_s", "end_s"):
        if key in meta:
            meta[key] = _csv_number(meta[key], key)
    name = str(meta.pop("name", "") or "CSV recording")
    return [make_sequence(frames.reshape(-1, 8, 8), t_s, name, frame_rate, meta)]


def _csv_number(text, field: str) -> float:
    """A finite number from a ``# key: value`` line: nan and inf would be stored and then
    written as JSON that no parser reads."""
    try:
        value = float(text)
    except ValueError:
        raise EpgFormatError(f"{text!r} is not a number", field=field) from None
    if not math.isfinite(value):
        raise EpgFormatError(f"{text!r} is not a finite number", field=field)
    return value


def write_csv(seq: EpgSequence) -> bytes:
    out = io.StringIO()
    out.write(f"{CSV_MAGIC}\n# name: {_one_line(seq.name)}\n")
    if seq.frame_rate_hz is not None:
        out.write(f"# frame_rate_hz: {seq.frame_rate_hz!r}\n")
    for key, value in seq.meta.items():
        if key not in ("name", "frame_rate_hz"):
            value = repr(value) if isinstance(value, float) else str(value)
            out.write(f"# {_one_line(str(key).replace(':', '_'))}: {_one_line(value)}\n")
    out.write(",".join(["t_s", *CSV_ELECTRODES]) + "\n")
    flat = seq.frames.reshape(len(seq.frames), 64)[:, _CSV_CELLS]
    for t, values in zip(seq.t_s, flat, strict=True):
        out.write(f"{float(t)!r}," + ",".join("1" if v else "0" for v in values) + "\n")
    return out.getvalue().encode()


def _one_line(text: str) -> str:
    return " ".join(text.split())
