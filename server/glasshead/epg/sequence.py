"""An EPG recording in memory: contact frames with their times, checked on construction.

Frames are ``(n, 8, 8)`` uint8 0/1 (row 0 = R1 at the front, column 0 = electrode column 1; the
R1 corners are always 0); times ``t_s`` are ``(n,)`` float64 seconds, strictly increasing.

The compact "raw" form is emuR's EPG-compressed layout (emuR ``palate()``, R/epg.class.R): 8 bytes
per frame, byte 0 = R8 ... byte 7 = R1, and bit c (least significant first) of a byte = electrode
column c + 1. It is what the reference data carries as ``raw``, what SSFF files hold, and what the
database stores.
"""

from dataclasses import dataclass, field

import numpy as np

from glasshead.constants import EPG_COLUMNS, EPG_MISSING_CELLS, EPG_ROWS

#: Most frames one recording may hold: 10 minutes at 200 frames per second.
MAX_FRAMES = 120_000
#: Bit weights of electrode columns 1..8 within a raw byte.
_BIT_WEIGHTS = (1 << np.arange(EPG_COLUMNS)).astype(np.uint8)
#: Bits of the R1 byte that would be R1 columns 1 and 8, which have no electrode.
R1_MISSING_BITS = sum(1 << cell for cell in EPG_MISSING_CELLS)


class EpgFormatError(ValueError):
    """Bad EPG input; names the frame (0-based, when one is at fault) and the field."""

    def __init__(self, message: str, *, field: str, frame: int | None = None,
                 segment: int | None = None):
        self.reason = message
        self.field = field
        self.frame = frame
        self.segment = segment
        where = []
        if segment is not None:
            where.append(f"segment {segment}")
        if frame is not None:
            where.append(f"frame {frame}")
        where.append(f"field {field}")
        super().__init__(f"{', '.join(where)}: {message}")

    def in_segment(self, segment: int) -> "EpgFormatError":
        """The same error, located in one segment of a multi-segment file."""
        return EpgFormatError(self.reason, field=self.field, frame=self.frame, segment=segment)


@dataclass
class EpgSequence:
    """One recording: ``frames`` (n, 8, 8) uint8, ``t_s`` (n,) float64 s, a name and metadata.

    ``frame_rate_hz`` is the rate the recording was made at (declared by the file, else derived
    from the median frame interval; None for a single frame with no declared rate).
    """

    frames: np.ndarray
    t_s: np.ndarray
    name: str
    frame_rate_hz: float | None = None
    meta: dict = field(default_factory=dict)

    @property
    def n_frames(self) -> int:
        return len(self.frames)


def make_sequence(frames, t_s, name: str, frame_rate_hz: float | None = None,
                  meta: dict | None = None) -> EpgSequence:
    """Check frames and times and build an EpgSequence; raises EpgFormatError naming the fault."""
    frames = np.asarray(frames)
    t_s = np.asarray(t_s, dtype=np.float64)
    if frames.ndim != 3 or frames.shape[1:] != (EPG_ROWS, EPG_COLUMNS):
        raise EpgFormatError(f"expected frames of 8 x 8 contacts, got shape {frames.shape}",
                             field="frames")
    if len(frames) == 0:
        raise EpgFormatError("a recording needs at least one frame", field="frames")
    if len(frames) > MAX_FRAMES:
        raise EpgFormatError(f"{len(frames)} frames is more than the limit of {MAX_FRAMES}",
                             field="frames")
    if t_s.shape != (len(frames),):
        raise EpgFormatError(f"{t_s.size} times for {len(frames)} frames", field="t_s")
    bad = ~np.isin(frames, (0, 1))
    if bad.any():
        frame, row, column = (int(v) for v in np.argwhere(bad)[0])
        raise EpgFormatError(f"value {frames[frame, row, column]} is not 0 or 1",
                             field=f"R{row + 1}C{column + 1}", frame=frame)
    corners = frames.reshape(len(frames), -1)[:, list(EPG_MISSING_CELLS)]
    if corners.any():
        frame, which = (int(v) for v in np.argwhere(corners)[0])
        column = EPG_MISSING_CELLS[which] + 1
        raise EpgFormatError(f"R1 has no electrode in column {column}; its contact must be 0",
                             field=f"R1C{column}", frame=frame)
    check_times(t_s)
    if frame_rate_hz is None:
        frame_rate_hz = derived_frame_rate(t_s)
    elif not (np.isfinite(frame_rate_hz) and frame_rate_hz > 0):
        raise EpgFormatError(f"{frame_rate_hz} is not a positive frame rate", field="frame_rate_hz")
    name = str(name).strip() or "EPG recording"
    return EpgSequence(frames.astype(np.uint8), t_s, name[:200], float(frame_rate_hz)
                       if frame_rate_hz is not None else None, dict(meta or {}))


def check_times(t_s: np.ndarray) -> None:
    """Times must be finite, not negative and strictly increasing; raises EpgFormatError."""
    bad = ~np.isfinite(t_s)
    if bad.any():
        frame = int(np.argmax(bad))
        raise EpgFormatError(f"{float(t_s[frame])} is not a finite time", field="t_s",
                             frame=frame)
    if t_s[0] < 0:
        raise EpgFormatError(f"time {float(t_s[0])} s is negative", field="t_s", frame=0)
    steps = np.diff(t_s)
    if (steps <= 0).any():
        frame = int(np.argmax(steps <= 0)) + 1
        raise EpgFormatError(
            f"time {float(t_s[frame])!r} s is not after the previous frame's "
            f"{float(t_s[frame - 1])!r} s",
            field="t_s", frame=frame)


def derived_frame_rate(t_s: np.ndarray) -> float | None:
    """Frames per second from the median frame interval (None for a single frame).

    Rounded to 1e-6 Hz: times read as milliseconds carry float noise (5 ms -> 200.0000000002 Hz).
    """
    if len(t_s) < 2:
        return None
    return round(float(1.0 / np.median(np.diff(t_s))), 6)


def frames_to_raw(frames: np.ndarray) -> np.ndarray:
    """``(n, 8, 8)`` 0/1 -> ``(n, 8)`` uint8 in emuR's compressed layout (R8 byte first)."""
    packed = (np.asarray(frames, dtype=np.uint8) * _BIT_WEIGHTS).sum(axis=2, dtype=np.uint16)
    return packed[:, ::-1].astype(np.uint8)


def raw_to_frames(raw: np.ndarray) -> np.ndarray:
    """``(n, 8)`` uint8 in emuR's compressed layout -> ``(n, 8, 8)`` uint8 0/1 (R1 row first)."""
    raw = np.asarray(raw, dtype=np.uint8)
    rows = raw[:, ::-1]
    return ((rows[:, :, None] & _BIT_WEIGHTS) > 0).astype(np.uint8)


def rows_to_strings(frame: np.ndarray) -> list[str]:
    """One ``(8, 8)`` frame -> 8 strings of '0'/'1', R1 first (the emuR JSON ``rows`` form)."""
    return ["".join("1" if v else "0" for v in row) for row in frame]
