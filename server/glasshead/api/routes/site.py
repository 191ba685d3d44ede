"""GET /site: what a page needs to know about where this server is reached."""

from fastapi import APIRouter
from pydantic import BaseModel, Field

from glasshead.settings import get_settings

router = APIRouter(tags=["health"])


class Site(BaseModel):
    public_url: str | None = Field(
        description="the address the school reaches this server at (GLASSHEAD_PUBLIC_URL), "
                    "without a trailing slash; null: not set, use the address the page has")


@router.get("/site", operation_id="getSite", response_model=Site)
def site() -> Site:
    """Where children's tablets reach this server, for the join link a teacher shows."""
    public_url = get_settings().public_url.rstrip("/")
    return Site(public_url=public_url or None)
