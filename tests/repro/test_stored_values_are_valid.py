"""Values that were stored although nothing can use them are refused on import.

A CSV recording with ``# start_s: nan`` or ``# end_s: inf`` was stored as NaN or Infinity, and its
emuR export was then JSON that no parser reads; an SSFF ``Record_Freq 1e-300`` was accepted. And
every export must import again under the upload limit, or be refused saying why.
"""

import json

import numpy as np
import pytest

from accounts_support import signed_in
from glasshead.api.routes import recordings
from glasshead.epg import formats
from glasshead.epg.sequence import MAX_FRAMES, make_sequence
from glasshead.epg.ssff import SSFF_END, SSFF_MAGIC

API = "/api/v1"
ZEROS = ",".join(["0"] * 62)


@pytest.fixture
def client(start_app):
    return signed_in(start_app()[1], "admin")


def csv_with(*meta_lines: str) -> str:
    header = ",".join(["t_s", *formats.CSV_ELECTRODES])
    return "\n".join([formats.CSV_MAGIC, *meta_lines, header, f"0.0,{ZEROS}", f"0.01,{ZEROS}"])


def ssff_with(rate: str) -> bytes:
    header = "\n".join([SSFF_MAGIC, "Machine IBM-PC", f"Record_Freq {rate}", "Start_Time 0.0",
                        "Column epg BYTE 8", SSFF_END]) + "\n"
    return header.encode() + bytes(16)


def count(client) -> int:
    return client.get(f"{API}/epg/recordings").json()["total"]


@pytest.mark.parametrize("line, field", [
    ("# start_s: nan", "start_s"),
    ("# end_s: inf", "end_s"),
    ("# end_s: -Infinity", "end_s"),
    ("# frame_rate_hz: nan", "frame_rate_hz"),
    ("# frame_rate_hz: 1e-300", "frame_rate_hz"),
])
def test_a_csv_recording_with_a_value_that_is_not_a_finite_number_is_refused(client, line, field):
    response = client.post(f"{API}/epg/recordings", json={"format": "csv",
                                                          "content": csv_with(line)})
    assert response.status_code == 422, response.text
    assert f"field {field}" in response.json()["detail"]
    assert count(client) == 0


def test_a_csv_recording_with_finite_start_and_end_is_stored_and_exports_valid_json(client):
    response = client.post(f"{API}/epg/recordings", json={
        "format": "csv", "content": csv_with("# start_s: 1.5", "# end_s: 2.25")})
    assert response.status_code == 201, response.text
    record = response.json()["recordings"][0]
    exported = client.get(f"{API}/epg/recordings/{record['id']}/export?format=emur-json")
    # The strict parser refuses NaN and Infinity, which the export once held.
    segment = json.loads(exported.content, parse_constant=lambda name: pytest.fail(name))
    assert segment["segments"][0]["start_ms"] == pytest.approx(1500.0, abs=1e-9)
    assert segment["segments"][0]["end_ms"] == pytest.approx(2250.0, abs=1e-9)


@pytest.mark.parametrize("rate", ["1e-300", "0.5", "1e6", "nan"])
def test_an_ssff_record_freq_outside_1_to_100000_hz_is_refused(client, rate):
    response = client.post(f"{API}/epg/recordings",
                           files={"file": ("bad.epg", ssff_with(rate))})
    assert response.status_code == 422, response.text
    assert "Record_Freq" in response.json()["detail"]
    assert count(client) == 0


@pytest.mark.parametrize("rate", ["1", "200", "100000"])
def test_an_ssff_record_freq_within_the_range_is_stored(client, rate):
    response = client.post(f"{API}/epg/recordings",
                           files={"file": ("good.epg", ssff_with(rate))})
    assert response.status_code == 201, response.text
    assert response.json()["recordings"][0]["frame_rate_hz"] == pytest.approx(float(rate),
                                                                               rel=1e-12)


def test_the_largest_recording_exports_in_every_format_within_the_upload_limit():
    frames = np.ones((MAX_FRAMES, 8, 8), dtype=np.uint8)
    frames[:, 0, [0, 7]] = 0  # R1 has no electrode in columns 1 and 8
    t_s = 123456.789012345 + np.arange(MAX_FRAMES) / 199.99
    meta = {"label": "l" * 200, "utterance": "u" * 200, "word": "w" * 200,
            "start_s": 123456.7891234567, "end_s": 123999.123456789}
    sequence = make_sequence(frames, t_s, "n" * 200, 199.99, meta)
    for fmt in formats.FORMATS:
        content = formats.serialise([sequence], fmt)
        assert len(content) <= recordings.MAX_UPLOAD_BYTES, fmt
    # The emuR JSON sent as a string inside a JSON body, its quotes escaped, fits too.
    as_string = json.dumps({"format": "emur-json",
                            "content": formats.serialise([sequence], "emur-json").decode()})
    assert len(as_string) <= recordings.MAX_UPLOAD_BYTES


def test_an_export_larger_than_the_upload_limit_is_refused_naming_its_size(client, monkeypatch):
    response = client.post(f"{API}/epg/recordings", json={"format": "csv",
                                                          "content": csv_with("# note: x")})
    recording_id = response.json()["recordings"][0]["id"]
    monkeypatch.setattr(recordings, "MAX_UPLOAD_BYTES", 100)
    response = client.get(f"{API}/epg/recordings/{recording_id}/export?format=csv")
    assert response.status_code == 409
    detail = response.json()["detail"]
    assert detail.startswith("the csv export is 0.0 MiB, more than the 0 MiB an import takes")
    assert "export as ssff" in detail


def test_an_ssff_export_at_a_rate_the_import_refuses_is_a_409(client):
    # emuR JSON has no frame rate: frames 1 microsecond apart are read as 1 MHz.
    frames = [{"t_ms": i / 1000.0, "rows": ["00000000"] * 8} for i in range(3)]
    response = client.post(f"{API}/epg/recordings",
                           json={"format": "emur-json", "content": {"frames": frames}})
    assert response.status_code == 201, response.text
    record = response.json()["recordings"][0]
    assert record["frame_rate_hz"] == pytest.approx(1e6, rel=1e-6)
    exported = client.get(f"{API}/epg/recordings/{record['id']}/export?format=ssff")
    assert exported.status_code == 409
    assert "between 1 and 100000 Hz" in exported.json()["detail"]
