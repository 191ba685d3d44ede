"""GET /face/rig: the face rig definition (skin and lips on the jaw, the lip parameters).

Built by `glasshead build` (``pipeline.face_rig``); the web app poses the face itself every frame
(``web/src/core/faceRig.js``), the Python twin being ``geometry.face_rig``.
"""

from fastapi import APIRouter
from pydantic import BaseModel, ConfigDict, Field

from glasshead.api.deps import AssetsDep

router = APIRouter(tags=["face"])


class FaceParameter(BaseModel):
    model_config = ConfigDict(extra="allow")

    name: str
    unit: str = Field(description="mm or ratio")
    min: float
    max: float
    neutral: float
    group: str
    description: str


class FaceRigDefinition(BaseModel):
    """The face rig (format in glasshead.pipeline.face_rig); more fields than these are present
    and kept: per-vertex jaw weights of each mesh, the lip field, the incisor tables."""

    model_config = ConfigDict(extra="allow")

    format_version: int
    frame: dict
    jaw_parameter: str = Field(description="the tongue rig's parameter whose jaw pose the face "
                                           "follows")
    parameters: list[FaceParameter]
    field: dict
    teeth: dict
    meshes: dict = Field(description="face_skin, upper_lip, lower_lip, head_shell: vertex_count, "
                                     "jaw_weights (one per vertex of the built GLB), probes")


@router.get("/face/rig", operation_id="getFaceRig", response_model=FaceRigDefinition)
def face_rig(assets: AssetsDep) -> dict:
    return assets.get("face_rig")
