"""Shared fixtures: the reference data (required, never skipped), the built assets and a
throwaway PostgreSQL server per module that asks for one."""

import json
import os
import shutil
from pathlib import Path

import pytest

from glasshead.settings import get_settings
from postgres_support import throwaway_postgres

# Starlette's TestClient sends "Host: testserver"; the host allow-list (api/security.py) must let
# it through. Tests of the allow-list itself set GLASSHEAD_ALLOWED_HOSTS or delete it.
os.environ.setdefault("GLASSHEAD_ALLOWED_HOSTS", "testserver,localhost,127.0.0.1,::1")


@pytest.fixture(scope="session", autouse=True)
def compute_workers_shared_by_the_apps_of_the_session():
    """The compute workers outlive each test's app and serve the next one's (a server makes
    them once; spawning them again for each of hundreds of apps took about a minute of the
    suite). They are ended when the session ends. A test of the pool itself makes its own."""
    from glasshead.jobs import compute

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(compute.ComputePool, "shutdown", lambda self: None)
        yield
    compute.shutdown_pool()


@pytest.fixture(scope="session")
def data_dir() -> Path:
    """The reference data directory; a missing one fails the test with the path expected."""
    path = get_settings().data_dir
    if not (path / "anatomy" / "artisynth-badin").is_dir():
        pytest.fail(f"reference data missing: expected {path} (set GLASSHEAD_DATA_DIR)")
    return path


@pytest.fixture
def data_copy(tmp_path, data_dir):
    """A writable copy of the folders the build reads from (those of sources.EXPECTED_FILES),
    for tests that break a file."""
    from glasshead.pipeline.sources import EXPECTED_FILES

    copy = tmp_path / "data"
    for folder in sorted({path.parent for path in EXPECTED_FILES}):
        shutil.copytree(data_dir / folder, copy / folder, dirs_exist_ok=True)
    return copy


@pytest.fixture(scope="session")
def built_assets(data_dir) -> Path:
    """The assets directory after `glasshead build` (instant when already up to date)."""
    from glasshead.pipeline.build import run

    assets = get_settings().assets_dir
    run(data_dir, assets, log=lambda message: None)
    return assets


@pytest.fixture(scope="session")
def built_store(built_assets):
    """An asset store of the built assets, shared by the session's tests that read them."""
    from glasshead.asset_store import AssetStore

    return AssetStore(built_assets)


@pytest.fixture(scope="session")
def head_tract(built_store):
    """The head's tract shape (speech.tract_shape) of the built assets."""
    from glasshead.tract_assets import tract_shape

    return tract_shape(built_store)


@pytest.fixture(scope="session")
def migrated_sqlite(tmp_path_factory) -> Path:
    """A SQLite database at the newest migration, with nothing else in it, its WAL folded into
    the file: each app of ``start_app`` starts on a copy (migrating a new file for each of
    hundreds of apps took about a tenth of a second each). The app's start still runs the
    migrations, which find the copy at head."""
    from glasshead.store.db import engine_for, upgrade_to_head

    path = tmp_path_factory.mktemp("migrated") / "template.sqlite3"
    engine = engine_for(f"sqlite:///{path}")
    upgrade_to_head(engine)
    with engine.connect() as connection:
        connection.exec_driver_sql("PRAGMA wal_checkpoint(TRUNCATE)")
    engine.dispose()
    return path


@pytest.fixture(scope="session")
def loaded_assets():
    """The configured assets, loaded once for the apps of ``start_app`` that use them. An app's
    start loads every asset again, which re-reads and re-hashes each file and parses only those
    whose content changed, as a running server's store does."""
    from glasshead.asset_store import AssetStore

    return AssetStore(get_settings().assets_dir)


@pytest.fixture
def start_app(tmp_path, monkeypatch, migrated_sqlite, loaded_assets):
    """``start_app(assets=None)``: a new app on ``assets`` (default: the configured assets
    directory, with the store shared by the session's apps) and a fresh SQLite database (a copy
    of ``migrated_sqlite``), started as the server starts (migrations run, assets loaded);
    returns (app, client). Every app started is stopped after the test."""
    from fastapi.testclient import TestClient

    from glasshead.api.app import create_app

    started = []

    def start(assets=None):
        if assets is not None:
            monkeypatch.setenv("GLASSHEAD_ASSETS_DIR", str(assets))
        database = tmp_path / f"app-{len(started)}.sqlite3"
        shutil.copyfile(migrated_sqlite, database)
        monkeypatch.setenv("GLASSHEAD_DATABASE_URL", f"sqlite:///{database}")
        monkeypatch.setenv("GLASSHEAD_WEB_DIST_DIR", str(tmp_path / "no-web"))
        get_settings.cache_clear()
        try:
            app = create_app()
            if assets is None or Path(assets) == loaded_assets.assets_dir:
                app.state.assets = loaded_assets
        finally:
            get_settings.cache_clear()
        client = TestClient(app)
        client.__enter__()
        started.append(client)
        return app, client

    yield start
    for client in reversed(started):
        client.__exit__(None, None, None)
    get_settings.cache_clear()


@pytest.fixture(scope="session")
def manifest(built_assets) -> dict:
    return json.loads((built_assets / "manifest.json").read_text())


@pytest.fixture(scope="session")
def build_report(built_assets) -> dict:
    return json.loads((built_assets / "build-report.json").read_text())


@pytest.fixture(scope="module")
def postgres_server():
    """A throwaway PostgreSQL server (``postgres_support``) per test module, stopped after it."""
    with throwaway_postgres() as server:
        yield server
