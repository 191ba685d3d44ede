"""A class shared with its staff: a clinician who follows a teacher's pupil reaches the class, its
children, their practice and (as a clinician) their EPG recordings as the owner does, but does not
delete the class or change who it is shared with; a non-member still gets 404, and removing a
member takes the access away. Both on SQLite and on a real PostgreSQL server
(tests/postgres_support.py).
"""

import pytest

from accounts_support import add_user, header, token_for
from backend_support import app_on_new_database

API = "/api/v1"
ONE_FRAME = {"format": "emur-json",
             "content": {"frames": [{"t_ms": 0, "rows": ["00011000"] + ["00000000"] * 7}]}}


@pytest.fixture(scope="module", params=["sqlite", "postgresql"])
def client(request, tmp_path_factory, built_assets):
    """The app on a new database of each backend, shared by this module's tests."""
    with app_on_new_database(request, tmp_path_factory, "staff") as client:
        yield client


def as_user(role: str, username: str | None = None) -> tuple[int, dict]:
    user_id = add_user(role, username)
    return user_id, header(token_for(user_id))


def class_with_practice(client, teacher: dict) -> tuple[dict, dict, dict]:
    """(class, child, practice record): a teacher's class with Ada, who practised lesson 1."""
    school_class = client.post(f"{API}/classes", json={"name": "2A"}, headers=teacher).json()
    child = client.post(f"{API}/children", headers=teacher, json={
        "class_id": school_class["id"], "display_name": "Ada", "avatar": "owl"}).json()
    practice = client.post(f"{API}/practice", headers=teacher, json={
        "child_id": child["id"], "lesson_id": 1, "item_index": 0}).json()
    return school_class, child, practice


def test_staff_read_the_shared_class_its_practice_and_import_a_recording_for_its_child(client):
    ann_id, ann = as_user("teacher")
    cleo_id, cleo = as_user("clinician", "cleo@clinic.example")
    _, dan = as_user("clinician")
    school_class, child, practice = class_with_practice(client, ann)
    staff_url = f"{API}/classes/{school_class['id']}/staff"
    assert client.get(f"{API}/children/{child['id']}", headers=cleo).status_code == 404

    added = client.post(staff_url, json={"username": " CLEO@clinic.example "}, headers=ann)
    assert added.status_code == 201
    assert added.json()["user_id"] == cleo_id and added.json()["role"] == "clinician"
    listed = client.get(staff_url, headers=cleo).json()
    assert listed["owner"]["user_id"] == ann_id
    assert [m["username"] for m in listed["staff"]] == ["cleo@clinic.example"]

    classes = client.get(f"{API}/classes", headers=cleo).json()
    assert [c["id"] for c in classes["classes"]] == [school_class["id"]]
    children = client.get(f"{API}/children", params={"class_id": school_class["id"]},
                          headers=cleo).json()
    assert [c["id"] for c in children["children"]] == [child["id"]]
    records = client.get(f"{API}/practice", params={"child_id": child["id"]},
                         headers=cleo).json()
    assert [r["id"] for r in records["records"]] == [practice["id"]]
    assert client.get(f"{API}/practice/{practice['id']}", headers=cleo).status_code == 200

    imported = client.post(f"{API}/epg/recordings", headers=cleo,
                           json={**ONE_FRAME, "name": "ada", "child_id": child["id"]})
    assert imported.status_code == 201
    recording = imported.json()["recordings"][0]
    assert recording["child_id"] == child["id"]
    compare = {"reference": {"recording_id": recording["id"]}}
    assert client.post(f"{API}/epg/recordings/{recording['id']}/compare", json=compare,
                       headers=cleo).status_code == 200
    # Someone the class is not shared with: still a 404 for the class, child and recording.
    for url in (f"{API}/classes/{school_class['id']}", f"{API}/children/{child['id']}",
                f"{API}/practice/{practice['id']}", f"{API}/epg/recordings/{recording['id']}",
                staff_url):
        assert client.get(url, headers=dan).status_code == 404, url
    assert client.post(staff_url, json={"username": "someone"}, headers=dan).status_code == 404


def test_removing_a_member_takes_their_access_away(client):
    _, ann = as_user("teacher")
    cleo_id, cleo = as_user("clinician")
    school_class, child, practice = class_with_practice(client, ann)
    staff_url = f"{API}/classes/{school_class['id']}/staff"
    username = client.get(f"{API}/auth/me", headers=cleo).json()["username"]
    assert client.post(staff_url, json={"username": username}, headers=ann).status_code == 201
    assert client.get(f"{API}/children/{child['id']}", headers=cleo).status_code == 200

    assert client.delete(f"{staff_url}/{cleo_id}", headers=ann).status_code == 204
    assert client.get(staff_url, headers=ann).json()["staff"] == []
    for url in (f"{API}/classes/{school_class['id']}", f"{API}/children/{child['id']}",
                f"{API}/practice/{practice['id']}"):
        assert client.get(url, headers=cleo).status_code == 404, url
    assert client.get(f"{API}/classes", headers=cleo).json()["total"] == 0
    refused = client.post(f"{API}/epg/recordings", headers=cleo,
                          json={**ONE_FRAME, "child_id": child["id"]})
    assert refused.status_code == 422 and "child_id" in refused.json()["detail"]
    assert client.delete(f"{staff_url}/{cleo_id}", headers=ann).status_code == 404


def test_staff_neither_delete_the_class_nor_change_its_staff(client):
    _, ann = as_user("teacher")
    cleo_id, cleo = as_user("clinician")
    _, tom = as_user("teacher")
    school_class, child, _ = class_with_practice(client, ann)
    class_url = f"{API}/classes/{school_class['id']}"
    cleo_name = client.get(f"{API}/auth/me", headers=cleo).json()["username"]
    tom_name = client.get(f"{API}/auth/me", headers=tom).json()["username"]
    assert client.post(f"{class_url}/staff", json={"username": cleo_name},
                       headers=ann).status_code == 201

    assert client.delete(class_url, headers=cleo).status_code == 403
    assert client.post(f"{class_url}/staff", json={"username": tom_name},
                       headers=cleo).status_code == 403
    assert client.delete(f"{class_url}/staff/{cleo_id}", headers=cleo).status_code == 403
    assert client.get(class_url, headers=cleo).status_code == 200
    # What the owner may otherwise do, staff may: rename the class, add a child.
    assert client.patch(class_url, json={"name": "2A speech"}, headers=cleo).status_code == 200
    assert client.post(f"{API}/children", headers=cleo, json={
        "class_id": school_class["id"], "display_name": "Ben", "avatar": "fox"}).status_code == 201
    assert client.get(f"{API}/children/{child['id']}", headers=ann).status_code == 200


def test_a_class_is_shared_only_with_teachers_and_clinicians_each_once(client):
    _, ann = as_user("teacher")
    as_user("author", "writer@test.example")
    admin_name = "boss@test.example"
    as_user("admin", admin_name)
    _, cleo = as_user("clinician", "cleo2@test.example")
    school_class = client.post(f"{API}/classes", json={"name": "3B"}, headers=ann).json()
    staff_url = f"{API}/classes/{school_class['id']}/staff"
    answers = {name: client.post(staff_url, json={"username": name}, headers=ann)
               for name in ("nobody@test.example", "writer@test.example", admin_name)}
    # Unknown, an author and an admin alike: nothing tells which usernames exist.
    assert {a.status_code for a in answers.values()} == {422}
    assert len({a.json()["detail"] for a in answers.values()}) == 1
    assert "no such user" in answers["nobody@test.example"].json()["detail"]
    own = client.get(f"{API}/auth/me", headers=ann).json()["username"]
    assert client.post(staff_url, json={"username": own}, headers=ann).status_code == 422
    assert client.post(staff_url, json={"username": "cleo2@test.example"},
                       headers=ann).status_code == 201
    again = client.post(staff_url, json={"username": "cleo2@test.example"}, headers=ann)
    assert again.status_code == 409
    assert [m["username"] for m in client.get(staff_url, headers=ann).json()["staff"]] == [
        "cleo2@test.example"]
    assert client.get(staff_url, headers=cleo).status_code == 200
    # An admin changes any class's staff.
    admin = as_user("admin")[1]
    member = client.get(staff_url, headers=ann).json()["staff"][0]["user_id"]
    assert client.delete(f"{staff_url}/{member}", headers=admin).status_code == 204
