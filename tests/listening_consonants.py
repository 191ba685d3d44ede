"""Consonant measures from tracks: /s/ against /ʃ/ in children's sentences, and F3 in /r/.

Sibilants (speechocean762 children, no time alignment). Each tracker finds them in its own
track:

1. Frication frames: unvoiced, a spectral centroid above ``FRICATION_CENTROID_HZ``, and an
   intensity at least ``FRICATION_ABOVE_FLOOR_DB`` above the file's noise floor (the 10th
   percentile of its frames' intensity, frames more than 60 dB below its loud frames counted
   at that level, so that digital silence does not set the floor).
2. Runs of such frames (a one-frame gap bridged) of at least ``FRICATION_MIN_S``: bursts of
   /t/ and /k/ are shorter.
3. The canonical transcription (utterances.tsv) places each phone at an even share of the
   speech (first to last frame 20 dB above the floor): a rough expected time. The sentence's
   sibilants (S Z SH ZH CH JH, in order; neighbours merged into one item) are matched to the runs
   in order, by dynamic programming: a match costs the distance between the item's expected
   time and the run's centre (at most ``MATCH_WINDOW_S``), an item left unmatched costs
   ``MATCH_WINDOW_S``, a run left over (/f/, /θ/, aspiration) costs nothing.
4. An item that is a lone S or SH and has a run is a token; its centroid is the median of the
   run's frames. A child's pairs are each of their /s/ tokens with each of their /ʃ/ tokens,
   from all six of their sentences.

/r/ (praatio's mary.wav, a man; phone TextGrid): an /r/ interval's F3 is the lowest F3, after a
three-frame running median, of the frames centred in it; the speaker's vowel F3 is the mean,
over the TextGrid's vowel intervals, of each interval's median F3.
"""

import csv

import numpy as np

from glasshead.speech.textgrid import read_textgrid
from listening_support import HOP_S, Track, require, speech_dir

#: A frication frame's spectral centroid is above this, Hz.
FRICATION_CENTROID_HZ = 2500.0

#: ... and its intensity this far above the file's noise floor, dB.
FRICATION_ABOVE_FLOOR_DB = 15.0

#: Speech is this far above the noise floor, dB.
SPEECH_ABOVE_FLOOR_DB = 20.0

#: Shortest run of frication frames taken for a sibilant, s.
FRICATION_MIN_S = 0.05

#: Farthest a run's centre may be from its phone's expected time, s.
MATCH_WINDOW_S = 0.4

#: The phones that are sibilants (ARPAbet).
SIBILANTS = frozenset({"S", "Z", "SH", "ZH", "CH", "JH"})

#: IPA vowel letters of the praatio TextGrids' phone labels.
IPA_VOWELS = frozenset("aeiouyæɑɒɔəɛɜɪʊʌœøɐɘɵɤɯ")


def children_sentences() -> list[dict]:
    """speechocean762's children's sentences: dicts with ``path``, ``speaker``, ``text`` and
    ``phones`` (canonical ARPAbet without stress or position tags, in order)."""
    folder = speech_dir() / "speechocean762-children"
    sentences = []
    with require(folder / "utterances.tsv").open(newline="") as handle:
        for row in csv.reader(handle, delimiter="\t"):
            if row[0] == "utt_id":
                continue
            phones = [p.split("_")[0].rstrip("012") for word in row[7].split("|")
                      for p in word.split()]
            sentences.append({"path": require(folder / row[1]), "speaker": row[2],
                              "text": row[6], "phones": phones})
    return sentences


def _levels(track: Track):
    level = np.where(np.isfinite(track.intensity_db), track.intensity_db, -np.inf)
    level = np.maximum(level, np.nanpercentile(track.intensity_db, 95) - 60.0)
    return level, float(np.percentile(level, 10))


def _runs(mask, shortest):
    """[(first, end)] frame ranges of True in ``mask`` (one-frame gaps bridged)."""
    mask = mask.copy()
    mask[1:-1] |= mask[:-2] & mask[2:]
    edges = np.flatnonzero(np.diff(np.concatenate([[0], mask.astype(int), [0]])))
    return [(a, b) for a, b in zip(edges[::2], edges[1::2], strict=True) if b - a >= shortest]


def _items(phones):
    """[(label, first, last)]: the sibilants in order, neighbours merged ("S+SH")."""
    items: list[tuple[str, int, int]] = []
    for k, phone in enumerate(phones):
        if phone not in SIBILANTS:
            continue
        if items and items[-1][2] == k - 1:
            label, first, _ = items[-1]
            items[-1] = (f"{label}+{phone}", first, k)
        else:
            items.append((phone, k, k))
    return items


def _align(expected, centres):
    """Monotone matching of items (expected times) to runs (centres): {item: run}."""
    n, m = len(expected), len(centres)
    cost = np.full((n + 1, m + 1), np.inf)
    cost[0, :] = 0.0
    step = np.zeros((n + 1, m + 1), dtype=int)  # 0 item skipped, 1 run skipped, 2 matched
    for i in range(1, n + 1):
        cost[i, 0] = cost[i - 1, 0] + MATCH_WINDOW_S
        for j in range(1, m + 1):
            distance = abs(expected[i - 1] - centres[j - 1])
            options = (cost[i - 1, j] + MATCH_WINDOW_S, cost[i, j - 1],
                       cost[i - 1, j - 1] + distance if distance <= MATCH_WINDOW_S else np.inf)
            step[i, j] = int(np.argmin(options))
            cost[i, j] = options[step[i, j]]
    matches, i, j = {}, n, m
    while i > 0 and j > 0:
        if step[i, j] == 2:
            matches[i - 1] = j - 1
        i, j = (i - 1, j) if step[i, j] == 0 else (i, j - 1) if step[i, j] == 1 else (i - 1, j - 1)
    return matches


def sibilant_tokens(sentence: dict, track: Track) -> list[dict]:
    """The lone S and SH of a sentence found in its track: dicts with ``phone``, ``start_s``,
    ``end_s`` and ``centroid`` (Hz)."""
    level, floor = _levels(track)
    speech = np.flatnonzero(level > floor + SPEECH_ABOVE_FLOOR_DB)
    first, last = track.t[speech[0]], track.t[speech[-1]]
    frication = (np.isnan(track.f0) & (track.centroid > FRICATION_CENTROID_HZ)
                 & (level > floor + FRICATION_ABOVE_FLOOR_DB))
    runs = _runs(frication, round(FRICATION_MIN_S / HOP_S))
    phones = sentence["phones"]
    items = _items(phones)
    expected = [first + (a + b + 1) / 2 / len(phones) * (last - first) for _, a, b in items]
    centres = [(track.t[a] + track.t[b - 1]) / 2 for a, b in runs]
    tokens = []
    for item, run in sorted(_align(expected, centres).items()):
        if items[item][0] in ("S", "SH"):
            a, b = runs[run]
            tokens.append({"phone": items[item][0], "start_s": float(track.t[a]),
                           "end_s": float(track.t[b - 1]),
                           "centroid": float(np.nanmedian(track.centroid[a:b]))})
    return tokens


def sibilant_pairs(tokens_by_speaker: dict) -> tuple[int, int]:
    """(pairs, pairs with the /s/ centroid above the /ʃ/ one) over the speakers' tokens."""
    pairs = above = 0
    for tokens in tokens_by_speaker.values():
        s = [t["centroid"] for t in tokens if t["phone"] == "S"]
        sh = [t["centroid"] for t in tokens if t["phone"] == "SH"]
        pairs += len(s) * len(sh)
        above += sum(a > b for a in s for b in sh)
    return pairs, above


def mary_phones() -> list[dict]:
    """The phone intervals of praatio's mary.TextGrid (``symbol``, ``start_s``, ``end_s``)."""
    folder = speech_dir() / "praatio-examples"
    return read_textgrid(require(folder / "mary.TextGrid").read_bytes())


def r_f3(track: Track, phones) -> tuple[list[float], float]:
    """([lowest F3 of each /r/ interval], mean vowel F3), Hz."""
    f3 = track.formants[:, 2]
    smooth = np.array([np.nanmedian(f3[max(0, i - 1):i + 2]) if np.isfinite(f3[i]) else np.nan
                       for i in range(len(f3))])

    def inside(phone):
        return (track.t >= phone["start_s"]) & (track.t < phone["end_s"])

    lows = [float(np.nanmin(smooth[inside(p)])) for p in phones if p["symbol"] == "r"]
    vowels = [float(np.nanmedian(f3[inside(p)])) for p in phones
              if p["symbol"] and set(p["symbol"]) <= IPA_VOWELS]
    return lows, float(np.mean(vowels))
