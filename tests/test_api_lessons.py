"""Lessons over HTTP: CRUD, paging, If-Match, 422s that name the field, ids never reused, import
and export, the published JSON Schema, and the starter lessons of a new database."""

import json
from pathlib import Path

import pytest

from accounts_support import signed_in
from glasshead.lessons.schema import json_schema
from glasshead.lessons.starter import STARTER_LESSONS
from glasshead.phonemes import lookup

API = "/api/v1"
SCHEMA_FILE = Path(__file__).parent.parent / "docs" / "lesson.schema.json"
SIP_SHIP = {"title": "sip and ship", "language": "en-GB", "description": "",
            "items": [{"target": {"kind": "phoneme", "text": "s"}, "presentation": "static",
                       "audio": {"kind": "lowpass", "cutoff_hz": 800.0},
                       "views": {"skin_transparency": 0.9, "epg": True}, "speed": 0.25},
                      {"target": {"kind": "word", "text": "ship"}}]}
N_STARTER = len(STARTER_LESSONS)


@pytest.fixture
def client(start_app):
    """The app with an admin signed in (who reaches every record; tests/test_api_roles.py has
    the other roles)."""
    return signed_in(start_app()[1], "admin")


def create(client, lesson=SIP_SHIP):
    response = client.post(f"{API}/lessons", json=lesson)
    assert response.status_code == 201, response.text
    return response


def test_a_lesson_is_created_and_read_back_with_its_items_in_order_and_defaults_filled(client):
    created = create(client)
    lesson = created.json()
    assert created.headers["etag"] == f'"lesson-{lesson["id"]}-v1"'
    again = client.get(f"{API}/lessons/{lesson['id']}")
    assert again.json() == lesson and again.headers["etag"] == created.headers["etag"]
    first, second = lesson["items"]
    assert first["audio"] == {"kind": "lowpass", "cutoff_hz": 800.0, "channels": None}
    assert first["views"]["skin_transparency"] == pytest.approx(0.9, abs=1e-12)
    assert first["views"]["cutaway"] is False and first["speed"] == pytest.approx(0.25)
    assert second["target"] == {"kind": "word", "text": "ship"}
    assert second["presentation"] == "dynamic" and second["speed"] == pytest.approx(1.0)


def test_put_replaces_patch_changes_only_given_fields_and_delete_removes(client):
    lesson = create(client).json()
    url = f"{API}/lessons/{lesson['id']}"
    replaced = client.put(url, json={"title": "t and k",
                                     "items": [{"target": {"kind": "phoneme", "text": "K"}}]})
    assert replaced.status_code == 200 and replaced.headers["etag"].endswith('-v2"')
    assert replaced.json()["language"] == "en-US" and len(replaced.json()["items"]) == 1
    patched = client.patch(url, json={"description": "front, back"}).json()
    assert (patched["title"], patched["description"]) == ("t and k", "front, back")
    assert client.patch(url, json={"title": None}).status_code == 422
    assert client.delete(url).status_code == 204
    assert client.get(url).status_code == 404
    assert client.delete(url).status_code == 404


def test_a_stale_if_match_is_a_412_that_changes_nothing_and_names_the_current_etag(client):
    created = create(client)
    url, first_tag = f"{API}/lessons/{created.json()['id']}", created.headers["etag"]
    mine = client.patch(url, json={"title": "mine"}, headers={"If-Match": first_tag})
    assert mine.status_code == 200
    for method, body in (("PATCH", {"title": "theirs"}), ("PUT", SIP_SHIP), ("DELETE", None)):
        stale = client.request(method, url, json=body, headers={"If-Match": first_tag})
        assert stale.status_code == 412 and stale.headers["etag"].endswith('-v2"')
    assert client.get(url).json()["title"] == "mine"


@pytest.mark.parametrize(("change", "field"), [
    ({"title": ""}, "body.title"),
    ({"language": "english please"}, "body.language"),
    ({"items": []}, "body.items"),
    ({"items": [{"target": {"kind": "phoneme", "text": "Q9"}}]}, "body.items.0.target"),
    ({"items": [{"target": {"kind": "word", "text": "x"}, "speed": 0.05}]},
     "body.items.0.speed"),
    ({"items": [{"target": {"kind": "word", "text": "x"}, "audio": {"kind": "muffled"}}]},
     "body.items.0.audio.kind"),
    ({"items": [{"target": {"kind": "word", "text": "x"}, "views": {"xray": True}}]},
     "body.items.0.views.xray"),
    ({"items": [{"target": {"kind": "word", "text": "x"}, "listen": {"measure": "pitch"}}]},
     "body.items.0.listen"),
    ({"items": [{"target": {"kind": "word", "text": "x"},
                 "listen": {"measure": "vowel", "vowel": "xx"}}]},
     "body.items.0.listen.vowel.vowel"),
    ({"items": [{"target": {"kind": "word", "text": "x"},
                 "listen": {"measure": "rhotic", "f3_below_hz": 9000}}]},
     "body.items.0.listen.rhotic.f3_below_hz"),
    ({"items": [{"target": {"kind": "word", "text": "x"}, "views": {"labels": ["nose"]}}]},
     "'nose' is not a label"),
    ({"items": [{"target": {"kind": "word", "text": "x"}, "views": {"labels": []}}]},
     "name 1 to 6 labels"),
    ({"items": [{"target": {"kind": "word", "text": "x"},
                 "views": {"labels": ["lips", "velar", "lips"]}}]}, "lips named more than once"),
    ({"items": [{"target": {"kind": "word", "text": "x"}, "views": {"camera": "top"}}]},
     "body.items.0.views.camera"),
    ({"items": [{"target": {"kind": "word", "text": "x"}, "views": {"zoom": 5}}]},
     "body.items.0.views.zoom"),
    ({"items": [{"target": {"kind": "word", "text": "ship"}, "said_as": "syllable"}]},
     "said_as: only a phoneme target"),
    ({"items": [{"target": {"kind": "phoneme", "text": "t"}, "said_as": "twice"}]},
     "body.items.0.said_as"),
])
def test_invalid_lessons_are_422s_that_name_the_field_and_store_nothing(client, change, field):
    response = client.post(f"{API}/lessons", json={**SIP_SHIP, **change})
    assert response.status_code == 422 and field in response.json()["detail"]
    assert client.get(f"{API}/lessons").json()["total"] == N_STARTER


def test_an_item_keeps_what_a_try_is_measured_on_and_its_zone(client):
    items = [{"target": {"kind": "phoneme", "text": "i"},
              "listen": {"measure": "vowel", "vowel": "iy", "within_sd": 2}},
             {"target": {"kind": "word", "text": "ship"},
              "listen": {"measure": "sibilant", "sound": "sh"}},
             {"target": {"kind": "phoneme", "text": "r"}, "listen": {"measure": "rhotic"}},
             {"target": {"kind": "word", "text": "tea"}}]
    lesson = create(client, {**SIP_SHIP, "items": items}).json()
    assert [item["listen"] for item in lesson["items"]] == [
        {"measure": "vowel", "vowel": "iy", "within_sd": 2.0},
        {"measure": "sibilant", "sound": "sh", "from_share": 0.6},
        {"measure": "rhotic", "f3_below_hz": 2600.0}, None]
    starters = client.get(f"{API}/lessons", params={"limit": 100}).json()["lessons"]
    vowels = next(lesson for lesson in starters if lesson["title"] == "The vowels")
    measured = client.get(f"{API}/lessons/{vowels['id']}").json()["items"]
    assert all(item["listen"]["measure"] == "vowel" for item in measured)


def test_an_item_names_its_labels_camera_zoom_and_how_its_sound_is_said(client):
    items = [{"target": {"kind": "phoneme", "text": "t"}, "said_as": "repeated",
              "views": {"labels": ["tongue_tip", "alveolar"], "camera": "front", "zoom": 2}},
             {"target": {"kind": "word", "text": "tea"}}]
    lesson = create(client, {**SIP_SHIP, "items": items}).json()
    first, second = lesson["items"]
    assert first["said_as"] == "repeated" and second["said_as"] is None
    assert (first["views"]["labels"], first["views"]["camera"], first["views"]["zoom"]) == (
        ["tongue_tip", "alveolar"], "front", 2.0)
    assert (second["views"]["labels"], second["views"]["camera"], second["views"]["zoom"]) == (
        False, "profile", 1.0)


def test_an_unknown_phoneme_symbol_is_named_in_the_422(client):
    response = client.post(f"{API}/lessons", json={
        **SIP_SHIP, "items": [SIP_SHIP["items"][0], {"target": {"kind": "phoneme", "text": "ʘ"}}]})
    assert response.status_code == 422
    assert "body.items.1.target" in response.json()["detail"] and "'ʘ'" in response.json()["detail"]


def test_listings_page_with_limit_and_offset_in_the_order_lessons_were_made(client):
    ids = [create(client, {**SIP_SHIP, "title": f"lesson {k}"}).json()["id"] for k in range(5)]
    listing = client.get(f"{API}/lessons", params={"offset": N_STARTER + 1, "limit": 3}).json()
    assert listing["total"] == N_STARTER + 5
    assert [lesson["id"] for lesson in listing["lessons"]] == ids[1:4]
    assert listing["lessons"][0]["n_items"] == 2 and "items" not in listing["lessons"][0]
    assert client.get(f"{API}/lessons", params={"limit": 0}).status_code == 422


def test_the_id_of_a_deleted_lesson_is_never_given_to_a_new_one(client):
    last = create(client).json()["id"]
    assert client.delete(f"{API}/lessons/{last}").status_code == 204
    assert create(client).json()["id"] == last + 1


def test_an_exported_lesson_imports_as_a_new_lesson_with_the_same_content(client):
    lesson = create(client).json()
    exported = client.get(f"{API}/lessons/{lesson['id']}/export")
    assert exported.status_code == 200 and "attachment" in exported.headers["content-disposition"]
    content = exported.json()
    assert content["format_version"] == 1 and "id" not in content
    imported = client.post(f"{API}/lessons/import", json=content)
    assert imported.status_code == 201 and imported.json()["id"] != lesson["id"]
    assert client.get(f"{API}/lessons/{imported.json()['id']}/export").json() == content
    newer = client.post(f"{API}/lessons/import", json={**content, "format_version": 2})
    assert newer.status_code == 422 and "format_version" in newer.json()["detail"]


def test_the_published_schema_is_the_models_schema_and_the_file_in_docs(client):
    served = client.get(f"{API}/lessons/schema").json()
    assert served == json_schema() == json.loads(SCHEMA_FILE.read_text()), (
        "docs/lesson.schema.json is stale: glasshead lesson-schema")
    assert served["required"] == ["title", "items"]


def test_a_new_database_has_the_starter_lessons_and_a_restart_adds_none(start_app, tmp_path,
                                                                        monkeypatch):
    from glasshead.store.db import engine_for, upgrade_to_head

    client = signed_in(start_app()[1], "admin")
    listing = client.get(f"{API}/lessons").json()
    titles = [lesson["title"] for lesson in listing["lessons"]]
    assert titles == ["/s/ and /ʃ/", "/t/ and /k/", "/r/ and /l/", "Nasals and their oral pairs",
                      "The vowels"]
    client.delete(f"{API}/lessons/{listing['lessons'][0]['id']}")
    upgrade_to_head(engine_for(f"sqlite:///{tmp_path / 'app-0.sqlite3'}"))
    assert client.get(f"{API}/lessons").json()["total"] == N_STARTER - 1
    nasals = client.get(f"{API}/lessons/{listing['lessons'][3]['id']}").json()
    symbols = [item["target"]["text"] for item in nasals["items"]
               if item["target"]["kind"] == "phoneme"]
    assert {lookup(s).nasal for s in symbols} == {True, False} and len(symbols) == 6
