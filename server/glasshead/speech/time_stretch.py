"""Stretching speech in time without moving its pitch or its spectrum: WSOLA.

Waveform-similarity overlap-add (Verhelst and Roelands 1993, "An overlap-add technique based on
waveform similarity (WSOLA) for high quality time-scale modification of speech", ICASSP): the
output is built of Hann-windowed frames at a fixed hop of half a frame, each copied from near the
source time that the output time maps to, shifted by up to ``TOLERANCE_S`` to where it best
continues the frame before (the largest normalised cross-correlation with that frame's
natural continuation). Held periodic sound keeps its period and a held hiss its band, where
resampling would lower both by the stretch: an /s/ held five times as long stays an /s/ at 5 to
8 kHz, not a hiss at 1 kHz. Each frame is read from inside its own phone's source span, so a
phone boundary moves exactly where it is asked, give or take the half-frame crossfade.
"""

import numpy as np

#: The frame, s: two or three periods of a low voice, short enough for a 20 ms stop burst.
FRAME_S = 0.03
#: How far a frame may move from its mapped time to continue the one before, s: more than
#: half the period of an 80 Hz voice.
TOLERANCE_S = 0.008


def stretch_to(samples: np.ndarray, sample_rate: float, source_bounds, target_bounds
               ) -> np.ndarray:
    """(m,) float64 samples lasting ``target_bounds[-1]`` s in which each source span between
    consecutive ``source_bounds`` (s, increasing) fills the span between the same
    ``target_bounds``, its pitch and spectrum kept. A span may shrink as well as grow."""
    x = np.asarray(samples, dtype=np.float64)
    n_out = int(round(target_bounds[-1] * sample_rate))
    if n_out <= 0:
        return np.zeros(0)
    frame = max(2 * int(round(FRAME_S * sample_rate / 2)), 4)
    hop = frame // 2
    tolerance = max(int(round(TOLERANCE_S * sample_rate)), 1)
    # A periodic Hann window: at a hop of half its length the frames sum to exactly one.
    window = 0.5 - 0.5 * np.cos(2.0 * np.pi * np.arange(frame) / frame)
    pad = frame + tolerance
    source = np.concatenate([np.zeros(pad), x, np.zeros(pad)])
    n_frames = n_out // hop + 2
    # Frame k is centred at output sample k * hop; its source centre comes from the bounds.
    times = np.arange(n_frames) * hop / sample_rate
    centres = np.round(np.interp(times, target_bounds, source_bounds) * sample_rate) + pad
    spans = _spans(times, source_bounds, target_bounds, sample_rate, pad, frame)
    out = np.zeros(n_frames * hop + frame)
    previous_start = None
    for k, (centre, (first, last)) in enumerate(zip(centres, spans, strict=True)):
        start = min(max(int(centre) - hop, first), last)
        if previous_start is not None:
            natural = source[previous_start + hop:previous_start + hop + frame]
            lo, hi = max(start - tolerance, first), min(start + tolerance, last)
            if hi > lo and np.any(natural):
                start = lo + _best_match(source[lo:hi + frame], natural)
        out[k * hop:k * hop + frame] += window * source[start:start + frame]
        previous_start = start
    # Output sample 0 is the centre of frame 0.
    return out[hop:hop + n_out]


def _spans(times, source_bounds, target_bounds, sample_rate, pad, frame):
    """Per output frame, the first and last source sample its frame may start at: inside the
    source span of the phone its centre falls in, so that no frame carries the next phone's
    sound into this one's stretched time (a span shorter than a frame is read at its middle)."""
    phone = np.clip(np.searchsorted(target_bounds, times, side="right") - 1, 0,
                    len(target_bounds) - 2)
    lo = np.round(np.asarray(source_bounds)[phone] * sample_rate).astype(np.int64) + pad
    hi = np.round(np.asarray(source_bounds)[phone + 1] * sample_rate).astype(np.int64) + pad
    short = hi - lo < frame
    middle = (lo + hi) // 2 - frame // 2
    first = np.where(short, middle, lo)
    last = np.where(short, middle, hi - frame)
    return list(zip(first.tolist(), last.tolist(), strict=True))


def _best_match(region: np.ndarray, natural: np.ndarray) -> int:
    """The offset in ``region`` where a frame of ``len(natural)`` samples is most like
    ``natural``: the largest cross-correlation over the candidate's own norm, so that a louder
    stretch nearby does not win by loudness alone."""
    frame = len(natural)
    score = np.correlate(region, natural, mode="valid")
    energy = np.concatenate([[0.0], np.cumsum(region * region)])
    norms = np.sqrt(np.maximum(energy[frame:] - energy[:-frame], 0.0)) + 1e-12
    return int(np.argmax(score / norms))
