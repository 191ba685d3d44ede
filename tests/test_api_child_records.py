"""One child's records: the practice CSV for the adults who follow the child, and an admin's
export of everything stored about a child and its deletion, on SQLite and on a real PostgreSQL
server (tests/postgres_support.py)."""

import base64
import csv
import io

import pytest
from fastapi.testclient import TestClient
from sqlalchemy import inspect, text
from sqlalchemy.orm import Session

from glasshead import accounts
from glasshead.epg.formats import CSV_ELECTRODES, CSV_MAGIC
from glasshead.settings import get_settings
from glasshead.store.db import engine_for, get_engine
from wav_support import tone_wav

API = "/api/v1"
PASSWORD = "correct horse battery"
USERS = (("root", "admin"), ("tess", "teacher"), ("cleo", "clinician"), ("ava", "author"))
#: Columns that name a child, table by table: after a deletion none may hold the child's id.
CHILD_COLUMNS = {"children": "id", "practice_records": "child_id", "assignments": "child_id",
                 "child_tokens": "child_id", "epg_recordings": "child_id",
                 "practice_audio": "child_id", "audio_recording_switches": "child_id"}


def add_users(engine) -> None:
    with Session(engine) as session:
        for username, role in USERS:
            accounts.create_user(session, username, PASSWORD, role, username.title())
        session.commit()


def bearer(client, username) -> dict:
    answer = client.post(f"{API}/auth/sessions", json={"username": username,
                                                       "password": PASSWORD})
    assert answer.status_code == 201, answer.text
    return {"Authorization": f"Bearer {answer.json()['token']}"}


def post(client, path, body, headers=None):
    response = client.post(f"{API}/{path}", json=body, headers=headers or {})
    assert response.status_code == 201, response.text
    return response.json()


def add_recording(engine, client, admin, child_id: int) -> int:
    """An EPG recording of three frames imported (with an Idempotency-Key) and given to the
    child; answers its id."""
    contact = ",".join(["1"] * 8 + ["0"] * (len(CSV_ELECTRODES) - 8))
    text_csv = "\n".join([CSV_MAGIC, ",".join(["t_s", *CSV_ELECTRODES]),
                          *(f"{t},{contact}" for t in ("0.0", "0.01", "0.02"))]) + "\n"
    made = client.post(f"{API}/epg/recordings", json={"format": "csv", "content": text_csv,
                                                      "name": "ada-take-1"},
                       headers={**admin, "Idempotency-Key": f"take-of-{child_id}"})
    assert made.status_code == 201, made.text
    recording_id = made.json()["recordings"][0]["id"]
    with engine.begin() as connection:
        connection.execute(text("UPDATE epg_recordings SET child_id = :child WHERE id = :id"),
                           {"child": child_id, "id": recording_id})
    return recording_id


#: What the listening page measured on a go (docs/listening.md): kept with the record.
MEASURED = {"f0": 251.5, "f1": 410.0, "f2": 3050.0, "centroid": None, "verdict": "in",
            "target_vowel": "iy"}


def make_setting(client, admin):
    """Two children in a class, one in another class, a lesson, assignments, practice and a
    child's sign-in; answers (class, ada, bo, lesson)."""
    school_class = post(client, "classes", {"name": "Year 2"}, admin)
    other = post(client, "classes", {"name": "Year 3"}, admin)
    ada = post(client, "children", {"class_id": school_class["id"], "display_name": "Ada",
                                    "avatar": "owl"}, admin)
    bo = post(client, "children", {"class_id": school_class["id"],
                                   "display_name": "=HYPERLINK(1)", "avatar": "frog"}, admin)
    post(client, "children", {"class_id": other["id"], "display_name": "Cy", "avatar": "cat"},
         admin)
    lesson = post(client, "lessons", {"title": "sip, ship", "items": [
        {"target": {"kind": "phoneme", "text": "s"}},
        {"target": {"kind": "word", "text": "ship"}, "speed": 0.5}]}, admin)
    post(client, "assignments", {"lesson_id": lesson["id"], "class_id": school_class["id"]},
         admin)
    post(client, "assignments", {"lesson_id": lesson["id"], "child_id": ada["id"]}, admin)
    post(client, "assignments", {"lesson_id": lesson["id"], "child_id": bo["id"]}, admin)
    for child, index, when, rating in ((ada, 1, "2026-03-02T09:30:00Z", 3),
                                       (ada, 0, "2026-03-01T09:00:00Z", None),
                                       (bo, 0, "2026-03-01T10:00:00Z", 2)):
        post(client, "practice", {"child_id": child["id"], "lesson_id": lesson["id"],
                                  "item_index": index, "practised_at": when, "replays": 2,
                                  **({"rating": rating, "rated_by": "adult",
                                      "measures": MEASURED} if rating else {})},
             admin)
    signed = client.post(f"{API}/auth/child-sessions", json={
        "join_code": school_class["join_code"], "child_id": ada["id"]})
    assert signed.status_code == 201, signed.text
    return school_class, ada, bo, lesson


@pytest.fixture
def sqlite(start_app):
    client = start_app()[1]
    add_users(get_engine())
    return get_engine(), client


@pytest.fixture
def postgres(postgres_server, tmp_path, monkeypatch):
    from glasshead.api.app import create_app

    url = postgres_server.url(postgres_server.create_database())
    monkeypatch.setenv("GLASSHEAD_DATABASE_URL", url)
    monkeypatch.setenv("GLASSHEAD_WEB_DIST_DIR", str(tmp_path / "no-web"))
    get_settings.cache_clear()
    try:
        with TestClient(create_app()) as client:
            add_users(engine_for(url))
            yield engine_for(url), client
    finally:
        get_settings.cache_clear()
        engine_for(url).dispose()


def child_rows(engine, child_id: int) -> dict[str, int]:
    """How many rows of each child-naming table hold ``child_id``."""
    tables = set(inspect(engine).get_table_names())
    counts = {}
    with engine.connect() as connection:
        for table, column in CHILD_COLUMNS.items():
            assert table in tables, f"table {table} missing"
            counts[table] = connection.execute(
                text(f"SELECT count(*) FROM {table} WHERE {column} = :id"),  # noqa: S608
                {"id": child_id}).scalar_one()
    return counts


def test_the_practice_csv_lists_every_go_oldest_first_with_its_target_and_rating(sqlite):
    _, client = sqlite
    admin = bearer(client, "root")
    _, ada, bo, lesson = make_setting(client, admin)
    answer = client.get(f"{API}/children/{ada['id']}/practice.csv", headers=admin)
    assert answer.status_code == 200
    assert answer.headers["content-type"].startswith("text/csv")
    assert f'child-{ada["id"]}-practice.csv' in answer.headers["content-disposition"]
    rows = list(csv.reader(io.StringIO(answer.text)))
    measured = ["f0", "f1", "f2", "f3", "f3_minus_f2", "centroid", "duration_s", "verdict",
                "target_vowel"]
    assert rows[0] == ["practice_id", "child_id", "child", "lesson_id", "lesson", "item_index",
                       "target_kind", "target", "practised_at", "replays", "rating",
                       "rated_by", *(f"measured_{m}" for m in measured)]
    assert [row[5:] for row in rows[1:]] == [
        ["0", "phoneme", "s", "2026-03-01T09:00:00Z", "2", "", "", *[""] * len(measured)],
        ["1", "word", "ship", "2026-03-02T09:30:00Z", "2", "3", "adult",
         "251.5", "410.0", "3050.0", "", "", "", "", "in", "iy"]]
    assert {row[2] for row in rows[1:]} == {"Ada"} and rows[1][4] == lesson["title"]
    bo_rows = list(csv.reader(io.StringIO(
        client.get(f"{API}/children/{bo['id']}/practice.csv", headers=admin).text)))
    assert len(bo_rows) == 2 and bo_rows[1][2] == "'=HYPERLINK(1)"  # never a formula


def test_the_csv_is_refused_without_a_token_to_an_author_and_for_another_adults_child(sqlite):
    _, client = sqlite
    admin = bearer(client, "root")
    _, ada, _, _ = make_setting(client, admin)
    url = f"{API}/children/{ada['id']}/practice.csv"
    assert client.get(url).status_code == 401
    assert client.get(url, headers=bearer(client, "ava")).status_code == 403
    # The class is not the teacher's: the same 404 as a child that does not exist.
    theirs, missing = (client.get(u, headers=bearer(client, "tess"))
                       for u in (url, f"{API}/children/999/practice.csv"))
    assert theirs.status_code == missing.status_code == 404
    assert theirs.json()["detail"].startswith("no child with id")


def test_the_owner_of_the_childs_class_gets_the_csv_and_another_clinician_does_not(sqlite):
    engine, client = sqlite
    admin = bearer(client, "root")
    school_class, ada, _, _ = make_setting(client, admin)
    with engine.begin() as connection:
        connection.execute(text("UPDATE classes SET owner_id = "
                                "(SELECT id FROM users WHERE username = 'tess') WHERE id = :id"),
                           {"id": school_class["id"]})
    url = f"{API}/children/{ada['id']}/practice.csv"
    owner = client.get(url, headers=bearer(client, "tess"))
    assert owner.status_code == 200 and len(owner.text.strip().splitlines()) == 3
    assert client.get(url, headers=bearer(client, "cleo")).status_code == 404


def test_an_admin_export_holds_everything_stored_about_the_child_and_no_token_secret(sqlite):
    engine, client = sqlite
    admin = bearer(client, "root")
    school_class, ada, _, lesson = make_setting(client, admin)
    recording_id = add_recording(engine, client, admin, ada["id"])
    answer = client.get(f"{API}/children/{ada['id']}/export", headers=admin)
    assert answer.status_code == 200
    body = answer.json()
    assert body["export_version"] == 2
    assert body["child"]["display_name"] == "Ada" and body["child"]["avatar"] == "owl"
    assert body["school_class"]["id"] == school_class["id"]
    assert body["school_class"]["join_code"] == school_class["join_code"]
    assert [(a["class_id"], a["child_id"]) for a in body["assignments"]] == [
        (school_class["id"], None), (None, ada["id"])]
    assert [(p["item_index"], p["rating"]) for p in body["practice"]] == [(0, None), (1, 3)]
    assert all(p["child_id"] == ada["id"] and p["lesson_id"] == lesson["id"]
               for p in body["practice"])
    assert len(body["tokens"]) == 1 and set(body["tokens"][0]) == {
        "created_at", "expires_at", "revoked_at"}
    assert "token_sha256" not in answer.text and "sha256" not in answer.text
    [recording] = body["recordings"]
    assert recording["id"] == recording_id and recording["name"] == "ada-take-1"
    assert recording["t_s"] == pytest.approx([0.0, 0.01, 0.02], abs=1e-9)
    # The first 8 electrodes on: the front row's 6 (columns 2 to 7) and 2 of the next row.
    assert recording["frames"][0][:3] == ["01111110", "11000000", "00000000"]
    assert recording["export_url"] == f"/api/v1/epg/recordings/{recording_id}/export"
    assert body["audio"] == [] and body["audio_recording_switches"] == []


def test_the_export_holds_each_kept_attempt_recording_and_every_change_of_its_switch(sqlite):
    _, client = sqlite
    admin = bearer(client, "root")
    _, ada, _, _ = make_setting(client, admin)
    wav = keep_an_attempt(client, admin, ada["id"])
    body = client.get(f"{API}/children/{ada['id']}/export", headers=admin).json()
    [audio] = body["audio"]
    assert base64.b64decode(audio["wav_base64"]) == wav
    assert audio["sample_rate"] == 16_000 and audio["duration_s"] == pytest.approx(0.5)
    assert audio["audio_url"] == f"/api/v1/practice/{audio['practice_id']}/audio"
    assert [(c["enabled"], c["set_by_name"]) for c in body["audio_recording_switches"]] == [
        (True, "Root")]


def keep_an_attempt(client, admin, child_id: int) -> bytes:
    """Recording switched on for the child, and half a second of a tone kept with their newest
    practice record; answers the WAV file."""
    assert client.put(f"{API}/children/{child_id}/audio-recording", json={"enabled": True},
                      headers=admin).status_code == 200
    [newest, *_] = client.get(f"{API}/practice", params={"child_id": child_id},
                              headers=admin).json()["records"]
    wav = tone_wav(16_000, 0.5)
    kept = client.put(f"{API}/practice/{newest['id']}/audio", content=wav,
                      headers={**admin, "Content-Type": "audio/wav"})
    assert kept.status_code == 201, kept.text
    return wav


@pytest.mark.parametrize("username", ["tess", "cleo", "ava"])
def test_only_an_admin_exports_or_deletes_a_child(sqlite, username):
    _, client = sqlite
    admin = bearer(client, "root")
    _, ada, _, _ = make_setting(client, admin)
    other = bearer(client, username)
    for method, path in (("GET", "export"), ("DELETE", "data")):
        url = f"{API}/children/{ada['id']}/{path}"
        assert client.request(method, url).status_code == 401
        assert client.request(method, url, headers=other).status_code == 403
    assert client.get(f"{API}/children/{ada['id']}", headers=admin).status_code == 200


def forget_and_check(engine, client) -> None:
    admin = bearer(client, "root")
    school_class, ada, bo, lesson = make_setting(client, admin)
    add_recording(engine, client, admin, ada["id"])
    keep_an_attempt(client, admin, ada["id"])
    before = child_rows(engine, ada["id"])
    assert before == {"children": 1, "practice_records": 2, "assignments": 1,
                      "child_tokens": 1, "epg_recordings": 1, "practice_audio": 1,
                      "audio_recording_switches": 1}
    url = f"{API}/children/{ada['id']}/data"
    stale = client.delete(url, headers={**admin, "If-Match": f'"child-{ada["id"]}-v9"'})
    assert stale.status_code == 412 and child_rows(engine, ada["id"]) == before
    gone = client.delete(url, headers=admin)
    assert gone.status_code == 200, gone.text
    assert gone.json() == {"child_id": ada["id"], "children": 1, "practice_records": 2,
                           "assignments": 1, "recordings": 1, "practice_audio": 1,
                           "audio_recording_switches": 1, "child_tokens": 1,
                           "idempotency_keys": 1}
    assert set(child_rows(engine, ada["id"]).values()) == {0}
    with engine.connect() as connection:  # nor the import's answer kept for its retries
        assert connection.execute(text("SELECT count(*) FROM idempotency_keys")).scalar_one() == 0
    # The rest of the class is untouched: Bo, the class's assignment, the lesson.
    assert child_rows(engine, bo["id"])["practice_records"] == 1
    assert client.get(f"{API}/classes/{school_class['id']}", headers=admin).status_code == 200
    assert client.get(f"{API}/lessons/{lesson['id']}", headers=admin).status_code == 200
    assert client.get(f"{API}/children/{ada['id']}/export", headers=admin).status_code == 404
    assert client.delete(url, headers=admin).status_code == 404


def test_deleting_a_childs_data_leaves_nothing_about_them_in_any_table_on_sqlite(sqlite):
    forget_and_check(*sqlite)


def test_deleting_a_childs_data_leaves_nothing_about_them_in_any_table_on_postgres(postgres):
    forget_and_check(*postgres)
