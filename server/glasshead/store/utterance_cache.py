"""The ``utterance_cache`` table: made utterances kept in the database, for every server to serve.

An utterance is named by a hash of its request and of what it was made from
(``speech.utterance.request_id``), so one made by any server answers the same request on any
other, and its audio URL can be fetched from any of them. On PostgreSQL (``settings
.utterance_cache``) the cache is this table, not a directory on one machine's disk: app
containers on several hosts share it through the database. A row holds the response's JSON
exactly as it was sent and the WAV (None for an utterance without audio), written together, so
a row with audio is never seen without it. Rows are disposable: deleting any of them only means
that the next request for it makes it again.
"""

from datetime import datetime

from sqlalchemy import LargeBinary, String, select
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Mapped, Session, mapped_column

from glasshead.store.base import Base, UtcDateTime, utc_now


class CachedUtterance(Base):
    """One made utterance: its response and its audio."""

    __tablename__ = "utterance_cache"

    #: ``speech.utterance.request_id``: 24 hex digits.
    id: Mapped[str] = mapped_column(String(24), primary_key=True)
    #: The response body (UTF-8 JSON), byte for byte as first sent.
    answer: Mapped[bytes] = mapped_column(LargeBinary)
    #: A 16-bit mono WAV file; None for ``audio.kind`` none.
    wav: Mapped[bytes | None] = mapped_column(LargeBinary)
    created_at: Mapped[datetime] = mapped_column(UtcDateTime(), default=utc_now, index=True)


class DatabaseCache:
    """The utterance cache in the database at ``database_url`` (the interface of
    ``speech.utterance.DirectoryCache``). Picklable: a compute worker opens its own engine."""

    def __init__(self, database_url: str):
        self.database_url = database_url

    @property
    def location(self) -> dict:
        """What a compute worker is sent to open this cache again."""
        return {"database_url": self.database_url}

    def _session(self) -> Session:
        from glasshead.store.db import engine_for

        return Session(engine_for(self.database_url))

    def answer(self, utterance_id: str, *, with_audio: bool = False) -> bytes | None:
        """The cached response's JSON bytes, or None (with ``with_audio``: also None when the
        row holds no WAV)."""
        query = select(CachedUtterance.answer).where(CachedUtterance.id == utterance_id)
        if with_audio:
            query = query.where(CachedUtterance.wav.is_not(None))
        with self._session() as session:
            return session.scalar(query)

    def audio(self, utterance_id: str) -> bytes | None:
        with self._session() as session:
            return session.scalar(select(CachedUtterance.wav)
                                  .where(CachedUtterance.id == utterance_id))

    def put(self, utterance_id: str, answer: bytes, wav: bytes | None) -> None:
        """Keep an utterance; one that another server kept first (the same bytes, made from
        the same request) is left as it is."""
        with self._session() as session:
            session.add(CachedUtterance(id=utterance_id, answer=answer, wav=wav))
            try:
                session.commit()
            except IntegrityError:
                session.rollback()
