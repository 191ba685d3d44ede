"""POST /tract/acoustics: a pose's area function and the formants of its tube.

The pose's mid-sagittal section (tongue, jaw, lips, velum, and the still palate, pharynx and
larynx) gives the air's width at stations from the larynx to the lips; each width becomes an
area (``acoustics.area_function``), and the lossy tube of those areas its transfer function and
formants (``acoustics.tube``). The browser computes the same area function each frame
(``web/src/core/areaFunction.js``). Runs in a compute worker (``jobs.compute``).
"""

from typing import Annotated

import numpy as np
from fastapi import APIRouter, HTTPException, Response
from pydantic import BaseModel, ConfigDict, Field

from glasshead.acoustics.area_function import REGIONS
from glasshead.api.deps import ComputeDep
from glasshead.api.params import split_params
from glasshead.asset_store import AssetStore
from glasshead.geometry.tongue_surface import ParameterError
from glasshead.tract_assets import tract_shape

router = APIRouter(tags=["tract"])

Number = Annotated[float, Field(strict=False, allow_inf_nan=False)]


class AcousticsRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={"examples": [
        {"params": {"dorsum_height": 6.0, "dorsum_advancement": 4.0, "jaw_opening": 2.0}}]})
    params: Annotated[dict[str, Number], Field(max_length=128)] = Field(
        default_factory=dict,
        description="articulation parameters by name (tongue, jaw, lips, velum_opening); names "
                    "left out are neutral")


class NasalBranch(BaseModel):
    at: int = Field(description="the tube's sections before the junction (the larynx's and the "
                                "pharynx's): the nose leaves between section at - 1 and at")
    length_mm: list[float] = Field(description="the nose's sections, the velum's port first, "
                                               "to the nostrils")
    area_mm2: list[float] = Field(description="their areas; the first is the port's")


class AreaFunction(BaseModel):
    position_mm: list[float] = Field(description="the middle of each section, from the glottis")
    length_mm: list[float] = Field(description="each section's length along the midline")
    area_mm2: list[float] = Field(description="each section's cross-section area")
    width_mm: list[float | None] = Field(description="each section's mid-sagittal width (null "
                                                     "for the larynx tube)")
    region: list[str] = Field(description="larynx, pharynx, oral or lips")
    total_length_mm: float
    closed: bool = Field(description="some section is shut (its area is the least one passes)")
    nasal_port_mm2: float = Field(description="the velum's port to the nose")
    nasal: NasalBranch | None = Field(description="the nose as a side branch of the tube, in "
                                                  "the formants; null while the port is shut")


class Formant(BaseModel):
    name: str = Field(description="F1 to F4")
    frequency_hz: float | None = Field(description="null when the band holds fewer peaks")
    bandwidth_hz: float | None = Field(description="3 dB down")


class AcousticsResponse(BaseModel):
    area_function: AreaFunction
    formants: list[Formant]


@router.post("/tract/acoustics", operation_id="computeTractAcoustics",
             response_model=AcousticsResponse)
async def tract_acoustics(request: AcousticsRequest, compute: ComputeDep) -> Response:
    """The pose's area function, glottis first, and the first four formants of that tube."""
    return await compute.respond(acoustics_json, request)


def _plain(value: float) -> float | None:
    return None if np.isnan(value) else round(float(value), 3)


def acoustics_json(assets: AssetStore, request: AcousticsRequest) -> bytes:
    """The AcousticsResponse of a request, as JSON (runs in a compute worker)."""
    split = split_params(assets, request.params)
    try:
        assets.get("tongue_rig").values_from(split.tongue)
    except ParameterError as exc:
        raise HTTPException(status_code=422, detail=f"params.{exc.parameter}: {exc}") from None
    result = tract_shape(assets).acoustics(request.params)
    tube = result["area_function"]
    area = AreaFunction(
        position_mm=np.round(tube["position_mm"], 3).tolist(),
        length_mm=np.round(tube["length_mm"], 3).tolist(),
        area_mm2=np.round(tube["area_mm2"], 3).tolist(),
        width_mm=[_plain(w) for w in tube["width_mm"]],
        region=["larynx" if r < 0 else REGIONS[r] for r in tube["region"]],
        total_length_mm=round(float(np.sum(tube["length_mm"])), 3), closed=tube["closed"],
        nasal_port_mm2=round(float(tube["nasal_port_mm2"]), 3),
        nasal=None if tube["nasal"] is None else NasalBranch(
            at=tube["nasal"]["at"], length_mm=np.round(tube["nasal"]["length_mm"], 3).tolist(),
            area_mm2=np.round(tube["nasal"]["area_mm2"], 3).tolist()))
    formants = [Formant(name=f"F{k + 1}", frequency_hz=_plain(f), bandwidth_hz=_plain(b))
                for k, (f, b) in enumerate(zip(result["formants"], result["bandwidths"],
                                               strict=True))]
    return AcousticsResponse(area_function=area, formants=formants).model_dump_json().encode()
