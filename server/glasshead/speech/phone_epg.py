"""The synthetic EPG of a recording's own phones on its own timing, and the comparison phone by
phone.

Comparing every frame of an /s/-to-/k/ take with one static /k/ target scores the /s/ frames
against the wrong sound. Here the head says the phones the recording holds, on the recording's
clock, and each phone's frames are compared with the head's frames of the same phone:

- **Phones.** Given by the caller, or read from the recording's label: emuR's engassim labels
  name the sounds in order, ``"s->k"`` is /s/ then /k/. Each symbol is an ARPAbet or IPA symbol
  of the inventory (``glasshead.phonemes.lookup``).
- **Timing.** The recording's first frame is time 0 and its phones share its span, to one frame
  period after its last frame. The boundaries are given by the caller, or read from the
  recording: for two phones, the first frame after the frontmost centre of gravity (emuR
  ``epgcog``) of the first third of the take where the centre has come halfway to the backmost
  of the last third (the tongue on its way from the first place to the second); when it never
  moves back (two phones at one place, a take without contact) and for one phone or more than
  two, the span is split evenly. ``boundary_source`` says which.
- **Motion.** The coarticulation model (``speech.coarticulation``) makes the parameter tracks at
  the recording's frame rate; each frame's tongue is corrected against the palate and probed for
  contacts as the browser does (``epg.synthetic``).
- **Scores.** ``epg.compare`` frame by frame, then ``epg.compare.phone_scores``: per phone the
  mean agreement, kappa and contact agreement over its frames, and the means over the phones
  that have frames.
"""

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from glasshead.epg.contacts import Probes
from glasshead.epg.indices import centre_of_gravity
from glasshead.epg.synthetic import synthetic_frame
from glasshead.phonemes import UnknownPhonemeError, lookup
from glasshead.speech.coarticulation import coarticulate_arrays

#: What separates the sounds in a recording's label ("s->k").
LABEL_SEPARATOR = "->"
#: Most phones one recording is split into.
MAX_PHONES = 20


class PhoneSegmentError(ValueError):
    """Phones or boundaries that cannot be used; ``field`` names what is wrong."""

    def __init__(self, message: str, field: str):
        super().__init__(message)
        self.field = field


@dataclass
class PhoneSegment:
    """One phone on the recording's clock: ARPAbet ``symbol``, ``ipa``, [start_s, end_s)."""

    symbol: str
    ipa: str
    start_s: float
    end_s: float


def phones_from_label(label: str | None) -> list[str]:
    """The sounds a label names, in order: ``"s->k"`` -> ``["s", "k"]``."""
    if not label or not label.strip():
        raise PhoneSegmentError("the recording has no label to read its phones from; send "
                                "them as phones", field="phones")
    return [part.strip() for part in label.split(LABEL_SEPARATOR)]


def arpabet_symbols(symbols: Sequence[str], field: str = "phones") -> list[tuple[str, str]]:
    """(ARPAbet, IPA) of each symbol; PhoneSegmentError naming the first one not known."""
    if not 1 <= len(symbols) <= MAX_PHONES:
        raise PhoneSegmentError(f"{len(symbols)} phones; give 1 to {MAX_PHONES}", field=field)
    out = []
    for i, symbol in enumerate(symbols):
        try:
            phoneme = lookup(symbol)
        except UnknownPhonemeError:
            raise PhoneSegmentError(f"{symbol!r} is not a phoneme of the inventory (ARPAbet "
                                    "or IPA, see GET /phonemes)", field=f"{field}[{i}]") from None
        out.append((phoneme.arpabet, phoneme.ipa))
    return out


def frame_period(t_s: np.ndarray, frame_rate_hz: float | None) -> float:
    """Seconds between frames: the declared rate, else the median interval (10 ms for one)."""
    if frame_rate_hz:
        return 1.0 / float(frame_rate_hz)
    return float(np.median(np.diff(t_s))) if len(t_s) > 1 else 0.01


def boundary_from_contact(frames: np.ndarray, relative_t: np.ndarray) -> float | None:
    """Where a take moves from its first place to its second: the time of the first frame after
    the first third's frontmost centre of gravity at which the centre has come halfway to the
    last third's backmost; None when it never moves back."""
    n = len(frames)
    if n < 3:
        return None
    cog = centre_of_gravity(frames)
    third = max(1, n // 3)
    front_at = int(np.argmax(cog[:third]))
    front, back = float(cog[front_at]), float(cog[n - third:].min())
    if not front - back > 0.5:  # under half a row: no move from front to back
        return None
    halfway = 0.5 * (front + back)
    after = np.nonzero(cog[front_at:] <= halfway)[0]
    return float(relative_t[front_at + after[0]]) if len(after) else None


def phone_segments(symbols: Sequence[tuple[str, str]], frames: np.ndarray,
                   relative_t: np.ndarray, period_s: float,
                   boundaries_s: Sequence[float] | None = None) -> tuple[list[PhoneSegment], str]:
    """The phones on the recording's clock and where their boundaries came from ("given",
    "centre of gravity" or "even split")."""
    end = float(relative_t[-1]) + period_s
    count = len(symbols)
    if boundaries_s is not None:
        cuts = [float(b) for b in boundaries_s]
        if len(cuts) != count - 1:
            raise PhoneSegmentError(f"{len(cuts)} boundaries for {count} phones; give "
                                    f"{count - 1}", field="boundaries_s")
        edges = [0.0, *cuts, end]
        rising = all(b > a for a, b in zip(edges, edges[1:], strict=False))
        if not rising or not all(np.isfinite(cuts)):
            raise PhoneSegmentError(f"boundaries must rise strictly inside the recording's "
                                    f"0 to {end:.3f} s", field="boundaries_s")
        source = "given"
    else:
        cut = boundary_from_contact(frames, relative_t) if count == 2 else None
        if cut is not None and 0.0 < cut < end:
            edges, source = [0.0, cut, end], "centre of gravity"
        else:
            edges, source = list(np.linspace(0.0, end, count + 1)), "even split"
    segments = [PhoneSegment(symbol, ipa, float(edges[i]), float(edges[i + 1]))
                for i, (symbol, ipa) in enumerate(symbols)]
    return segments, source


def synthetic_frames(segments: Sequence[PhoneSegment], relative_t: np.ndarray, period_s: float,
                     targets: dict, rig, tables, probes: Probes) -> np.ndarray:
    """(n, 8, 8) uint8: the head's palatogram at each of the recording's frames while it says
    ``segments``."""
    phones = [{"symbol": s.symbol, "start_s": s.start_s, "end_s": s.end_s} for s in segments]
    rate_hz = 1.0 / period_s
    arrays = coarticulate_arrays(phones, targets, rate_hz=rate_hz)
    names, tracks = arrays["names"], arrays["tracks"]
    last = tracks.shape[1] - 1
    out = np.zeros((len(relative_t), 8, 8), dtype=np.uint8)
    for k, t in enumerate(relative_t):
        frame = min(last, max(0, int(round(float(t) * rate_hz))))
        values = rig.values_clipped(dict(zip(names, tracks[:, frame], strict=True)))
        out[k] = synthetic_frame(rig, values, tables, probes).grid
    return out

