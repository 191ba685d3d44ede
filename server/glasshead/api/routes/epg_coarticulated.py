"""POST /epg/recordings/{id}/coarticulated: the head's palatogram while it says the recording's
own phones on the recording's own timing (``speech.phone_epg``), frame for frame with it.

Send the answer's ``frames``, ``t_s`` and ``phones`` as the ``reference`` of
``POST /epg/recordings/{id}/compare`` to score the recording phone by phone. Clinicians and
admins, on recordings they may read; the work (the coarticulation and one corrected tongue per
frame, 0.5 to 1 s for a take of 50 frames) runs in a compute worker.
"""

from typing import Annotated

from fastapi import APIRouter, Depends, HTTPException, Response
from fastapi.concurrency import run_in_threadpool
from pydantic import BaseModel, ConfigDict, Field
from sqlalchemy.orm import Session

from glasshead.api.auth import require_role
from glasshead.api.deps import ComputeDep
from glasshead.api.lookups import RecordId, get_record
from glasshead.api.ownership import recording_for
from glasshead.asset_store import AssetStore
from glasshead.probe_assets import layout_probes
from glasshead.speech import phone_epg
from glasshead.store.db import database_url, engine_for, get_engine
from glasshead.store.users import User

router = APIRouter(tags=["epg recordings"])

Clinician = Annotated[User, Depends(require_role("clinician", "admin"))]
#: Most frames a recording may have to be said by the head (60 s at 200 Hz), and most seconds
#: it may span: the head's tracks are made at the recording's rate over its whole span.
MAX_SAID_FRAMES = 12_000
MAX_SAID_SECONDS = 60.0


class CoarticulateRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={"examples": [
        {}, {"phones": ["s", "k"], "boundaries_s": [0.15]}]})
    phones: list[Annotated[str, Field(max_length=20)]] | None = Field(
        None, max_length=phone_epg.MAX_PHONES,
        description="the phones the recording holds, in order (ARPAbet or IPA); default: read "
                    "from its label, 's->k' is /s/ then /k/")
    boundaries_s: list[float] | None = Field(
        None, max_length=phone_epg.MAX_PHONES,
        description="where each phone after the first begins, seconds from the recording's "
                    "first frame; default: read from the recording's centre of gravity (two "
                    "phones) or an even split")


class PhoneSpan(BaseModel):
    symbol: str = Field(description="ARPAbet")
    ipa: str
    start_s: float = Field(description="seconds from the recording's first frame")
    end_s: float


class CoarticulatedEpg(BaseModel):
    recording_id: int
    label: str = Field(description="what the frames show, for a chooser or a plot")
    phones: list[PhoneSpan]
    boundary_source: str = Field(description="given, centre of gravity or even split")
    t_s: list[float] = Field(description="the recording's frame times, seconds from its first")
    frames: list[list[str]] = Field(description="per frame 8 strings of '0'/'1', R1 first")


@router.post("/epg/recordings/{recording_id}/coarticulated", operation_id="coarticulateRecording",
             response_model=CoarticulatedEpg)
async def coarticulate_recording(recording_id: RecordId, request: CoarticulateRequest,
                                 compute: ComputeDep, user: Clinician) -> Response:
    """The synthetic EPG of the recording's phones, said on its timing."""
    await run_in_threadpool(_check_readable, user, recording_id)
    return await compute.respond(coarticulated_json, (database_url(), recording_id, request))


def _check_readable(user: User, recording_id: int) -> None:
    with Session(get_engine()) as session:
        recording_for(session, user, recording_id)


def coarticulated_json(assets: AssetStore, payload: tuple) -> bytes:
    """The CoarticulatedEpg of (database URL, recording id, request), as JSON (compute worker)."""
    url, recording_id, request = payload
    with Session(engine_for(url)) as session:
        sequence = get_record(session, recording_id).to_sequence()
    relative = sequence.t_s - sequence.t_s[0]
    period = phone_epg.frame_period(sequence.t_s, sequence.frame_rate_hz)
    frames_made = max(sequence.n_frames, relative[-1] / period)  # the tracks span it at its rate
    if relative[-1] + period > MAX_SAID_SECONDS or frames_made > MAX_SAID_FRAMES:
        raise HTTPException(status_code=422, detail=(
            f"the recording has {sequence.n_frames} frames over {relative[-1]:.1f} s at "
            f"{1.0 / period:g} frames a second; the head says at most {MAX_SAID_SECONDS:g} s and "
            f"{MAX_SAID_FRAMES} frames: import the segment to compare on its own"))
    try:
        symbols = request.phones if request.phones is not None else \
            phone_epg.phones_from_label(sequence.meta.get("label"))
        named = phone_epg.arpabet_symbols(symbols)
        segments, source = phone_epg.phone_segments(named, sequence.frames, relative, period,
                                                    request.boundaries_s)
    except phone_epg.PhoneSegmentError as error:
        raise HTTPException(status_code=422, detail=f"field {error.field}: {error}") from None
    probes = layout_probes(assets)
    frames = phone_epg.synthetic_frames(segments, relative, period,
                                        assets.get("phoneme_targets"), assets.get("tongue_rig"),
                                        assets.get("collision_tables"), probes)
    said = " ".join(f"/{s.ipa}/" for s in segments)
    return CoarticulatedEpg(
        recording_id=recording_id, label=f"{said} said as in {sequence.name}",
        phones=[PhoneSpan(symbol=s.symbol, ipa=s.ipa, start_s=s.start_s, end_s=s.end_s)
                for s in segments],
        boundary_source=source, t_s=relative.tolist(),
        frames=[["".join(str(int(v)) for v in row) for row in frame] for frame in frames],
    ).model_dump_json().encode()
