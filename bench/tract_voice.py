"""Benchmark: the tract voice (speech.tract_voice) against VocalTractLab's own articulatory
voice (speech.vtl_voice) on the same timed phones, in the same run.

The phones are a ten-word sentence's, as espeak-ng times them; both voices make 44.1 kHz audio
of the same length. The tract voice poses every 10 ms frame of the coarticulated tracks,
computes its area function and runs VocalTractLab's tube synthesis through those tubes; the
articulatory voice makes a gestural score from the phones and synthesises it with JD3's own
vocal tract. Printed: the median seconds per second of audio of each (a real-time factor: under
1 is faster than real time), the tract voice's two parts (the area functions, the synthesis),
and the ratio. The issue's goal is the tract voice at least 5 times faster than real time on
one core (a factor under 0.2). Checked: both make audio of the phones' length, finite, and not
silent.

    .venv/bin/python bench/tract_voice.py [runs]        (GLASSHEAD_BENCH_QUICK=1: 1 run)
"""

import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
SENTENCE = "The quick brown fox jumps over the lazy dog today."
GOAL_RTF = 0.2
QUICK = os.environ.get("GLASSHEAD_BENCH_QUICK") == "1"


def main():
    from glasshead.asset_store import AssetStore
    from glasshead.settings import get_settings
    from glasshead.speech import espeak, tract_voice, vtl_voice
    from glasshead.speech.coarticulation import coarticulate
    from glasshead.speech.pronounce import pronounce
    from glasshead.tract_assets import tract_shape

    runs = 1 if QUICK else int(sys.argv[1]) if len(sys.argv) > 1 else 3
    store = AssetStore(get_settings().assets_dir)
    shape = tract_shape(store)
    engine = espeak.get_engine()
    said = pronounce(SENTENCE, engine)
    synthesis = engine.synthesize([w.phones for w in said.items], 1.0)
    phones = [{"symbol": p["symbol"], "stress": p.get("stress", 0), "start_s": p["start_s"],
               "end_s": p["end_s"]} for p in synthesis.phones]
    duration = phones[-1]["end_s"]
    tracks = coarticulate(phones, store.get("phoneme_targets"), rate_hz=100.0)["tracks"]

    geometry, tract, articulatory = [], [], []
    checks = []
    for _ in range(runs):
        start = time.perf_counter()
        area_functions = shape.frames(tracks)
        fricatives = tract_voice.fricative_frames(len(area_functions), 100.0, phones)
        frames = tract_voice.tubes_of_frames(area_functions, fricatives)
        middle = time.perf_counter()
        samples, rate = tract_voice.synthesize(frames, 100.0, phones)
        end = time.perf_counter()
        geometry.append((middle - start) / duration)
        tract.append((end - start) / duration)
        checks.append(("tract", samples, rate))
        start = time.perf_counter()
        samples, rate = vtl_voice.synthesize(phones)
        articulatory.append((time.perf_counter() - start) / duration)
        checks.append(("articulatory", samples, rate))

    ours, theirs = statistics.median(tract), statistics.median(articulatory)
    print(f"tract voice: {SENTENCE!r}, {len(phones)} phones, {duration:.2f} s of audio, "
          f"median of {runs} run(s); seconds per second of audio:")
    print(f"  tract voice          {ours:.3f}  (area functions {statistics.median(geometry):.3f},"
          f" synthesis {ours - statistics.median(geometry):.3f})")
    print(f"  articulatory (JD3)   {theirs:.3f}")
    print(f"  ratio                {theirs / ours:.2f}x; goal < {GOAL_RTF} "
          f"(5x real time): {'met' if ours < GOAL_RTF else 'NOT met'}")
    failed = False
    for _name, samples, rate in checks:
        ok = (abs(len(samples) / rate - duration) < 0.1 and np.all(np.isfinite(samples))
              and float(np.max(np.abs(samples))) > 0.1)
        failed |= not ok
    print(f"check: both voices make finite, audible audio of the phones' length: "
          f"{'FAILED' if failed else 'ok'}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
