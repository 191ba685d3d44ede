"""Dependencies shared by the routes, as ``Annotated`` aliases: ``AssetsDep`` (the built assets),
``SpeechCacheDep`` (where utterances are cached).

The database session is ``glasshead.store.session.SessionDep``.
"""

from pathlib import Path
from typing import Annotated

from fastapi import Depends, Request

from glasshead.asset_store import AssetStore
from glasshead.settings import get_settings


def get_asset_store(request: Request) -> AssetStore:
    """The application's one asset store, made in ``create_app`` and loaded at start-up."""
    return request.app.state.assets


AssetsDep = Annotated[AssetStore, Depends(get_asset_store)]


def get_speech_cache_dir() -> Path:
    """The directory utterances are cached in (settings.speech_cache_dir)."""
    return Path(get_settings().speech_cache_dir)


SpeechCacheDep = Annotated[Path, Depends(get_speech_cache_dir)]
