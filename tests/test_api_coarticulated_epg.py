"""A recording compared phone by phone with the head saying its own phones on its own timing
(POST /epg/recordings/{id}/coarticulated, then /compare with the phones), on real engassim takes."""

import json

import numpy as np
import pytest

from accounts_support import signed_in
from glasshead.epg.formats import rows_to_frame
from glasshead.epg.indices import centre_of_gravity
from glasshead.vectors.sources import emur_path

API = "/api/v1"


@pytest.fixture(scope="module")
def segments():
    return json.loads(emur_path().read_bytes())["segments"]


@pytest.fixture
def client(start_app):
    return signed_in(start_app()[1], "clinician")


def upload(client, segment) -> int:
    response = client.post(f"{API}/epg/recordings",
                           json={"format": "emur-json", "content": segment})
    assert response.status_code == 201, response.text
    return response.json()["recordings"][0]["id"]


def cog(rows_list) -> np.ndarray:
    return centre_of_gravity(np.stack([rows_to_frame(rows, i) for i, rows in enumerate(rows_list)]))


def test_the_head_says_s_then_k_on_the_takes_clock_and_moves_back_as_the_speaker_does(
        client, segments):
    segment = segments[0]  # sp1bescan, s->k
    rid = upload(client, segment)
    response = client.post(f"{API}/epg/recordings/{rid}/coarticulated", json={})
    assert response.status_code == 200, response.text
    said = response.json()
    n = len(segment["frames"])
    assert [p["symbol"] for p in said["phones"]] == ["S", "K"]
    assert said["boundary_source"] == "centre of gravity"
    assert len(said["frames"]) == len(said["t_s"]) == n and said["t_s"][0] == 0.0
    first, second = said["phones"]
    assert first["start_s"] == 0.0 and first["end_s"] == second["start_s"] < second["end_s"]
    assert second["end_s"] > said["t_s"][-1]
    times = np.asarray(said["t_s"])
    in_s, in_k = times < first["end_s"], times >= second["start_s"]
    # The boundary is where the speaker's contact has moved back: the take's centre of gravity
    # (rows from the back) is further forward in the /s/ frames than in the /k/ frames, and the
    # head's follows the same way.
    real = cog([f["rows"] for f in segment["frames"]])
    head = cog(said["frames"])
    assert real[in_s].mean() > real[in_k].mean() + 1.0, (real[in_s].mean(), real[in_k].mean())
    assert head[in_s].mean() > head[in_k].mean(), (head[in_s].mean(), head[in_k].mean())
    assert said["label"].startswith("/s/ /k/ said as in")


def test_each_phone_is_scored_against_the_same_phone_not_one_static_target(client, segments):
    segment = segments[0]
    rid = upload(client, segment)
    said = client.post(f"{API}/epg/recordings/{rid}/coarticulated", json={}).json()
    reference = {"label": said["label"], "frames": said["frames"], "t_s": said["t_s"],
                 "phones": [{k: p[k] for k in ("symbol", "ipa", "start_s", "end_s")}
                            for p in said["phones"]]}
    report = client.post(f"{API}/epg/recordings/{rid}/compare",
                         json={"reference": reference}).json()
    scores = report["phones"]
    assert [(s["symbol"], s["ipa"]) for s in scores] == [("S", "s"), ("K", "k")]
    assert sum(s["frames"] for s in scores) == len(segment["frames"])
    kappa = np.asarray(report["kappa"])
    times = np.asarray(said["t_s"])
    first = scores[0]
    assert first["mean_kappa"] == pytest.approx(kappa[times < first["end_s"]].mean(), abs=1e-12)
    assert report["summary"]["phones"]["phones_scored"] == 2
    assert report["summary"]["phones"]["mean_kappa"] == pytest.approx(
        np.mean([s["mean_kappa"] for s in scores]), abs=1e-12)
    # The /s/ frames against the head's /s/ agree better than against the static /k/ target.
    k_target = client.get(f"{API}/phonemes/K").json()["epg"]["rows"]
    static = client.post(f"{API}/epg/recordings/{rid}/compare",
                         json={"reference": {"frames": [k_target]}}).json()
    s_frames = times < first["end_s"]
    assert first["mean_kappa"] > np.mean(np.asarray(static["kappa"])[s_frames]) + 0.1
    # Without phones the report has none.
    assert static["phones"] is None and "phones" not in static["summary"]


def test_given_phones_and_boundaries_are_used_as_sent(client, segments):
    rid = upload(client, segments[0])
    said = client.post(f"{API}/epg/recordings/{rid}/coarticulated",
                       json={"phones": ["ʃ", "g"], "boundaries_s": [0.1]}).json()
    assert [p["symbol"] for p in said["phones"]] == ["SH", "G"]
    assert said["boundary_source"] == "given" and said["phones"][0]["end_s"] == 0.1
    three = client.post(f"{API}/epg/recordings/{rid}/coarticulated",
                        json={"phones": ["AH", "S", "K"]}).json()
    assert three["boundary_source"] == "even split" and len(three["phones"]) == 3


@pytest.mark.parametrize("body, field", [
    ({"phones": ["s", "qq"]}, "phones[1]"),
    ({"phones": []}, "phones"),
    ({"phones": ["s", "k"], "boundaries_s": [0.1, 0.2]}, "boundaries_s"),
    ({"phones": ["s", "k"], "boundaries_s": [5.0]}, "boundaries_s"),
    ({"phones": ["s", "k"], "boundaries_s": [0.0]}, "boundaries_s"),
])
def test_bad_phones_or_boundaries_get_a_422_naming_them(client, segments, body, field):
    rid = upload(client, segments[0])
    response = client.post(f"{API}/epg/recordings/{rid}/coarticulated", json=body)
    assert response.status_code == 422, response.text
    assert field in json.dumps(response.json()["detail"]), response.text


def test_a_recording_without_a_label_asks_for_its_phones_and_a_missing_one_is_404(client):
    rows = ["0" * 8] * 8
    rid = upload(client, {"frames": [{"t_ms": 5.0 * i, "rows": rows} for i in range(4)]})
    response = client.post(f"{API}/epg/recordings/{rid}/coarticulated", json={})
    assert response.status_code == 422 and "send them as phones" in response.json()["detail"]
    missing = client.post(f"{API}/epg/recordings/999999/coarticulated", json={})
    assert missing.status_code == 404
    unknown = client.post(f"{API}/epg/recordings/{rid}/coarticulated", json={"voice": "x"})
    assert unknown.status_code == 422


def test_a_recording_spanning_more_than_a_minute_is_refused_before_any_work(client):
    rows = ["0" * 8] * 8
    rid = upload(client, {"label": "s->k", "frames": [{"t_ms": t, "rows": rows}
                                                      for t in (0.0, 5.0, 90_000.0)]})
    response = client.post(f"{API}/epg/recordings/{rid}/coarticulated", json={})
    assert response.status_code == 422
    assert "at most 60 s" in response.json()["detail"], response.text
