"""Signed-in callers for API tests: users and children with bearer tokens, made straight in the
database the app uses.

Signing in through the API costs an argon2id hash (over a second on a busy machine) per token,
and each failure counts against the attempt limits; these helpers store a user with a cheap
hash of PASSWORD and a token's SHA-256 as ``accounts.sign_in`` would, so a test gets a caller
at once. The routes see the same rows either way. ``signed_in(client, role)`` sets the token as
the client's default header; ``bearer(role)`` gives the header alone.
"""

import secrets
from itertools import count

from argon2 import PasswordHasher
from sqlalchemy import Engine
from sqlalchemy.orm import Session

from glasshead import accounts
from glasshead.store.base import utc_now
from glasshead.store.db import get_engine
from glasshead.store.users import AuthToken, ChildToken, User

PASSWORD = "correct horse battery"
#: A valid argon2id hash of PASSWORD with the cheapest parameters (signing in with it works and
#: upgrades the hash, as for any weaker hash).
CHEAP_HASH = PasswordHasher(time_cost=1, memory_cost=8, parallelism=1).hash(PASSWORD)
_numbers = count(1)


def add_user(role: str, username: str | None = None, engine: Engine | None = None) -> int:
    """A new user of ``role`` (username ``<role>-<n>@test.example`` unless given); its id."""
    username = username or f"{role}-{next(_numbers)}@test.example"
    with Session(engine or get_engine()) as session:
        user = User(username=username, display_name=username.split("@")[0], role=role,
                    password_hash=CHEAP_HASH)
        session.add(user)
        session.commit()
        return user.id


def token_for(user_id: int, engine: Engine | None = None) -> str:
    """A new valid token of user ``user_id``."""
    token = secrets.token_urlsafe(accounts.TOKEN_BYTES)
    now = utc_now()
    with Session(engine or get_engine()) as session:
        session.add(AuthToken(token_sha256=accounts.token_sha256(token), user_id=user_id,
                              created_at=now, expires_at=now + accounts.TOKEN_LIFETIME))
        session.commit()
    return token


def child_token_for(child_id: int, engine: Engine | None = None) -> str:
    """A new valid token of child ``child_id`` (as from POST /auth/child-sessions)."""
    token = secrets.token_urlsafe(accounts.TOKEN_BYTES)
    now = utc_now()
    with Session(engine or get_engine()) as session:
        session.add(ChildToken(token_sha256=accounts.token_sha256(token), child_id=child_id,
                               created_at=now, expires_at=now + accounts.CHILD_TOKEN_LIFETIME))
        session.commit()
    return token


def header(token: str) -> dict:
    return {"Authorization": f"Bearer {token}"}


def bearer(role: str, username: str | None = None, engine: Engine | None = None) -> dict:
    """The Authorization header of a new user of ``role``."""
    return header(token_for(add_user(role, username, engine), engine))


def child_bearer(child_id: int, engine: Engine | None = None) -> dict:
    return header(child_token_for(child_id, engine))


def signed_in(client, role: str = "admin", username: str | None = None):
    """``client`` with a new user of ``role`` signed in on every request; returns it."""
    client.headers.update(bearer(role, username))
    return client
