"""GET /site: what a page needs to know about where this server is reached."""

from fastapi import APIRouter
from pydantic import BaseModel, Field

from glasshead.api.deps import PublicUrlDep

router = APIRouter(tags=["health"])


class Site(BaseModel):
    public_url: str | None = Field(
        description="the address the school reaches this server at (GLASSHEAD_PUBLIC_URL), "
                    "without a trailing slash; null: not set, use the address the page has")


@router.get("/site", operation_id="getSite", response_model=Site)
def site(public_url: PublicUrlDep) -> Site:
    """Where children's tablets reach this server, for the join link a teacher shows."""
    return Site(public_url=public_url)
