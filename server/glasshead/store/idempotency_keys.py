"""The ``idempotency_keys`` table: the first answer to an import, kept for its retries.

A client that sends an upload and loses the response (a dropped connection, a timeout) cannot
tell whether it was stored. With an ``Idempotency-Key`` header it can simply send it again: the
first request's key is stored with a hash of what was uploaded and the answer given, in the same
transaction as what the import stored, so a retry finds either both or neither. Rows are kept
for ``api/idempotency.py``'s KEEP_FOR (24 h) and then deleted.
"""

from datetime import datetime

from sqlalchemy import JSON, Integer, String
from sqlalchemy.orm import Mapped, mapped_column

from glasshead.store.base import Base, UtcDateTime, utc_now

#: Longest key accepted, characters (a UUID is 36).
MAX_KEY_LENGTH = 200


class IdempotencyKey(Base):
    """One key as one operation received it, with the answer it gave."""

    __tablename__ = "idempotency_keys"

    #: The operation id (createRecordings, createFit): a key means nothing across operations.
    operation: Mapped[str] = mapped_column(String(40), primary_key=True)
    key: Mapped[str] = mapped_column(String(MAX_KEY_LENGTH), primary_key=True)
    #: SHA-256 (hex) of what was uploaded: the file's bytes and the form's fields.
    request_sha256: Mapped[str] = mapped_column(String(64))
    status_code: Mapped[int] = mapped_column(Integer)
    #: The response body, as the JSON value sent.
    response: Mapped[dict] = mapped_column(JSON)
    #: Response headers to send again (Location).
    headers: Mapped[dict] = mapped_column(JSON)
    created_at: Mapped[datetime] = mapped_column(UtcDateTime(), default=utc_now, index=True)
