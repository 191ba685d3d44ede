"""Passwords and bearer tokens: the rules of signing in, shared by the API and the CLI.

Passwords are hashed with argon2id (argon2-cffi's ``PasswordHasher``: RFC 9106's low-memory
profile, 64 MiB, 3 passes, a random 16-byte salt per hash); a hash made with weaker parameters is
replaced by a new one the next time its owner signs in. A token is 32 random bytes from
``secrets`` (256 bits, URL-safe base64, 43 characters); the database keeps only its SHA-256,
which is enough because a random 256-bit value cannot be guessed, unlike a password, so it needs
no slow hash. A token lasts TOKEN_LIFETIME, then its owner signs in again. A child signs in
with their class's join code and their own id (picked by name and avatar), for a token of the
same kind that lasts CHILD_TOKEN_LIFETIME and names the child, not a user.

An unknown username is checked against a dummy hash, so that it costs as long as a wrong
password and both get the same answer: nobody learns which usernames exist by asking.
"""

import hashlib
import secrets
from dataclasses import dataclass
from datetime import datetime, timedelta
from functools import cache

from argon2 import PasswordHasher
from argon2.exceptions import InvalidHashError, VerificationError
from sqlalchemy import func, select
from sqlalchemy.orm import Session

from glasshead.store.base import utc_now
from glasshead.store.lessons import Child, SchoolClass
from glasshead.store.users import MAX_USERNAME_LENGTH, ROLES, AuthToken, ChildToken, User

#: How long a token from signing in lasts.
TOKEN_LIFETIME = timedelta(hours=12)
#: How long a child's token lasts: a school day.
CHILD_TOKEN_LIFETIME = timedelta(hours=8)
#: Random bytes in a token (256 bits).
TOKEN_BYTES = 32
#: Password length bounds, characters: long enough to resist guessing, short enough that hashing
#: one is not a way to tie up the server.
MIN_PASSWORD_LENGTH = 8
MAX_PASSWORD_LENGTH = 1024

_hasher = PasswordHasher()


@cache
def _dummy_hash() -> str:
    """Verified against when the username is unknown, so both failures take as long; made on
    first use rather than at import (a hash takes a good part of a second)."""
    return _hasher.hash(secrets.token_urlsafe(16))


class AccountError(ValueError):
    """A username, role or password that cannot be used, with the reason as its message."""


@dataclass(frozen=True)
class IssuedToken:
    """A token as given to its owner once; only its hash is stored."""

    token: str
    expires_at: datetime
    user: User


@dataclass(frozen=True)
class IssuedChildToken:
    """A child's token as given once; only its hash is stored."""

    token: str
    expires_at: datetime
    child: Child


def hash_password(password: str) -> str:
    """The argon2id hash of ``password`` (PHC string), after checking its length."""
    check_password(password)
    return _hasher.hash(password)


def verify_password(password_hash: str, password: str) -> bool:
    """Whether ``password`` is the one ``password_hash`` was made from."""
    try:
        return _hasher.verify(password_hash, password)
    except (VerificationError, InvalidHashError):
        return False


def check_password(password: str) -> None:
    if not MIN_PASSWORD_LENGTH <= len(password) <= MAX_PASSWORD_LENGTH:
        raise AccountError(f"a password has {MIN_PASSWORD_LENGTH} to {MAX_PASSWORD_LENGTH} "
                           f"characters; this one has {len(password)}")


def normalise_username(username: str) -> str:
    """Trimmed and lower-cased; AccountError when empty, too long or containing spaces."""
    name = username.strip().lower()
    if not name or len(name) > MAX_USERNAME_LENGTH or any(c.isspace() for c in name):
        raise AccountError(f"a username has 1 to {MAX_USERNAME_LENGTH} characters and no "
                           f"spaces: {username!r}")
    return name


def check_role(role: str) -> str:
    if role not in ROLES:
        raise AccountError(f"role {role!r} is not one of {', '.join(ROLES)}")
    return role


def token_sha256(token: str) -> str:
    return hashlib.sha256(token.encode("utf-8", "surrogatepass")).hexdigest()


def find_user(session: Session, username: str) -> User | None:
    try:
        name = normalise_username(username)
    except AccountError:
        return None
    return session.scalar(select(User).where(User.username == name))


def create_user(session: Session, username: str, password: str, role: str,
                display_name: str | None = None) -> User:
    """A new user (added to ``session``, not committed); AccountError for a taken username, an
    unknown role or a password out of bounds."""
    name = normalise_username(username)
    check_role(role)
    if session.scalar(select(User.id).where(User.username == name)) is not None:
        raise AccountError(f"username {name!r} is taken")
    user = User(username=name, display_name=(display_name or "").strip() or name, role=role,
                password_hash=hash_password(password))
    session.add(user)
    return user


def count_admins(session: Session) -> int:
    return session.scalar(select(func.count()).where(User.role == "admin")) or 0


def sign_in(session: Session, username: str, password: str) -> IssuedToken | None:
    """A new token for the user with this username and password (committed), or None."""
    user = find_user(session, username)
    if user is None:
        verify_password(_dummy_hash(), password)
        return None
    if not verify_password(user.password_hash, password):
        return None
    if _hasher.check_needs_rehash(user.password_hash):
        user.password_hash = _hasher.hash(password)
    token = secrets.token_urlsafe(TOKEN_BYTES)
    now = utc_now()
    record = AuthToken(token_sha256=token_sha256(token), user=user, created_at=now,
                       expires_at=now + TOKEN_LIFETIME)
    session.add(record)
    session.commit()
    return IssuedToken(token=token, expires_at=record.expires_at, user=user)


def valid_token(session: Session, token: str) -> AuthToken | None:
    """The stored token for ``token`` while it is neither expired nor revoked, else None."""
    record = session.scalar(select(AuthToken).where(AuthToken.token_sha256 == token_sha256(token)))
    if record is None or record.revoked_at is not None or record.expires_at <= utc_now():
        return None
    return record


def revoke(record: AuthToken | ChildToken) -> None:
    record.revoked_at = utc_now()


def revoke_all(session: Session, user: User) -> int:
    """Revoke every live token of ``user`` (a changed password signs them out everywhere)."""
    now = utc_now()
    live = [t for t in user.tokens if t.revoked_at is None and t.expires_at > now]
    for record in live:
        record.revoked_at = now
    return len(live)


def sign_in_child(session: Session, join_code: str, child_id: int) -> IssuedChildToken | None:
    """A new token for child ``child_id`` when they are in the class with ``join_code`` (any
    case, spaces ignored), committed; None otherwise."""
    code = "".join(join_code.split()).upper()
    child = session.scalar(select(Child).join(SchoolClass, Child.class_id == SchoolClass.id)
                           .where(SchoolClass.join_code == code, Child.id == child_id))
    if child is None:
        return None
    token = secrets.token_urlsafe(TOKEN_BYTES)
    now = utc_now()
    record = ChildToken(token_sha256=token_sha256(token), child=child, created_at=now,
                        expires_at=now + CHILD_TOKEN_LIFETIME)
    session.add(record)
    session.commit()
    return IssuedChildToken(token=token, expires_at=record.expires_at, child=child)


def valid_child_token(session: Session, token: str) -> ChildToken | None:
    """The stored child's token for ``token`` while neither expired nor revoked, else None."""
    record = session.scalar(select(ChildToken)
                            .where(ChildToken.token_sha256 == token_sha256(token)))
    if record is None or record.revoked_at is not None or record.expires_at <= utc_now():
        return None
    return record
