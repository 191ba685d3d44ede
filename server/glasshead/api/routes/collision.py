"""GET /collision/tables: the liner and voxel tables. POST /collision/correct: the Python reference.

With ``velum_opening`` the correction also moves the tongue out of the velum at that opening and
out of the pharyngeal wall, after the palate, as the web app's frame does
(``geometry.tract_collision``; docs/collision.md).

The tables are one binary file built by `glasshead build` (format in
``glasshead.geometry.collision_format``). GET /collision/tables answers with its JSON header and
the URL of the binary; the browser fetches the binary, checks it and corrects the tongue itself
every frame. POST /collision/correct runs the Python twin of that correction on given vertices,
in a compute worker (``jobs.compute``).
"""

from typing import Annotated

from fastapi import APIRouter, Response
from pydantic import BaseModel, ConfigDict, Field

from glasshead.api.deps import AssetsDep, ComputeDep
from glasshead.asset_store import AssetStore
from glasshead.constants import (
    COLLISION_MAX_VERTICES,
    COLLISION_TABLES_FILE,
    COLLISION_TABLES_FORMAT_VERSION,
)
from glasshead.geometry.collision import correct_vertices
from glasshead.geometry.tract_collision import TractCollider, correct_tract, prepare_tract

router = APIRouter(tags=["collision"])

Coordinate = Annotated[float, Field(strict=True, allow_inf_nan=False)]
Vertex = Annotated[list[Coordinate], Field(min_length=3, max_length=3)]


class CorrectRequest(BaseModel):
    # Three midline vertices of the tongue at the /t/ target: the blade's highest, which is
    # inside the palate and corrected; the tip, tested and outside; the dorsum, screened.
    model_config = ConfigDict(json_schema_extra={"examples": [
        {"vertices": [[10.97, 17.92, 0.0], [22.81, 5.75, 0.0], [-19.3, 11.19, 0.0]],
         "velum_opening": 0.0}]})
    vertices: Annotated[list[Vertex], Field(max_length=COLLISION_MAX_VERTICES,
                                            description="Tongue vertices [x, y, z], mm, "
                                                        "project frame.")]
    velum_opening: Annotated[float | None, Field(
        default=None, ge=0.0, le=1.0, allow_inf_nan=False,
        description="When given (0 raised to 1 lowered), the vertices are then also corrected "
                    "against the velum at this opening and the pharyngeal wall.")] = None


class CollisionCounts(BaseModel):
    screened: int
    tested: int
    corrected: int


class CorrectResponse(BaseModel):
    vertices: list[list[float]] = Field(description="The vertices after correction.")
    flags: list[int] = Field(description="Per vertex: 0 screened by the voxel table, 1 tested "
                                         "against the liner and outside, 2 corrected.")
    counts: CollisionCounts
    tract_flags: list[int] | None = Field(
        default=None, description="With velum_opening: per vertex 0 screened, 1 tested and "
                                  "outside, 2 corrected against the velum or the wall.")
    tract_counts: CollisionCounts | None = None
    format_version: int


class TablesInfo(BaseModel):
    format_version: int
    url: str = Field(description="The binary tables file (JSON header inside).")
    bytes: int
    header: dict


@router.get("/collision/tables", operation_id="getCollisionTables", response_model=TablesInfo)
def collision_tables(assets: AssetsDep) -> TablesInfo:
    tables = assets.entry("collision_tables")
    return TablesInfo(format_version=COLLISION_TABLES_FORMAT_VERSION,
                      url=f"/assets/build/{COLLISION_TABLES_FILE}?v={tables.sha256[:16]}",
                      bytes=tables.size, header=tables.value.header)


@router.post("/collision/correct", operation_id="correctCollision",
             response_model=CorrectResponse)
async def collision_correct(request: CorrectRequest, compute: ComputeDep) -> Response:
    return await compute.respond(correct, request)


def correct(assets: AssetStore, request: CorrectRequest) -> bytes:
    """The CorrectResponse of a request, as JSON (runs in a compute worker)."""
    return _correct(assets, request).model_dump_json().encode()


def _correct(assets: AssetStore, request: CorrectRequest) -> CorrectResponse:
    tables = assets.get("collision_tables")
    if not request.vertices:
        counts = CollisionCounts(screened=0, tested=0, corrected=0)
        return CorrectResponse(vertices=[], flags=[], counts=counts,
                               format_version=COLLISION_TABLES_FORMAT_VERSION)
    corrected, flags, counts = correct_vertices(request.vertices, tables)
    tract_flags = tract_counts = None
    if request.velum_opening is not None:
        corrected, tract, tract_stats = correct_tract(corrected, tract_collider(assets),
                                                      request.velum_opening)
        tract_flags, tract_counts = tract.tolist(), CollisionCounts(**tract_stats)
    return CorrectResponse(vertices=corrected.tolist(), flags=flags.tolist(),
                           counts=CollisionCounts(**counts), tract_flags=tract_flags,
                           tract_counts=tract_counts,
                           format_version=COLLISION_TABLES_FORMAT_VERSION)


def tract_collider(assets) -> TractCollider:
    """The velum and pharyngeal wall collider, prepared once per version of its three assets."""
    velum_faces = assets.get("velum_mesh")[1]
    wall = assets.get("pharynx_mesh")
    key = ("tract", assets.entry("velum_mesh").sha256, assets.entry("pharynx_mesh").sha256)
    return assets.derived("velum_rig", key,
                          lambda rig: prepare_tract(rig, velum_faces, wall[0], wall[1]))
