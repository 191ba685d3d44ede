"""GET /epg/layout: the electrodes on the palate. POST /epg/contacts: synthetic EPG (Python twin).

The layout is built by `glasshead build` (``pipeline.epg_layout``); the browser computes contacts
itself every frame (``web/src/core/epgContacts.js``). POST /epg/contacts runs the Python twin,
in a compute worker (``jobs.compute``):
with ``params`` it evaluates the tongue, corrects it against the palate and tests the probes;
with ``vertices`` it tests a tongue the client already has (the rig's triangles, unless
``triangles`` are given).
"""

from typing import Annotated, Literal

import numpy as np
from fastapi import APIRouter, HTTPException, Query, Response
from pydantic import BaseModel, ConfigDict, Field, model_validator

from glasshead.api.deps import AssetsDep, ComputeDep
from glasshead.api.params import split_params
from glasshead.asset_store import AssetStore
from glasshead.constants import COLLISION_MAX_VERTICES, EPG_LAYOUT_FORMAT_VERSION
from glasshead.epg.contacts import contact_grid, electrode_contacts
from glasshead.epg.indices import INDEX_SLOTS, epg_indices
from glasshead.epg.sequence import rows_to_strings
from glasshead.epg.synthetic import synthetic_frame
from glasshead.geometry.tongue_surface import ParameterError
from glasshead.probe_assets import layout_probes

router = APIRouter(tags=["epg"])

GridName = Literal["reading62", "dense96"]
Coordinate = Annotated[float, Field(strict=True, allow_inf_nan=False)]
Vertex = Annotated[list[Coordinate], Field(min_length=3, max_length=3)]
#: A triangle's vertex indices: below the most vertices accepted (a larger one could name no
#: vertex, and past 64 bits would not even fit the index array).
Triangle = Annotated[list[Annotated[int, Field(ge=0, lt=COLLISION_MAX_VERTICES)]],
                     Field(min_length=3, max_length=3)]
#: Most triangles accepted with ``vertices``.
MAX_TRIANGLES = 2 * COLLISION_MAX_VERTICES


class Electrode(BaseModel):
    id: str = Field(description="R<row>C<column>, e.g. R3C5")
    row: int = Field(description="1 (front) ... rows")
    column: int = Field(description="1 (subject's left) ... 8 (right)")
    cell: int = Field(description="flat index (row - 1) * columns + (column - 1)")
    position: list[float] = Field(description="[x, y, z] on the palate, mm, project frame")
    normal: list[float] = Field(description="unit normal toward the tongue")


class Layout(BaseModel):
    format_version: int
    grid: str
    description: str
    rows: int
    columns: int
    cells: int
    missing_cells: list[int] = Field(description="cells with no electrode (R1 columns 1 and 8 "
                                                 "of the Reading palate)")
    electrodes: list[Electrode]
    contact: dict = Field(description="the probe: tolerance_mm in front, behind_mm behind")
    midline: dict = Field(description="the palate midline the rows are spaced along")
    frame: dict


class ContactsRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={"examples": [
        {"params": {"tip_height": 5.79, "tip_advancement": 0.28, "blade_height": 8.28,
                    "jaw_opening": 0.0}, "grid": "reading62"}]})
    params: dict[str, float] | None = Field(
        None, description="articulation parameters (names left out are neutral)",
        examples=[{"tip_height": 6.0, "tip_advancement": 4.0}])
    vertices: Annotated[list[Vertex], Field(max_length=COLLISION_MAX_VERTICES)] | None = Field(
        None, description="a corrected tongue, [x, y, z] mm per vertex")
    triangles: Annotated[list[Triangle], Field(max_length=MAX_TRIANGLES)] | None = Field(
        None, description="with vertices: their triangles (default: the tongue rig's)")
    grid: GridName = "reading62"

    @model_validator(mode="after")
    def _one_source(self):
        if (self.params is None) == (self.vertices is None):
            raise ValueError("give exactly one of params, vertices")
        if self.triangles is not None and self.vertices is None:
            raise ValueError("triangles go with vertices")
        return self


class ContactsResponse(BaseModel):
    grid: str
    rows: list[str] = Field(description="one string of '0'/'1' per row, row 1 (front) first; "
                                        "character c = column c + 1")
    cells: list[int] = Field(description="rows * columns contacts, row-major, row 1 first")
    electrodes: list[str] = Field(description="electrode ids, in the order of contacts")
    contacts: list[int] = Field(description="per electrode: 1 contacted, 0 not")
    contacted: list[str] = Field(description="ids of the contacted electrodes")
    indices: dict[str, float] | None = Field(
        description="emuR indices of the frame (Reading palate only; see POST /epg/indices)")
    collision: dict | None = Field(description="with params: tongue vertices screened, tested "
                                               "and corrected against the palate")


@router.get("/epg/layout", operation_id="getEpgLayout", response_model=Layout)
def epg_layout(assets: AssetsDep,
               grid: Annotated[GridName, Query(description="which electrode grid")]
               = "reading62") -> Layout:
    """The electrodes of a grid on the scene's palate: position, normal toward the tongue, row,
    column and id. See docs/epg.md for the placement rule."""
    document = assets.get("epg_layout")
    layout = document["grids"][grid]
    return Layout(format_version=EPG_LAYOUT_FORMAT_VERSION, grid=grid,
                  description=layout["description"], rows=layout["rows"],
                  columns=layout["columns"], cells=layout["cells"],
                  missing_cells=layout["missing_cells"], electrodes=layout["electrodes"],
                  contact=document["contact"], midline=document["midline"],
                  frame=document["frame"])


@router.post("/epg/contacts", operation_id="computeEpgContacts", response_model=ContactsResponse)
async def epg_contacts(request: ContactsRequest, compute: ComputeDep) -> Response:
    """Which electrodes the tongue touches, and the EPG indices of that frame."""
    return await compute.respond(contacts_json, request)


def contacts_json(assets: AssetStore, request: ContactsRequest) -> bytes:
    """The ContactsResponse of a request, as JSON (runs in a compute worker)."""
    return _contacts(assets, request).model_dump_json().encode()


def _contacts(assets: AssetStore, request: ContactsRequest) -> ContactsResponse:
    probes = layout_probes(assets, request.grid)
    collision = None
    if request.params is not None:
        rig = assets.get("tongue_rig")
        tongue = split_params(assets, request.params).tongue  # lips and velum: no palate contact
        try:
            values = rig.values_from(tongue)
        except ParameterError as exc:
            raise HTTPException(status_code=422, detail=f"params.{exc.parameter}: {exc}") \
                from None
        tables = assets.get("collision_tables")
        frame = synthetic_frame(rig, values, tables, probes)
        contacts, grid, collision = frame.contacts, frame.grid, frame.collision
    else:
        vertices = np.asarray(request.vertices, dtype=np.float64).reshape(-1, 3)
        if request.triangles is not None:
            triangles = np.asarray(request.triangles, dtype=np.int64).reshape(-1, 3)
            if len(triangles) and triangles.max() >= len(vertices):
                raise HTTPException(status_code=422, detail=(
                    f"triangles: vertex {int(triangles.max())} does not exist "
                    f"({len(vertices)} vertices)"))
        else:
            rig = assets.get("tongue_rig")
            if len(vertices) != rig.vertex_count:
                raise HTTPException(status_code=422, detail=(
                    f"vertices: the tongue has {rig.vertex_count} vertices, got "
                    f"{len(vertices)}; send triangles with another mesh"))
            triangles = rig.triangles
        contacts = electrode_contacts(vertices, triangles, probes)
        grid = contact_grid(contacts, probes)
    indices = None
    if request.grid == "reading62":
        values = epg_indices(grid[None])
        indices = {name: float(values[name][0]) for name in INDEX_SLOTS}
    return ContactsResponse(
        grid=request.grid, rows=rows_to_strings(grid), cells=grid.ravel().tolist(),
        electrodes=probes.ids, contacts=contacts.tolist(),
        contacted=[i for i, c in zip(probes.ids, contacts, strict=True) if c], indices=indices,
        collision=collision)
