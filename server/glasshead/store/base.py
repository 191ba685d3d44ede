"""The declarative base shared by every table, and column types used across them."""

from datetime import UTC, datetime

from sqlalchemy import DateTime, Integer, MetaData, Table, TypeDecorator, text
from sqlalchemy.orm import DeclarativeBase, Mapped, declared_attr, mapped_column

#: Constraint names that Alembic can find again on every backend (SQLite batch migrations need
#: named constraints to alter them).
NAMING_CONVENTION = {
    "ix": "ix_%(column_0_label)s",
    "uq": "uq_%(table_name)s_%(column_0_name)s",
    "ck": "ck_%(table_name)s_%(constraint_name)s",
    "fk": "fk_%(table_name)s_%(column_0_name)s_%(referred_table_name)s",
    "pk": "pk_%(table_name)s",
}


class Base(DeclarativeBase):
    metadata = MetaData(naming_convention=NAMING_CONVENTION)


class UtcDateTime(TypeDecorator):
    """A timezone-aware UTC datetime on every backend (SQLite keeps no zone; we restore it)."""

    impl = DateTime(timezone=True)
    cache_ok = True

    def process_bind_param(self, value: datetime | None, dialect):
        if value is not None and value.tzinfo is None:
            raise ValueError("datetimes stored in the database must be timezone-aware")
        return value.astimezone(UTC) if value is not None else None

    def process_result_value(self, value: datetime | None, dialect):
        if value is None:
            return None
        return value.replace(tzinfo=UTC) if value.tzinfo is None else value.astimezone(UTC)


def utc_now() -> datetime:
    return datetime.now(UTC)


class Timestamped:
    """``created_at`` and ``updated_at`` columns, set by the application in UTC."""

    created_at: Mapped[datetime] = mapped_column(UtcDateTime(), default=utc_now)
    updated_at: Mapped[datetime] = mapped_column(UtcDateTime(), default=utc_now,
                                                 onupdate=utc_now)


class Versioned:
    """A ``version`` counted up by every update, for optimistic concurrency.

    SQLAlchemy's version counter writes ``UPDATE ... WHERE id = ? AND version = ?``, so of two
    writers that read the same version only the first changes the row; the second gets
    ``StaleDataError``. The routes give it as the ETag, and ``If-Match`` names the version a
    client last read. Tables that have one also never reuse an id (``sqlite_autoincrement``;
    PostgreSQL's sequences never do), so a stale link cannot open a newer record.
    """

    version: Mapped[int] = mapped_column(Integer, nullable=False, server_default=text("1"))

    @declared_attr.directive
    def __mapper_args__(cls):  # noqa: N805 (a class-level directive)
        table: Table = cls.__table__  # type: ignore[attr-defined]  # set on the mapped subclass
        return {"version_id_col": table.c.version}

    @declared_attr.directive
    def __table_args__(cls):  # noqa: N805
        return {"sqlite_autoincrement": True}
