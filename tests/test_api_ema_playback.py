"""An EMA recording beside the head (POST /ema/playback) on real HPRC recordings: the answer's
frames, the sensors and flesh points in the project frame, the same scores as
``glasshead compare-ema`` gives the recording alone, and a clear 4xx for every bad upload."""

import pytest

from accounts_support import signed_in
from glasshead.asset_store import AssetStore
from glasshead.ema import read_ema
from glasshead.flesh_point_assets import flesh_point_rig
from glasshead.speech import ema_comparison as cmp

API = "/api/v1"
NAME = "F01_B01_S01_R01_N"


@pytest.fixture(scope="module")
def hprc(data_dir):
    folder = data_dir / "ema" / "hprc"
    return {"csv": (folder / f"{NAME}_ema.csv").read_bytes(),
            "phones": (folder / f"{NAME}_phones.tsv").read_bytes(),
            "path": folder / f"{NAME}_ema.csv"}


@pytest.fixture
def client(start_app):
    return signed_in(start_app()[1], "clinician")


def play(client, csv: bytes, phones: bytes | None, filename=f"{NAME}_ema.csv", **fields):
    files = {"file": (filename, csv)}
    if phones is not None:
        files["labels"] = ("phones.tsv", phones)
    return client.post(f"{API}/ema/playback", files=files, data=fields)


def test_a_real_recording_plays_beside_the_head_with_the_scores_compare_ema_gives_it(
        client, hprc, built_assets):
    answer = play(client, hprc["csv"], hprc["phones"])
    assert answer.status_code == 200, answer.text
    body = answer.json()
    assert body["name"] == NAME and body["source"]["speaker"] == "F01"
    assert body["source"]["frames"] == 262 and body["source"]["sample_rate_hz"] == 100.0
    n = len(body["t_s"])
    assert n == 262 and body["t_s"][0] == 0.0 and body["t_s"][1] == pytest.approx(0.01)
    assert len(body["speech"]) == n and 0 < sum(body["speech"]) < n
    assert body["phones"][0]["symbol"] == "sil" and body["phones"][0]["ipa"] is None
    assert body["phones"][1] == {"symbol": "DH", "ipa": "ð", "start_s": 0.2, "end_s": 0.2399}
    for name in cmp.COMPARED:
        assert len(body["measured"][name]) == n and len(body["head"][name]) == n
    assert {"jaw_opening", "tip_height"} <= set(body["params"])
    assert all(len(track) == n for track in body["params"].values())
    # Both in the project frame, on the head: the speaker's tongue tip (registered) and the
    # head's lie within a few millimetres of each other during the speech.
    assert body["display_registration"]["fitted_on"] == "all of the speech"
    assert body["display_registration"]["rms_mm"] < 6.0
    # The same scores as the comparison of this recording alone (two folds in time).
    store = AssetStore(built_assets)
    alone = cmp.compare([read_ema(hprc["path"])], store.get("phoneme_targets"),
                        flesh_point_rig(store))["recordings"][0]
    scores = body["scores"]
    assert scores["registration"] == "the other half of the recording"
    assert scores["frames"] == alone["frames"]
    for signal, figures in alone["signals"].items():
        assert scores["signals"][signal]["r"] == pytest.approx(figures["r"], abs=1e-9), signal
    assert scores["sensors"]["tongue_tip"]["vertical"]["rmse_mm"] == pytest.approx(
        alone["sensors"]["tongue_tip"]["vertical"]["rmse_mm"], abs=1e-9)


@pytest.mark.parametrize(("change", "status", "words"), [
    (lambda csv, phones: (csv, phones + b"2.9000\t3.1000\tAA1\n"), 422,
     "phones.tsv, line 31: label"),
    (lambda csv, phones: (csv, phones.replace(b"\tDH\n", b"\tQX\n")), 422, "QX"),
    (lambda csv, phones: (csv.replace(b"time_s", b"seconds", 1), phones), 422, "time_s"),
    (lambda csv, phones: (csv, b""), 422, "field labels: the file is empty"),
    (lambda csv, phones: (b"x" * (16 * 1024 * 1024 + 1), phones), 413, "16 MiB limit"),
])
def test_a_bad_upload_is_a_4xx_that_names_the_problem(client, hprc, change, status, words):
    csv, phones = change(hprc["csv"], hprc["phones"])
    answer = play(client, csv, phones)
    assert answer.status_code == status, answer.text
    assert words in answer.json()["detail"]


def test_dropouts_past_50_ms_are_refused_naming_the_sensor_and_missing_labels_the_field(
        client, hprc):
    lines = hprc["csv"].decode().splitlines()
    header = lines[0].split(",")
    column = header.index("TT_x")
    for k in range(50, 60):  # 100 ms of the tongue tip lost
        fields = lines[k].split(",")
        fields[column] = "NaN"
        lines[k] = ",".join(fields)
    answer = play(client, ("\n".join(lines) + "\n").encode(), hprc["phones"])
    assert answer.status_code == 422, answer.text
    assert "TT" in answer.json()["detail"] or "tongue_tip" in answer.json()["detail"]
    missing = play(client, hprc["csv"], None)
    assert missing.status_code == 422 and "labels" in answer.text + missing.text


def test_carstens_channels_must_be_a_json_map_of_channel_numbers(client, hprc):
    answer = play(client, hprc["csv"], hprc["phones"], filename="take.pos", format="ag501",
                  channels="TT=3")
    assert answer.status_code == 422
    assert "field channels: expected a JSON object" in answer.json()["detail"]
