"""GET /health: liveness, version, and whether the built assets are present."""

from fastapi import APIRouter
from pydantic import BaseModel

from glasshead import __version__
from glasshead.settings import get_settings

router = APIRouter(tags=["health"])


class Health(BaseModel):
    status: str
    version: str
    assets_built: bool


@router.get("/health", operation_id="getHealth", response_model=Health)
def health() -> Health:
    settings = get_settings()
    return Health(status="ok", version=__version__,
                  assets_built=(settings.assets_dir / "manifest.json").is_file())
