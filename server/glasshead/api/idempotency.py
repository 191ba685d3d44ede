"""``Idempotency-Key`` for imports: an upload retried after a lost response is stored once.

POST /epg/recordings and POST /fits take an optional ``Idempotency-Key`` header (1 to 200
printable ASCII characters; a UUID is the usual choice). The first request with a key is handled
as usual, and its answer is stored with the key and a SHA-256 of what was uploaded (the file's
bytes and the form's fields, not the multipart framing, whose boundary a client may change on a
retry), in the same transaction as the recordings or the fit job. Then, for KEEP_FOR:

- the same key with the same upload gets the first answer again (same status, body and
  Location, plus ``Idempotent-Replayed: true``) and stores nothing new;
- the same key with a different upload is a 422 naming the key;
- two requests with one key at once: one commits, the other finds its row taken (the primary
  key), rolls its own work back and answers as a retry.

A request without the header is never deduplicated. Keys are kept per operation.
"""

import hashlib
from datetime import timedelta
from typing import Annotated

from fastapi import Header, HTTPException
from fastapi.responses import JSONResponse
from sqlalchemy import delete
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Session

from glasshead.store.base import utc_now
from glasshead.store.idempotency_keys import MAX_KEY_LENGTH, IdempotencyKey

#: How long a key is kept: a retry after this is a new upload.
KEEP_FOR = timedelta(hours=24)
#: The header that marks an answer given again.
REPLAYED_HEADER = "Idempotent-Replayed"

IdempotencyKeyHeader = Annotated[str | None, Header(
    alias="Idempotency-Key", min_length=1, max_length=MAX_KEY_LENGTH, pattern=r"^[!-~]+$",
    description="any unique string (a UUID): a retry with the same key and the same upload "
                "within 24 h gets the first answer and stores nothing new; with a different "
                "upload, 422")]


def upload_digest(*parts: bytes | str | int | None) -> str:
    """SHA-256 (hex) of the upload's parts in order, each length-prefixed, None distinct."""
    digest = hashlib.sha256()
    for part in parts:
        if part is None:
            digest.update(b"\xff" * 8)
            continue
        data = part if isinstance(part, bytes) else str(part).encode()
        digest.update(len(data).to_bytes(8, "little"))
        digest.update(data)
    return digest.hexdigest()


def replay(session: Session, operation: str, key: str | None,
           digest: str) -> JSONResponse | None:
    """The first answer for ``key`` (None: the key is new, expired or not given); 422 when the
    key came with a different upload."""
    if key is None:
        return None
    row = session.get(IdempotencyKey, (operation, key))
    if row is None:
        return None
    if row.created_at < utc_now() - KEEP_FOR:
        session.delete(row)
        session.commit()
        return None
    if row.request_sha256 != digest:
        raise HTTPException(status_code=422, detail=(
            f"header Idempotency-Key: {key!r} was already used for a different upload; send a "
            f"new key with a new upload"))
    return JSONResponse(row.response, status_code=row.status_code,
                        headers={**row.headers, REPLAYED_HEADER: "true"})


def remember(session: Session, operation: str, key: str | None, digest: str, status_code: int,
             response: dict, headers: dict | None = None) -> None:
    """Add the answer for ``key`` to the session, to be committed with the work it answers
    (nothing without a key); keys past KEEP_FOR are deleted on the way."""
    if key is None:
        return
    session.execute(delete(IdempotencyKey).where(IdempotencyKey.created_at
                                                 < utc_now() - KEEP_FOR))
    session.add(IdempotencyKey(operation=operation, key=key, request_sha256=digest,
                               status_code=status_code, response=response,
                               headers=headers or {}))


def commit_or_replay(session: Session, operation: str, key: str | None,
                     digest: str) -> JSONResponse | None:
    """Commit the work and its key. None when it was committed; the other request's answer when
    a request with the same key committed first (this one's work is rolled back)."""
    try:
        session.commit()
    except IntegrityError:
        session.rollback()
        if key is None:
            raise
        answer = replay(session, operation, key, digest)
        if answer is None:
            raise
        return answer
    return None
