"""The tract voice (glasshead.speech.tract_voice): the head's own tubes through VocalTractLab's
tube synthesis. Its vowels have the formants the tube computes, measured by the listening
kernels (scripts/measure.mjs) and by Praat; /m/ hums through the nose; /s/ hisses; a closed
tract is carried, not NaN; and POST /utterances speaks with it."""


import numpy as np
import parselmouth
import pytest

from glasshead.speech import tract_voice
from glasshead.speech.audio import write_wav
from glasshead.speech.coarticulation import coarticulate
from listening_support import measure_hops

#: How far the formants measured in the synthesised vowels may be from the tube's (issue 31;
#: measured: within 8.1 % by both trackers, the largest F2 of /i/).
FORMANT_TOLERANCE = 0.10
RATE_HZ = 100.0


@pytest.fixture(scope="module")
def store(built_store):
    return built_store


@pytest.fixture(scope="module")
def shape(head_tract):
    return head_tract


def timed(*items):
    phones, t = [], 0.0
    for symbol, seconds in items:
        phones.append({"symbol": symbol, "stress": 1, "start_s": t, "end_s": t + seconds})
        t += seconds
    return phones


def spoken(shape, store, phones, path=None):
    tracks = coarticulate(phones, store.get("phoneme_targets"), rate_hz=RATE_HZ)["tracks"]
    samples, rate = tract_voice.speak(shape, tracks, RATE_HZ, phones)
    if path is not None:
        write_wav(path, samples, rate)
    return samples, rate


def test_the_tube_keeps_a_closure_and_the_incisors_and_has_forty_sections():
    area = {"length_mm": [10.0] + [4.0] * 40, "area_mm2": [50.0] + [300.0] * 20 + [0.1]
            + [300.0] * 19, "region": [-1] + [0] * 10 + [1] * 25 + [2] * 5,
            "nasal_port_mm2": 25.0}
    lengths, areas, articulators, incisor, velum = tract_voice.vtl_tube(area)
    assert len(lengths) == len(areas) == len(articulators) == tract_voice.SECTIONS
    assert lengths.sum() == pytest.approx(17.0)
    assert areas.min() < 0.01  # a 4 mm closure stays shut in a 4.25 mm section
    assert incisor == pytest.approx(15.0) and velum == pytest.approx(0.25)
    assert articulators[-1] == tract_voice.LOWER_LIP and articulators[0] == tract_voice.OTHER
    assert tract_voice.LOWER_INCISORS in articulators


def test_the_source_voices_vowels_opens_for_voiceless_sounds_and_breathes_in_pauses():
    shapes = {"voiced": np.array([120.0, 8000.0, 0.01] + [0.0] * 8),
              "voiceless fricative": np.array([105.0, 8000.0, 0.1] + [0.0] * 8),
              "voiceless stop": np.array([105.0, 8000.0, 0.2] + [0.0] * 8)}
    phones = timed(("sil", 0.1), ("AA", 0.2), ("S", 0.2), ("sil", 0.1))
    times = np.array([0.05, 0.2, 0.4, 0.58])
    source = tract_voice.source_tracks(phones, shapes, times)
    assert source[0, 1] == 0.0 and source[-1, 1] == 0.0  # no breath in the pauses
    assert source[1, 1] == 8000.0 and source[1, 2] == pytest.approx(0.01)
    assert source[2, 2] == pytest.approx(0.1)  # the /s/ opens the glottis
    assert source[0, 0] > source[-1, 0]  # F0 falls


@pytest.mark.parametrize(("word", "symbol", "ipa"), [("heed", "IY", "i"), ("hod", "AA", "ɑ"),
                                                     ("who'd", "UW", "u")])
def test_the_vowels_of_heed_hod_and_whod_have_the_tubes_formants(shape, store, tmp_path, word,
                                                                 symbol, ipa):
    path = tmp_path / "vowel.wav"
    spoken(shape, store, timed(("sil", 0.1), ("HH", 0.08), (symbol, 0.3), ("D", 0.08),
                               ("sil", 0.1)), path)
    target = next(t for t in store.get("phoneme_targets")["targets"] if t["ipa"] == ipa)
    tube = shape.acoustics(target["params"])["formants"][:3]
    middle = (0.23, 0.43)  # the vowel's steady middle
    hops = [h for h in measure_hops(path, "man")
            if middle[0] <= h["t"] <= middle[1] and h["voiced"]]
    assert len(hops) >= 10, f"{word}: {len(hops)} voiced hops"
    ours = np.median([h["formants"][:3] for h in hops], axis=0)
    formant = parselmouth.Sound(str(path)).to_formant_burg(maximum_formant=5000.0)
    times = np.linspace(*middle, 11)
    praat = np.array([np.nanmedian([formant.get_value_at_time(k, t) for t in times])
                      for k in (1, 2, 3)])
    for name, measured in (("ours", ours), ("Praat", praat)):
        error = np.abs(measured - tube) / tube
        assert np.all(error <= FORMANT_TOLERANCE), (word, name, np.round(measured),
                                                    np.round(tube))


def _bands(samples, rate, start_s, end_s):
    part = parselmouth.Sound(samples, rate).extract_part(start_s, end_s)
    spectrum = part.to_spectrum()
    total = spectrum.get_band_energy(0.0, 11000.0)
    return (part.get_rms(), spectrum.get_band_energy(0.0, 500.0) / total,
            spectrum.get_band_energy(3000.0, 11000.0) / total, spectrum.get_centre_of_gravity())


def test_m_hums_through_the_nose_and_s_hisses(shape, store):
    samples, rate = spoken(shape, store, timed(("sil", 0.1), ("M", 0.4), ("sil", 0.1)))
    rms, low, _, _ = _bands(samples, rate, 0.2, 0.4)
    assert rms > 0.1 and low > 0.9, (rms, low)  # a loud murmur, nearly all below 500 Hz
    samples, rate = spoken(shape, store, timed(("sil", 0.1), ("S", 0.4), ("sil", 0.1)))
    rms, _, high, centroid = _bands(samples, rate, 0.2, 0.4)
    assert rms > 0.05 and high > 0.8 and centroid > 3000.0, (rms, high, centroid)


def test_a_stop_is_carried_through_its_closure_with_no_nan(shape, store):
    samples, rate = spoken(shape, store, timed(("sil", 0.05), ("AA", 0.15), ("T", 0.12),
                                               ("AA", 0.15), ("sil", 0.05)))
    assert np.all(np.isfinite(samples)) and len(samples) == pytest.approx(0.52 * rate, abs=120)
    closure, _, _, _ = _bands(samples, rate, 0.23, 0.29)
    vowel, _, _, _ = _bands(samples, rate, 0.08, 0.18)
    assert closure < 0.3 * vowel, (closure, vowel)


def test_post_utterances_speaks_with_the_tract_voice(start_app):
    _, client = start_app()
    answer = client.post("/api/v1/utterances", json={"phonemes": "ɑ m ɑ",
                                                     "audio": {"kind": "tract"}})
    assert answer.status_code == 200, answer.text
    body = answer.json()
    assert body["voice"] == tract_voice.VOICE and body["audio"]["kind"] == "tract"
    audio = client.get(body["audio_url"])
    assert audio.status_code == 200 and audio.content[:4] == b"RIFF"
    again = client.post("/api/v1/utterances", json={"phonemes": "ɑ m ɑ",
                                                    "audio": {"kind": "tract"}})
    assert again.json()["id"] == body["id"]  # cached
