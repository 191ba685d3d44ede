"""One espeak-ng synthesis through libespeak-ng: real audio, and the phones timed by its events."""

import numpy as np
import pytest

from glasshead.speech import espeak
from glasshead.speech.espeak import (
    LAST_PHONE_MIN_S,
    MAX_SYNTH_CHARS,
    align_events,
    event_phones,
    get_engine,
    sounding_end,
    synthesis_batches,
)

#: How far the last phone's end may lie from the audio's end, s.
COVER_TOLERANCE_S = 0.001

STEW_KEY = [[("S", None), ("T", None), ("UW", 1)], [("sil", None)], [("K", None), ("IY", 1)]]


@pytest.fixture(scope="module")
def stew_key():
    return get_engine().synthesize(STEW_KEY, 1.0)


def test_the_phones_timed_are_exactly_the_phones_asked_for(stew_key):
    assert [p["symbol"] for p in stew_key.phones] == ["S", "T", "UW", "sil", "K", "IY"]
    assert [p["index"] for p in stew_key.phones] == [0, 1, 2, 3, 4, 5]
    assert stew_key.samples.dtype == np.int16 and stew_key.sample_rate == 22050


def test_phone_times_increase_and_cover_the_audio(stew_key):
    phones = stew_key.phones
    assert phones[0]["start_s"] == 0.0
    for before, after in zip(phones, phones[1:], strict=False):
        assert before["start_s"] < before["end_s"] == after["start_s"]
    assert abs(phones[-1]["end_s"] - stew_key.duration_s) <= COVER_TOLERANCE_S
    assert 0.4 < stew_key.duration_s < 1.5


def _rms(synthesis, phone):
    rate = synthesis.sample_rate
    part = synthesis.samples[int(phone["start_s"] * rate):int(phone["end_s"] * rate)]
    return float(np.sqrt(np.mean(part.astype(np.float64) ** 2)))


def test_a_voiced_vowel_has_far_more_energy_than_the_pause(stew_key):
    by_symbol = {p["symbol"]: p for p in stew_key.phones}
    vowel, pause = _rms(stew_key, by_symbol["UW"]), _rms(stew_key, by_symbol["sil"])
    assert vowel > 1000.0
    assert vowel > 20 * pause


def test_a_faster_rate_speaks_the_same_phones_in_less_time(stew_key):
    fast = get_engine().synthesize(STEW_KEY, 2.0)
    assert [p["symbol"] for p in fast.phones] == [p["symbol"] for p in stew_key.phones]
    assert fast.duration_s < 0.75 * stew_key.duration_s


def test_events_espeak_changed_are_aligned_back_to_the_request():
    # A flap (t#) for /t/, a marker (;) espeak-ng inserted and a trailing pause it added.
    events = [(0, "b"), (100, "V"), (300, "t#"), (350, ";"), (360, "3"), (500, "_:"),
              (600, "_")]
    phones = align_events(["B", "AH", "T", "ER"], events, 600, 1000)
    assert [(p["symbol"], p["start_s"], p["end_s"]) for p in phones] == [
        ("B", 0.0, 0.1), ("AH", 0.1, 0.3), ("T", 0.3, 0.36), ("ER", 0.36, 0.5),
        ("sil", 0.5, 0.6)]
    assert phones[-1]["index"] is None


def test_a_phone_espeak_dropped_shares_the_time_of_the_one_before():
    events = [(0, "s"), (100, "u:"), (300, "_")]
    phones = align_events(["S", "T", "UW"], events, 300, 1000)
    assert [(p["symbol"], p["start_s"], p["end_s"]) for p in phones] == [
        ("S", 0.0, 0.05), ("T", 0.05, 0.1), ("UW", 0.1, 0.3)]


def test_what_was_spoken_before_does_not_change_how_long_a_word_lasts():
    """espeak-ng ended a synthesis with a run of silence that depended on the words before it:
    "K IY1" lasted 0.337 s, and 0.376 s in a worker that had spoken "M AA1 T" before."""
    engine = get_engine()
    key = [[("K", None), ("IY", 1)]]
    lengths = []
    for before in ([[("M", None), ("AA", 1)]], [[("M", None), ("AA", 1), ("T", None)]],
                   [[("S", None), ("IY", 1)]] * 3, [[("T", None)]]):
        engine.synthesize(before, 1.0)
        synthesis = engine.synthesize(key, 1.0)
        assert synthesis.samples[-1] != 0  # ends where the sound ends
        lengths.append(synthesis.duration_s)
    assert max(lengths) - min(lengths) < 0.005, lengths


def test_a_last_phone_espeak_gave_no_sound_keeps_its_time_and_runs_forward():
    """Of 500 zeros, the last phone began after the last sound, and its closing pause event
    12 ms later: cut at the sound, the phone ran backwards, and the utterance failed."""
    rate = 22050
    samples = np.zeros(rate, dtype=np.int16)
    samples[:15_000] = 1000
    events = [(0, "z"), (2_000, "i:"), (9_000, "r"), (15_100, "oU"), (15_250, "_:"),
              (15_400, "_")]
    end = sounding_end(samples, events, rate)
    assert end == 15_100 + round(LAST_PHONE_MIN_S * rate)
    phones = align_events(["Z", "IY", "R", "OW"], events, end, rate)
    assert [p["symbol"] for p in phones] == ["Z", "IY", "R", "OW"]
    assert all(p["end_s"] > p["start_s"] for p in phones), phones
    assert phones[-1]["end_s"] == end / rate
    samples[:] = 0
    assert sounding_end(samples, events, rate) == rate  # silence alone is left as it is


ONE = [("W", None), ("AH", 1), ("N", None)]


def test_a_long_request_is_spoken_as_asked_to_its_end(monkeypatch):
    """espeak-ng split a clause of about 700 characters and read the rest as English text: of
    500 "one"s, the 146th on came out as "double-u vee en" (3,287 phones for 1,500), and lining
    those up took 20 s. Now every batch espeak-ng speaks is the phones asked for."""
    spoken: list[list[str]] = []

    def spy(wanted, events, n_samples, sample_rate):
        spoken.append([s for _, m in events for s, _ in event_phones(m) if s != "sil"])
        assert spoken[-1] == wanted, f"espeak-ng spoke {spoken[-1][:12]} for {wanted[:12]}"
        return align_events(wanted, events, n_samples, sample_rate)

    monkeypatch.setattr(espeak, "align_events", spy)
    engine = get_engine()
    hundred, three_hundred = engine.synthesize([ONE] * 100), engine.synthesize([ONE] * 300)
    assert len(spoken) > 2  # the long one in batches
    assert [p["symbol"] for p in three_hundred.phones if p["index"] is not None] == \
        [s for s, _ in ONE] * 300
    assert 2.8 < three_hundred.duration_s / hundred.duration_s < 3.2
    phones = three_hundred.phones
    assert phones[0]["start_s"] == 0.0
    assert all(a["end_s"] == b["start_s"] and a["start_s"] < a["end_s"]
               for a, b in zip(phones, phones[1:], strict=False))
    assert abs(phones[-1]["end_s"] - three_hundred.duration_s) <= COVER_TOLERANCE_S
    last_vowel = [p for p in phones if p["symbol"] == "AH"][-1]
    assert _rms(three_hundred, last_vowel) > 1000.0  # sound to the end, not a gap


def test_batches_stay_under_the_limit_and_start_at_a_pause_where_one_is_near():
    texts = ["w'Vn"] * 200
    pauses = [False] * 200
    batches = synthesis_batches(texts, pauses)
    assert batches[0][0] == 0 and batches[-1][1] == 200
    assert all(a[1] == b[0] for a, b in zip(batches, batches[1:], strict=False))
    assert all(len(" ".join(texts[lo:hi])) <= MAX_SYNTH_CHARS for lo, hi in batches)
    assert len(batches) == 3  # 80 pieces of 5 characters per batch
    pauses[60] = True  # in the second half of the first batch: it ends before the pause
    assert synthesis_batches(texts, pauses)[0] == (0, 60)
    pauses[60], pauses[20] = False, True  # in the first half: no cut there
    assert synthesis_batches(texts, pauses)[0] == (0, 80)
    assert synthesis_batches(["x" * 900, "ab"], [False, False]) == [(0, 1), (1, 2)]
    assert synthesis_batches([], []) == []
