"""The database engine and migrations.

The URL comes from ``GLASSHEAD_DATABASE_URL`` (settings.database_url): a SQLite file under
``<repo>/var/`` by default, which needs no set-up, or ``postgresql+psycopg://...`` (install the
``postgres`` extra). ``upgrade_to_head`` applies the Alembic migrations shipped inside this
package; the application runs it at start-up, and ``glasshead migrate`` runs it alone.
"""

import fcntl
from contextlib import contextmanager
from functools import lru_cache
from pathlib import Path
from typing import Any

from alembic import command
from alembic.config import Config
from sqlalchemy import Engine, create_engine, event, text
from sqlalchemy.engine import make_url
from sqlalchemy.pool import StaticPool

from glasshead.settings import get_settings

#: Where Alembic finds env.py and versions/, as a package resource (works from an install).
MIGRATIONS = "glasshead.store:migrations"
#: The PostgreSQL advisory lock held while migrating (any constant of our own: "glasshead").
MIGRATION_LOCK_KEY = 0x676C617373686561
#: How long a SQLite writer waits for another connection's lock before "database is locked".
SQLITE_BUSY_TIMEOUT_MS = 5000


def database_url() -> str:
    return get_settings().database_url


@lru_cache(maxsize=8)
def engine_for(url: str) -> Engine:
    """One engine per URL. SQLite: the file's directory is created, foreign keys are enforced,
    a file is in WAL mode (readers never block the writer, and a killed server leaves a database
    that the next start recovers) with a busy timeout instead of an immediate "database is
    locked", and an in-memory database is shared by every connection of the process."""
    parsed = make_url(url)
    if parsed.get_backend_name() != "sqlite":
        return create_engine(url, pool_pre_ping=True)
    options: dict[str, Any] = {"connect_args": {"check_same_thread": False}}
    if parsed.database in (None, "", ":memory:"):
        options["poolclass"] = StaticPool
    else:
        Path(parsed.database).expanduser().parent.mkdir(parents=True, exist_ok=True)
    in_file = "poolclass" not in options
    engine = create_engine(url, **options)

    @event.listens_for(engine, "connect")
    def _on_connect(dbapi_connection, _record):
        cursor = dbapi_connection.cursor()
        cursor.execute("PRAGMA foreign_keys=ON")
        cursor.execute(f"PRAGMA busy_timeout={SQLITE_BUSY_TIMEOUT_MS}")
        if in_file:
            cursor.execute("PRAGMA journal_mode=WAL")
            # WAL's durable setting: a committed (acknowledged) write survives a killed process;
            # NORMAL would only risk the last commits on a power cut, FULL avoids that too.
            cursor.execute("PRAGMA synchronous=FULL")
        cursor.close()

    return engine


def get_engine() -> Engine:
    """The engine for the current settings."""
    return engine_for(database_url())


def alembic_config(url: str | None = None) -> Config:
    """An Alembic configuration without an alembic.ini: migrations from the package."""
    config = Config()
    config.set_main_option("script_location", MIGRATIONS)
    # ConfigParser treats % as interpolation; URLs may carry %-escaped passwords
    config.set_main_option("sqlalchemy.url", (url or database_url()).replace("%", "%%"))
    return config


def upgrade_to_head(engine: Engine | None = None) -> None:
    """Bring the database up to the newest migration (creating it if new).

    Several servers may start at once on one database (``uvicorn --workers``, app replicas):
    one migrates while the others wait, then find it at head. PostgreSQL: a transaction-scoped
    advisory lock; a SQLite file: an exclusive lock on a file beside it."""
    engine = engine or get_engine()
    config = alembic_config(engine.url.render_as_string(hide_password=False))
    with _sqlite_migration_lock(engine.url), engine.begin() as connection:
        if engine.dialect.name == "postgresql":
            connection.execute(text("SELECT pg_advisory_xact_lock(:key)"),
                               {"key": MIGRATION_LOCK_KEY})
        config.attributes["connection"] = connection
        command.upgrade(config, "head")


@contextmanager
def _sqlite_migration_lock(url):
    database = url.database if url.get_backend_name() == "sqlite" else None
    if database in (None, "", ":memory:"):
        yield
        return
    with open(f"{Path(database).expanduser()}.migrate-lock", "a") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)

