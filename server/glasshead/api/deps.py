"""Dependencies shared by the routes, as ``Annotated`` aliases: ``AssetsDep`` (the built assets),
``BuiltUrlDep`` (content-hashed URLs of built files), ``ComputeDep`` (the worker processes of
the heavy routes and of speech), ``CacheDep`` (where utterances are kept).

The database session is ``glasshead.store.session.SessionDep``.
"""

from collections.abc import Callable
from typing import Annotated

from fastapi import Depends, Request

from glasshead.api.static import hashed_url
from glasshead.asset_store import AssetStore
from glasshead.jobs.compute import ComputePool
from glasshead.settings import get_settings
from glasshead.speech import utterance


def get_asset_store(request: Request) -> AssetStore:
    """The application's one asset store, made in ``create_app`` and loaded at start-up."""
    return request.app.state.assets


AssetsDep = Annotated[AssetStore, Depends(get_asset_store)]


def get_built_url(request: Request) -> Callable[[str], str]:
    """``built_url(name)``: the immutable, content-hashed URL of a built file (relative to the
    assets directory), so that routes name files without reading them."""
    assets_dir = request.app.state.assets.assets_dir
    return lambda name: hashed_url(assets_dir, name)


BuiltUrlDep = Annotated[Callable[[str], str], Depends(get_built_url)]


def get_public_url() -> str | None:
    """Where the school reaches this server (``public_url``), without a trailing slash; None
    when it is not set."""
    return get_settings().public_url.rstrip("/") or None


PublicUrlDep = Annotated[str | None, Depends(get_public_url)]


def get_compute_pool(request: Request) -> ComputePool:
    """The application's compute pool, made in ``create_app``."""
    return request.app.state.compute


ComputeDep = Annotated[ComputePool, Depends(get_compute_pool)]


def open_cache(location: dict) -> utterance.UtteranceCache:
    """The utterance cache a ``location`` names: ``{"cache_dir": path}`` or
    ``{"database_url": url}``."""
    if location.get("database_url"):
        from glasshead.store.utterance_cache import DatabaseCache

        return DatabaseCache(location["database_url"])
    return utterance.DirectoryCache(location["cache_dir"])


def get_utterance_cache() -> utterance.UtteranceCache:
    """The utterance cache of the settings (``utterance_cache``, ``speech_cache_dir``)."""
    settings = get_settings()
    if settings.utterance_cache_kind == "database":
        return open_cache({"database_url": settings.database_url})
    return open_cache({"cache_dir": str(settings.speech_cache_dir)})


CacheDep = Annotated[utterance.UtteranceCache, Depends(get_utterance_cache)]
