"""POST /utterances and its TextGrid form: timed phones, tracks, cues and audio; bad input; the
cache; 503 without espeak-ng."""

import io
import wave

import numpy as np
import pytest
from fastapi import HTTPException

from glasshead.api.routes.utterances import UtteranceRequest, speak
from glasshead.speech import espeak, neural_voice

API = "/api/v1"
TEXTGRID = """File type = "ooTextFile"
Object class = "TextGrid"

xmin = 0
xmax = 0.5
tiers? <exists>
size = 1
item []:
    item [1]:
        class = "IntervalTier"
        name = "phones"
        xmin = 0
        xmax = 0.5
        intervals: size = 4
        intervals [1]:
            xmin = 0
            xmax = 0.1
            text = ""
        intervals [2]:
            xmin = 0.1
            xmax = 0.2
            text = "K"
        intervals [3]:
            xmin = 0.2
            xmax = 0.4
            text = "IY1"
        intervals [4]:
            xmin = 0.4
            xmax = 0.5
            text = ""
"""


@pytest.fixture
def client(built_assets, start_app, tmp_path, monkeypatch):
    monkeypatch.setenv("GLASSHEAD_SPEECH_CACHE_DIR", str(tmp_path / "utterances"))
    return start_app(built_assets)[1]


@pytest.fixture
def syntheses(client):
    """``syntheses()``: how many utterances the compute workers have made since the fixture
    began (a cached answer never reaches a worker)."""
    pool = client.app.state.compute.pool
    before = pool.tasks
    return lambda: pool.tasks - before


def test_text_gives_timed_phones_tracks_cues_and_audio(client):
    response = client.post(f"{API}/utterances", json={"text": "Stew, key."})
    assert response.status_code == 200
    body = response.json()
    assert [p["symbol"] for p in body["phones"]] == ["S", "T", "UW", "sil", "K", "IY"]
    assert body["phones"][2] == {**body["phones"][2], "ipa": "u", "stress": 1, "word": "stew"}
    assert [w["text"] for w in body["words"]] == ["stew", "key"]
    assert body["rate_hz"] >= 100
    n = body["n_frames"]
    assert abs(n - body["duration_s"] * body["rate_hz"]) <= 1
    assert {"velum_opening", "jaw_opening", "lip_opening"} <= set(body["tracks"])
    assert all(len(track) == n for track in body["tracks"].values())
    assert set(body["cues"]) == {"voicing", "nasal_airflow", "frication"}
    assert body["voice"] == neural_voice.VOICE and body["warnings"] == []
    wav = client.get(body["audio_url"])
    assert wav.status_code == 200 and wav.headers["content-type"] == "audio/wav"
    with wave.open(io.BytesIO(wav.content)) as audio:
        duration = audio.getnframes() / audio.getframerate()
    assert abs(duration - body["phones"][-1]["end_s"]) < 0.001


def test_ipa_and_arpabet_phonemes_give_the_same_utterance(client):
    ipa = client.post(f"{API}/utterances", json={"phonemes": ["k", "ˈi"]}).json()
    arpabet = client.post(f"{API}/utterances", json={"phonemes": "K IY1"}).json()
    assert [(p["symbol"], p["stress"]) for p in ipa["phones"]] == [("K", None), ("IY", 1)]
    assert [(p["symbol"], p["stress"]) for p in arpabet["phones"]] == [("K", None), ("IY", 1)]
    # espeak-ng's buffering may end a synthesis a few samples apart between calls.
    for a, b in zip(ipa["phones"], arpabet["phones"], strict=True):
        assert abs(a["start_s"] - b["start_s"]) < 0.005 and abs(a["end_s"] - b["end_s"]) < 0.005


def test_given_phones_keep_their_times_divided_by_the_rate(client):
    phones = [{"symbol": "sil", "start_s": 0.0, "end_s": 0.1},
              {"symbol": "t", "start_s": 0.1, "end_s": 0.2},
              {"symbol": "UW", "start_s": 0.2, "end_s": 0.6}]
    body = client.post(f"{API}/utterances", json={"phones": phones, "rate": 2.0}).json()
    assert [(p["symbol"], p["start_s"], p["end_s"]) for p in body["phones"]] == [
        ("sil", 0.0, 0.05), ("T", 0.05, 0.1), ("UW", 0.1, 0.3)]
    with wave.open(io.BytesIO(client.get(body["audio_url"]).content)) as audio:
        assert abs(audio.getnframes() / audio.getframerate() - 0.3) < 0.001


def _wav_samples(client, url):
    with wave.open(io.BytesIO(client.get(url).content)) as wav:
        rate = wav.getframerate()
        return np.frombuffer(wav.readframes(wav.getnframes()), "<i2") / 32768.0, rate


def _centroid_hz(samples, rate):
    power = np.abs(np.fft.rfft(samples)) ** 2
    return float(np.sum(power * np.fft.rfftfreq(len(samples), 1 / rate)) / np.sum(power))


def test_an_s_held_for_700_ms_is_a_hiss_all_through_at_the_band_of_the_voices_own_s(client):
    held = [{"symbol": "sil", "start_s": 0.0, "end_s": 0.2},
            {"symbol": "s", "start_s": 0.2, "end_s": 0.9},
            {"symbol": "sil", "start_s": 0.9, "end_s": 1.1}]
    body = client.post(f"{API}/utterances", json={"phones": held}).json()
    natural = client.post(f"{API}/utterances", json={"phonemes": "s"}).json()
    samples, rate = _wav_samples(client, body["audio_url"])
    own, own_rate = _wav_samples(client, natural["audio_url"])
    s = next(p for p in natural["phones"] if p["symbol"] == "S")
    own_s = own[int(s["start_s"] * own_rate):int(s["end_s"] * own_rate)]
    hiss = samples[int(0.25 * rate):int(0.85 * rate)]
    quarters = [np.sqrt(np.mean(q ** 2)) for q in np.array_split(hiss, 4)]
    assert min(quarters) > 0.3 * max(quarters), f"the hiss fades: RMS by quarter {quarters}"
    assert min(quarters) > 0.3 * np.sqrt(np.mean(own_s ** 2))
    assert abs(_centroid_hz(hiss, rate) - _centroid_hz(own_s, own_rate)) < 0.15 * _centroid_hz(
        own_s, own_rate)


def test_a_gap_between_given_phones_is_silence(client):
    phones = [{"symbol": "K", "start_s": 0.05, "end_s": 0.2},
              {"symbol": "IY", "start_s": 0.25, "end_s": 0.4}]
    body = client.post(f"{API}/utterances", json={"phones": phones,
                                                  "audio": {"kind": "none"}}).json()
    assert [(p["symbol"], p["start_s"], p["end_s"]) for p in body["phones"]] == [
        ("sil", 0.0, 0.05), ("K", 0.05, 0.2), ("sil", 0.2, 0.25), ("IY", 0.25, 0.4)]


def test_a_textgrid_upload_is_the_file_form_of_phones(client):
    response = client.post(f"{API}/utterances/textgrid",
                           files={"file": ("key.TextGrid", TEXTGRID.encode(), "text/plain")})
    assert response.status_code == 200
    body = response.json()
    assert [(p["symbol"], p["stress"], p["start_s"], p["end_s"]) for p in body["phones"]] == [
        ("sil", None, 0.0, 0.1), ("K", None, 0.1, 0.2), ("IY", 1, 0.2, 0.4),
        ("sil", None, 0.4, 0.5)]
    assert body["audio_url"] is None and body["voice"] is None  # the upload's default: none
    broken = client.post(f"{API}/utterances/textgrid",
                         files={"file": ("x.TextGrid", b"not a textgrid", "text/plain")})
    assert broken.status_code == 422 and "TextGrid" in broken.json()["detail"]


def test_an_unpronounceable_word_is_named_and_the_rest_spoken(client):
    body = client.post(f"{API}/utterances", json={"text": "say 日本 again"}).json()
    assert [w["text"] for w in body["words"]] == ["say", "again"]
    assert len(body["warnings"]) == 1 and "日本" in body["warnings"][0]


@pytest.mark.parametrize(("body", "named"), [
    ({"text": ""}, "text"),
    ({"text": "   "}, "text is empty"),
    ({"text": "a" * 501}, "500 characters"),
    ({"phonemes": "S XX UW"}, "unknown phoneme 'XX'"),
    ({"phones": [{"symbol": "K", "start_s": 0.2, "end_s": 0.1}]}, "runs backwards"),
    ({"phones": [{"symbol": "K", "start_s": 0.0, "end_s": 0.2},
                 {"symbol": "IY", "start_s": 0.1, "end_s": 0.3}]}, "overlapping"),
    ({"phones": [{"symbol": "Q", "start_s": 0.0, "end_s": 0.2}]}, "unknown phoneme 'Q'"),
    ({"text": "hi", "rate": 3}, "rate"),
    ({"text": "hi", "rate": 0.4}, "rate"),
    ({"text": "hi", "audio": {"kind": "loud"}}, "audio.kind"),
    ({"text": "hi", "phonemes": "HH AY"}, "exactly one of text, phonemes and phones"),
    ({"text": "日本"}, "no word in it can be pronounced"),
])
def test_bad_input_is_refused_with_422_naming_the_problem(client, body, named):
    response = client.post(f"{API}/utterances", json=body)
    assert response.status_code == 422
    assert named in response.json()["detail"]


def test_a_repeated_request_is_answered_from_the_cache_without_synthesis(client, syntheses):
    body = {"text": "the cat sat on the mat", "audio": {"kind": "lowpass", "cutoff_hz": 800}}
    first = client.post(f"{API}/utterances", json=body).json()
    assert syntheses() == 1
    again = client.post(f"{API}/utterances", json=body).json()
    assert syntheses() == 1
    assert again == first
    other = client.post(f"{API}/utterances", json={**body, "rate": 1.5}).json()
    assert other["id"] != first["id"] and syntheses() == 2


def test_a_cached_utterance_whose_audio_was_deleted_is_made_again(client, syntheses,
                                                                   tmp_path):
    first = client.post(f"{API}/utterances", json={"text": "hello"}).json()
    (tmp_path / "utterances" / f"{first['id']}.wav").unlink()
    again = client.post(f"{API}/utterances", json={"text": "hello"}).json()
    assert again["id"] == first["id"] and syntheses() == 2
    assert client.get(again["audio_url"]).status_code == 200


def test_without_espeak_ng_the_speech_task_answers_503_saying_what_to_install(
        client, monkeypatch, tmp_path):
    """The route's task, run here as a worker runs it (the workers' own espeak-ng is real);
    the pool answers what a task raises as the route would (tests/repro)."""
    def missing():
        raise OSError("libespeak-ng.so.1: cannot open shared object file")

    monkeypatch.setattr(espeak, "_ENGINE", None)
    monkeypatch.setattr(espeak, "load_library", missing)
    request = UtteranceRequest(text="hello there").model_dump(mode="json")
    with pytest.raises(HTTPException) as refused:
        speak(client.app.state.assets, {"request": request, "cache_dir": str(tmp_path)})
    assert refused.value.status_code == 503
    assert "apt-get install espeak-ng" in refused.value.detail
    assert client.get(f"{API}/health").status_code == 200


def test_audio_of_an_unknown_utterance_is_404(client):
    assert client.get(f"{API}/utterances/{'0' * 24}/audio.wav").status_code == 404
    assert client.get(f"{API}/utterances/not-an-id/audio.wav").status_code == 404
