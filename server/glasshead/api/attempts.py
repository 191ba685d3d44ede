"""Limits on failed sign-ins: passwords per username and per client address, join codes per
client address.

Each failure is a row in ``sign_in_attempts`` (schema revision 0008), so that every worker of
a deployment counts the same failures. Before a sign-in is checked, the failures of its keys in
the last ``WINDOW`` are counted; at the limit the answer is 429 with ``Retry-After`` (the
seconds until the oldest of them leaves the window), and no password is hashed. A successful
sign-in clears its username's failures (not its address's: one person's success says nothing
of the guesses of another behind the same address).

A username gets ``USERNAME_LIMIT`` failures: enough for a few typing mistakes, too few for
guessing. An address gets more (``ADDRESS_LIMIT``), since a school's classroom often reaches
the server through one address: it bounds one machine trying many usernames, or many join
codes (25^6 of them: at 30 failures in 15 minutes, finding one takes years).
"""

from datetime import timedelta

from fastapi import HTTPException, Request
from sqlalchemy import delete, func, select
from sqlalchemy.orm import Session

from glasshead.api.error_responses import Responses
from glasshead.store.base import utc_now
from glasshead.store.users import SignInAttempt

#: How long a failure counts.
WINDOW = timedelta(minutes=15)
#: Failures of one username within WINDOW before its sign-ins are refused.
USERNAME_LIMIT = 5
#: Failures from one client address within WINDOW before its sign-ins are refused.
ADDRESS_LIMIT = 30
#: The 429 of an operation with attempt limits, for its ``responses``.
TOO_MANY: Responses = {429: {
    "description": "too many failed attempts for this username or from this address in the last "
                   "15 minutes; Retry-After gives the seconds to wait",
    "headers": {"Retry-After": {"description": "seconds", "schema": {"type": "integer"}}}}}


def username_key(username: str) -> str:
    return "username:" + username.strip().lower()[:280]


def address_key(request: Request, kind: str = "address") -> str:
    """``kind:<the client's address>`` (the proxy's, behind a reverse proxy that does not pass
    it on: run uvicorn with --proxy-headers there)."""
    host = request.client.host if request.client is not None else "unknown"
    return f"{kind}:{host}"


def check(session: Session, *keys: str) -> None:
    """429 with Retry-After when any of ``keys`` has reached its limit within WINDOW."""
    since = utc_now() - WINDOW
    for key in keys:
        limit = USERNAME_LIMIT if key.startswith("username:") else ADDRESS_LIMIT
        count, oldest = session.execute(
            select(func.count(), func.min(SignInAttempt.failed_at))
            .where(SignInAttempt.key == key, SignInAttempt.failed_at > since)).one()
        if count >= limit:
            retry_after = max(1, int((oldest + WINDOW - utc_now()).total_seconds()) + 1)
            raise HTTPException(
                status_code=429, headers={"Retry-After": str(retry_after)},
                detail=f"too many failed attempts ({count} in {WINDOW.seconds // 60} minutes); "
                       f"try again in {retry_after} s")


def record_failure(session: Session, *keys: str) -> None:
    """Count a failure against each of ``keys`` (committed), forgetting those past WINDOW."""
    now = utc_now()
    session.execute(delete(SignInAttempt).where(SignInAttempt.key.in_(keys),
                                                SignInAttempt.failed_at <= now - WINDOW))
    session.add_all(SignInAttempt(key=key, failed_at=now) for key in keys)
    session.commit()


def clear(session: Session, key: str) -> None:
    """Forget ``key``'s failures (committed): its owner has just signed in."""
    session.execute(delete(SignInAttempt).where(SignInAttempt.key == key))
    session.commit()
