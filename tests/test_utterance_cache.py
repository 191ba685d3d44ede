"""The utterance cache in the database: chosen by the settings, written by the compute worker
that makes an utterance, read back by the route with no synthesis, and its audio served whole or
by byte range from the table (tests/test_two_servers_postgres.py shares it between servers)."""

import pytest
from sqlalchemy import select
from sqlalchemy.orm import Session

from glasshead.api.routes.utterances import byte_range_response
from glasshead.settings import Settings
from glasshead.store.db import get_engine
from glasshead.store.utterance_cache import CachedUtterance

API = "/api/v1"


@pytest.mark.parametrize(("url", "setting", "kind"), [
    ("sqlite:///var/x.sqlite3", "auto", "directory"),
    ("postgresql+psycopg://u@db/glasshead", "auto", "database"),
    ("postgresql+psycopg://u@db/glasshead", "directory", "directory"),
    ("sqlite:///var/x.sqlite3", "database", "database"),
])
def test_the_cache_is_the_database_on_postgresql_unless_a_setting_says_otherwise(url, setting,
                                                                                 kind):
    assert Settings(database_url=url, utterance_cache=setting).utterance_cache_kind == kind


@pytest.fixture
def client(built_assets, start_app, tmp_path, monkeypatch):
    monkeypatch.setenv("GLASSHEAD_UTTERANCE_CACHE", "database")
    monkeypatch.setenv("GLASSHEAD_SPEECH_CACHE_DIR", str(tmp_path / "utterances"))
    return start_app(built_assets)[1]


def test_an_utterance_is_kept_in_the_table_and_answered_from_it_without_a_synthesis(
        client, tmp_path):
    pool = client.app.state.compute.pool
    body = {"text": "sip", "audio": {"kind": "lowpass", "cutoff_hz": 800}}
    made = client.post(f"{API}/utterances", json=body)
    assert made.status_code == 200, made.text
    tasks = pool.tasks
    with Session(get_engine()) as session:
        row = session.scalars(select(CachedUtterance)).one()
    assert row.id == made.json()["id"] and row.answer == made.content
    assert row.wav[:4] == b"RIFF"
    again = client.post(f"{API}/utterances", json=body)
    assert again.content == made.content and pool.tasks == tasks  # no worker was asked
    audio = client.get(made.json()["audio_url"])
    assert audio.status_code == 200 and audio.content == row.wav
    assert audio.headers["content-type"] == "audio/wav"
    assert audio.headers["accept-ranges"] == "bytes"
    assert not (tmp_path / "utterances").exists()


def test_audio_not_in_the_table_is_404(client):
    assert client.get(f"{API}/utterances/{'0' * 24}/audio.wav").status_code == 404
    assert client.get(f"{API}/utterances/not-an-id/audio.wav").status_code == 404


@pytest.mark.parametrize(("header", "status", "body", "content_range"), [
    (None, 200, b"0123456789", None),
    ("bytes=2-5", 206, b"2345", "bytes 2-5/10"),
    ("bytes=7-", 206, b"789", "bytes 7-9/10"),
    ("bytes=-3", 206, b"789", "bytes 7-9/10"),
    ("bytes=8-100", 206, b"89", "bytes 8-9/10"),
    ("bytes=5-2", 200, b"0123456789", None),  # not a valid range: ignored
    ("bytes=0-1,4-5", 200, b"0123456789", None),  # several ranges: the whole
    ("items=0-1", 200, b"0123456789", None),
])
def test_a_byte_range_is_answered_206_and_anything_else_whole(header, status, body,
                                                              content_range):
    response = byte_range_response(b"0123456789", "audio/wav", header)
    assert response.status_code == status and response.body == body
    assert response.headers.get("content-range") == content_range


def test_a_range_past_the_end_is_416_naming_the_size():
    from fastapi import HTTPException

    with pytest.raises(HTTPException) as refused:
        byte_range_response(b"0123456789", "audio/wav", "bytes=10-")
    assert refused.value.status_code == 416
    assert refused.value.headers["Content-Range"] == "bytes */10"
