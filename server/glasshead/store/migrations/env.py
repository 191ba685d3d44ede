"""Alembic environment for the Glasshead store, configured from code (see store.db).

Online: runs on the connection handed over in ``config.attributes["connection"]``, or on an engine
for the configured URL. Offline (``--sql``): renders SQL for the configured URL's dialect.
SQLite gets batch mode, since it can alter a table only by copying it.
"""

from alembic import context

from glasshead.store import models  # noqa: F401  (registers the tables on Base.metadata)
from glasshead.store.base import Base

config = context.config
target_metadata = Base.metadata


def run_offline() -> None:
    context.configure(url=config.get_main_option("sqlalchemy.url"),
                      target_metadata=target_metadata, literal_binds=True,
                      render_as_batch=True, dialect_opts={"paramstyle": "named"})
    with context.begin_transaction():
        context.run_migrations()


def run_on(connection) -> None:
    context.configure(connection=connection, target_metadata=target_metadata,
                      render_as_batch=connection.dialect.name == "sqlite")
    with context.begin_transaction():
        context.run_migrations()


def run_online() -> None:
    connection = config.attributes.get("connection")
    if connection is not None:
        run_on(connection)
        return
    from glasshead.store.db import engine_for

    with engine_for(config.get_main_option("sqlalchemy.url")).begin() as connection:
        run_on(connection)


if context.is_offline_mode():
    run_offline()
else:
    run_online()
