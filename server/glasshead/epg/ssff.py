"""EPG in SSFF, the Simple Signal File Format of the EMU speech database system.

Specification: The EMU-SDMS Manual (Winkelmann et al., IPS-LMU), appendix "File formats", section
"The SSFF file format"; the reference reader and writer are libassp's ``headers.c``
(getSSFFhdr/putSSFFhdr), where the column keyword ``epg`` is the EPG data type (DT_EPG) and
``BYTE`` is an unsigned 8-bit value.

A plain text header, one item per line::

    SSFF -- (c) SHLRC            file type marker
    Machine IBM-PC               byte order of the data (IBM-PC little-endian, SPARC big-endian)
    Record_Freq 200.0            records per second
    Start_Time 155.965           time of the first record, seconds (not negative)
    Column epg BYTE 8            one line per column: name, type, values per record
    name CHAR sp1bescan s->k     optional single values: name, type, value
    -----------------            end of the header

then the binary records, columns interleaved in header order. EPG is 8 bytes per frame in emuR's
compressed layout (byte 0 = R8 ... byte 7 = R1, bit c = electrode column c + 1). Frames are evenly
spaced: t = Start_Time + i / Record_Freq.
"""

import math

import numpy as np

from glasshead.epg.sequence import (
    MAX_FRAMES,
    EpgFormatError,
    EpgSequence,
    frames_to_raw,
    make_sequence,
    raw_to_frames,
)

SSFF_MAGIC = "SSFF -- (c) SHLRC"
SSFF_END = "-----------------"
SSFF_TYPE_SIZES = {"CHAR": 1, "BYTE": 1, "SHORT": 2, "LONG": 4, "FLOAT": 4, "DOUBLE": 8}
#: Declared frame rates accepted on import, Hz. EPG systems sample at 100-200 Hz; outside this
#: range a rate is a mistake (``Record_Freq 1e-300`` would spread 8 frames over 1e300 seconds).
FRAME_RATE_RANGE_HZ = (1.0, 100_000.0)
#: Metadata written to SSFF as ``key CHAR text`` and ``key DOUBLE number`` lines and read back.
SSFF_META_KEYS = ("name", "label", "utterance", "word")
SSFF_META_NUMBERS = ("start_s", "end_s")


def parse_ssff(content: bytes) -> list[EpgSequence]:
    end = content.find(b"\n" + SSFF_END.encode())
    if not content.startswith(SSFF_MAGIC.encode()) or end < 0:
        raise EpgFormatError(f"an SSFF file starts with {SSFF_MAGIC!r} and its header ends "
                             f"with {SSFF_END!r}", field="header")
    data_at = content.index(b"\n", end + 1) + 1 if b"\n" in content[end + 1:] else len(content)
    header = content[:end].decode("latin-1").splitlines()[1:]
    rate = start = None
    columns: list[tuple[str, str, int]] = []
    meta: dict[str, str | float] = {}
    for line in header:
        fields = line.split()
        if not fields:
            continue
        key = fields[0]
        if key == "Record_Freq":
            rate = _ssff_number(fields, "Record_Freq")
        elif key == "Start_Time":
            start = _ssff_number(fields, "Start_Time")
        elif key == "Column":
            # isdigit() alone accepts digits int() cannot read, such as a superscript two
            count = fields[3] if len(fields) == 4 else ""
            if not (count.isascii() and count.isdigit()) or fields[2] not in SSFF_TYPE_SIZES:
                raise EpgFormatError(f"{line.strip()!r} is not 'Column name TYPE count'",
                                     field="Column")
            columns.append((fields[1], fields[2], int(fields[3])))
        elif len(fields) >= 3 and fields[1] == "CHAR" and key in SSFF_META_KEYS:
            meta[key] = line.split(None, 2)[2].strip()
        elif len(fields) == 3 and fields[1] == "DOUBLE" and key in SSFF_META_NUMBERS:
            meta[key] = _ssff_number(fields[1:], key)
    if rate is None:
        raise EpgFormatError("a Record_Freq line is required", field="Record_Freq")
    check_frame_rate(rate, "Record_Freq")
    if start is None or start < 0:
        raise EpgFormatError("a Start_Time line of 0 or more seconds is required",
                             field="Start_Time")
    epg = [c for c in columns if c[0].lower() == "epg"] or columns
    if len(epg) != 1 or epg[0][1:] != ("BYTE", 8):
        found = ", ".join(f"{n} {t} {k}" for n, t, k in columns) or "none"
        raise EpgFormatError(f"expected one column 'epg BYTE 8' (8 bytes per frame, R8 first); "
                             f"found {found}", field="Column")
    record = sum(SSFF_TYPE_SIZES[t] * k for _, t, k in columns)
    offset = 0
    for column in columns:
        if column is epg[0]:
            break
        offset += SSFF_TYPE_SIZES[column[1]] * column[2]
    data = np.frombuffer(content[data_at:], dtype=np.uint8)
    if data.size % record:
        raise EpgFormatError(f"{data.size} data bytes are not whole {record}-byte records; "
                             f"the last is cut short", field="data", frame=data.size // record)
    raw = data.reshape(-1, record)[:, offset:offset + 8]
    if len(raw) > MAX_FRAMES:
        raise EpgFormatError(f"{len(raw)} frames is more than the limit of {MAX_FRAMES}",
                             field="frames")
    corners = raw[:, 7] & 0b10000001
    if corners.any():
        raise EpgFormatError("R1 has no electrode in columns 1 and 8; bits 0 and 7 of byte 8 "
                             "must be 0", field="epg[7]", frame=int(np.argmax(corners > 0)))
    t_s = start + np.arange(len(raw)) / rate
    name = str(meta.pop("name", "") or "SSFF recording")
    return [make_sequence(raw_to_frames(raw), t_s, name, rate, meta)]


def check_frame_rate(rate: float, field: str) -> None:
    """A declared frame rate must lie in FRAME_RATE_RANGE_HZ; raises EpgFormatError."""
    low, high = FRAME_RATE_RANGE_HZ
    if not low <= rate <= high:
        raise EpgFormatError(f"{rate:g} Hz is not a frame rate between {low:g} and {high:g} Hz",
                             field=field)


def _ssff_number(fields: list[str], key: str) -> float:
    try:
        value = float(fields[1])
    except (IndexError, ValueError):
        raise EpgFormatError(f"{' '.join(fields)!r} has no number", field=key) from None
    if not math.isfinite(value):
        raise EpgFormatError(f"{value} is not finite", field=key)
    return value


def write_ssff(seq: EpgSequence) -> bytes:
    """SSFF needs a constant frame rate: times must be Start_Time + i / Record_Freq."""
    rate = seq.frame_rate_hz
    if rate is None:
        rate = 1.0
    check_frame_rate(rate, "frame_rate_hz")  # what the reader would refuse is not written
    expected = seq.t_s[0] + np.arange(seq.n_frames) / rate
    drift = np.abs(seq.t_s - expected)
    if (drift > 0.01 / rate).any():
        frame = int(np.argmax(drift > 0.01 / rate))
        raise EpgFormatError(f"frames are not evenly spaced at {rate:g} Hz, which SSFF needs",
                             field="t_s", frame=frame)
    lines = [SSFF_MAGIC, "Machine IBM-PC", f"Record_Freq {rate!r}",
             f"Start_Time {float(seq.t_s[0])!r}", "Column epg BYTE 8"]
    values = {"name": seq.name, **{k: seq.meta[k] for k in SSFF_META_KEYS if k in seq.meta}}
    for key, value in values.items():
        lines.append(f"{key} CHAR {' '.join(str(value).split())[:200]}")
    for key in SSFF_META_NUMBERS:
        if isinstance(seq.meta.get(key), (int, float)):
            lines.append(f"{key} DOUBLE {float(seq.meta[key])!r}")
    header = ("\n".join(lines) + "\n" + SSFF_END + "\n").encode("latin-1", "replace")
    return header + frames_to_raw(seq.frames).tobytes()
