"""Benchmark: coarticulated tracks for a ten-word sentence (``speech.coarticulation``).

"Please call Stella, ask her to bring these things with" (35 phones with the two silences,
timed by ``training.coarticulation.timed``, 2.5 s) at 100 Hz: every parameter and cue track,
against a naive implementation in the same run, a Python loop over frames and phones that
evaluates each phone's dominance per parameter group once per frame and accumulates each
parameter's weighted sum (the same result, checked). Prints the medians and the ratio.

    .venv/bin/python bench/coarticulation.py [--runs N]
    GLASSHEAD_BENCH_QUICK=1: 5 runs.
"""

import argparse
import json
import math
import os
import statistics
import time
from pathlib import Path

import numpy as np

from glasshead.speech import dominance
from glasshead.speech.coarticulation import (
    coarticulate,
    parameter_names,
    segments,
    target_matrix,
)
from glasshead.training.coarticulation import timed

REPO = Path(__file__).resolve().parents[1]
SENTENCE = ("P L IY Z  K AO L  S T EH L AH0  AE S K  HH ER0  T UW  B R IH NG  DH IY Z  "
            "TH IH NG Z  W IH DH")
RATE_HZ = 100.0
QUICK = os.environ.get("GLASSHEAD_BENCH_QUICK") == "1"


def naive_tracks(phones, targets, constants, rate_hz=RATE_HZ):
    """Per frame, per phone (segment: a diphthong is two): the dominance of each group, then
    each parameter's weighted sum."""
    names = parameter_names(targets)
    symbols, starts, ends, _ = segments(phones)
    values = target_matrix(symbols, targets, names).tolist()
    groups = [dominance.parameter_group(n) for n in names]
    specs = []
    for symbol, start, end in zip(symbols, starts.tolist(), ends.tolist(), strict=True):
        entry = constants["classes"][dominance.phone_class(symbol)]
        alpha = dict(entry["alpha"])
        alpha["velum"] = constants["velum_alpha"][dominance.velum_class(symbol)]
        specs.append((0.5 * (start + end), entry["theta_anticipation"],
                      entry["theta_carryover"], alpha))
    c = constants["c"]
    n_frames = math.ceil(phones[-1]["end_s"] * rate_hz - 1e-9)
    tracks = {name: [0.0] * n_frames for name in names}
    for i in range(n_frames):
        t = i / rate_hz
        numerator = [0.0] * len(names)
        denominator = dict.fromkeys(dominance.GROUPS, 0.0)
        for j, (centre, before, after, alpha) in enumerate(specs):
            tau = t - centre
            shape = math.exp(-(before if tau < 0 else after) * abs(tau) ** c)
            d = {g: a * shape for g, a in alpha.items()}
            for g in d:
                denominator[g] += d[g]
            row = values[j]
            for k, g in enumerate(groups):
                numerator[k] += d[g] * row[k]
        for k, name in enumerate(names):
            tracks[name][i] = numerator[k] / denominator[groups[k]]
    return tracks


def median_ms(function, runs):
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        function()
        times.append((time.perf_counter() - start) * 1e3)
    return statistics.median(times)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5 if QUICK else 50)
    args = parser.parse_args(argv)
    targets = json.loads((REPO / "assets" / "build" / "phoneme-targets.json").read_text())
    phones = timed(SENTENCE)
    constants = dominance.load_constants()
    ours = coarticulate(phones, targets)
    slow = naive_tracks(phones, targets, constants)
    worst = max(float(np.max(np.abs(np.asarray(ours["tracks"][n]) - np.asarray(slow[n]))))
                for n in slow)
    if worst > 1e-9:
        raise SystemExit(f"the naive tracks differ from coarticulate's by {worst}")
    ours_ms = median_ms(lambda: coarticulate(phones, targets), args.runs)
    naive_ms = median_ms(lambda: naive_tracks(phones, targets, constants),
                         max(1 if QUICK else 3, args.runs // 10))
    print(f"sentence: {len(phones)} phones, {phones[-1]['end_s']:.2f} s, {ours['n_frames']} "
          f"frames at {RATE_HZ:.0f} Hz, {len(ours['tracks'])} parameters + "
          f"{len(ours['cues'])} cues (largest difference {worst:.1e})")
    print(f"coarticulate (numpy, with the lists returned): median {ours_ms:.2f} ms over "
          f"{args.runs} runs")
    print(f"naive loop over frames and phones: median {naive_ms:.1f} ms "
          f"({naive_ms / ours_ms:.0f}x slower)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
