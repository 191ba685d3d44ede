"""The ``users`` and ``auth_tokens`` tables: who may sign in, and the tokens they were given.

A user signs in with a username (an email address will do) and a password; only an argon2 hash
of the password is stored (``glasshead.accounts``). Signing in gives a random opaque bearer token;
only its SHA-256 is stored, so a copy of the database lets nobody sign in as anyone. A token has
an expiry and is revoked (not deleted) when its user signs out, so a revoked token is told apart
from one that never existed in the logs of a later audit. Deleting a user deletes their tokens.
Children sign in too, with their class's join code, and get tokens of their own
(``child_tokens``, revision 0007). Failed sign-ins are kept a while in ``sign_in_attempts``
(revision 0008) to limit guessing.
"""

from datetime import datetime
from typing import TYPE_CHECKING

from sqlalchemy import ForeignKey, Integer, String
from sqlalchemy.orm import Mapped, mapped_column, relationship

from glasshead.store.base import Base, Timestamped, UtcDateTime, Versioned, utc_now

if TYPE_CHECKING:
    from glasshead.store.lessons import Child

#: The roles a user can have (docs/auth.md says what each may do).
ROLES = ("author", "teacher", "clinician", "admin")
#: Longest username, characters (the longest email address is 254).
MAX_USERNAME_LENGTH = 254
MAX_DISPLAY_NAME_LENGTH = 120


class User(Versioned, Timestamped, Base):
    """A person who signs in: an author, teacher, clinician or admin (children do not)."""

    __tablename__ = "users"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    #: Unique, stored as given after trimming and lower-casing (so "Ann@X.org" is "ann@x.org").
    username: Mapped[str] = mapped_column(String(MAX_USERNAME_LENGTH), unique=True)
    display_name: Mapped[str] = mapped_column(String(MAX_DISPLAY_NAME_LENGTH))
    #: One of ROLES.
    role: Mapped[str] = mapped_column(String(20))
    #: argon2id in PHC string format ($argon2id$v=19$m=...,t=...,p=...$salt$hash).
    password_hash: Mapped[str] = mapped_column(String(200))

    tokens: Mapped[list["AuthToken"]] = relationship(
        back_populates="user", cascade="all, delete-orphan", passive_deletes=True)


class AuthToken(Base):
    """One sign-in: the SHA-256 of a bearer token, whose it is, until when, and whether revoked."""

    __tablename__ = "auth_tokens"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    #: SHA-256 (hex) of the token sent in ``Authorization: Bearer``; the token itself is not kept.
    token_sha256: Mapped[str] = mapped_column(String(64), unique=True)
    user_id: Mapped[int] = mapped_column(ForeignKey("users.id", ondelete="CASCADE"), index=True)
    created_at: Mapped[datetime] = mapped_column(UtcDateTime(), default=utc_now)
    expires_at: Mapped[datetime] = mapped_column(UtcDateTime())
    #: When its user signed out with it (or an admin changed their password); None while valid.
    revoked_at: Mapped[datetime | None] = mapped_column(UtcDateTime(), nullable=True)

    user: Mapped[User] = relationship(back_populates="tokens")


class ChildToken(Base):
    """A child's sign-in with their class's join code: a token as ``AuthToken`` is, for a child.

    Kept apart from ``auth_tokens`` so that a child's token can never pass for a user's: the
    dependencies that look for a user do not read this table.
    """

    __tablename__ = "child_tokens"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    token_sha256: Mapped[str] = mapped_column(String(64), unique=True)
    child_id: Mapped[int] = mapped_column(ForeignKey("children.id", ondelete="CASCADE"),
                                          index=True)
    created_at: Mapped[datetime] = mapped_column(UtcDateTime(), default=utc_now)
    expires_at: Mapped[datetime] = mapped_column(UtcDateTime())
    revoked_at: Mapped[datetime | None] = mapped_column(UtcDateTime(), nullable=True)

    child: Mapped["Child"] = relationship()


class SignInAttempt(Base):
    """A failed sign-in, kept for a while to limit guessing (``glasshead.attempts``).

    ``key`` says what failed: ``username:<name>``, ``address:<client address>``, or
    ``child-address:<client address>`` for a child's join code. Kept in the database, not in a
    worker's memory, so that every worker of a deployment counts the same attempts.
    """

    __tablename__ = "sign_in_attempts"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    key: Mapped[str] = mapped_column(String(300), index=True)
    failed_at: Mapped[datetime] = mapped_column(UtcDateTime(), default=utc_now)
