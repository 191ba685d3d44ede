"""GET /velum/rig: the velum rig definition (three measured poses, velum_opening, the nasal port).

Built by `glasshead build` (``pipeline.velum_rig``); the web app poses the velum and measures the
port itself every frame (``web/src/core/velum.js``), the Python twin being ``geometry.velum``.
"""

from fastapi import APIRouter
from pydantic import BaseModel, ConfigDict, Field

from glasshead.api.deps import AssetsDep

router = APIRouter(tags=["velum"])


class VelumParameter(BaseModel):
    model_config = ConfigDict(extra="allow")

    name: str
    unit: str = Field(description="ratio")
    min: float
    max: float
    neutral: float = Field(description="the rest pose's share r of the raised -> lowered path")
    group: str
    description: str


class VelumRigDefinition(BaseModel):
    """The velum rig (format in docs/velum.md); more fields than these are present and kept."""

    model_config = ConfigDict(extra="allow")

    format_version: int
    description: str
    frame: dict
    parameters: list[VelumParameter]
    poses: dict = Field(description="names (raised, rest, lowered), at (0, r, 1), vertex_count, "
                                    "positions: per pose a flat list of x, y, z (mm) in the "
                                    "velum GLBs' vertex order")
    port: dict = Field(description="the nasal port's samples: vertices, weights, normals, rows, "
                                   "row_count, width_mm (see docs/velum.md)")


@router.get("/velum/rig", operation_id="getVelumRig", response_model=VelumRigDefinition)
def velum_rig(assets: AssetsDep) -> dict:
    return assets.get("velum_rig").definition
