"""Benchmark: POST /api/v1/utterances for a ten-word sentence, cached against uncached, in the
same run (the uncached request is the cached one's baseline).

The requests go through the whole application in-process (FastAPI's test client, the built
phoneme targets, a temporary cache directory). Uncached: the cache directory is emptied before
each request, so each one pronounces, synthesises (espeak-ng, then the natural voice, aligned
with it), coarticulates and writes the JSON and WAV. Cached: the same request again, answered
with the stored JSON. The first request of the process (CMUdict loaded, espeak-ng initialised,
the natural voice loaded) is printed apart. Also printed: the uncached
request's parts, timed alone. Checked: the cached answer is the uncached answer it stored. Also
printed: whether every uncached answer was the same (a fresh espeak-ng engine has been seen to
time its first sentence differently from the next ones, so an answer can depend on which worker
made it; that is the server's to fix, and tests', not this benchmark's, to catch).

The client speaks to the application as a browser on this machine does: its Host header is a
name the server's allow-list accepts (api/security.py; by default the loopback names).

    .venv/bin/python bench/utterances.py [uncached_runs] [cached_runs]
    GLASSHEAD_BENCH_QUICK=1: the first request stands for the uncached ones; 10 cached runs.
"""

import os
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
SENTENCE = "The quick brown fox jumps over the lazy dog today."
CACHED_GOAL_MS = 50.0
UNCACHED_GOAL_MS = 1000.0
QUICK = os.environ.get("GLASSHEAD_BENCH_QUICK") == "1"


def served_base_url(hosts):
    """A base URL whose Host the allow-list serves: 127.0.0.1 when it is served, else the first
    plain name, else a name under the first wildcard ("*.example.org")."""
    if "127.0.0.1" in hosts or "*" in hosts:
        return "http://127.0.0.1"
    plain = sorted(name for name in hosts if "*" not in name)
    host = plain[0] if plain else "bench" + sorted(hosts)[0].lstrip("*")
    return f"http://[{host}]" if ":" in host else f"http://{host}"


def timed(fn):
    start = time.perf_counter()
    out = fn()
    return (time.perf_counter() - start) * 1e3, out


def median_ms(fn, runs, before=None):
    times = []
    for _ in range(runs):
        if before:
            before()
        times.append(timed(fn)[0])
    return statistics.median(times)


def main():
    uncached_runs = int(sys.argv[1]) if len(sys.argv) > 1 else (0 if QUICK else 15)
    cached_runs = int(sys.argv[2]) if len(sys.argv) > 2 else (10 if QUICK else 200)
    if not (REPO / "assets" / "build" / "phoneme-targets.json").is_file():
        sys.exit("assets/build/phoneme-targets.json is missing: run `glasshead build` first")
    cache = Path(tempfile.mkdtemp(prefix="glasshead-bench-utterances-"))
    os.environ["GLASSHEAD_SPEECH_CACHE_DIR"] = str(cache)
    os.environ["GLASSHEAD_DATABASE_URL"] = f"sqlite:///{cache / 'bench.sqlite3'}"
    from fastapi.testclient import TestClient

    from glasshead.api.app import create_app
    from glasshead.api.security import allowed_host_names
    from glasshead.settings import get_settings
    from glasshead.speech import align, coarticulation, espeak, neural_voice, pronounce
    from glasshead.speech.utterance import RATE_HZ

    body = {"text": SENTENCE}

    def clear():
        for path in cache.glob("*.json"):
            path.unlink()
        for path in cache.glob("*.wav"):
            path.unlink()

    base_url = served_base_url(allowed_host_names(get_settings()))
    try:
        with TestClient(create_app(), base_url=base_url) as client:
            answers = []

            def post():
                response = client.post("/api/v1/utterances", json=body)
                assert response.status_code == 200, response.text
                answers.append(response.content)
                return response

            cold_ms, first = timed(post)
            n_words = len(first.json()["words"])
            uncached = median_ms(post, uncached_runs, before=clear) if uncached_runs else cold_ms
            stored = answers[-1]  # the last uncached answer, which the cache now holds
            variants = len(set(answers))
            cached = median_ms(post, cached_runs)
            same = post().content == stored

            engine = espeak.get_engine()
            said = pronounce.pronounce(SENTENCE, engine)
            part_runs = max(1, uncached_runs)
            pronounce_ms = median_ms(lambda: pronounce.pronounce(SENTENCE, engine), part_runs)
            words = [w.phones for w in said.items]
            synth_ms = median_ms(lambda: engine.synthesize(words, 1.0), part_runs)
            phones = [{k: p[k] for k in ("symbol", "stress", "start_s", "end_s")}
                      for p in first.json()["phones"]]
            targets = client.app.state.assets.get("phoneme_targets")
            coart_ms = median_ms(lambda: coarticulation.coarticulate(phones, targets,
                                                                     rate_hz=RATE_HZ),
                                 part_runs)
            synthesis = engine.synthesize(words, 1.0)
            speech = neural_voice.synthesize(SENTENCE)
            neural_ms = median_ms(lambda: neural_voice.synthesize(SENTENCE), part_runs)
            bounds = [synthesis.phones[0]["start_s"]] + [p["end_s"] for p in synthesis.phones]
            align_ms = median_ms(lambda: align.map_times(
                bounds, (synthesis.samples, synthesis.sample_rate),
                (speech.samples, speech.sample_rate)), part_runs)
    finally:
        shutil.rmtree(cache, ignore_errors=True)

    print(f"POST /utterances, a {n_words}-word sentence ({len(first.content)} bytes of JSON, "
          f"{first.json()['duration_s']:.2f} s of speech), medians:")
    print(f"  cached   {cached:8.2f} ms   goal < {CACHED_GOAL_MS:.0f} ms: "
          f"{'met' if cached < CACHED_GOAL_MS else 'MISSED'}   uncached / cached "
          f"{uncached / cached:.1f}x")
    print(f"  uncached {uncached:8.2f} ms   goal < {UNCACHED_GOAL_MS:.0f} ms: "
          f"{'met' if uncached < UNCACHED_GOAL_MS else 'MISSED'}")
    print(f"    pronounce {pronounce_ms:.2f} ms, espeak-ng synthesis {synth_ms:.2f} ms, "
          f"natural voice {neural_ms:.2f} ms, alignment {align_ms:.2f} ms, "
          f"coarticulation {coart_ms:.2f} ms")
    print(f"  first request of the process (CMUdict loaded, espeak-ng started, the voice "
          f"loaded) {cold_ms:.0f} ms")
    print(f"  uncached answers: {variants} different of {1 + uncached_runs}")
    print(f"check: the cached answer is the uncached one it stored: {'ok' if same else 'FAILED'}")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
