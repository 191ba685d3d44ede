"""Failed sign-ins are limited: passwords per username and per client address, join codes per
address, with 429 and Retry-After past the limit; a success clears its username's failures;
the count lives in the database, so a second app on the same database (another worker) sees
it. And the class roster a child picks their name from."""

from datetime import timedelta

import pytest
from fastapi.testclient import TestClient
from sqlalchemy import func, select
from sqlalchemy.orm import Session

from accounts_support import PASSWORD, add_user
from glasshead.api import attempts
from glasshead.store.db import get_engine
from glasshead.store.lessons import Child, SchoolClass
from glasshead.store.users import SignInAttempt

API = "/api/v1"
CODE = "7KQ4MX"


@pytest.fixture
def client(start_app):
    client = start_app()[1]
    add_user("teacher", "ann@school.example")
    add_user("teacher", "bob@school.example")
    with Session(get_engine()) as session:
        owls = SchoolClass(name="Owls", join_code=CODE)
        session.add(owls)
        session.flush()
        session.add_all([Child(class_id=owls.id, display_name=name, avatar=avatar)
                         for name, avatar in (("Zoe", "cat"), ("Ada", "owl"))])
        session.commit()
    return client


def sign_in(client, username, password="not the password"):
    return client.post(f"{API}/auth/sessions", json={"username": username, "password": password})


def test_the_sixth_wrong_password_in_a_row_is_a_429_even_with_the_right_one(client):
    assert [sign_in(client, "ann@school.example").status_code
            for _ in range(attempts.USERNAME_LIMIT)] == [401] * attempts.USERNAME_LIMIT
    refused = sign_in(client, "ANN@school.example ", PASSWORD)  # the same username
    assert refused.status_code == 429
    retry_after = int(refused.headers["Retry-After"])
    assert 0 < retry_after <= attempts.WINDOW.total_seconds() + 1
    assert "too many failed attempts" in refused.json()["detail"]
    # Another username from the same address is not limited yet.
    assert sign_in(client, "bob@school.example", PASSWORD).status_code == 201


def test_failures_older_than_the_window_no_longer_count(client, monkeypatch):
    for _ in range(attempts.USERNAME_LIMIT):
        sign_in(client, "ann@school.example")
    later = attempts.utc_now() + attempts.WINDOW + timedelta(seconds=1)
    monkeypatch.setattr(attempts, "utc_now", lambda: later)
    assert sign_in(client, "ann@school.example", PASSWORD).status_code == 201


def test_a_success_clears_the_usernames_failures(client):
    for _ in range(attempts.USERNAME_LIMIT - 1):
        assert sign_in(client, "ann@school.example").status_code == 401
    assert sign_in(client, "ann@school.example", PASSWORD).status_code == 201
    for _ in range(attempts.USERNAME_LIMIT - 1):
        assert sign_in(client, "ann@school.example").status_code == 401
    assert sign_in(client, "ann@school.example", PASSWORD).status_code == 201


def test_one_address_trying_many_usernames_is_limited_too(client, monkeypatch):
    monkeypatch.setattr(attempts, "ADDRESS_LIMIT", 3)
    assert [sign_in(client, f"guess{k}@school.example").status_code for k in range(3)] \
        == [401] * 3
    assert sign_in(client, "ann@school.example", PASSWORD).status_code == 429


def test_the_count_is_shared_by_every_app_on_the_database(client):
    from glasshead.api.app import create_app

    for _ in range(attempts.USERNAME_LIMIT):
        sign_in(client, "ann@school.example")
    other = TestClient(create_app())  # another app (a worker) on the same database
    assert sign_in(other, "ann@school.example", PASSWORD).status_code == 429
    with Session(get_engine()) as session:
        stored = session.scalar(select(func.count()).select_from(SignInAttempt)
                                .where(SignInAttempt.key == "username:ann@school.example"))
    assert stored == attempts.USERNAME_LIMIT


def test_wrong_join_codes_are_limited_per_address_for_sign_in_and_the_roster(client,
                                                                           monkeypatch):
    monkeypatch.setattr(attempts, "ADDRESS_LIMIT", 4)
    assert client.post(f"{API}/auth/class-roster", json={"join_code": "WRONG1"}).status_code \
        == 404
    for _ in range(3):
        wrong = client.post(f"{API}/auth/child-sessions", json={"join_code": "WRONG1",
                                                                "child_id": 1})
        assert wrong.status_code == 401
    for refused in (client.post(f"{API}/auth/class-roster", json={"join_code": CODE}),
                    client.post(f"{API}/auth/child-sessions", json={"join_code": CODE,
                                                                    "child_id": 1})):
        assert refused.status_code == 429 and int(refused.headers["Retry-After"]) > 0


def test_the_roster_names_the_class_and_its_children_by_name_with_their_avatars(client):
    roster = client.post(f"{API}/auth/class-roster", json={"join_code": " 7kq4mx "})
    assert roster.status_code == 200
    body = roster.json()
    assert body["class_name"] == "Owls"
    assert [(c["display_name"], c["avatar"]) for c in body["children"]] == [("Ada", "owl"),
                                                                            ("Zoe", "cat")]
    ada = body["children"][0]["id"]
    signed = client.post(f"{API}/auth/child-sessions", json={"join_code": CODE,
                                                             "child_id": ada})
    assert signed.status_code == 201 and signed.json()["child"]["display_name"] == "Ada"
