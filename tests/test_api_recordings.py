"""EPG recordings over HTTP: import, playback data, export, bad uploads, comparison and plots."""

import base64
import json
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from accounts_support import signed_in
from glasshead.api.routes import recordings
from glasshead.epg.formats import CSV_ELECTRODES, CSV_MAGIC
from glasshead.vectors.sources import emur_path

API = "/api/v1"


@pytest.fixture
def client(start_app):
    """The app on a fresh SQLite file, migrated at start-up, with an admin signed in."""
    return signed_in(start_app()[1], "admin")


@pytest.fixture(scope="module")
def emur_bytes():
    return emur_path().read_bytes()


def one_segment(emur_bytes, index=0) -> dict:
    return json.loads(emur_bytes)["segments"][index]


def count(client) -> int:
    return client.get(f"{API}/epg/recordings").json()["total"]


def csv_text(rows):
    header = ",".join(["t_s", *CSV_ELECTRODES])
    return "\n".join([CSV_MAGIC, header, *rows]) + "\n"


def test_uploading_the_emur_file_stores_one_recording_per_segment(client, emur_bytes):
    response = client.post(f"{API}/epg/recordings",
                           files={"file": ("engassim.json", emur_bytes, "application/json")})
    assert response.status_code == 201
    created = response.json()["recordings"]
    assert len(created) == 32 == count(client)
    assert sum(r["n_frames"] for r in created) == 1421
    first = created[0]
    assert first["name"] == "sp1bescan s->k" and first["source_format"] == "emur-json"
    # Times in s from the file's ms (a division that rounds in the last bit): within 1 ns.
    assert first["frame_rate_hz"] == pytest.approx(200.0, rel=1e-9)
    assert first["start_s"] == pytest.approx(155.965, abs=1e-9)
    assert first["duration_s"] == pytest.approx(0.255, abs=1e-9)


def test_a_recording_gives_each_frame_with_its_own_time_for_playback(client, emur_bytes):
    segment = one_segment(emur_bytes, 4)
    created = client.post(f"{API}/epg/recordings",
                          json={"format": "emur-json", "content": segment}).json()
    detail = client.get(f"{API}/epg/recordings/{created['recordings'][0]['id']}").json()
    assert detail["frame_rate_hz"] == pytest.approx(200.0, rel=1e-9)
    assert detail["n_frames"] == len(segment["frames"]) == len(detail["t_s"])
    # s from the file's ms: within 1 ns.
    assert detail["t_s"] == pytest.approx([f["t_ms"] / 1000 for f in segment["frames"]], abs=1e-9)
    assert detail["frames"] == [f["rows"] for f in segment["frames"]]
    assert detail["meta"]["word"] == segment["word"]


@pytest.mark.parametrize("fmt", ["csv", "emur-json", "ssff"])
def test_an_exported_recording_imports_back_identical(client, emur_bytes, fmt):
    segment = one_segment(emur_bytes, 9)
    first = client.post(f"{API}/epg/recordings", json={"format": "emur-json",
                                                       "content": segment}).json()
    rid = first["recordings"][0]["id"]
    exported = client.get(f"{API}/epg/recordings/{rid}/export", params={"format": fmt})
    assert exported.status_code == 200
    assert "attachment" in exported.headers["content-disposition"]
    again = client.post(f"{API}/epg/recordings",
                        files={"file": (f"take.{ {'emur-json': 'json'}.get(fmt, fmt)}",
                                        exported.content)},
                        data={"format": fmt}).json()["recordings"][0]
    a = client.get(f"{API}/epg/recordings/{rid}").json()
    b = client.get(f"{API}/epg/recordings/{again['id']}").json()
    assert b["frames"] == a["frames"] and b["t_s"] == pytest.approx(a["t_s"], abs=1e-9)
    assert (b["name"], b["meta"]) == (a["name"], a["meta"])
    assert b["frame_rate_hz"] == pytest.approx(a["frame_rate_hz"], rel=1e-9)  # from exported times
    assert b["source_format"] == fmt


def test_csv_and_ssff_can_be_sent_as_json_bodies(client):
    zeros = ",".join(["0"] * 62)
    text = csv_text([f"0.0,{zeros}", f"0.01,{zeros}"])
    made = client.post(f"{API}/epg/recordings", json={"format": "csv", "content": text,
                                                     "name": "rest"})
    assert made.status_code == 201
    assert made.json()["recordings"][0]["frame_rate_hz"] == pytest.approx(100.0, rel=1e-9)
    rid = made.json()["recordings"][0]["id"]
    ssff = client.get(f"{API}/epg/recordings/{rid}/export", params={"format": "ssff"}).content
    again = client.post(f"{API}/epg/recordings", json={
        "format": "ssff", "content_base64": base64.b64encode(ssff).decode()})
    assert again.status_code == 201 and again.json()["recordings"][0]["name"] == "rest"


@pytest.mark.parametrize("rows, message", [
    # wrong number of electrodes
    ([f"0.0,{','.join(['0'] * 61)}"],
     "frame 0, field electrodes: line 3: expected 62 electrodes, got 61"),
    # a value that is not 0 or 1
    ([f"0.0,{','.join(['0'] * 62)}", f"0.01,{','.join(['0'] * 40 + ['2'] + ['0'] * 21)}"],
     "frame 1, field R6C3: line 4: value '2' is not 0 or 1"),
    # times that do not increase
    ([f"0.02,{','.join(['0'] * 62)}", f"0.01,{','.join(['0'] * 62)}"],
     "frame 1, field t_s: time 0.01 s is not after the previous frame's 0.02 s"),
])
def test_a_bad_csv_upload_gets_422_naming_frame_and_field_and_stores_nothing(client, rows,
                                                                             message):
    response = client.post(f"{API}/epg/recordings",
                           files={"file": ("take.csv", csv_text(rows).encode(), "text/csv")})
    assert response.status_code == 422
    assert response.json()["detail"] == message
    assert count(client) == 0


def test_one_bad_frame_in_the_last_segment_keeps_the_whole_file_out(client, emur_bytes):
    document = json.loads(emur_bytes)
    frame = document["segments"][-1]["frames"][7]
    frame["rows"] = frame["rows"][:7]
    response = client.post(f"{API}/epg/recordings",
                           files={"file": ("bad.json", json.dumps(document).encode())})
    assert response.status_code == 422
    assert response.json()["detail"].startswith("segment 31, frame 7, field rows:")
    assert count(client) == 0


def test_uploads_over_the_size_limit_are_refused_with_413(client, monkeypatch):
    monkeypatch.setattr(recordings, "MAX_UPLOAD_BYTES", 1000)
    big = csv_text([f"{i / 100},{','.join(['0'] * 62)}" for i in range(20)]).encode()
    assert client.post(f"{API}/epg/recordings", files={"file": ("big.csv", big)}).status_code == 413
    assert client.post(f"{API}/epg/recordings",
                       json={"format": "csv", "content": big.decode()}).status_code == 413
    assert count(client) == 0


def test_an_upload_that_is_neither_a_file_nor_json_gets_415(client):
    response = client.post(f"{API}/epg/recordings", content=b"0,1",
                           headers={"content-type": "text/plain"})
    assert response.status_code == 415


def test_a_json_body_needs_exactly_one_content_field(client):
    response = client.post(f"{API}/epg/recordings", json={"format": "csv"})
    assert response.status_code == 422 and "content" in response.json()["detail"]
    response = client.post(f"{API}/epg/recordings", json={"format": "mp3", "content": "x"})
    assert response.status_code == 422 and "field format" in response.json()["detail"]


def test_listing_pages_newest_first_and_delete_removes(client, emur_bytes):
    client.post(f"{API}/epg/recordings", files={"file": ("e.json", emur_bytes)})
    page = client.get(f"{API}/epg/recordings", params={"offset": 2, "limit": 5}).json()
    assert page["total"] == 32 and len(page["recordings"]) == 5
    ids = [r["id"] for r in page["recordings"]]
    assert ids == sorted(ids, reverse=True) and ids[0] == 30
    assert client.delete(f"{API}/epg/recordings/{ids[0]}").status_code == 204
    assert client.get(f"{API}/epg/recordings/{ids[0]}").status_code == 404
    assert count(client) == 31


def test_ssff_export_of_unevenly_timed_frames_is_a_409(client):
    zeros = ",".join(["0"] * 62)
    text = csv_text([f"0.0,{zeros}", f"0.01,{zeros}", f"0.02,{zeros}", f"0.035,{zeros}"])
    rid = client.post(f"{API}/epg/recordings", json={"format": "csv", "content": text}
                      ).json()["recordings"][0]["id"]
    response = client.get(f"{API}/epg/recordings/{rid}/export", params={"format": "ssff"})
    assert response.status_code == 409 and "frame 3, field t_s" in response.json()["detail"]


def test_comparing_with_a_static_target_reports_agreement_and_index_differences(client,
                                                                                emur_bytes):
    segment = one_segment(emur_bytes, 0)
    rid = client.post(f"{API}/epg/recordings", json={"format": "emur-json", "content": segment}
                      ).json()["recordings"][0]["id"]
    target = segment["frames"][20]["rows"]
    response = client.post(f"{API}/epg/recordings/{rid}/compare",
                           json={"reference": {"label": "pose: s", "frames": [target]}})
    assert response.status_code == 200
    report = response.json()
    n = len(segment["frames"])
    assert report["reference_label"] == "pose: s" and len(report["agreement"]) == n
    # Identical frames: agreement 62/62 and a cog difference of nothing, up to rounding.
    assert report["agreement"][20] == pytest.approx(1.0, abs=1e-12)
    assert report["index_difference"]["cog"][20] == pytest.approx(0.0, abs=1e-12)
    r1 = target[0]  # identical frames: each R1 electrode is '1' (both on) or '0' (both off)
    assert report["codes"][20][0] == "9" + r1[1:7] + "9"
    assert report["electrode_agreement"][0][0] is None
    assert 0 < report["summary"]["mean_agreement"] < 1


def test_comparing_two_recordings_and_plotting_them(client, emur_bytes):
    client.post(f"{API}/epg/recordings", files={"file": ("e.json", emur_bytes)})
    report = client.post(f"{API}/epg/recordings/1/compare",
                         json={"reference": {"recording_id": 2}}).json()
    assert report["reference_label"] == "sp1bescombe s->k"
    plot = client.post(f"{API}/epg/recordings/1/compare/plot",
                       json={"reference": {"recording_id": 2}},
                       params={"panels": ["cog", "anteriority"]})
    assert plot.headers["content-type"] == "image/svg+xml"
    panels = ET.fromstring(plot.text).findall("{http://www.w3.org/2000/svg}g")
    assert [p.get("data-index") for p in panels] == ["cog", "anteriority"]
    assert all(len(p.findall("{http://www.w3.org/2000/svg}polyline")) == 2 for p in panels)
    alone = client.get(f"{API}/epg/recordings/1/plot")
    assert alone.status_code == 200 and alone.text.count("<polyline") == 5
    assert client.get(f"{API}/epg/recordings/1/plot", params={"panels": "pitch"}
                      ).status_code == 422
    missing = client.post(f"{API}/epg/recordings/1/compare",
                          json={"reference": {"recording_id": 999}})
    assert missing.status_code == 404


def test_a_reference_made_from_a_saved_pose_is_labelled_with_the_pose_name(client,
                                                                           emur_bytes):
    segment = one_segment(emur_bytes, 0)
    rid = client.post(f"{API}/epg/recordings", json={"format": "emur-json", "content": segment}
                      ).json()["recordings"][0]["id"]
    pose = client.post(f"{API}/poses", json={"name": "s target", "params": {"tip_height": 3.0}}
                       ).json()
    body = {"reference": {"pose_id": pose["id"], "frames": [segment["frames"][0]["rows"]]}}
    report = client.post(f"{API}/epg/recordings/{rid}/compare", json=body).json()
    assert report["reference_label"] == "s target"
    assert report["agreement"][0] == pytest.approx(1.0, abs=1e-12)  # the same frame
    body["reference"]["pose_id"] = pose["id"] + 1
    assert client.post(f"{API}/epg/recordings/{rid}/compare", json=body).status_code == 404


def test_a_bad_reference_frame_is_named_in_the_error(client, emur_bytes):
    rid = client.post(f"{API}/epg/recordings", json={"format": "emur-json",
                                                     "content": one_segment(emur_bytes)}
                      ).json()["recordings"][0]["id"]
    bad = [["00000000"] * 8, ["00000000"] * 7 + ["0000000"]]
    response = client.post(f"{API}/epg/recordings/{rid}/compare",
                           json={"reference": {"frames": bad, "t_s": [0.0, 0.1]}})
    assert response.status_code == 422
    assert response.json()["detail"] == \
        "reference: frame 1, field rows[7]: expected 8 contacts, got 7"


def test_indices_of_posted_frames_match_the_recording_indices(client, emur_bytes):
    segment = one_segment(emur_bytes, 0)
    rid = client.post(f"{API}/epg/recordings", json={"format": "emur-json", "content": segment}
                      ).json()["recordings"][0]["id"]
    tracks = client.get(f"{API}/epg/recordings/{rid}/indices").json()
    posted = client.post(f"{API}/epg/indices",
                         json={"frames": [f["rows"] for f in segment["frames"]]}).json()
    assert posted["names"][:2] == ["contacts", "percent"]
    # The same frames through the same kernel: equal up to rounding (relative 1e-12).
    assert sorted(posted["indices"]) == sorted(tracks["indices"])
    for name, values in tracks["indices"].items():
        np.testing.assert_allclose(posted["indices"][name], values, rtol=1e-12, atol=1e-12,
                                   err_msg=name)
    assert tracks["indices"]["cog"][0] == pytest.approx(39.5 / 15, rel=1e-12)  # test_epg_indices


def test_posting_a_frame_with_a_contact_in_a_missing_r1_corner_gets_422(client):
    response = client.post(f"{API}/epg/indices",
                           json={"frames": [["00000001"] + ["00000000"] * 7]})
    assert response.status_code == 422
    assert response.json()["detail"].startswith("frame 0, field rows[0]: R1 has no electrode")


def test_the_openapi_document_lists_the_epg_operations(client):
    document = client.get(f"{API}/openapi.json").json()
    ids = {op["operationId"] for path in document["paths"].values() for op in path.values()}
    assert {"createRecordings", "listRecordings", "getRecording", "getRecordingIndices",
            "exportRecording", "deleteRecording", "compareRecording", "plotComparison",
            "plotRecording", "computeEpgIndices"} <= ids
    body = document["paths"][f"{API}/epg/recordings"]["post"]["requestBody"]["content"]
    assert {"multipart/form-data", "application/json"} <= set(body)


def test_the_comparison_reports_kappa_that_an_empty_target_cannot_win(client, emur_bytes):
    segment = one_segment(emur_bytes, 0)
    rid = client.post(f"{API}/epg/recordings", json={"format": "emur-json", "content": segment}
                      ).json()["recordings"][0]["id"]
    empty = ["0" * 8] * 8
    report = client.post(f"{API}/epg/recordings/{rid}/compare",
                         json={"reference": {"frames": [empty]}}).json()
    n = len(segment["frames"])
    assert len(report["kappa"]) == n and len(report["contact_agreement"]) == n
    assert report["summary"]["mean_agreement"] > 0.5
    assert report["summary"]["mean_kappa"] == pytest.approx(0.0, abs=1e-12)
    assert report["summary"]["mean_contact_agreement"] == pytest.approx(0.0, abs=1e-12)
    same = client.post(f"{API}/epg/recordings/{rid}/compare",
                       json={"reference": {"recording_id": rid}}).json()
    assert same["kappa"] == pytest.approx([1.0] * n, abs=1e-12)
