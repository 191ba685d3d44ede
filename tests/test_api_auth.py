"""Signing in and out, and the users admins manage, over HTTP: 401s, 403s, 409s and 412s."""

from datetime import datetime, timedelta

import pytest
from sqlalchemy.orm import Session

from glasshead import accounts
from glasshead.store.db import get_engine

API = "/api/v1"
PASSWORD = "correct horse battery"
WRONG = "unknown username or wrong password"


@pytest.fixture
def client(start_app):
    client = start_app()[1]
    with Session(get_engine()) as session:
        accounts.create_user(session, "root", PASSWORD, "admin", "Head Office")
        accounts.create_user(session, "ann@school.example", PASSWORD, "teacher", "Ann")
        session.commit()
    return client


def sign_in(client, username, password=PASSWORD):
    return client.post(f"{API}/auth/sessions", json={"username": username, "password": password})


def bearer(client, username) -> dict:
    return {"Authorization": f"Bearer {sign_in(client, username).json()['token']}"}


def test_signing_in_gives_a_token_that_names_its_user(client):
    before = accounts.utc_now()
    answer = sign_in(client, "  ANN@school.example")
    after = accounts.utc_now()
    assert answer.status_code == 201
    body = answer.json()
    assert body["token_type"] == "bearer" and len(body["token"]) == 43
    assert body["user"]["username"] == "ann@school.example" and body["user"]["role"] == "teacher"
    expires = datetime.fromisoformat(body["expires_at"].replace("Z", "+00:00"))
    # Issued during the request: between the clock read before it and after it.
    assert before.replace(microsecond=0) <= expires - accounts.TOKEN_LIFETIME <= after
    me = client.get(f"{API}/auth/me", headers={"Authorization": f"Bearer {body['token']}"})
    assert me.status_code == 200 and me.json()["display_name"] == "Ann"
    assert "password_hash" not in me.json()


def test_a_wrong_password_and_an_unknown_user_get_the_same_401(client):
    wrong, unknown = sign_in(client, "ann@school.example", "not it at all"), sign_in(client, "eve")
    assert wrong.status_code == unknown.status_code == 401
    assert wrong.json() == unknown.json() == {"detail": WRONG}


@pytest.mark.parametrize("header", [None, "Bearer not-a-token", "Basic cm9vdDpyb290", "Bearer"])
def test_a_missing_or_unknown_token_is_a_401_asking_for_a_bearer_token(client, header):
    answer = client.get(f"{API}/auth/me", headers={} if header is None else
                        {"Authorization": header})
    assert answer.status_code == 401 and answer.headers["WWW-Authenticate"] == "Bearer"
    assert answer.json()["detail"].startswith("not signed in")


def test_signing_out_revokes_the_token_and_only_that_one(client):
    first, second = bearer(client, "ann@school.example"), bearer(client, "ann@school.example")
    assert client.delete(f"{API}/auth/sessions/current", headers=first).status_code == 204
    assert client.get(f"{API}/auth/me", headers=first).status_code == 401
    assert client.delete(f"{API}/auth/sessions/current", headers=first).status_code == 401
    assert client.get(f"{API}/auth/me", headers=second).status_code == 200


def test_an_expired_token_is_a_401(client, monkeypatch):
    headers = bearer(client, "ann@school.example")
    later = accounts.utc_now() + accounts.TOKEN_LIFETIME + timedelta(seconds=1)
    monkeypatch.setattr(accounts, "utc_now", lambda: later)
    answer = client.get(f"{API}/auth/me", headers=headers)
    assert answer.status_code == 401 and answer.headers["WWW-Authenticate"] == "Bearer"


@pytest.mark.parametrize("method, path", [("GET", "/users"), ("POST", "/users"),
                                          ("GET", "/users/1"), ("PATCH", "/users/1"),
                                          ("DELETE", "/users/1")])
def test_user_management_is_for_admins_only(client, method, path):
    body = {"username": "bob", "role": "author", "password": PASSWORD} if method == "POST" \
        else {"display_name": "x"} if method == "PATCH" else None
    anonymous = client.request(method, API + path, json=body)
    assert anonymous.status_code == 401
    teacher = client.request(method, API + path, json=body,
                             headers=bearer(client, "ann@school.example"))
    assert teacher.status_code == 403
    assert teacher.json()["detail"] == "this needs the role admin; ann@school.example is teacher"


def test_an_admin_creates_lists_and_finds_users_by_role(client):
    admin = bearer(client, "root")
    created = client.post(f"{API}/users", headers=admin, json={
        "username": "Cleo@Clinic.example", "role": "clinician", "password": PASSWORD})
    assert created.status_code == 201 and created.headers["ETag"].startswith('"user-')
    assert created.json()["username"] == "cleo@clinic.example"
    assert sign_in(client, "cleo@clinic.example").status_code == 201
    listing = client.get(f"{API}/users", headers=admin).json()
    assert listing["total"] == 3
    assert [u["username"] for u in listing["users"]] == ["ann@school.example",
                                                         "cleo@clinic.example", "root"]
    clinicians = client.get(f"{API}/users?role=clinician", headers=admin).json()
    assert [u["role"] for u in clinicians["users"]] == ["clinician"]
    clash = client.post(f"{API}/users", headers=admin, json={
        "username": "CLEO@clinic.example", "role": "author", "password": PASSWORD})
    assert clash.status_code == 409 and "taken" in clash.json()["detail"]
    short = client.post(f"{API}/users", headers=admin, json={
        "username": "dan", "role": "author", "password": "short"})
    assert short.status_code == 422


def test_a_stale_if_match_is_a_412_and_a_new_password_signs_the_user_out(client):
    admin = bearer(client, "root")
    ann_token = bearer(client, "ann@school.example")
    [ann] = client.get(f"{API}/users?role=teacher", headers=admin).json()["users"]
    tag = client.get(f"{API}/users/{ann['id']}", headers=admin).headers["ETag"]
    changed = client.patch(f"{API}/users/{ann['id']}", headers={**admin, "If-Match": tag},
                           json={"role": "author", "password": "a new password"})
    assert changed.status_code == 200 and changed.json()["role"] == "author"
    assert changed.headers["ETag"] != tag
    stale = client.patch(f"{API}/users/{ann['id']}", headers={**admin, "If-Match": tag},
                         json={"display_name": "Ann B"})
    assert stale.status_code == 412 and stale.headers["ETag"] == changed.headers["ETag"]
    assert client.get(f"{API}/auth/me", headers=ann_token).status_code == 401
    assert sign_in(client, "ann@school.example").status_code == 401
    assert sign_in(client, "ann@school.example", "a new password").status_code == 201


def test_the_last_admin_cannot_be_demoted_or_removed(client):
    admin = bearer(client, "root")
    me = client.get(f"{API}/auth/me", headers=admin).json()
    demote = client.patch(f"{API}/users/{me['id']}", headers=admin, json={"role": "teacher"})
    assert demote.status_code == 409 and "only admin" in demote.json()["detail"]
    assert client.delete(f"{API}/users/{me['id']}", headers=admin).status_code == 409
    assert client.get(f"{API}/auth/me", headers=admin).json()["role"] == "admin"


def test_a_removed_user_and_their_tokens_are_gone(client):
    admin, ann_token = bearer(client, "root"), bearer(client, "ann@school.example")
    ann_id = client.get(f"{API}/auth/me", headers=ann_token).json()["id"]
    assert client.delete(f"{API}/users/{ann_id}", headers=admin).status_code == 204
    assert client.get(f"{API}/auth/me", headers=ann_token).status_code == 401
    assert client.get(f"{API}/users/{ann_id}", headers=admin).status_code == 404
    assert client.get(f"{API}/users", headers=admin).json()["total"] == 1
