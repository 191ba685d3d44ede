"""The database engine and migrations.

The URL comes from ``GLASSHEAD_DATABASE_URL`` (settings.database_url): a SQLite file under
``<repo>/var/`` by default, which needs no set-up, or ``postgresql+psycopg://...`` (install the
``postgres`` extra). ``upgrade_to_head`` applies the Alembic migrations shipped inside this
package; the application runs it at start-up, and ``python -m glasshead.store.db`` runs it alone.
"""

import sys
from functools import lru_cache
from pathlib import Path

from alembic import command
from alembic.config import Config
from sqlalchemy import Engine, create_engine, event
from sqlalchemy.engine import make_url
from sqlalchemy.pool import StaticPool

from glasshead.settings import get_settings

#: Where Alembic finds env.py and versions/, as a package resource (works from an install).
MIGRATIONS = "glasshead.store:migrations"


def database_url() -> str:
    return get_settings().database_url


@lru_cache(maxsize=8)
def engine_for(url: str) -> Engine:
    """One engine per URL. SQLite: the file's directory is created, foreign keys are enforced,
    and an in-memory database is shared by every connection of the process."""
    parsed = make_url(url)
    if parsed.get_backend_name() != "sqlite":
        return create_engine(url, pool_pre_ping=True)
    options = {"connect_args": {"check_same_thread": False}}
    if parsed.database in (None, "", ":memory:"):
        options["poolclass"] = StaticPool
    else:
        Path(parsed.database).expanduser().parent.mkdir(parents=True, exist_ok=True)
    engine = create_engine(url, **options)

    @event.listens_for(engine, "connect")
    def _enforce_foreign_keys(dbapi_connection, _record):
        cursor = dbapi_connection.cursor()
        cursor.execute("PRAGMA foreign_keys=ON")
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
    """Bring the database up to the newest migration (creating it if new)."""
    engine = engine or get_engine()
    config = alembic_config(engine.url.render_as_string(hide_password=False))
    with engine.begin() as connection:
        config.attributes["connection"] = connection
        command.upgrade(config, "head")


def main() -> int:
    upgrade_to_head()
    print(f"database at {make_url(database_url()).render_as_string(hide_password=True)} "
          "is up to date")
    return 0


if __name__ == "__main__":
    sys.exit(main())
