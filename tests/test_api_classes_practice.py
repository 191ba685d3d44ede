"""Classes, children, assignments and practice records over HTTP: CRUD, join codes, If-Match,
paging, and 422s that name the field."""

import pytest

from accounts_support import signed_in
from glasshead.store.lessons import AVATARS, JOIN_CODE_ALPHABET, JOIN_CODE_LENGTH

API = "/api/v1"
LOOK_ALIKES = set("0O1IL2Z5S8B")


@pytest.fixture
def client(start_app):
    """The app with an admin signed in (who reaches every record; tests/test_api_roles.py has
    the other roles)."""
    return signed_in(start_app()[1], "admin")


def post(client, path, body):
    response = client.post(f"{API}/{path}", json=body)
    assert response.status_code == 201, response.text
    return response.json()


@pytest.fixture
def setting(client):
    """A class with two children, and the first starter lesson."""
    school_class = post(client, "classes", {"name": "Year 2"})
    ada = post(client, "children", {"class_id": school_class["id"], "display_name": "Ada",
                                    "avatar": "owl"})
    bo = post(client, "children", {"class_id": school_class["id"], "display_name": "Bo",
                                   "avatar": "frog"})
    lesson = client.get(f"{API}/lessons", params={"limit": 1}).json()["lessons"][0]
    return school_class, ada, bo, lesson


def test_classes_get_unique_unambiguous_join_codes_that_find_them_in_any_case(client):
    classes = [post(client, "classes", {"name": f"class {k}"}) for k in range(20)]
    codes = [c["join_code"] for c in classes]
    assert len(set(codes)) == 20
    assert all(len(code) == JOIN_CODE_LENGTH and set(code) <= set(JOIN_CODE_ALPHABET)
               for code in codes)
    assert not LOOK_ALIKES & set("".join(codes))
    found = client.get(f"{API}/classes", params={"join_code": codes[7].lower()}).json()
    assert found["total"] == 1 and found["classes"][0]["id"] == classes[7]["id"]
    renamed = client.put(f"{API}/classes/{classes[7]['id']}", json={"name": "Owls"}).json()
    assert renamed["join_code"] == codes[7] and renamed["name"] == "Owls"
    url, tag = f"{API}/classes/{classes[7]['id']}", f'"class-{classes[7]["id"]}-v2"'
    patched = client.patch(url, json={"name": "Larks"}, headers={"If-Match": tag})
    assert patched.status_code == 200 and patched.json()["join_code"] == codes[7]
    assert client.patch(url, json={"name": "Wrens"}, headers={"If-Match": tag}).status_code == 412
    assert client.get(url).json()["name"] == "Larks"


def test_children_have_a_display_name_and_an_avatar_from_the_list_and_nothing_else(client,
                                                                                   setting):
    school_class, ada, _, _ = setting
    assert client.get(f"{API}/children/avatars").json() == list(AVATARS)
    assert set(ada) == {"id", "class_id", "display_name", "avatar", "created_at", "updated_at"}
    for bad, field in (({"avatar": "dragon"}, "body.avatar"),
                       ({"birth_date": "2019-01-01"}, "body.birth_date"),
                       ({"display_name": "x" * 41}, "body.display_name"),
                       ({"class_id": 999}, "body.class_id")):
        response = client.post(f"{API}/children", json={
            "class_id": school_class["id"], "display_name": "Cy", "avatar": "cat", **bad})
        assert response.status_code == 422 and field in response.json()["detail"]
    listing = client.get(f"{API}/children", params={"class_id": school_class["id"]}).json()
    assert listing["total"] == 2


def test_child_and_class_writes_honour_if_match_and_deleting_a_class_deletes_its_children(
        client, setting):
    school_class, ada, bo, _ = setting
    url = f"{API}/children/{ada['id']}"
    tag = client.get(url).headers["etag"]
    assert client.patch(url, json={"avatar": "cat"}, headers={"If-Match": tag}).status_code == 200
    stale = client.patch(url, json={"avatar": "dog"}, headers={"If-Match": tag})
    assert stale.status_code == 412 and client.get(url).json()["avatar"] == "cat"
    replaced = client.put(url, json={"class_id": school_class["id"], "display_name": "Ada L",
                                     "avatar": "fox"}).json()
    assert (replaced["display_name"], replaced["avatar"]) == ("Ada L", "fox")
    class_url = f"{API}/classes/{school_class['id']}"
    assert client.delete(class_url, headers={"If-Match": '"class-1-v9"'}).status_code == 412
    assert client.delete(class_url).status_code == 204
    assert client.get(f"{API}/children/{bo['id']}").status_code == 404


def test_a_lesson_is_assigned_to_a_class_or_to_one_child_never_both_or_neither(client, setting):
    school_class, ada, _, lesson = setting
    to_class = post(client, "assignments", {"lesson_id": lesson["id"],
                                            "class_id": school_class["id"]})
    to_child = post(client, "assignments", {"lesson_id": lesson["id"], "child_id": ada["id"]})
    assert (to_class["child_id"], to_child["class_id"]) == (None, None)
    for body in ({"lesson_id": lesson["id"]},
                 {"lesson_id": lesson["id"], "class_id": school_class["id"],
                  "child_id": ada["id"]}):
        response = client.post(f"{API}/assignments", json=body)
        assert response.status_code == 422 and "exactly one" in response.json()["detail"]
    missing = client.post(f"{API}/assignments", json={"lesson_id": 10**6, "child_id": ada["id"]})
    assert missing.status_code == 422 and "body.lesson_id" in missing.json()["detail"]
    mine = client.get(f"{API}/assignments", params={"child_id": ada["id"]}).json()
    assert [a["id"] for a in mine["assignments"]] == [to_child["id"]]
    url = f"{API}/assignments/{to_class['id']}"
    moved = client.put(url, json={"lesson_id": lesson["id"], "child_id": ada["id"]},
                       headers={"If-Match": f'"assignment-{to_class["id"]}-v1"'})
    assert moved.status_code == 200 and moved.json()["child_id"] == ada["id"]
    assert client.delete(url).status_code == 204 and client.get(url).status_code == 404


def test_practice_is_recorded_rated_later_by_an_adult_and_listed_newest_first(client, setting):
    _, ada, bo, lesson = setting
    times = ["2026-11-02T09:00:00Z", "2026-11-02T09:05:00+01:00", "2026-11-02T09:03:00Z"]
    records = [post(client, "practice", {"child_id": ada["id"], "lesson_id": lesson["id"],
                                         "item_index": k, "practised_at": t, "replays": k})
               for k, t in enumerate(times)]
    post(client, "practice", {"child_id": bo["id"], "lesson_id": lesson["id"], "item_index": 0,
                              "rating": 3, "rated_by": "child"})
    listing = client.get(f"{API}/practice", params={"child_id": ada["id"], "limit": 2}).json()
    assert listing["total"] == 3
    assert [r["id"] for r in listing["records"]] == [records[2]["id"], records[0]["id"]]
    url = f"{API}/practice/{records[1]['id']}"
    rated = client.patch(url, json={"rating": 2, "rated_by": "adult"},
                         headers={"If-Match": f'"practice-{records[1]["id"]}-v1"'})
    assert rated.status_code == 200 and (rated.json()["rating"], rated.json()["rated_by"]) == \
        (2, "adult")
    assert client.patch(url, json={"replays": 9},
                        headers={"If-Match": f'"practice-{records[1]["id"]}-v1"'}).status_code \
        == 412
    assert client.delete(url).status_code == 204


@pytest.mark.parametrize(("change", "field"), [
    ({"item_index": 99}, "body.item_index"),
    ({"child_id": 999}, "body.child_id"),
    ({"lesson_id": 999}, "body.lesson_id"),
    ({"rating": 3}, "rated_by"),
    ({"rating": 4, "rated_by": "adult"}, "body.rating"),
    ({"rated_by": "parrot", "rating": 1}, "body.rated_by"),
    ({"practised_at": "2026-11-02T09:00:00"}, "body.practised_at"),
    ({"replays": -1}, "body.replays"),
    ({"measures": {"f0": 20}}, "body.measures.f0"),
    ({"measures": {"f2": "high"}}, "body.measures.f2"),
    ({"measures": {"verdict": "great"}}, "body.measures.verdict"),
    ({"measures": {"audio": "UklGRg=="}}, "body.measures.audio"),
    ({"measures": {"target_vowel": "IY!"}}, "body.measures.target_vowel"),
])
def test_invalid_practice_is_a_422_that_names_the_field(client, setting, change, field):
    _, ada, _, lesson = setting
    response = client.post(f"{API}/practice", json={
        "child_id": ada["id"], "lesson_id": lesson["id"], "item_index": 0, **change})
    assert response.status_code == 422 and field in response.json()["detail"]
    assert client.get(f"{API}/practice").json()["total"] == 0


def test_a_go_keeps_what_the_voice_measured_and_only_what_was_measured(client, setting):
    _, ada, _, lesson = setting
    measures = {"f0": 251.5, "f1": 410.0, "f2": 3050.0, "f3": None, "duration_s": 0.26,
                "verdict": "near", "target_vowel": "iy"}
    made = post(client, "practice", {"child_id": ada["id"], "lesson_id": lesson["id"],
                                     "item_index": 0, "rating": 2, "rated_by": "child",
                                     "measures": measures})
    kept = client.get(f"{API}/practice/{made['id']}").json()["measures"]
    assert {k: v for k, v in kept.items() if v is not None} == \
        {"f0": 251.5, "f1": 410.0, "f2": 3050.0, "duration_s": 0.26, "verdict": "near",
         "target_vowel": "iy"}
    plain = post(client, "practice", {"child_id": ada["id"], "lesson_id": lesson["id"],
                                      "item_index": 1})
    assert plain["measures"] is None


def test_ids_of_deleted_children_and_practice_are_never_reused(client, setting):
    school_class, _, bo, lesson = setting
    client.delete(f"{API}/children/{bo['id']}")
    cy = post(client, "children", {"class_id": school_class["id"], "display_name": "Cy",
                                   "avatar": "bear"})
    assert cy["id"] == bo["id"] + 1
    first = post(client, "practice", {"child_id": cy["id"], "lesson_id": lesson["id"],
                                      "item_index": 0})
    client.delete(f"{API}/practice/{first['id']}")
    assert post(client, "practice", {"child_id": cy["id"], "lesson_id": lesson["id"],
                                     "item_index": 1})["id"] == first["id"] + 1


def test_the_documented_examples_are_accepted_in_order_on_a_new_database(client):
    schemas = client.get(f"{API}/openapi.json").json()["components"]["schemas"]
    for path, schema in (("lessons", "LessonContent"), ("classes", "ClassIn"),
                         ("children", "ChildIn"), ("assignments", "AssignmentIn"),
                         ("practice", "PracticeIn")):
        examples = schemas[schema]["examples"]
        assert examples, schema
        for example in examples:
            response = client.post(f"{API}/{path}", json=example)
            assert response.status_code == 201, (schema, response.text)
    rating = schemas["PracticePatch"]["examples"][0]
    assert client.patch(f"{API}/practice/1", json=rating).json()["rated_by"] == "adult"
