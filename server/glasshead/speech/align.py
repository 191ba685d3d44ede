"""Phone timings for audio that comes without them, by aligning it with audio that has them.

The natural voice (``speech.neural_voice``) says a text but does not time its phones; espeak-ng
says the same text and does. Both are turned into the same features, a log mel spectrum every
``HOP_S`` (``FRAME_S`` windows, ``MEL_BANDS`` bands up to ``MEL_TOP_HZ``, each utterance's
features brought to zero mean and unit variance per band, so that two voices compare by the
shape of their spectra); dynamic time warping (steps right, down and diagonal, the diagonal
costing as one) finds the cheapest monotonic path between the two; each espeak-ng phone
boundary is carried along it to the other audio's clock (the mean time of the frames the path
pairs with it). This is alignment by synthesis, as speech technology long did before neural
aligners (e.g. Paulo and Oliveira 2004, "Automatic phonetic alignment and its confidence
measures"). Pure numpy.
"""

import numpy as np
import numpy.typing as npt

HOP_S = 0.01
FRAME_S = 0.025
MEL_BANDS = 40
MEL_TOP_HZ = 8000.0
#: The shortest phone after alignment, s (a boundary never overtakes the next).
MIN_PHONE_S = 0.01

Floats = npt.NDArray[np.float64]


def _mel_filters(sample_rate: int, size: int) -> Floats:
    top = min(MEL_TOP_HZ, sample_rate / 2.0)
    mel = np.linspace(0.0, 2595.0 * np.log10(1.0 + top / 700.0), MEL_BANDS + 2)
    hz = 700.0 * (10.0 ** (mel / 2595.0) - 1.0)
    bins = np.fft.rfftfreq(size, 1.0 / sample_rate)
    filters = np.zeros((MEL_BANDS, len(bins)))
    for k in range(MEL_BANDS):
        lo, mid, hi = hz[k], hz[k + 1], hz[k + 2]
        filters[k] = np.clip(np.minimum((bins - lo) / (mid - lo), (hi - bins) / (hi - mid)),
                             0.0, None)
    return filters


def features(samples: npt.ArrayLike, sample_rate: int) -> Floats:
    """(frames, MEL_BANDS) normalised log mel spectra, one every HOP_S."""
    x = np.asarray(samples, dtype=np.float64)
    hop, size = int(round(HOP_S * sample_rate)), int(round(FRAME_S * sample_rate))
    count = max(1, 1 + (len(x) - size) // hop) if len(x) >= size else 1
    padded = np.pad(x, (0, max(0, (count - 1) * hop + size - len(x))))
    frames = np.lib.stride_tricks.sliding_window_view(padded, size)[::hop][:count]
    spectra = np.abs(np.fft.rfft(frames * np.hanning(size), axis=1)) ** 2
    mel = np.log(spectra @ _mel_filters(sample_rate, size).T + 1e-10)
    return (mel - mel.mean(axis=0)) / (mel.std(axis=0) + 1e-9)


def warp_path(a: Floats, b: Floats) -> npt.NDArray[np.int64]:
    """The cheapest monotonic path (k, 2) of frame pairs from (0, 0) to the two last frames,
    by Euclidean distance between feature rows."""
    cost = np.sqrt(((a[:, None, :] - b[None, :, :]) ** 2).sum(axis=2))
    n, m = cost.shape
    total = np.full((n + 1, m + 1), np.inf)
    total[0, 0] = 0.0
    for i in range(1, n + 1):
        row = cost[i - 1]
        diagonal_or_up = np.minimum(total[i - 1, :-1], total[i - 1, 1:]) + row
        # Along the row a cell may also come from its left neighbour: t_j = min(d_j, t_(j-1) +
        # c_j) is min over k <= j of d_k + S_j - S_k (S the running sum of c), one vector
        # operation with a running minimum.
        running = np.cumsum(row)
        total[i, 1:] = np.minimum.accumulate(diagonal_or_up - running) + running
    i, j, path = n, m, [(n - 1, m - 1)]
    while i > 1 or j > 1:
        steps = [(total[i - 1, j - 1], i - 1, j - 1), (total[i - 1, j], i - 1, j),
                 (total[i, j - 1], i, j - 1)]
        _, i, j = min((s for s in steps if s[1] >= 1 and s[2] >= 1), key=lambda s: s[0])
        path.append((i - 1, j - 1))
    return np.asarray(path[::-1], dtype=np.int64)


def map_times(times_s: npt.ArrayLike, source: tuple[npt.ArrayLike, int],
              target: tuple[npt.ArrayLike, int]) -> Floats:
    """Times in the source audio (samples, rate) carried to the target audio's clock: the mean
    time of the target frames the warp path pairs with the source frame at each time; kept
    increasing by at least MIN_PHONE_S, within the target's length."""
    a, b = features(*source), features(*target)
    path = warp_path(a, b)
    pairs = np.zeros(len(a))
    counts = np.zeros(len(a))
    np.add.at(pairs, path[:, 0], path[:, 1])
    np.add.at(counts, path[:, 0], 1.0)
    mean_target = pairs / np.maximum(counts, 1.0)
    times = np.asarray(times_s, dtype=np.float64)
    frame = np.clip(times / HOP_S, 0.0, len(a) - 1)
    mapped = np.interp(frame, np.arange(len(a)), mean_target) * HOP_S
    length = len(np.asarray(target[0])) / target[1]
    mapped = np.clip(mapped, 0.0, length)
    for k in range(1, len(mapped)):
        mapped[k] = max(mapped[k], mapped[k - 1] + MIN_PHONE_S)
    return mapped
