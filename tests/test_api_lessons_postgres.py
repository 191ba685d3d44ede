"""Lessons, classes, children, assignments and practice on a real PostgreSQL server (started by
the test, tests/postgres_support.py): the same CRUD, If-Match, ids and starter lessons as on
SQLite (tests/test_api_lessons.py, tests/test_api_classes_practice.py)."""

import pytest
from fastapi.testclient import TestClient

from accounts_support import signed_in
from glasshead.lessons.starter import STARTER_LESSONS
from glasshead.settings import get_settings
from glasshead.store.db import engine_for, upgrade_to_head

API = "/api/v1"
LESSON = {"title": "sip", "items": [{"target": {"kind": "phoneme", "text": "ʃ"}},
                                    {"target": {"kind": "word", "text": "sip"}, "speed": 0.5}]}


@pytest.fixture
def database(postgres_server, tmp_path, monkeypatch):
    """(url, client): the app on a fresh PostgreSQL database, started as the server starts,
    with an admin signed in."""
    from glasshead.api.app import create_app

    url = postgres_server.url(postgres_server.create_database())
    monkeypatch.setenv("GLASSHEAD_DATABASE_URL", url)
    monkeypatch.setenv("GLASSHEAD_WEB_DIST_DIR", str(tmp_path / "no-web"))
    get_settings.cache_clear()
    try:
        with TestClient(create_app()) as client:
            yield url, signed_in(client, "admin")
    finally:
        get_settings.cache_clear()
        engine_for(url).dispose()


def test_postgres_starts_with_the_starter_lessons_once(database):
    url, client = database
    assert client.get(f"{API}/lessons").json()["total"] == len(STARTER_LESSONS)
    upgrade_to_head(engine_for(url))
    lessons = client.get(f"{API}/lessons").json()["lessons"]
    assert [lesson["title"] for lesson in lessons] == [s["title"] for s in STARTER_LESSONS]
    vowels = client.get(f"{API}/lessons/{lessons[-1]['id']}").json()
    assert vowels["items"][0]["target"] == {"kind": "phoneme", "text": "i"}


def test_postgres_lesson_crud_with_if_match_and_ids_never_reused(database):
    _, client = database
    created = client.post(f"{API}/lessons", json=LESSON)
    assert created.status_code == 201
    url, tag = f"{API}/lessons/{created.json()['id']}", created.headers["etag"]
    assert client.patch(url, json={"title": "ship"}, headers={"If-Match": tag}).status_code == 200
    assert client.put(url, json=LESSON, headers={"If-Match": tag}).status_code == 412
    assert client.get(url).json()["items"] == created.json()["items"]
    exported = client.get(f"{url}/export").json()
    imported = client.post(f"{API}/lessons/import", json=exported).json()
    assert client.delete(f"{API}/lessons/{imported['id']}").status_code == 204
    assert client.post(f"{API}/lessons", json=LESSON).json()["id"] == imported["id"] + 1


def test_postgres_class_child_assignment_and_practice_crud_and_cascade(database):
    _, client = database
    school_class = client.post(f"{API}/classes", json={"name": "2A"}).json()
    child = client.post(f"{API}/children", json={"class_id": school_class["id"],
                                                 "display_name": "Ada", "avatar": "owl"}).json()
    assigned = client.post(f"{API}/assignments", json={"lesson_id": 1, "child_id": child["id"]})
    assert assigned.status_code == 201
    practice = client.post(f"{API}/practice", json={"child_id": child["id"], "lesson_id": 1,
                                                    "item_index": 1, "replays": 3,
                                                    "rating": 2, "rated_by": "adult"})
    assert practice.status_code == 201 and practice.json()["replays"] == 3
    assert client.post(f"{API}/practice", json={"child_id": child["id"], "lesson_id": 1,
                                                "item_index": 500}).status_code == 422
    found = client.get(f"{API}/classes", params={"join_code": school_class["join_code"]}).json()
    assert found["classes"][0]["id"] == school_class["id"]
    assert client.delete(f"{API}/classes/{school_class['id']}").status_code == 204
    assert client.get(f"{API}/practice/{practice.json()['id']}").status_code == 404
    assert client.get(f"{API}/assignments").json()["total"] == 0
