"""Dependencies shared by the routes, as ``Annotated`` aliases: ``AssetsDep`` (the built assets).

The database session is ``glasshead.store.session.SessionDep``.
"""

from typing import Annotated

from fastapi import Depends, Request

from glasshead.asset_store import AssetStore


def get_asset_store(request: Request) -> AssetStore:
    """The application's one asset store, made in ``create_app`` and loaded at start-up."""
    return request.app.state.assets


AssetsDep = Annotated[AssetStore, Depends(get_asset_store)]
