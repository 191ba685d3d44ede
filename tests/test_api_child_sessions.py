"""Children signing in with their class's join code: a token that names the child, never a user."""

from datetime import timedelta

import pytest
from sqlalchemy.orm import Session

from glasshead import accounts
from glasshead.store.db import get_engine
from glasshead.store.lessons import Child, SchoolClass

API = "/api/v1"
CODE = "7KQ4MX"
WRONG = "no child with that id in the class with that code"


@pytest.fixture
def children(start_app):
    """(client, ids): two classes with a child each; ids names them."""
    client = start_app()[1]
    with Session(get_engine()) as session:
        owls = SchoolClass(name="Owls", join_code=CODE)
        foxes = SchoolClass(name="Foxes", join_code="3CDEFG")
        mia = Child(display_name="Mia", avatar="cat")
        leo = Child(display_name="Leo", avatar="dog")
        session.add_all([owls, foxes])
        session.flush()
        mia.class_id, leo.class_id = owls.id, foxes.id
        session.add_all([mia, leo])
        session.commit()
        return client, {"mia": mia.id, "leo": leo.id}


def sign_in(client, code, child_id):
    return client.post(f"{API}/auth/child-sessions", json={"join_code": code,
                                                           "child_id": child_id})


def test_a_child_signs_in_with_the_class_code_in_any_case_and_is_named_by_the_token(children):
    client, ids = children
    answer = sign_in(client, " 7kq 4mx ", ids["mia"])
    assert answer.status_code == 201
    body = answer.json()
    assert body["child"]["display_name"] == "Mia" and body["child"]["avatar"] == "cat"
    assert len(body["token"]) == 43
    me = client.get(f"{API}/auth/child-sessions/current",
                    headers={"Authorization": f"Bearer {body['token']}"})
    assert me.status_code == 200 and me.json()["id"] == ids["mia"]


def test_a_child_of_another_class_or_a_wrong_code_gets_the_same_401(children):
    client, ids = children
    other_class, wrong_code = sign_in(client, CODE, ids["leo"]), sign_in(client, "AAAAAA", 1)
    assert other_class.status_code == wrong_code.status_code == 401
    assert other_class.json() == wrong_code.json() == {"detail": WRONG}


def test_a_childs_token_is_not_a_users_and_a_users_is_not_a_childs(children):
    client, ids = children
    with Session(get_engine()) as session:
        accounts.create_user(session, "root", "correct horse battery", "admin")
        session.commit()
    child = {"Authorization": f"Bearer {sign_in(client, CODE, ids['mia']).json()['token']}"}
    user_token = client.post(f"{API}/auth/sessions", json={
        "username": "root", "password": "correct horse battery"}).json()["token"]
    assert client.get(f"{API}/auth/me", headers=child).status_code == 401
    # A route for some roles of users: the child's token is valid, only not for this.
    refused = client.get(f"{API}/users", headers=child)
    assert refused.status_code == 403
    assert refused.json()["detail"] == f"this needs the role admin; child {ids['mia']}"
    assert client.get(f"{API}/auth/child-sessions/current",
                      headers={"Authorization": f"Bearer {user_token}"}).status_code == 401


def test_signing_out_and_expiry_end_a_childs_token(children, monkeypatch):
    client, ids = children
    first = {"Authorization": f"Bearer {sign_in(client, CODE, ids['mia']).json()['token']}"}
    second = {"Authorization": f"Bearer {sign_in(client, CODE, ids['mia']).json()['token']}"}
    assert client.delete(f"{API}/auth/child-sessions/current", headers=first).status_code == 204
    assert client.get(f"{API}/auth/child-sessions/current", headers=first).status_code == 401
    assert client.get(f"{API}/auth/child-sessions/current", headers=second).status_code == 200
    later = accounts.utc_now() + accounts.CHILD_TOKEN_LIFETIME + timedelta(seconds=1)
    monkeypatch.setattr(accounts, "utc_now", lambda: later)
    expired = client.get(f"{API}/auth/child-sessions/current", headers=second)
    assert expired.status_code == 401 and expired.headers["WWW-Authenticate"] == "Bearer"
