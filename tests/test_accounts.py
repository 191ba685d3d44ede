"""Passwords and tokens (glasshead.accounts): argon2 hashes, signing in, expiry and revocation,
on SQLite and on a real PostgreSQL server (tests/postgres_support.py)."""

from datetime import timedelta

import pytest
from sqlalchemy import select
from sqlalchemy.orm import Session

from glasshead import accounts
from glasshead.accounts import AccountError
from glasshead.store.db import engine_for, upgrade_to_head
from glasshead.store.lessons import Child, SchoolClass
from glasshead.store.users import AuthToken

PASSWORD = "correct horse battery"


@pytest.fixture(params=["sqlite", "postgresql"])
def session(request, tmp_path):
    """A session on a new, migrated database: a SQLite file, then a real PostgreSQL server."""
    if request.param == "sqlite":
        url = f"sqlite:///{tmp_path / 'store.sqlite3'}"
    else:
        server = request.getfixturevalue("postgres_server")
        url = server.url(server.create_database())
    engine = engine_for(url)
    upgrade_to_head(engine)
    with Session(engine, expire_on_commit=False) as session:
        yield session
    engine.dispose()


@pytest.fixture
def ann(session):
    user = accounts.create_user(session, "  Ann@School.example ", PASSWORD, "teacher", "Ann")
    session.commit()
    return user


def test_a_password_is_stored_as_an_argon2id_hash_that_verifies_only_itself():
    hashed = accounts.hash_password(PASSWORD)
    assert hashed.startswith("$argon2id$") and PASSWORD not in hashed
    assert accounts.verify_password(hashed, PASSWORD)
    assert not accounts.verify_password(hashed, PASSWORD + "!")
    assert not accounts.verify_password("not a hash", PASSWORD)
    assert accounts.hash_password(PASSWORD) != hashed  # a new salt every time


def test_passwords_shorter_than_eight_characters_are_refused():
    with pytest.raises(AccountError, match="8 to 1024 characters; this one has 7"):
        accounts.hash_password("1234567")


def test_usernames_are_trimmed_lower_cased_and_unique(session, ann):
    assert ann.username == "ann@school.example" and ann.display_name == "Ann"
    with pytest.raises(AccountError, match="taken"):
        accounts.create_user(session, "ANN@school.example", PASSWORD, "author")
    with pytest.raises(AccountError, match="no spaces"):
        accounts.create_user(session, "ann smith", PASSWORD, "author")
    with pytest.raises(AccountError, match="role 'pupil' is not one of"):
        accounts.create_user(session, "bob", PASSWORD, "pupil")


def test_signing_in_gives_a_token_whose_sha256_alone_is_stored(session, ann):
    issued = accounts.sign_in(session, "ANN@school.example", PASSWORD)
    assert issued is not None and issued.user.id == ann.id and len(issued.token) == 43
    stored = session.scalars(select(AuthToken)).one()
    assert stored.token_sha256 == accounts.token_sha256(issued.token) != issued.token
    lifetime = stored.expires_at - stored.created_at
    assert lifetime == accounts.TOKEN_LIFETIME == timedelta(hours=12)
    assert accounts.valid_token(session, issued.token).user.id == ann.id


def test_a_wrong_password_and_an_unknown_user_both_give_no_token(session, ann):
    assert accounts.sign_in(session, "ann@school.example", "wrong password") is None
    assert accounts.sign_in(session, "nobody@school.example", PASSWORD) is None
    assert accounts.sign_in(session, "", PASSWORD) is None
    assert session.scalars(select(AuthToken)).all() == []


def test_a_token_is_refused_from_the_moment_it_expires(session, ann, monkeypatch):
    issued = accounts.sign_in(session, ann.username, PASSWORD)
    start = issued.expires_at - accounts.TOKEN_LIFETIME
    monkeypatch.setattr(accounts, "utc_now", lambda: start + timedelta(hours=11, minutes=59))
    assert accounts.valid_token(session, issued.token) is not None
    monkeypatch.setattr(accounts, "utc_now", lambda: issued.expires_at)
    assert accounts.valid_token(session, issued.token) is None


def test_a_revoked_token_is_refused_and_others_of_the_user_are_not(session, ann):
    first = accounts.sign_in(session, ann.username, PASSWORD)
    second = accounts.sign_in(session, ann.username, PASSWORD)
    accounts.revoke(accounts.valid_token(session, first.token))
    session.commit()
    assert accounts.valid_token(session, first.token) is None
    assert accounts.valid_token(session, second.token) is not None
    assert accounts.revoke_all(session, ann) == 1
    session.commit()
    assert accounts.valid_token(session, second.token) is None


def test_an_unknown_token_is_refused(session, ann):
    assert accounts.valid_token(session, "x" * 43) is None


def test_a_child_signs_in_only_with_their_own_class_code(session):
    owls = SchoolClass(name="Owls", join_code="7KQ4MX")
    session.add(owls)
    session.flush()
    mia = Child(class_id=owls.id, display_name="Mia", avatar="cat")
    session.add(mia)
    session.commit()
    issued = accounts.sign_in_child(session, "7kq4mx", mia.id)
    assert issued is not None and issued.child.id == mia.id
    stored = accounts.valid_child_token(session, issued.token)
    assert stored.expires_at - stored.created_at == timedelta(hours=8)
    assert accounts.valid_token(session, issued.token) is None  # not a user's token
    assert accounts.sign_in_child(session, "AAAAAA", mia.id) is None
    assert accounts.sign_in_child(session, "7KQ4MX", mia.id + 1) is None
