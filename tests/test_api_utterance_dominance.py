"""POST /utterances with ``"dominance": true``: each phone's dominance curves, for the player."""

import pytest

API = "/api/v1"


@pytest.fixture
def client(built_assets, start_app, tmp_path, monkeypatch):
    monkeypatch.setenv("GLASSHEAD_SPEECH_CACHE_DIR", str(tmp_path / "utterances"))
    return start_app(built_assets)[1]


def test_dominance_is_sent_only_when_asked_for(client):
    body = client.post(f"{API}/utterances", json={"phonemes": "M AA", "audio": {"kind": "none"}})
    assert body.status_code == 200
    assert body.json().get("dominance") is None


def test_each_phone_dominates_its_group_most_inside_its_own_interval(client):
    response = client.post(f"{API}/utterances", json={"phonemes": "M AA T", "dominance": True,
                                                      "audio": {"kind": "none"}})
    assert response.status_code == 200
    body = response.json()
    dominance, phones, n = body["dominance"], body["phones"], body["n_frames"]
    assert dominance["parameters"]["velum_opening"] == "velum"
    assert set(dominance["parameters"]) == set(body["tracks"])
    assert set(dominance["parameters"].values()) == set(dominance["groups"])
    rate = body["rate_hz"]
    for group, curves in dominance["groups"].items():
        assert len(curves) == len(phones), group
        for k, (phone, curve) in enumerate(zip(phones, curves, strict=True)):
            assert len(curve) == n
            assert min(curve) >= 0.0
            if phone["symbol"] == "sil":
                continue
            # Each curve peaks at its phone's centre: inside the phone, give or take a frame.
            peak_s = max(range(n), key=curve.__getitem__) / rate
            assert phone["start_s"] - 1 / rate <= peak_s <= phone["end_s"] + 1 / rate, \
                f"{group}, phone {k} ({phone['symbol']}) peaks at {peak_s} s"
    # /m/ closes the lips: it dominates lip closure more than /a/ does at its own centre.
    m = next(k for k, p in enumerate(phones) if p["symbol"] == "M")
    a = next(k for k, p in enumerate(phones) if p["symbol"] == "AA")
    closure = dominance["groups"]["lip_closure"]
    assert max(closure[m]) > max(closure[a])
