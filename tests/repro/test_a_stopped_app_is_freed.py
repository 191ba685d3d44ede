"""A stopped app and its asset store are freed.

The Python suite held 5.8 GB: every app a test made stayed alive with its asset store (tens
of MB of meshes and tables), because the catch-all API route closed over its app and FastAPI
keeps the callables of routes in a process-wide cache (fastapi.dependencies.models). The
route reads ``request.app`` now; one module of tests went from 1,143 MB to 418 MB."""

import gc
import weakref

from fastapi.testclient import TestClient

from glasshead.api.app import create_app
from glasshead.settings import get_settings


def test_an_app_that_served_requests_and_stopped_is_garbage_collected(built_assets, tmp_path,
                                                                       monkeypatch):
    monkeypatch.setenv("GLASSHEAD_ASSETS_DIR", str(built_assets))
    monkeypatch.setenv("GLASSHEAD_DATABASE_URL", f"sqlite:///{tmp_path / 'app.sqlite3'}")
    monkeypatch.setenv("GLASSHEAD_WEB_DIST_DIR", str(tmp_path / "no-web"))
    get_settings.cache_clear()
    try:
        app = create_app()
    finally:
        get_settings.cache_clear()
    with TestClient(app) as client:
        assert client.get("/api/v1/health").status_code == 200
        assert client.get("/api/v1/no-such-route").status_code == 404
        assert client.post("/api/v1/epg/layout").status_code == 405
    app_ref, store_ref = weakref.ref(app), weakref.ref(app.state.assets)
    del app, client
    gc.collect()
    assert app_ref() is None, [type(r).__name__ for r in gc.get_referrers(app_ref())]
    assert store_ref() is None
