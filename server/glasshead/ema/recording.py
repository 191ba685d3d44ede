"""An EMA recording in memory, checked when it is built, and the error every reader raises.

The frame (docs/ema.md): millimetres; +x anterior (toward the lips), +y toward the speaker's
left, +z up. HPRC files are already in it (origin at the upper incisor); MOCHA's 2D x/y and
Carstens' x/y/z are turned into it by a signed axis map (``orient``). The project's rendering
frame (DESIGN.md: +y up, +z left) is the same with the last two axes swapped: ``project_axes``.

Sensor names are articulatory, the same whatever the device called them (``SENSOR_NAMES``).
"""

import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from types import MappingProxyType
from typing import NamedTuple

import numpy as np

#: Articulatory sensor names. Readers map their files' codes onto these (docs/ema.md); a code
#: they do not know is kept in lower case.
SENSOR_NAMES = ("tongue_tip", "tongue_blade", "tongue_dorsum", "upper_lip", "lower_lip",
                "lower_incisor", "upper_incisor", "jaw_left", "mouth_left", "velum",
                "nose_bridge")

#: Short sensor codes (HPRC's, and the usual ones of other labs) -> sensor name.
SENSOR_CODES = {"TT": "tongue_tip", "TB": "tongue_blade", "TR": "tongue_dorsum",
                "TD": "tongue_dorsum", "UL": "upper_lip", "LL": "lower_lip",
                "JAW": "lower_incisor", "LI": "lower_incisor", "UI": "upper_incisor",
                "JAWL": "jaw_left", "ML": "mouth_left", "V": "velum", "BN": "nose_bridge"}

#: Longest run of missing samples (NaN) that is filled by linear interpolation, in seconds.
#: 50 ms is shorter than most phones, so a filled gap cannot invent a whole gesture.
MAX_GAP_S = 0.05

#: Slack on time comparisons (s): the readers' times are written with 4 to 6 decimals.
TIME_TOL_S = 1e-6

#: Deviation of any frame interval from 1 / sample rate allowed before the times are refused
#: as not matching the rate (a fraction of the period; float32 times at 500 Hz are far inside).
RATE_TOL = 0.05

_AXIS_TOKEN = re.compile(r"^([+-]?)([xyz])$")


class EmaFormatError(ValueError):
    """Bad EMA input. ``source`` is the file (or the name given for bytes); ``line`` is the
    1-based line at fault in a text file, when there is one."""

    def __init__(self, problem: str, *, source: str | None = None, line: int | None = None):
        self.problem = problem
        self.source = source
        self.line = line
        where = source or "EMA input"
        if line is not None:
            where += f", line {line}"
        super().__init__(f"{where}: {problem}")


class Phone(NamedTuple):
    """A timed phone: an ARPAbet symbol without its stress digit (or ``PAUSE``), and the stress
    (0, 1 or 2) when the label carried one."""

    start_s: float
    end_s: float
    symbol: str
    stress: int | None = None


class Word(NamedTuple):
    """A timed word (``PAUSE`` for a pause)."""

    start_s: float
    end_s: float
    label: str


class Dropout(NamedTuple):
    """A run of missing samples of one sensor that was filled: ``start_s`` is the time of the
    first missing sample, ``end_s`` that of the first sample after the run (or the last one plus
    one period), ``frames`` the number of samples filled."""

    sensor: str
    start_s: float
    end_s: float
    frames: int


@dataclass(frozen=True, eq=False)
class EmaRecording:
    """One utterance of articulography.

    ``t_s``: (n,) float64 seconds, strictly increasing. ``sensors``: name -> (n, 3) float64 mm in
    the frame of this module (x anterior, y left, z up); 2D sources have y = 0. Arrays are
    read-only. ``phones`` and ``words`` lie within the signal (one frame of slack), in order and
    without overlaps. ``dropouts``: what was interpolated.
    """

    name: str
    sample_rate_hz: float
    t_s: np.ndarray
    sensors: Mapping[str, np.ndarray]
    phones: tuple[Phone, ...] = ()
    words: tuple[Word, ...] = ()
    source_format: str = ""
    dropouts: tuple[Dropout, ...] = ()

    @property
    def n_frames(self) -> int:
        return len(self.t_s)

    @property
    def duration_s(self) -> float:
        """From the first sample to one period after the last."""
        return float(self.t_s[-1] - self.t_s[0]) + 1.0 / self.sample_rate_hz


def orient(xyz: np.ndarray, axes: str, *, source: str, allowed: str = "xyz") -> np.ndarray:
    """Values in a file's axes -> the frame (x anterior, y left, z up).

    ``xyz``: (n, k) float, the file's axes in order (k = len(allowed)). ``axes``: three
    space-separated tokens, the file axis (with sign) that becomes anterior, left and up, or
    ``0`` where the file has no such axis: "+x +y +z" keeps the file's axes; MOCHA's "-x 0 +y"
    says that its x grows toward the back and its y upward. Returns (n, 3) float64.
    """
    tokens = axes.split()
    if len(tokens) != 3:
        raise EmaFormatError(f"axes {axes!r} needs three tokens (anterior, left, up), such as "
                             "'+x +y +z' or '-x 0 +y'", source=source)
    out = np.zeros((len(xyz), 3))
    used = set()
    for k, token in enumerate(tokens):
        if token == "0":
            continue
        match = _AXIS_TOKEN.match(token)
        if not match or match.group(2) not in allowed:
            raise EmaFormatError(f"axes {axes!r}: {token!r} is not one of "
                                 f"{', '.join(f'+{a} -{a}' for a in allowed)} or 0",
                                 source=source)
        if match.group(2) in used:
            raise EmaFormatError(f"axes {axes!r} uses {match.group(2)} twice", source=source)
        used.add(match.group(2))
        sign = -1.0 if match.group(1) == "-" else 1.0
        out[:, k] = sign * xyz[:, allowed.index(match.group(2))]
    return out


def project_axes(points: np.ndarray) -> np.ndarray:
    """(n, 3) points in this module's frame -> the project's frame (DESIGN.md: +x anterior,
    +y up, +z left): the same millimetres with y and z swapped."""
    points = np.asarray(points, dtype=float)
    return points[..., [0, 2, 1]]


def build_recording(*, name: str, source: str, source_format: str, t_s: np.ndarray,
                    sensors: Mapping[str, np.ndarray], sample_rate_hz: float | None,
                    phones: tuple[Phone, ...] = (), words: tuple[Word, ...] = (),
                    labels_source: str | None = None, words_source: str | None = None,
                    phone_lines: Sequence[tuple[int, str]] | None = None,
                    word_lines: Sequence[tuple[int, str]] | None = None,
                    frame_lines: Sequence[int] | None = None,
                    required: Sequence[str] | None = None,
                    max_gap_s: float = MAX_GAP_S) -> EmaRecording:
    """Check a reader's arrays and labels and freeze them into an ``EmaRecording``.

    ``sensors``: name -> (n, 3) float in the frame, NaN where a sample is missing.
    ``sample_rate_hz``: the declared rate, or None to take it from the times. ``frame_lines``:
    the text line of each frame, for messages. ``required``: sensor names that must be there.
    ``phone_lines``, ``word_lines``: (line, label as written) of each label, for messages.
    Missing runs up to ``max_gap_s`` are filled linearly and reported; longer ones are refused.
    """
    t_s = np.asarray(t_s, dtype=np.float64)
    n = len(t_s)
    if n == 0:
        raise EmaFormatError("no samples", source=source)
    _check_times(t_s, source, frame_lines)
    rate = _sample_rate(t_s, sample_rate_hz, source, frame_lines)
    missing = [s for s in (required or ()) if s not in sensors]
    if missing:
        raise EmaFormatError(f"sensor(s) {', '.join(missing)} asked for but not in the file "
                             f"(it has {', '.join(sensors) or 'none'})", source=source)
    filled: dict[str, np.ndarray] = {}
    dropouts: list[Dropout] = []
    for sensor, values in sensors.items():
        values = np.array(values, dtype=np.float64)
        if values.shape != (n, 3):
            raise ValueError(f"sensor {sensor}: expected shape ({n}, 3), got {values.shape}")
        dropouts += _fill_gaps(t_s, values, sensor, rate, max_gap_s, source)
        values.flags.writeable = False
        filled[sensor] = values
    end_s = float(t_s[-1])
    _check_within(phones, float(t_s[0]), end_s, rate, labels_source or source, phone_lines)
    _check_within(words, float(t_s[0]), end_s, rate, words_source or source, word_lines)
    t_s = t_s.copy()
    t_s.flags.writeable = False
    return EmaRecording(name=name, sample_rate_hz=rate, t_s=t_s, sensors=MappingProxyType(filled),
                        phones=tuple(phones), words=tuple(words), source_format=source_format,
                        dropouts=tuple(dropouts))


def _check_times(t_s: np.ndarray, source: str, frame_lines: Sequence[int] | None) -> None:
    def line(i: int) -> int | None:
        return frame_lines[i] if frame_lines is not None else None

    bad = np.flatnonzero(~np.isfinite(t_s))
    if len(bad):
        i = int(bad[0])
        raise EmaFormatError(f"frame {i}: time {t_s[i]} is not a number", source=source,
                             line=line(i))
    steps = np.diff(t_s)
    back = np.flatnonzero(steps <= 0)
    if len(back):
        i = int(back[0]) + 1
        raise EmaFormatError(f"frame {i}: times do not increase ({t_s[i - 1]:.6f} s, then "
                             f"{t_s[i]:.6f} s)", source=source, line=line(i))


def _sample_rate(t_s: np.ndarray, declared: float | None, source: str,
                 frame_lines: Sequence[int] | None) -> float:
    if declared is not None:
        if not math.isfinite(declared) or declared <= 0:
            raise EmaFormatError(f"sample rate {declared} Hz is not a positive number",
                                 source=source)
        rate = float(declared)
    elif len(t_s) < 2:
        raise EmaFormatError("one sample and no declared sample rate: give sample_rate_hz",
                             source=source)
    else:
        rate = (len(t_s) - 1) / float(t_s[-1] - t_s[0])
        # Times written as float32 or with few decimals: a rate within 0.1 % of a whole number
        # of hertz is that number.
        if abs(rate - round(rate)) <= 1e-3 * rate:
            rate = float(round(rate))
    off = np.flatnonzero(np.abs(np.diff(t_s) * rate - 1.0) > RATE_TOL)
    if len(off):
        i = int(off[0]) + 1
        raise EmaFormatError(
            f"frame {i}: the step from {t_s[i - 1]:.6f} s to {t_s[i]:.6f} s does not match the "
            f"sample rate of {rate:g} Hz", source=source,
            line=frame_lines[i] if frame_lines is not None else None)
    return rate


def _fill_gaps(t_s: np.ndarray, values: np.ndarray, sensor: str, rate: float,
               max_gap_s: float, source: str) -> list[Dropout]:
    """Fill runs of NaN samples in place (linearly between the neighbours; at either end, the
    nearest sample is held) and report them; refuse a run longer than ``max_gap_s``."""
    if np.isinf(values).any():
        i = int(np.flatnonzero(np.isinf(values).any(axis=1))[0])
        raise EmaFormatError(f"sensor {sensor}: an infinite value at {t_s[i]:.3f} s (frame {i})",
                             source=source)
    missing = np.isnan(values).any(axis=1)
    if not missing.any():
        return []
    n = len(t_s)
    edges = np.diff(np.concatenate([[0], missing.astype(np.int8), [0]]))
    starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    dropouts = []
    for i, j in zip(starts.tolist(), stops.tolist(), strict=True):
        count = j - i
        length_s = count / rate
        end_s = float(t_s[j]) if j < n else float(t_s[j - 1]) + 1.0 / rate
        if length_s > max_gap_s + TIME_TOL_S or count == n:
            raise EmaFormatError(
                f"sensor {sensor}: {count} samples missing from {t_s[i]:.3f} s to {end_s:.3f} s "
                f"({length_s * 1000:.0f} ms), longer than the {max_gap_s * 1000:.0f} ms that "
                "may be interpolated", source=source)
        if i == 0:
            values[i:j] = values[j]
        elif j == n:
            values[i:j] = values[i - 1]
        else:
            w = ((t_s[i:j] - t_s[i - 1]) / (t_s[j] - t_s[i - 1]))[:, None]
            values[i:j] = (1.0 - w) * values[i - 1] + w * values[j]
        dropouts.append(Dropout(sensor, float(t_s[i]), end_s, count))
    return dropouts


def _check_within(labels: Sequence[Phone | Word], start_s: float, end_s: float,
                  rate: float, source: str, lines: Sequence[tuple[int, str]] | None) -> None:
    """Labels must lie within the signal, with one frame of slack at either end."""
    slack = 1.0 / rate + TIME_TOL_S
    for k, label in enumerate(labels):
        line, text = lines[k] if lines is not None else (None, label[2])
        if label.end_s > end_s + slack:
            raise EmaFormatError(
                f"label {text!r} ends at {label.end_s:.4f} s, past the end of the signal "
                f"({end_s:.4f} s, last sample)", source=source, line=line)
        if label.start_s < start_s - slack:
            raise EmaFormatError(
                f"label {text!r} starts at {label.start_s:.4f} s, before the signal "
                f"({start_s:.4f} s, first sample)", source=source, line=line)
