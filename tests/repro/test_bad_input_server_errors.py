"""Bad input that once answered 500: each now gets a 4xx whose detail names the problem.

Found by schemathesis and by hand-made uploads (ids and offsets beyond 64 bits, emuR JSON nested
1,000 deep or with frames that are not a list, an SSFF column count written with a superscript
digit, a NUL byte in a static path).
"""

import json

import pytest

from accounts_support import signed_in

API = "/api/v1"
BEYOND_INT64 = 2**63  # one more than SQLite's and PostgreSQL's largest integer key


@pytest.fixture
def client(start_app):
    return signed_in(start_app()[1], "admin")


@pytest.mark.parametrize("path", [
    f"{API}/poses/{BEYOND_INT64}",
    f"{API}/epg/recordings/{BEYOND_INT64}",
    f"{API}/epg/recordings/{BEYOND_INT64}/indices",
    f"{API}/epg/recordings/{BEYOND_INT64}/export",
    f"{API}/epg/recordings/{BEYOND_INT64}/plot",
    f"{API}/fits/{BEYOND_INT64}",
])
def test_an_id_beyond_64_bits_is_a_422_naming_the_id(client, path):
    response = client.get(path)
    assert response.status_code == 422, response.text
    assert "id" in response.json()["detail"]


@pytest.mark.parametrize("method, path", [
    ("DELETE", f"{API}/poses/{BEYOND_INT64}"),
    ("DELETE", f"{API}/epg/recordings/{BEYOND_INT64}"),
    ("PATCH", f"{API}/poses/{BEYOND_INT64}"),
])
def test_a_write_to_an_id_beyond_64_bits_is_a_422(client, method, path):
    response = client.request(method, path, json={"name": "x"})
    assert response.status_code == 422, response.text


@pytest.mark.parametrize("route", ["poses", "epg/recordings", "fits"])
def test_an_offset_beyond_64_bits_is_a_422_naming_the_offset(client, route):
    response = client.get(f"{API}/{route}?offset={BEYOND_INT64}")
    assert response.status_code == 422, response.text
    assert "offset" in response.json()["detail"]


@pytest.mark.parametrize("reference", [
    {"recording_id": BEYOND_INT64},
    {"label": "target", "pose_id": BEYOND_INT64, "frames": [["00000000"] * 8]},
])
def test_a_comparison_naming_an_id_beyond_64_bits_is_a_422(client, reference):
    frames = {"format": "emur-json", "content": {"frames": [
        {"t_ms": 0, "rows": ["00000000"] * 8}]}}
    created = client.post(f"{API}/epg/recordings", json=frames)
    assert created.status_code == 201, created.text
    recording = created.json()["recordings"][0]["id"]
    response = client.post(f"{API}/epg/recordings/{recording}/compare",
                           json={"reference": reference})
    assert response.status_code == 422, response.text
    assert "_id" in response.json()["detail"]


def _import(client, content: bytes, fmt: str):
    return client.post(f"{API}/epg/recordings", data={"format": fmt},
                       files={"file": ("upload", content, "application/octet-stream")})


def test_emur_json_nested_a_thousand_deep_is_refused_by_name(client):
    response = _import(client, b"[" * 1000 + b"]" * 1000, "emur-json")
    assert response.status_code == 422, response.text
    assert "nested" in response.json()["detail"]
    assert client.get(f"{API}/epg/recordings").json()["total"] == 0


@pytest.mark.parametrize("frames", [5, None, "frames", {"t_ms": 0}])
def test_emur_json_whose_frames_are_not_a_list_is_refused_by_name(client, frames):
    content = json.dumps({"segments": [{"label": "s", "frames": frames}]}).encode()
    response = _import(client, content, "emur-json")
    assert response.status_code == 422, response.text
    assert "frames" in response.json()["detail"]
    assert client.get(f"{API}/epg/recordings").json()["total"] == 0


def test_an_ssff_column_count_in_a_superscript_digit_is_refused_by_name(client):
    header = ("SSFF -- (c) SHLRC\nMachine IBM-PC\nRecord_Freq 100.0\nStart_Time 0.0\n"
              "Column epg BYTE \u00b2\n-----------------\n")
    response = _import(client, header.encode("latin-1") + bytes(8), "ssff")
    assert response.status_code == 422, response.text
    assert "Column" in response.json()["detail"]


@pytest.mark.parametrize("path", ["/%00", "/assets/build/%00", "/assets/%00x.js",
                                  "/assets/build/manifest.json%00"])
def test_a_nul_byte_in_a_static_path_is_a_404_not_a_server_error(client, path):
    response = client.get(path)
    assert response.status_code in (400, 404), response.text
    assert "detail" in response.json()
