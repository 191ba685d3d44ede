"""Imports with an Idempotency-Key: an upload retried after a lost response is stored once.

Without a key a retried upload was stored twice. POST /epg/recordings and POST /fits now keep
the first answer of a key for 24 h (api/idempotency.py, schema 0004).
"""

import json
from concurrent.futures import ThreadPoolExecutor
from datetime import timedelta

import numpy as np
import pytest
from sqlalchemy import update

from accounts_support import signed_in
from glasshead.api import idempotency
from glasshead.epg import formats
from glasshead.store.base import utc_now
from glasshead.store.db import get_engine
from glasshead.store.idempotency_keys import IdempotencyKey

API = "/api/v1"
ZEROS = ",".join(["0"] * 62)


def csv_text(name: str) -> str:
    header = ",".join(["t_s", *formats.CSV_ELECTRODES])
    return "\n".join([formats.CSV_MAGIC, f"# name: {name}", header, f"0.0,{ZEROS}",
                      f"0.01,{ZEROS}"])


def count(client, route="epg/recordings") -> int:
    return client.get(f"{API}/{route}").json()["total"]


@pytest.fixture
def app_client(start_app):
    app, client = start_app()
    signed_in(client, "admin")
    return app, signed_in(client, "admin")


@pytest.fixture
def client(app_client):
    return app_client[1]


def test_a_retried_recording_upload_with_the_same_key_gets_the_first_answer_and_stores_nothing(
        client):
    headers = {"Idempotency-Key": "6f1c2e52-upload-1"}
    first = client.post(f"{API}/epg/recordings", headers=headers,
                        files={"file": ("take.csv", csv_text("take").encode())})
    assert first.status_code == 201, first.text
    # A client library makes a new multipart boundary for the retry: the upload is the same.
    again = client.post(f"{API}/epg/recordings", headers=headers,
                        files={"file": ("take.csv", csv_text("take").encode())})
    assert again.status_code == 201
    assert again.json() == first.json()
    assert again.headers["Idempotent-Replayed"] == "true"
    assert "Idempotent-Replayed" not in first.headers
    assert count(client) == 1


def test_the_same_key_with_a_different_upload_is_a_422_naming_the_key(client):
    headers = {"Idempotency-Key": "key-7"}
    body = {"format": "csv", "content": csv_text("one")}
    assert client.post(f"{API}/epg/recordings", headers=headers, json=body).status_code == 201
    body["content"] = csv_text("two")
    response = client.post(f"{API}/epg/recordings", headers=headers, json=body)
    assert response.status_code == 422
    assert "Idempotency-Key" in response.json()["detail"] and "key-7" in response.json()["detail"]
    assert count(client) == 1


def test_uploads_without_a_key_or_with_different_keys_are_each_stored(client):
    body = {"format": "csv", "content": csv_text("same")}
    for headers in ({}, {}, {"Idempotency-Key": "a"}, {"Idempotency-Key": "b"}):
        assert client.post(f"{API}/epg/recordings", headers=headers,
                           json=body).status_code == 201
    assert count(client) == 4


def test_a_bad_upload_keeps_no_key_so_its_corrected_retry_is_stored(client):
    headers = {"Idempotency-Key": "fix-and-retry"}
    bad = client.post(f"{API}/epg/recordings", headers=headers,
                      json={"format": "csv", "content": csv_text("x").replace(ZEROS, "2")})
    assert bad.status_code == 422
    good = client.post(f"{API}/epg/recordings", headers=headers,
                       json={"format": "csv", "content": csv_text("x")})
    assert good.status_code == 201 and count(client) == 1


def test_a_key_older_than_24_hours_is_forgotten_and_the_upload_stored_again(client):
    headers = {"Idempotency-Key": "old"}
    body = {"format": "csv", "content": csv_text("old")}
    assert client.post(f"{API}/epg/recordings", headers=headers, json=body).status_code == 201
    long_ago = utc_now() - idempotency.KEEP_FOR - timedelta(minutes=1)
    with get_engine().begin() as connection:
        connection.execute(update(IdempotencyKey).values(created_at=long_ago))
    again = client.post(f"{API}/epg/recordings", headers=headers, json=body)
    assert again.status_code == 201 and "Idempotent-Replayed" not in again.headers
    assert count(client) == 2


def test_concurrent_requests_with_one_key_store_one_recording(client):
    headers = {"Idempotency-Key": "raced"}
    body = {"format": "csv", "content": csv_text("raced")}
    with ThreadPoolExecutor(max_workers=6) as pool:
        answers = list(pool.map(lambda _: client.post(f"{API}/epg/recordings", headers=headers,
                                                      json=body), range(6)))
    assert [a.status_code for a in answers] == [201] * 6
    assert len({json.dumps(a.json(), sort_keys=True) for a in answers}) == 1
    assert count(client) == 1


@pytest.mark.parametrize("key", ["", "x" * 201, "spaced key"])
def test_a_key_that_is_empty_too_long_or_not_printable_ascii_is_a_422(client, key):
    response = client.post(f"{API}/epg/recordings", headers={"Idempotency-Key": key},
                           json={"format": "csv", "content": csv_text("k")})
    assert response.status_code == 422
    assert "Idempotency-Key" in response.json()["detail"]
    assert count(client) == 0


def test_a_retried_fit_upload_with_the_same_key_queues_one_job(app_client, built_assets):
    app, client = app_client
    woken = []
    app.state.fits.wake = lambda: woken.append(True)  # nothing runs: the queue is what is checked
    shapes = json.loads((built_assets / "vtl-observations.json").read_text())["shapes"]
    outline = np.array(next(s for s in shapes if s["name"] == "a")["tongue_outline"])
    content = ("x_mm,y_mm\n" + "".join(f"{x:.4f},{y:.4f}\n" for x, y in outline)).encode()
    headers = {"Idempotency-Key": "fit-1"}

    def upload(max_evals):
        return client.post(f"{API}/fits", headers=headers,
                           data={"kind": "contour", "max_evals": str(max_evals)},
                           files={"file": ("a.csv", content)})

    first, again = upload(400), upload(400)
    assert first.status_code == again.status_code == 202
    assert again.json() == first.json()
    location = f"{API}/fits/{first.json()['id']}"
    assert again.headers["Location"] == first.headers["Location"] == location
    assert len(woken) == 1  # the retry stored nothing and woke no worker
    assert count(client, "fits") == 1
    assert client.get(location).json()["state"] == "queued"
    different = upload(500)
    assert different.status_code == 422 and "fit-1" in different.json()["detail"]
    assert count(client, "fits") == 1
