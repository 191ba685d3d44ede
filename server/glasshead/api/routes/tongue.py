"""GET /tongue/rig: the rig definition. POST /tongue/surface: the tongue for a parameter set.

The surface comes from the Python reference evaluator (``geometry.tongue_surface``), run in a
compute worker (``jobs.compute``); the web app evaluates the same definition itself every
frame (``web/src/core/tongue.js``).
"""

from typing import Annotated

from fastapi import APIRouter, Body, HTTPException, Response
from pydantic import BaseModel, ConfigDict, Field

from glasshead.api.deps import AssetsDep, ComputeDep
from glasshead.api.params import split_params
from glasshead.asset_store import AssetStore
from glasshead.geometry.tongue_surface import ParameterError

router = APIRouter(tags=["tongue"])


class RigParameter(BaseModel):
    model_config = ConfigDict(extra="allow")

    name: str
    unit: str = Field(description="mm, deg or ratio")
    min: float
    max: float
    neutral: float
    group: str
    description: str
    moves: list[dict]


class RigDefinition(BaseModel):
    """The tongue rig definition (format in glasshead.geometry.tongue_rig); more fields than
    these are present and kept."""

    model_config = ConfigDict(extra="allow")

    format_version: int
    units: str
    frame: dict
    hub: dict
    sagittal: dict
    coronal: dict
    jaw: dict
    surface: dict
    parameters: list[RigParameter]
    fit: dict


class SurfaceRequest(BaseModel):
    model_config = ConfigDict(json_schema_extra={"examples": [
        {"params": {"tip_height": 5.79, "blade_height": 8.28, "jaw_opening": 2.0}}]})
    params: dict[str, float] = Field(
        default_factory=dict,
        description="Parameter name -> value; names left out take their neutral value. Lip "
                    "and velum parameters are accepted and range-checked; the surface is the "
                    "tongue's.",
        examples=[{"tip_height": 5.0, "jaw_opening": 10.0}])


class Surface(BaseModel):
    units: str = "mm"
    frame: str = "project"
    params: dict[str, float] = Field(description="Every parameter's value, as evaluated.")
    vertex_count: int
    triangle_count: int
    vertices: list[list[float]] = Field(description="(vertex_count, 3) positions, mm.")
    normals: list[list[float]] = Field(description="(vertex_count, 3) unit vertex normals.")
    triangles: list[list[int]] = Field(description="(triangle_count, 3) vertex indices, wound "
                                                   "counter-clockwise seen from outside.")
    volume_mm3: float


@router.get("/tongue/rig", operation_id="getTongueRig", response_model=RigDefinition)
def tongue_rig(assets: AssetsDep) -> dict:
    return assets.get("tongue_rig").definition


@router.post("/tongue/surface", operation_id="evaluateTongueSurface", response_model=Surface)
async def tongue_surface(request: Annotated[SurfaceRequest, Body()],
                         compute: ComputeDep) -> Response:
    return await compute.respond(evaluate_surface, request)


def evaluate_surface(assets: AssetStore, request: SurfaceRequest) -> bytes:
    """The Surface of a request, as JSON (runs in a compute worker)."""
    rig = assets.get("tongue_rig")
    tongue = split_params(assets, request.params).tongue  # lips and velum: checked, not used
    try:
        values = rig.values_from(tongue)
    except ParameterError as exc:
        raise HTTPException(status_code=422, detail=str(exc)) from None
    surface = rig.evaluate(values)
    return Surface(
        params=dict(zip(rig.parameter_names, values.tolist(), strict=True)),
        vertex_count=len(surface.vertices),
        triangle_count=len(surface.triangles),
        vertices=surface.vertices.tolist(),
        normals=surface.normals.tolist(),
        triangles=surface.triangles.tolist(),
        volume_mm3=surface.volume,
    ).model_dump_json().encode()
