"""POST /ema/playback: an EMA recording of a speaker, beside the head saying its phones.

A clinician (or an admin) sends the sensor file (HPRC ``_ema.csv``, MOCHA ``.ema``, Carstens
``.pos`` with its ``channels``) and its phone labels (HPRC ``_phones.tsv``, MOCHA ``.lab``); the
answer holds the speaker's sensors and the head's flesh points on the same frames, in the
project frame, the head's parameter tracks, and how closely the head follows (per sensor and
direction r and RMSE, and the signals' r and range ratios; ``speech.ema_playback``). Nothing is
stored. The reading, the head's speech and the scores run in a compute worker.
"""

import json
from typing import Annotated, Literal

from fastapi import APIRouter, Depends, File, Form, HTTPException, Response, UploadFile, status
from pydantic import BaseModel, Field

from glasshead.api.auth import require_role
from glasshead.api.deps import ComputeDep
from glasshead.asset_store import AssetStore
from glasshead.ema.recording import EmaFormatError
from glasshead.flesh_point_assets import flesh_point_rig
from glasshead.speech import ema_comparison, ema_playback
from glasshead.store.users import User

router = APIRouter(tags=["ema"])

Clinician = Annotated[User, Depends(require_role("clinician", "admin"))]
MIB = 1024 * 1024
#: Largest sensor file: a minute of MOCHA (20 channels at 500 Hz) is about 2.4 MB.
MAX_FILE_BYTES = 16 * MIB
#: Largest label file.
MAX_LABEL_BYTES = 1 * MIB
_CHUNK = 64 * 1024


class EmaPhone(BaseModel):
    symbol: str = Field(description="ARPAbet, or the pause label")
    ipa: str | None = Field(description="None for a pause")
    start_s: float
    end_s: float


class EmaPlayback(BaseModel):
    name: str
    source: dict = Field(description="format, speaker, sample_rate_hz, frames, sensors, dropouts")
    phones: list[EmaPhone]
    t_s: list[float] = Field(description="the frames played, seconds from the first sample "
                                         "(at most 100 a second)")
    speech: list[bool] = Field(description="per frame: inside the speech the scores compare")
    sensors: list[str] = Field(description="the sensors compared, in order")
    measured: dict[str, list[list[float | None]]] = Field(
        description="per sensor, [x, y, z] mm per frame in the project frame, registered onto "
                    "the head by an affine map fitted on all of the speech")
    head: dict[str, list[list[float]]] = Field(
        description="per flesh point, [x, y, z] mm per frame in the project frame")
    params: dict[str, list[float]] = Field(description="the head's parameter tracks per frame")
    display_registration: dict = Field(description="fitted_on, rms_mm")
    scores: dict = Field(description="registration (the folds), frames, sensors (per direction "
                                     "r and rmse_mm), signals (r, baseline_r, range ratios)")


async def _read(upload: UploadFile, field: str, limit: int) -> bytes:
    content = bytearray()
    while chunk := await upload.read(_CHUNK):
        content += chunk
        if len(content) > limit:
            raise HTTPException(status_code=413, detail=(
                f"field {field}: larger than the {limit // MIB} MiB limit"))
    if not content.strip():
        raise HTTPException(status_code=422, detail=f"field {field}: the file is empty")
    return bytes(content)


def _channels(text: str | None) -> dict[str, int] | None:
    if text is None:
        return None
    try:
        channels = json.loads(text)
    except json.JSONDecodeError:
        channels = None
    if not isinstance(channels, dict) or not channels or not all(
            isinstance(k, str) and isinstance(v, int) and not isinstance(v, bool) and v >= 1
            for k, v in channels.items()):
        raise HTTPException(status_code=422, detail=(
            "field channels: expected a JSON object of sensor code -> channel number from 1, "
            "e.g. {\"TT\": 3, \"UL\": 5}"))
    return channels


@router.post("/ema/playback", operation_id="playEmaRecording", response_model=EmaPlayback,
             openapi_extra={"requestBody": {"content": {"multipart/form-data": {"example": {
                 "file": "time_s,TT_x,TT_y,TT_z\n0.00,-11.3,-0.1,-10.5\n",
                 "labels": "start_s\tend_s\tlabel\n0.0\t0.2\tsp\n"}}}}},
             responses={413: {"description": "a file is past its size limit"},
                        422: {"description": "a file cannot be read, or the recording cannot "
                                             "be compared; the detail names the file and "
                                             "line"}})
async def play_ema_recording(
    compute: ComputeDep,
    user: Clinician,
    file: Annotated[UploadFile, File(description="the sensor file: HPRC _ema.csv, MOCHA .ema, "
                                                 "Carstens .pos")],
    labels: Annotated[UploadFile, File(description="the phone labels: HPRC _phones.tsv, "
                                                   "MOCHA .lab")],
    format: Annotated[Literal["hprc", "mocha", "ag500", "ag501"] | None, Form(
        description="the sensor file's format (default: from its name, else its first "
                    "bytes)")] = None,
    channels: Annotated[str | None, Form(
        max_length=2000, description="Carstens: JSON, sensor code -> channel from 1")] = None,
) -> Response:
    """The recording's sensors and the head saying its phones, frame for frame, with scores."""
    content = await _read(file, "file", MAX_FILE_BYTES)
    label_bytes = await _read(labels, "labels", MAX_LABEL_BYTES)
    payload = (content, file.filename or "upload", label_bytes, labels.filename or "labels",
               format, _channels(channels))
    return await compute.respond(playback_json, payload, doing="comparing an EMA recording")


def playback_json(assets: AssetStore, payload: tuple) -> bytes:
    """The EmaPlayback of (content, file name, labels, their file name, format, channels), as
    JSON (compute worker)."""
    content, filename, labels, labels_name, fmt, channels = payload
    try:
        recording = ema_playback.read_upload(content, filename, labels, labels_name=labels_name,
                                             format=fmt, channels=channels)
        document = ema_playback.playback(recording, assets.get("phoneme_targets"),
                                         flesh_point_rig(assets))
    except (EmaFormatError, ema_comparison.ComparisonError) as error:
        raise HTTPException(status_code=status.HTTP_422_UNPROCESSABLE_ENTITY,
                            detail=str(error)) from None
    return EmaPlayback.model_validate(document).model_dump_json().encode()
