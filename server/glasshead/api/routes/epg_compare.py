"""Compare a stored EPG recording with a reference, and plot indices over time.

The reference is another stored recording, or frames sent by the client: the synthetic EPG of a
target (a saved pose, or a phoneme target) computed where the tongue model runs. One reference
frame stands for the whole recording (a static target); a sequence is aligned by time from each
side's first frame (see ``glasshead.epg.compare``). The comparisons and plots run in a compute
worker (``jobs.compute``), which reads the recording from the database itself: one of
120,000 frames takes 2 to 4 s.

As reading a recording, these are for clinicians and admins, on recordings the caller may read
(``api/ownership.py``): the recording and a reference recording are checked in the request,
before the work is queued; another caseload's is a 404.
"""

from typing import Annotated

import numpy as np
from fastapi import APIRouter, Depends, HTTPException, Query, Response
from fastapi.concurrency import run_in_threadpool
from pydantic import BaseModel, ConfigDict, Field
from sqlalchemy.orm import Session

from glasshead.api.auth import require_role
from glasshead.api.deps import ComputeDep
from glasshead.api.lookups import MAX_ID, RecordId, get_pose_record, get_record
from glasshead.api.ownership import recording_for
from glasshead.asset_store import AssetStore
from glasshead.epg import compare as epg_compare
from glasshead.epg.formats import rows_to_frame
from glasshead.epg.indices import epg_indices
from glasshead.epg.plot import DEFAULT_PANELS, PANELS, Track, index_tracks_svg
from glasshead.epg.sequence import EpgFormatError, check_times
from glasshead.store.db import database_url, engine_for, get_engine
from glasshead.store.users import User

router = APIRouter(tags=["epg recordings"])

#: Most reference frames accepted in a request body.
MAX_REFERENCE_FRAMES = 20_000
#: Who reads recordings.
Clinician = Annotated[User, Depends(require_role("clinician", "admin"))]
PanelsQuery = Annotated[list[str] | None, Query(
    description=f"indices to plot, one panel each; default {', '.join(DEFAULT_PANELS)}")]
CODE_LEGEND = {
    str(epg_compare.BOTH_OFF): "both off",
    str(epg_compare.BOTH_ON): "both on",
    str(epg_compare.ONLY_RECORDING): "recording only",
    str(epg_compare.ONLY_REFERENCE): "reference only",
    str(epg_compare.NO_ELECTRODE): "no electrode (R1 columns 1 and 8)",
}


class RecordingReference(BaseModel):
    recording_id: int = Field(ge=1, le=MAX_ID)


class PhoneSpan(BaseModel):
    symbol: str = Field(max_length=20, description="the phone, as the reference names it")
    ipa: str | None = Field(None, max_length=20, description="its IPA, given back as sent")
    start_s: float = Field(description="seconds from the recording's first frame")
    end_s: float


class FramesReference(BaseModel):
    label: str = Field("target", max_length=200,
                       description="what the frames show; defaults to the pose's name")
    pose_id: int | None = Field(None, ge=1, le=MAX_ID,
                                description="the saved pose these frames are the "
                                "synthetic EPG of, if any")
    frames: list[list[str]] = Field(
        min_length=1, max_length=MAX_REFERENCE_FRAMES,
        description="per frame 8 strings of '0'/'1', R1 first")
    t_s: list[float] | None = Field(
        None, description="frame times, seconds; needed when there are 2 or more frames and "
                          "not one per recording frame")
    phones: list[PhoneSpan] | None = Field(
        None, max_length=200,
        description="the phones the frames say, on the recording's clock (as "
                    "POST /epg/recordings/{id}/coarticulated gives them): the report then scores "
                    "each phone's frames")


class CompareRequest(BaseModel):
    # Against the synthetic EPG of the /t/ target (assets/build/phoneme-targets.json), one frame
    # standing for the whole recording; or against another stored recording.
    model_config = ConfigDict(json_schema_extra={"examples": [
        {"reference": {"label": "/t/ target", "frames": [
            ["01111110", "11000011", "10000001", "10000001", "10000001", "11000011", "11000011",
             "11000011"]]}},
        {"reference": {"recording_id": 1}}]})
    reference: RecordingReference | FramesReference


class PhoneScore(BaseModel):
    symbol: str
    ipa: str | None
    start_s: float
    end_s: float
    frames: int
    mean_agreement: float | None
    mean_kappa: float | None
    mean_contact_agreement: float | None


class ComparisonReport(BaseModel):
    recording_id: int
    reference_label: str
    t_s: list[float]
    reference_frame: list[int] = Field(description="reference frame used for each frame")
    agreement: list[float] = Field(description="fraction of the 62 electrodes that agree")
    kappa: list[float] = Field(description="Cohen's kappa of each frame over the 62 electrodes: "
                               "agreement beyond chance, 0 for an empty side, 1 when identical")
    contact_agreement: list[float] = Field(
        description="electrodes on in both over electrodes on in either (1 when neither has one)")
    codes: list[list[str]] = Field(description="per frame 8 strings of codes, see code_legend")
    code_legend: dict[str, str]
    electrode_agreement: list[list[float | None]] = Field(
        description="8 x 8: fraction of frames in which each electrode agrees")
    recording_indices: dict[str, list[float]]
    reference_indices: dict[str, list[float]]
    index_difference: dict[str, list[float]] = Field(description="recording minus reference")
    phones: list[PhoneScore] | None = Field(
        None, description="with a reference's phones: each phone's frames and their mean "
                          "agreement, kappa and contact agreement (null without frames)")
    summary: dict = Field(description="means over the frames; with phones, also `phones`: the "
                                      "means over the phones that have frames")


def resolve_reference(session: Session, reference) -> tuple[str, np.ndarray, np.ndarray | None]:
    """(label, frames (m, 8, 8), times (m,) or None) of a reference; 404/422 when it is bad."""
    if isinstance(reference, RecordingReference):
        other = get_record(session, reference.recording_id).to_sequence()
        return other.name, other.frames, other.t_s
    label = reference.label
    if reference.pose_id is not None:
        pose = get_pose_record(session, reference.pose_id)
        if "label" not in reference.model_fields_set:
            label = pose.name
    try:
        frames = np.stack([rows_to_frame(rows, i) for i, rows in enumerate(reference.frames)])
        times = None
        if reference.t_s is not None:
            times = np.asarray(reference.t_s, dtype=np.float64)
            if times.shape != (len(frames),):
                raise EpgFormatError(f"{times.size} times for {len(frames)} frames", field="t_s")
            check_times(times)
    except EpgFormatError as error:
        raise HTTPException(status_code=422, detail=f"reference: {error}") from None
    return label, frames, times


def run_comparison(session: Session, recording_id: int, request: CompareRequest):
    sequence = get_record(session, recording_id).to_sequence()
    label, frames, times = resolve_reference(session, request.reference)
    try:
        result = epg_compare.compare(sequence.frames, sequence.t_s, frames, times)
    except ValueError as error:
        raise HTTPException(status_code=422, detail=f"reference: {error}") from None
    return sequence, label, frames, result


def _check_readable(user: User, recording_id: int, request: CompareRequest | None = None):
    """404 unless ``user`` may read the recording and a reference recording it names."""
    with Session(get_engine()) as session:
        recording_for(session, user, recording_id)
        if request is not None and isinstance(request.reference, RecordingReference):
            recording_for(session, user, request.reference.recording_id)


@router.post("/epg/recordings/{recording_id}/compare", operation_id="compareRecording",
             response_model=ComparisonReport)
async def compare_recording(recording_id: RecordId, request: CompareRequest,
                            compute: ComputeDep, user: Clinician) -> Response:
    """Electrode-by-electrode agreement per frame and the differences of the indices."""
    await run_in_threadpool(_check_readable, user, recording_id, request)
    return await compute.respond(comparison_json, (database_url(), recording_id, request))


@router.post("/epg/recordings/{recording_id}/compare/plot", operation_id="plotComparison",
             response_class=Response,
             responses={200: {"content": {"image/svg+xml": {}}}})
async def plot_comparison(recording_id: RecordId, request: CompareRequest, compute: ComputeDep,
                          user: Clinician, panels: PanelsQuery = None) -> Response:
    """SVG: the recording's indices over time (solid) against the reference's (dashed)."""
    await run_in_threadpool(_check_readable, user, recording_id, request)
    payload = (database_url(), recording_id, request, _check_panels(panels))
    return Response(await compute.run(comparison_svg, payload), media_type="image/svg+xml")


@router.get("/epg/recordings/{recording_id}/plot", operation_id="plotRecording",
            response_class=Response, responses={200: {"content": {"image/svg+xml": {}}}})
async def plot_recording(recording_id: RecordId, compute: ComputeDep, user: Clinician,
                         panels: PanelsQuery = None) -> Response:
    """SVG: the recording's indices over time."""
    await run_in_threadpool(_check_readable, user, recording_id)
    payload = (database_url(), recording_id, _check_panels(panels))
    return Response(await compute.run(recording_svg, payload), media_type="image/svg+xml")


# The work, in a compute worker (jobs.compute): a recording of 120,000 frames takes seconds.

def comparison_json(assets: AssetStore, payload: tuple) -> bytes:
    """The ComparisonReport of (database URL, recording id, request), as JSON."""
    url, recording_id, request = payload
    with Session(engine_for(url)) as session:
        sequence, label, _, result = run_comparison(session, recording_id, request)
    per_electrode = [[None if np.isnan(v) else float(v) for v in row]
                     for row in result.electrode_agreement]
    summary, phones = result.summary(), None
    spans = getattr(request.reference, "phones", None)
    if spans is not None:
        phones, summary["phones"] = epg_compare.phone_scores(
            result, [(p.symbol, p.start_s, p.end_s) for p in spans])
        for score, span in zip(phones, spans, strict=True):
            score["ipa"] = span.ipa
    return ComparisonReport(
        recording_id=recording_id, reference_label=label, t_s=sequence.t_s.tolist(),
        reference_frame=result.reference_frame.tolist(), agreement=result.agreement.tolist(),
        kappa=result.kappa.tolist(), contact_agreement=result.contact_agreement.tolist(),
        codes=[["".join(str(int(v)) for v in row) for row in frame] for frame in result.codes],
        code_legend=CODE_LEGEND, electrode_agreement=per_electrode,
        recording_indices=_lists(result.recording_indices),
        reference_indices=_lists(result.reference_indices),
        index_difference=_lists(result.index_difference),
        phones=phones, summary=summary).model_dump_json().encode()


def comparison_svg(assets: AssetStore, payload: tuple) -> bytes:
    """The SVG of (database URL, recording id, request, panels)."""
    url, recording_id, request, panels = payload
    with Session(engine_for(url)) as session:
        sequence, label, reference_frames, result = run_comparison(session, recording_id,
                                                                   request)
    aligned = reference_frames[result.reference_frame]
    tracks = [Track(sequence.name, sequence.t_s, epg_indices(sequence.frames)),
              Track(label, sequence.t_s, epg_indices(aligned))]
    return index_tracks_svg(tracks, panels,
                            title=f"{sequence.name} against {label}").encode()


def recording_svg(assets: AssetStore, payload: tuple) -> bytes:
    """The SVG of (database URL, recording id, panels)."""
    url, recording_id, panels = payload
    with Session(engine_for(url)) as session:
        sequence = get_record(session, recording_id).to_sequence()
    return index_tracks_svg([Track(sequence.name, sequence.t_s, epg_indices(sequence.frames))],
                            panels, title=sequence.name).encode()


def _check_panels(panels: list[str] | None) -> list[str]:
    panels = panels or list(DEFAULT_PANELS)
    unknown = [p for p in panels if p not in PANELS]
    if unknown:
        raise HTTPException(status_code=422, detail=f"field panels: unknown {unknown}; choose "
                                                    f"from {', '.join(sorted(PANELS))}")
    return panels


def _lists(values: dict) -> dict[str, list[float]]:
    return {k: np.asarray(v, dtype=float).tolist() for k, v in values.items()}
