"""Who may call what: every operation of the OpenAPI document, walked with no token and as a
child, an author, a teacher, a clinician and an admin, against ONE table (tests/route_roles.json:
operationId -> "open" or the callers allowed); and whose records each caller reaches.

"Allowed" is any answer but 401 and 403 (a made-up id is a 404, an empty body a 422); "denied"
is 401 without a token and 403 with one (401 for a user's token on a child's session route and
the other way round: that token is not a session of that kind). An operation missing from the
table fails the walk, so that no new route goes out without its roles. Both on SQLite and on a
real PostgreSQL server (tests/postgres_support.py).
"""

import json
from pathlib import Path

import pytest
from sqlalchemy.orm import Session

from accounts_support import add_user, child_bearer, header, token_for
from backend_support import app_on_new_database
from glasshead.api.routes.classes import new_join_code
from glasshead.store.db import get_engine
from glasshead.store.lessons import Child, SchoolClass

API = "/api/v1"
ROLE_TABLE = json.loads((Path(__file__).parent / "route_roles.json").read_text())
CALLERS = ("anonymous", "child", "author", "teacher", "clinician", "admin")
#: Session routes whose token must be of their own kind (a user's or a child's): another kind
#: of token is no session there, a 401.
SESSION_ROUTES = {"signOut", "getCurrentUser", "signOutChild", "getCurrentChild"}
#: An id that names nothing.
MADE_UP_ID = 987654321
LESSON = {"title": "sip", "items": [{"target": {"kind": "phoneme", "text": "s"}},
                                    {"target": {"kind": "word", "text": "sip"}}]}
ONE_FRAME = {"format": "emur-json",
             "content": {"frames": [{"t_ms": 0, "rows": ["00011000"] + ["00000000"] * 7}]}}


@pytest.fixture(scope="module", params=["sqlite", "postgresql"])
def client(request, tmp_path_factory, built_assets):
    """The app on a new database of each backend, shared by this module's tests (each makes its
    own users and records)."""
    with app_on_new_database(request, tmp_path_factory, "roles") as client:
        yield client


def make_class(owner_id: int, name: str = "Owls", children: tuple = ("Ada",)) -> tuple:
    """(class id, [child ids]): a class owned by ``owner_id``, made in the database."""
    with Session(get_engine()) as session:
        school_class = SchoolClass(name=name, join_code=new_join_code(), owner_id=owner_id)
        session.add(school_class)
        session.flush()
        made = [Child(class_id=school_class.id, display_name=n, avatar="owl") for n in children]
        session.add_all(made)
        session.commit()
        return school_class.id, [c.id for c in made]


def fill_path(path: str, parameters: list) -> str:
    for parameter in parameters:
        if parameter.get("in") == "path":
            kind = parameter.get("schema", {}).get("type")
            value = MADE_UP_ID if kind == "integer" else "zz-none"
            path = path.replace("{" + parameter["name"] + "}", str(value))
    return path


def test_every_operation_in_the_document_is_in_the_role_table_and_no_other(client):
    document = client.get(f"{API}/openapi.json").json()
    served = {op["operationId"] for ops in document["paths"].values() for op in ops.values()}
    missing = sorted(served - set(ROLE_TABLE))
    assert not missing, f"add these operations to tests/route_roles.json: {missing}"
    assert sorted(set(ROLE_TABLE) - served) == [], "operations no longer served"
    assert list(ROLE_TABLE) == sorted(ROLE_TABLE), "keep tests/route_roles.json sorted"
    for operation, allowed in ROLE_TABLE.items():
        assert allowed == "open" or (allowed and set(allowed) <= set(CALLERS[1:])), operation


def test_every_operation_answers_each_caller_as_the_role_table_says(client):
    document = client.get(f"{API}/openapi.json").json()
    ids = {role: add_user(role) for role in CALLERS[2:]}
    _, (child_id,) = make_class(ids["teacher"])
    wrong = []
    for path, operations in sorted(document["paths"].items()):
        for method, operation in sorted(operations.items()):
            name = operation["operationId"]
            allowed = ROLE_TABLE.get(name)
            assert allowed is not None, f"{name} is not in tests/route_roles.json"
            url = fill_path(path, operation.get("parameters", []))
            body = {} if "requestBody" in operation else None
            for caller in CALLERS:
                # A new token each time: signing out on the walk must not sign out the rest.
                headers = ({} if caller == "anonymous" else child_bearer(child_id)
                           if caller == "child" else header(token_for(ids[caller])))
                status = client.request(method.upper(), url, json=body,
                                        headers=headers).status_code
                if allowed == "open" or caller in allowed:
                    ok = status not in (401, 403) and status < 500
                    expected = "allowed"
                elif caller == "anonymous" or name in SESSION_ROUTES:
                    ok, expected = status == 401, "401"
                else:
                    ok, expected = status == 403, "403"
                if not ok:
                    wrong.append(f"{method.upper()} {path} ({name}) as {caller}: {status}, "
                                 f"expected {expected}")
    assert not wrong, "\n".join(wrong)


def as_user(role: str) -> tuple[int, dict]:
    user_id = add_user(role)
    return user_id, header(token_for(user_id))


def test_a_teacher_cannot_read_or_change_another_teachers_class_children_assignments_or_practice(
        client):
    _, ann = as_user("teacher")
    _, bob = as_user("teacher")
    school_class = client.post(f"{API}/classes", json={"name": "2A"}, headers=ann).json()
    child = client.post(f"{API}/children", headers=ann, json={
        "class_id": school_class["id"], "display_name": "Ada", "avatar": "owl"}).json()
    assignment = client.post(f"{API}/assignments", headers=ann, json={
        "lesson_id": 1, "class_id": school_class["id"]}).json()
    practice = client.post(f"{API}/practice", headers=ann, json={
        "child_id": child["id"], "lesson_id": 1, "item_index": 0}).json()
    for kind, record in (("classes", school_class), ("children", child),
                         ("assignments", assignment), ("practice", practice)):
        url = f"{API}/{kind}/{record['id']}"
        assert client.get(url, headers=ann).status_code == 200, kind
        assert client.get(url, headers=bob).status_code == 404, kind
        assert client.delete(url, headers=bob).status_code == 404, kind
    assert client.patch(f"{API}/classes/{school_class['id']}", headers=bob,
                        json={"name": "mine"}).status_code == 404
    assert client.patch(f"{API}/children/{child['id']}", headers=bob,
                        json={"display_name": "Eve"}).status_code == 404
    assert client.patch(f"{API}/practice/{practice['id']}", headers=bob,
                        json={"rating": 1, "rated_by": "adult"}).status_code == 404
    for listing, key in (("classes", "classes"), ("children", "children"),
                         ("assignments", "assignments"), ("practice", "records")):
        theirs = client.get(f"{API}/{listing}", headers=bob).json()
        assert theirs["total"] == 0 and theirs[key] == [], listing
        assert client.get(f"{API}/{listing}", headers=ann).json()["total"] == 1, listing
    # A body naming another's class or child is a reference to nothing.
    for path, body in (("children", {"class_id": school_class["id"], "display_name": "Eve",
                                     "avatar": "fox"}),
                       ("assignments", {"lesson_id": 1, "class_id": school_class["id"]}),
                       ("assignments", {"lesson_id": 1, "child_id": child["id"]}),
                       ("practice", {"child_id": child["id"], "lesson_id": 1,
                                     "item_index": 0})):
        refused = client.post(f"{API}/{path}", json=body, headers=bob)
        assert refused.status_code == 422 and "no c" in refused.json()["detail"], path
    admin = as_user("admin")[1]
    assert client.get(f"{API}/children/{child['id']}", headers=admin).status_code == 200
    assert client.get(f"{API}/classes/{school_class['id']}", headers=ann).json()["name"] == "2A"


def test_a_clinician_cannot_read_another_caseloads_recordings(client):
    _, cleo = as_user("clinician")
    _, dan = as_user("clinician")
    caseload = client.post(f"{API}/classes", json={"name": "Tuesday"}, headers=cleo).json()
    child = client.post(f"{API}/children", headers=cleo, json={
        "class_id": caseload["id"], "display_name": "Ada", "avatar": "owl"}).json()
    own = client.post(f"{API}/epg/recordings", headers=cleo,
                      json={**ONE_FRAME, "name": "ada", "child_id": child["id"]})
    assert own.status_code == 201 and own.json()["recordings"][0]["child_id"] == child["id"]
    recording = own.json()["recordings"][0]["id"]
    reference = client.post(f"{API}/epg/recordings", headers=cleo,
                            json={**ONE_FRAME, "name": "reference"}).json()["recordings"][0]
    assert reference["child_id"] is None
    for suffix in ("", "/indices", "/export", "/plot"):
        assert client.get(f"{API}/epg/recordings/{recording}{suffix}",
                          headers=cleo).status_code == 200, suffix
        assert client.get(f"{API}/epg/recordings/{recording}{suffix}",
                          headers=dan).status_code == 404, suffix
    compare = {"reference": {"recording_id": recording}}
    assert client.post(f"{API}/epg/recordings/{recording}/compare", json=compare,
                       headers=dan).status_code == 404
    # Another caseload's recording as the reference of one's own comparison: 404 too.
    assert client.post(f"{API}/epg/recordings/{reference['id']}/compare", json=compare,
                       headers=dan).status_code == 404
    assert client.post(f"{API}/epg/recordings/{reference['id']}/compare", json=compare,
                       headers=cleo).status_code == 200
    assert client.delete(f"{API}/epg/recordings/{recording}", headers=dan).status_code == 404
    listed = [r["id"] for r in client.get(f"{API}/epg/recordings", headers=dan).json()[
        "recordings"]]
    assert recording not in listed and reference["id"] in listed
    # A reference recording is read by every clinician, deleted only by whoever imported it.
    assert client.delete(f"{API}/epg/recordings/{reference['id']}",
                         headers=dan).status_code == 403
    mine = client.get(f"{API}/epg/recordings", params={"child_id": child["id"]},
                      headers=cleo).json()
    assert [r["id"] for r in mine["recordings"]] == [recording]
    stolen = client.post(f"{API}/epg/recordings", headers=dan,
                         json={**ONE_FRAME, "child_id": child["id"]})
    assert stolen.status_code == 422 and "child_id" in stolen.json()["detail"]


def test_a_child_reads_only_assigned_lessons_and_writes_only_their_own_practice(client):
    teacher_id, teacher = as_user("teacher")
    _, (ada, bo) = make_class(teacher_id, "Foxes", ("Ada", "Bo"))
    with Session(get_engine()) as session:
        class_id = session.get(Child, ada).class_id
    everyone, only_bo, nobody = (client.post(f"{API}/lessons", json={**LESSON, "title": t},
                                             headers=as_user("author")[1]).json()["id"]
                                 for t in ("everyone", "only Bo", "nobody"))
    for body in ({"lesson_id": everyone, "class_id": class_id},
                 {"lesson_id": only_bo, "child_id": bo}):
        assert client.post(f"{API}/assignments", json=body, headers=teacher).status_code == 201
    ada_h, bo_h = child_bearer(ada), child_bearer(bo)
    assert [x["id"] for x in client.get(f"{API}/lessons", headers=ada_h).json()["lessons"]] \
        == [everyone]
    assert [x["id"] for x in client.get(f"{API}/lessons", headers=bo_h).json()["lessons"]] \
        == [everyone, only_bo]
    assert client.get(f"{API}/lessons/{everyone}", headers=ada_h).status_code == 200
    for lesson in (only_bo, nobody):
        assert client.get(f"{API}/lessons/{lesson}", headers=ada_h).status_code == 404
    assert client.get(f"{API}/assignments", headers=ada_h).json()["total"] == 1
    assert client.get(f"{API}/assignments", headers=bo_h).json()["total"] == 2
    for_bo = client.post(f"{API}/practice", headers=ada_h,
                         json={"child_id": bo, "lesson_id": everyone, "item_index": 0})
    assert for_bo.status_code == 403
    unassigned = client.post(f"{API}/practice", headers=ada_h,
                             json={"child_id": ada, "lesson_id": only_bo, "item_index": 0})
    assert unassigned.status_code == 422
    mine = client.post(f"{API}/practice", headers=ada_h, json={
        "child_id": ada, "lesson_id": everyone, "item_index": 1, "rating": 3,
        "rated_by": "child"})
    assert mine.status_code == 201
    bos = client.post(f"{API}/practice", headers=bo_h,
                      json={"child_id": bo, "lesson_id": only_bo, "item_index": 0}).json()
    assert [r["id"] for r in client.get(f"{API}/practice", headers=ada_h).json()["records"]] \
        == [mine.json()["id"]]
    assert client.get(f"{API}/practice/{bos['id']}", headers=ada_h).status_code == 404
    assert client.patch(f"{API}/practice/{bos['id']}", headers=ada_h,
                        json={"replays": 9}).status_code == 404
    assert client.get(f"{API}/practice", headers=teacher).json()["total"] == 2


def test_lessons_and_poses_are_changed_only_by_their_owner_or_an_admin(client):
    _, ann = as_user("author")
    _, ben = as_user("author")
    admin = as_user("admin")[1]
    lesson = client.post(f"{API}/lessons", json=LESSON, headers=ann).json()
    url = f"{API}/lessons/{lesson['id']}"
    refused = client.patch(url, json={"title": "mine now"}, headers=ben)
    assert refused.status_code == 403 and "another user's" in refused.json()["detail"]
    assert client.delete(url, headers=ben).status_code == 403
    assert client.patch(url, json={"title": "sip!"}, headers=ann).status_code == 200
    assert client.patch(url, json={"title": "sip?"}, headers=admin).status_code == 200
    # A starter lesson has no owner: an author copies it through export and import.
    starter = f"{API}/lessons/1"
    assert client.patch(starter, json={"title": "x"}, headers=ann).status_code == 403
    copy = client.post(f"{API}/lessons/import", headers=ann,
                       json=client.get(f"{starter}/export", headers=ann).json())
    assert copy.status_code == 201
    assert client.patch(f"{API}/lessons/{copy.json()['id']}", json={"title": "my /s/"},
                        headers=ann).status_code == 200
    pose = client.post(f"{API}/poses", headers=ann,
                       json={"name": f"t {lesson['id']}", "params": {"tip_height": 1.0}}).json()
    assert pose["owner_id"] is not None
    pose_url = f"{API}/poses/{pose['id']}"
    teacher = as_user("teacher")[1]
    assert client.get(pose_url, headers=teacher).status_code == 200
    for someone_else in (ben, as_user("clinician")[1]):
        assert client.patch(pose_url, json={"description": "x"},
                            headers=someone_else).status_code == 403
    assert client.patch(pose_url, json={"description": "mine"}, headers=ann).status_code == 200
    assert client.delete(pose_url, headers=admin).status_code == 204


def test_the_document_declares_the_token_401_and_403_of_every_operation_that_needs_one(client):
    document = client.get(f"{API}/openapi.json").json()
    assert document["components"]["securitySchemes"]["bearerToken"] == {
        "type": "http", "scheme": "bearer", "description": "a token from POST /auth/sessions"}
    undocumented = []
    for path, operations in document["paths"].items():
        for method, operation in operations.items():
            allowed = ROLE_TABLE[operation["operationId"]]
            if allowed == "open":
                continue
            limited = set(allowed) != set(CALLERS[1:]) and operation["operationId"] not in \
                SESSION_ROUTES  # a session route refuses another kind of token with 401
            needs = {"401", "403"} if limited else {"401"}
            missing = needs - set(operation["responses"])
            if missing or {"bearerToken": []} not in operation.get("security", []):
                undocumented.append(f"{method.upper()} {path}: {sorted(missing)} or security")
    assert not undocumented, "\n".join(undocumented)
