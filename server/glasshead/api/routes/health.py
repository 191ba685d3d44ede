"""GET /health: liveness, version, and the state of every built asset."""

from typing import Literal

from fastapi import APIRouter
from pydantic import BaseModel, Field

from glasshead import __version__
from glasshead.api.deps import AssetsDep

router = APIRouter(tags=["health"])


class AssetState(BaseModel):
    file: str = Field(description="the file under the assets directory")
    status: Literal["ok", "missing", "corrupt"]
    sha256: str | None = Field(None, description="content hash of the loaded file")
    bytes: int | None = None
    detail: str | None = Field(None, description="what is wrong, and the command that fixes it")


class Health(BaseModel):
    status: Literal["ok", "degraded"] = Field(
        description="ok, or degraded when an asset is missing or corrupt (the routes that need "
                    "it answer 503 until it is rebuilt)")
    version: str
    assets_built: bool = Field(description="every built asset is present and valid")
    assets: dict[str, AssetState]


@router.get("/health", operation_id="getHealth", response_model=Health)
def health(assets: AssetsDep) -> Health:
    state = assets.status()
    return Health(status="ok" if state["ok"] else "degraded", version=__version__,
                  assets_built=state["ok"], assets=state["assets"])
