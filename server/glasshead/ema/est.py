"""The Edinburgh Speech Tools track file ("EST_File Track"), MOCHA-TIMIT's ``.ema`` format.

Layout, as Edinburgh Speech Tools writes and reads it (festvox/speech_tools,
speech_class/EST_TrackFile.cc ``save_est_binary_ts`` / ``load_est_ts``, utils/est_file.cc
``read_est_header``, base_class/EST_Token.cc ``EST_TokenStream::fread``)::

    EST_File Track
    DataType binary            binary or ascii (absent: ascii)
    ByteOrder 01               binary only: 01 little-endian, 10 big-endian
    NumFrames 1234
    NumChannels 20
    EqualSpace 1
    BreaksPresent true
    CommentChar ;

    Channel_0 ui_x             one line per channel, numbered from 0
    ...
    EST_Header_End

Binary data start one byte after ``EST_Header_End`` (the newline that ends it). Each frame is a
float32 time in seconds, a float32 break flag when breaks are present (0 = a break: the frame
holds no value), then NumChannels float32 values. ASCII data: one frame per line, the same
fields as whitespace-separated numbers. Aux channels are not supported.
"""

import math
from dataclasses import dataclass

import numpy as np

from glasshead.ema.recording import EmaFormatError

EST_MAGIC = b"EST_File"
HEADER_END = b"EST_Header_End"
#: ByteOrder value -> numpy byte order.
BYTE_ORDERS = {"01": "<", "10": ">"}


@dataclass(frozen=True)
class EstTrack:
    """A parsed track: ``t_s`` (n,) float64, ``values`` (n, c) float64 with NaN in break frames,
    ``channels`` their names, ``header`` the other header fields, ``frame_lines`` the text line
    of each frame (ASCII files; None for binary)."""

    channels: tuple[str, ...]
    t_s: np.ndarray
    values: np.ndarray
    header: dict[str, str]
    frame_lines: tuple[int, ...] | None


def parse_est_track(content: bytes, source: str) -> EstTrack:
    """Read an EST track from a file's bytes; EmaFormatError names the file and the line."""
    if not content.startswith(EST_MAGIC):
        raise EmaFormatError(f"not an EST file: it starts with {content[:16]!r}, not "
                             "'EST_File Track'", source=source)
    end = _header_end(content)
    if end < 0:
        raise EmaFormatError("no EST_Header_End line: the header is incomplete", source=source)
    header_text = content[:end].decode("latin-1")
    fields, lines, channels = _header_fields(header_text, source)
    n_frames = _count(fields, lines, "NumFrames", source, minimum=0)
    n_channels = _count(fields, lines, "NumChannels", source, minimum=1)
    aux = fields.get("NumAuxChannels", "0")
    if aux not in ("", "0"):
        raise EmaFormatError(f"NumAuxChannels {aux}: aux channels are not supported",
                             source=source, line=lines["NumAuxChannels"])
    names = []
    for i in range(n_channels):
        if i not in channels:
            raise EmaFormatError(f"NumChannels is {n_channels} but there is no Channel_{i} line",
                                 source=source)
        names.append(channels[i][0])
    extra = sorted(i for i in channels if i >= n_channels)
    if extra:
        raise EmaFormatError(f"Channel_{extra[0]} is beyond NumChannels {n_channels}",
                             source=source, line=channels[extra[0]][1])
    breaks = _flag(fields, lines, "BreaksPresent", source)
    data_type = fields.get("DataType", "ascii")
    body_at = end + len(HEADER_END) + 1
    if data_type == "binary":
        order = fields.get("ByteOrder")
        if order not in BYTE_ORDERS:
            raise EmaFormatError(
                f"ByteOrder {order!r}: binary data needs 01 (little-endian) or 10 (big-endian)",
                source=source, line=lines.get("ByteOrder"))
        t_s, values = _binary_frames(content[body_at:], n_frames, n_channels, breaks,
                                     BYTE_ORDERS[order], source)
        frame_lines = None
    elif data_type == "ascii":
        first_line = header_text.count("\n") + 2
        t_s, values, frame_lines = _ascii_frames(content[body_at:], first_line, n_frames,
                                                 n_channels, breaks, source)
    else:
        raise EmaFormatError(f"DataType {data_type!r} is neither binary nor ascii",
                             source=source, line=lines.get("DataType"))
    rest = {k: v for k, v in fields.items() if k not in ("NumFrames", "NumChannels")}
    return EstTrack(tuple(names), t_s, values, rest, frame_lines)


def _header_end(content: bytes) -> int:
    """Offset of the EST_Header_End token at the start of a line, or -1."""
    at = 0
    while True:
        at = content.find(HEADER_END, at)
        if at <= 0 or content[at - 1:at] == b"\n":
            return at
        at += 1


def _header_fields(text: str, source: str
                   ) -> tuple[dict[str, str], dict[str, int], dict[int, tuple[str, int]]]:
    """(fields, line of each field, channel index -> (name, line)) of the header text."""
    rows = text.split("\n")
    kind = rows[0].split()
    if kind[:2] not in (["EST_File", "Track"], ["EST_File", "track"]):
        raise EmaFormatError(f"an EST file of type {' '.join(kind[1:]) or '(none)'!r}, not "
                             "Track", source=source, line=1)
    fields: dict[str, str] = {}
    lines: dict[str, int] = {}
    channels: dict[int, tuple[str, int]] = {}
    comment = None
    for number, row in enumerate(rows[1:], start=2):
        row = row.strip()
        if not row or (comment and row.startswith(comment)):
            continue
        key, _, value = row.replace("\t", " ").partition(" ")
        value = value.strip()
        if key.startswith("Channel_"):
            index = key.removeprefix("Channel_")
            if not index.isdigit():
                raise EmaFormatError(f"{key!r} is not Channel_<number>", source=source,
                                     line=number)
            if int(index) in channels:
                raise EmaFormatError(f"{key} is named twice", source=source, line=number)
            if not value:
                raise EmaFormatError(f"{key} has no name", source=source, line=number)
            channels[int(index)] = (value, number)
            continue
        if key == "CommentChar":
            comment = value or None
        fields[key] = value
        lines[key] = number
    return fields, lines, channels


def _count(fields: dict[str, str], lines: dict[str, int], key: str, source: str,
           minimum: int) -> int:
    if key not in fields:
        raise EmaFormatError(f"the header has no {key}", source=source)
    text = fields[key]
    if not text.isdigit() or int(text) < minimum:
        raise EmaFormatError(f"{key} {text!r} is not a whole number of at least {minimum}",
                             source=source, line=lines[key])
    return int(text)


def _flag(fields: dict[str, str], lines: dict[str, int], key: str, source: str) -> bool:
    value = fields.get(key)
    if value is None:
        return False
    if value.lower() in ("true", "1"):
        return True
    if value.lower() in ("false", "0"):
        return False
    raise EmaFormatError(f"{key} {value!r} is neither true nor false", source=source,
                         line=lines[key])


def _binary_frames(body: bytes, n_frames: int, n_channels: int, breaks: bool, order: str,
                   source: str) -> tuple[np.ndarray, np.ndarray]:
    per_frame = 1 + int(breaks) + n_channels
    frame_bytes = 4 * per_frame
    expected = n_frames * frame_bytes
    whole, part = divmod(len(body), frame_bytes)
    if len(body) < expected:
        raise EmaFormatError(
            f"truncated: NumFrames {n_frames} of {frame_bytes} bytes need {expected} bytes of "
            f"data, the file holds {len(body)} ({whole} whole frames"
            + (f" and {part} bytes)" if part else ")"), source=source)
    if len(body) > expected:
        raise EmaFormatError(
            f"the header says NumFrames {n_frames}, but the data hold {len(body)} bytes: "
            f"{whole} frames of {frame_bytes} bytes" + (f" and {part} bytes" if part else ""),
            source=source)
    table = np.frombuffer(body, dtype=np.dtype(f"{order}f4")).reshape(n_frames, per_frame)
    table = table.astype(np.float64)
    values = table[:, 1 + int(breaks):].copy()
    if breaks:
        values[table[:, 1] == 0.0] = math.nan
    return table[:, 0].copy(), values


def _ascii_frames(body: bytes, first_line: int, n_frames: int, n_channels: int, breaks: bool,
                  source: str) -> tuple[np.ndarray, np.ndarray, tuple[int, ...]]:
    try:
        text = body.decode("ascii")
    except UnicodeDecodeError:
        raise EmaFormatError("DataType ascii, but the data are not ASCII text",
                             source=source) from None
    per_frame = 1 + int(breaks) + n_channels
    rows: list[list[float]] = []
    frame_lines: list[int] = []
    for number, line in enumerate(text.split("\n"), start=first_line):
        fields = line.split()
        if not fields:
            continue
        if len(fields) != per_frame:
            raise EmaFormatError(
                f"frame {len(rows)}: expected {per_frame} numbers (time"
                + (", break flag" if breaks else "") + f" and {n_channels} channels), got "
                f"{len(fields)}", source=source, line=number)
        try:
            rows.append([float(f) for f in fields])
        except ValueError:
            bad = next(f for f in fields if not _is_float(f))
            raise EmaFormatError(f"frame {len(rows)}: {bad!r} is not a number", source=source,
                                 line=number) from None
        frame_lines.append(number)
    if len(rows) != n_frames:
        raise EmaFormatError(f"the header says NumFrames {n_frames}, but the data have "
                             f"{len(rows)} frame lines", source=source)
    table = np.array(rows, dtype=np.float64).reshape(len(rows), per_frame)
    values = table[:, 1 + int(breaks):].copy()
    if breaks:
        values[table[:, 1] == 0.0] = math.nan
    return table[:, 0].copy(), values, tuple(frame_lines)


def _is_float(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True
