"""POST /epg/indices: the emuR EPG indices of frames sent by the client (in a compute worker)."""

import numpy as np
from fastapi import APIRouter, HTTPException, Response
from pydantic import BaseModel, ConfigDict, Field

from glasshead.api.deps import ComputeDep
from glasshead.asset_store import AssetStore
from glasshead.epg.formats import rows_to_frame
from glasshead.epg.indices import INDEX_SLOTS, epg_indices
from glasshead.epg.sequence import EpgFormatError

router = APIRouter(tags=["epg"])

#: Most frames per request.
MAX_FRAMES = 20_000


class IndicesRequest(BaseModel):
    # Two frames of the /s/ -> /k/ of "bescan" in the emuR reference data (sp1bescan).
    model_config = ConfigDict(json_schema_extra={"examples": [{"frames": [
        ["01100010", "11100011", "11100001", "11000001", "11000001", "11000001", "11000011",
         "11100011"],
        ["01000010", "11100011", "11100001", "11000001", "11000001", "11000001", "11000011",
         "11100111"]]}]})
    frames: list[list[str]] = Field(
        min_length=1, max_length=MAX_FRAMES,
        description="per frame 8 strings of '0'/'1', R1 (front) first; character c = column "
                    "c+1; R1 columns 1 and 8 have no electrode and must be 0")


class IndicesResponse(BaseModel):
    names: list[str] = Field(description="the indices, in the order of the JS kernel's target")
    indices: dict[str, list[float]] = Field(description="name -> one value per frame")


@router.post("/epg/indices", operation_id="computeEpgIndices", response_model=IndicesResponse)
async def compute_indices(request: IndicesRequest, compute: ComputeDep) -> Response:
    """Percent contact, contacts per row and zone, centre of gravity, anteriority, centrality
    and dorsopalatal indices (emuR, R/epg.class.R) of each frame."""
    return await compute.respond(indices_json, request)


def indices_json(assets: AssetStore, request: IndicesRequest) -> bytes:
    """The IndicesResponse of a request, as JSON (runs in a compute worker)."""
    try:
        frames = np.stack([rows_to_frame(rows, i) for i, rows in enumerate(request.frames)])
    except EpgFormatError as error:
        raise HTTPException(status_code=422, detail=str(error)) from None
    values = epg_indices(frames)
    return IndicesResponse(names=list(INDEX_SLOTS),
                           indices={k: v.tolist() for k, v in values.items()}
                           ).model_dump_json().encode()
