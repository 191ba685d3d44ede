"""GET /anatomy/landmarks: the teaching landmarks, the parts and places of articulation.

Built by `glasshead build` (``pipeline.landmarks``) from the meshes and the tongue rig; the web
app's label layer names the parts and places at these points.
"""

from fastapi import APIRouter
from pydantic import BaseModel, ConfigDict, Field

from glasshead.api.deps import AssetsDep

router = APIRouter(tags=["anatomy"])


class Landmark(BaseModel):
    model_config = ConfigDict(extra="allow")

    name: str
    label: str = Field(description="what the label layer shows")
    kind: str = Field(description="part, place (of articulation) or reference")
    position: list[float] = Field(description="[x, y, z] mm, project frame")
    mesh: str = Field(description="the mesh (or meshes) the point is found on")
    feature: str
    rule: str = Field(description="how the point is found on the anatomy")
    meshes: list[str] = Field(description="scene meshes a pointer over which this part names")
    order: int | None = Field(default=None, description="places: 0 (front) to 8 (glottal)")


class Landmarks(BaseModel):
    model_config = ConfigDict(extra="allow")

    format_version: int
    frame: dict
    landmarks: list[Landmark]
    measures: dict[str, float] = Field(description="distances between landmarks, mm")
    notes: dict[str, str]


@router.get("/anatomy/landmarks", operation_id="getLandmarks", response_model=Landmarks,
            response_model_exclude_none=True)
def landmarks(assets: AssetsDep) -> dict:
    return assets.get("landmarks")
