"""The API app on a new database of either backend, for module-scoped fixtures that run a
module's tests on SQLite and on a real PostgreSQL server (the module's ``postgres_server``
fixture, asked for only when needed)."""

import shutil
from contextlib import contextmanager

import pytest
from fastapi.testclient import TestClient

from glasshead.settings import get_settings
from glasshead.store.db import engine_for


@contextmanager
def app_on_new_database(request, tmp_path_factory, name: str):
    """A TestClient of a new app on a new ``request.param`` database ("sqlite" or "postgresql")
    named after ``name``; the settings cache is cleared before and after."""
    from glasshead.api.app import create_app

    folder = tmp_path_factory.mktemp(f"{name}-{request.param}")
    if request.param == "postgresql":
        server = request.getfixturevalue("postgres_server")
        url = server.url(server.create_database())
    else:  # a copy of the session's migrated file (conftest.migrated_sqlite)
        database = folder / f"{name}.sqlite3"
        shutil.copyfile(request.getfixturevalue("migrated_sqlite"), database)
        url = f"sqlite:///{database}"
    with pytest.MonkeyPatch.context() as env:
        env.setenv("GLASSHEAD_DATABASE_URL", url)
        env.setenv("GLASSHEAD_WEB_DIST_DIR", str(folder / "no-web"))
        env.setenv("GLASSHEAD_COMPUTE_WORKERS", "1")
        get_settings.cache_clear()
        try:
            app = create_app()
            app.state.assets = request.getfixturevalue("loaded_assets")  # as start_app's
            with TestClient(app) as client:
                yield client
        finally:
            get_settings.cache_clear()
            engine_for(url).dispose()
