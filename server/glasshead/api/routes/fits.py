"""Fits: an author's observation (a contour, a surface, EPG frames, flesh points, or several of
them together) fitted into a new target.

POST /fits takes a multipart upload (``file``, ``kind``, optional ``name``, ``method``,
``max_evals`` and, for EPG or flesh-point tracks, ``frame``; a ``combined`` fit takes
``contour_file``, ``epg_file`` and ``ema_file``, two or more, each with an optional weight),
reads and checks it whole (``glasshead.uploads``: 413 past
the kind's size limit, 415 not the kind's format, 422 bad content, each naming the problem; no
row is stored), stores a ``queued`` job and answers 202 with it and its Location. The fit runs
in a worker process of whichever server (``jobs.fit_runner``) takes it from the queue in the
database (``jobs.fit_queue``), never in the request. Its progress is read by
polling GET /fits/{id} or as server-sent events from GET /fits/{id}/events. A finished fit's
``params`` are a target, listed by GET /fits?state=done. docs/fits.md describes it all.

Fitted targets are shared as saved poses are: every signed-in adult reads them; authors,
clinicians and admins upload observations; a fit is deleted only by its uploader or an admin.
"""

import asyncio
import json
from datetime import datetime
from functools import partial
from typing import Annotated, Literal

from fastapi import (
    APIRouter,
    Depends,
    File,
    Form,
    HTTPException,
    Query,
    Request,
    Response,
    UploadFile,
    status,
)
from fastapi.concurrency import run_in_threadpool
from fastapi.responses import StreamingResponse
from pydantic import BaseModel, ConfigDict, Field
from sqlalchemy import func, select
from sqlalchemy.orm import Session

from glasshead import uploads
from glasshead.api import idempotency
from glasshead.api.auth import SignedInUser, require_role
from glasshead.api.examples import EMUR_EXAMPLE, FLESH_POINTS_EXAMPLE
from glasshead.api.lookups import Offset, RecordId
from glasshead.api.ownership import check_owner
from glasshead.fitting.authored import default_method
from glasshead.jobs.fit_runner import FitRunner
from glasshead.store.db import get_engine
from glasshead.store.fit_jobs import FitJob
from glasshead.store.session import SessionDep
from glasshead.store.users import User

router = APIRouter(tags=["fits"])

Kind = Literal["contour", "surface", "epg", "ema", "combined"]
Method = Literal["bobyqa", "praxis", "sbplx"]
State = Literal["queued", "running", "done", "failed"]
#: Seconds between looks at a job's row while streaming its events.
EVENT_POLL_S = 0.2
#: Seconds without a change after which the stream sends a comment, so proxies keep it open.
KEEP_ALIVE_S = 15.0
#: Seconds a client is asked to wait when the queue is full.
RETRY_AFTER_S = 30
#: Most evaluations an upload may ask a fit to spend.
MAX_EVALS = 20000
NO_FILE = "field file: the upload has no file part"
_CHUNK = 64 * 1024


def get_fit_runner(request: Request) -> FitRunner:
    return request.app.state.fits


RunnerDep = Annotated[FitRunner, Depends(get_fit_runner)]
#: Who uploads observations to fit.
Maker = Annotated[User, Depends(require_role("author", "clinician", "admin"))]


class FitProgress(BaseModel):
    evaluations: int = 0
    best_error: float | None = Field(None, description="the objective's best value so far")
    fraction: float = Field(0.0, description="share of the evaluation budget spent, 0 to 1")


class FitOut(BaseModel):
    model_config = ConfigDict(from_attributes=True)
    id: int
    name: str
    kind: Kind
    method: Method
    state: State
    message: str | None = Field(description="why the fit failed")
    progress: FitProgress
    source: dict = Field(description="the upload: file name, format, counts, options")
    params: dict[str, float] | None = Field(
        description="the fitted target: every rig parameter (tongue, jaw, lips, velum)")
    report: dict | None = Field(
        description="rms_mm, evaluations, seconds, volume_change_pct, at_limit, method, ...")
    owner_id: int | None = Field(None, description="the user who uploaded it")
    created_at: datetime
    updated_at: datetime
    started_at: datetime | None
    finished_at: datetime | None


class FitList(BaseModel):
    fits: list[FitOut]
    total: int


def get_fit_record(session: Session, fit_id: int) -> FitJob:
    job = session.get(FitJob, fit_id)
    if job is None:
        raise HTTPException(status_code=404, detail=f"no fit with id {fit_id}")
    return job


async def _read_limited(upload: UploadFile, kind: str) -> bytes:
    """The upload's bytes, read in chunks and refused (413) once past the kind's limit."""
    limit = uploads.MAX_BYTES[kind]
    content = bytearray()
    while chunk := await upload.read(_CHUNK):
        content += chunk
        if len(content) > limit:
            raise HTTPException(status_code=413, detail=uploads.size_limit_message(kind))
    return bytes(content)


@router.post("/fits", operation_id="createFit", status_code=status.HTTP_202_ACCEPTED,
             response_model=FitOut,
             openapi_extra={"requestBody": {"content": {"multipart/form-data": {"examples": {
                 "epg": {"summary": "EPG frames", "value": {
                     "kind": "epg", "file": json.dumps(EMUR_EXAMPLE), "name": "bescan s->k",
                     "method": "sbplx", "max_evals": 400}},
                 "combined": {"summary": "EPG frames and flesh points together", "value": {
                     "kind": "combined", "epg_file": json.dumps(EMUR_EXAMPLE),
                     "ema_file": FLESH_POINTS_EXAMPLE, "ema_weight": 2, "max_evals": 400}}}}}}},
             responses={413: {"description": "the file is past the kind's size limit"},
                        415: {"description": "the file is not in a format of the kind"},
                        503: {"description": "the queue is full; retry after Retry-After"}})
async def create_fit(
    request: Request,
    response: Response,
    session: SessionDep,
    runner: RunnerDep,
    user: Maker,
    kind: Annotated[Kind, Form(description="what the file holds")],
    idempotency_key: idempotency.IdempotencyKeyHeader = None,
    file: Annotated[UploadFile | None, File(description="the observation file")] = None,
    name: Annotated[str | None, Form(max_length=200,
                                     description="the target's name (default: the file's)")] = None,
    method: Annotated[Method | None, Form(
        description="the optimiser (default: bobyqa; sbplx for epg)")] = None,
    max_evals: Annotated[int | None, Form(ge=10, le=MAX_EVALS,
                                          description="cap on the fit's evaluations")] = None,
    frame: Annotated[int | None, Form(ge=0, description="epg: fit this frame (0-based) "
                                                        "instead of the majority; ema: this "
                                                        "frame of flesh-point tracks")] = None,
    contour_file: Annotated[UploadFile | None, File(
        description="combined: a contour CSV")] = None,
    epg_file: Annotated[UploadFile | None, File(
        description="combined: an EPG recording")] = None,
    ema_file: Annotated[UploadFile | None, File(
        description="combined: flesh points, CSV or JSON")] = None,
    contour_weight: Annotated[float | None, Form(ge=0, le=uploads.MAX_PART_WEIGHT, description=(
        "combined: the contour's weight (default 1)"))] = None,
    epg_weight: Annotated[float | None, Form(ge=0, le=uploads.MAX_PART_WEIGHT, description=(
        "combined: the EPG frames' weight (default 1)"))] = None,
    ema_weight: Annotated[float | None, Form(ge=0, le=uploads.MAX_PART_WEIGHT, description=(
        "combined: the flesh points' weight (default 1)"))] = None,
    ema_frame: Annotated[int | None, Form(ge=0, description=(
        "combined: the frame of flesh-point tracks to fit (default the first)"))] = None,
) -> FitJob:
    """Queue a fit of one uploaded observation, or of several together (``combined``); 202
    with the job, Location its URL. A retry with the same ``Idempotency-Key`` gets the first
    answer and queues nothing new."""
    declared = request.headers.get("content-length", "")
    if declared.isdigit() and int(declared) > uploads.MAX_BYTES[kind] + 3 * _CHUNK:
        raise HTTPException(status_code=413, detail=uploads.size_limit_message(kind))
    files = {"contour": contour_file, "epg": epg_file, "ema": ema_file}
    weights = {part: w for part, w in (("contour", contour_weight), ("epg", epg_weight),
                                       ("ema", ema_weight)) if w is not None}
    _check_fields(kind, file, files, weights, ema_frame)
    if kind == "combined":
        given = {part: upload for part, upload in files.items() if upload is not None}
        contents = {part: (await _read_limited(upload, part), upload.filename)
                    for part, upload in given.items()}
        digest = idempotency.upload_digest(kind, *[x for part, (content, filename) in
                                                   contents.items()
                                                   for x in (part, content, filename)],
                                           json.dumps(weights, sort_keys=True), name, method,
                                           max_evals, frame, ema_frame)
        read = partial(uploads.read_combined, contents, frame=frame, ema_frame=ema_frame)
        default_name = " + ".join(filename or part for part, (_, filename) in contents.items())
    else:
        if file is None:  # refused by _check_fields already; this says so to the types too
            raise HTTPException(status_code=422, detail=NO_FILE)
        content = await _read_limited(file, kind)
        digest = idempotency.upload_digest(kind, content, file.filename, name, method,
                                           max_evals, frame)
        read = partial(uploads.read_observation, kind, content, file.filename, frame=frame)
        default_name = file.filename or f"{kind} fit"
    replayed = await run_in_threadpool(idempotency.replay, session, "createFit",
                                       idempotency_key, digest)
    if replayed is not None:
        return replayed
    try:
        observation = await run_in_threadpool(read)
    except uploads.ObservationError as error:
        raise HTTPException(status_code=error.status, detail=str(error)) from None
    if weights:
        observation.source["weights"] = weights
    job = await run_in_threadpool(
        _store, session, runner, observation, name or default_name, method,
        max_evals, idempotency_key, digest, user.id,
        lambda fit_id: str(request.url_for("get_fit", fit_id=fit_id).path))
    if isinstance(job, Response):  # the same key's first request committed meanwhile
        return job
    response.headers["Location"] = str(request.url_for("get_fit", fit_id=job.id).path)
    return job


def _check_fields(kind: str, file: UploadFile | None, files: dict, weights: dict,
                  ema_frame: int | None) -> None:
    """422 for the fields ``kind`` does not take: a combined fit takes its parts' files, every
    other kind one ``file``."""
    def refuse(detail: str):
        raise HTTPException(status_code=422, detail=detail)

    if kind == "combined":
        if file is not None:
            refuse("field file: a combined fit takes contour_file, epg_file and ema_file, two "
                   "or more, not file")
        missing = [part for part, upload in files.items() if upload is None]
        if len(missing) > 1:
            refuse("a combined fit needs at least two of contour_file, epg_file and ema_file "
                   "(one alone is a fit of its own kind)")
        for part in weights:
            if files[part] is None:
                refuse(f"field {part}_weight: there is no {part}_file to weigh")
        return
    if file is None:
        refuse(NO_FILE)
    extra = [f"{part}_file" for part, upload in files.items() if upload is not None]
    extra += [f"{part}_weight" for part in weights]
    extra += ["ema_frame"] if ema_frame is not None else []
    if extra:
        refuse(f"field {extra[0]}: only a combined fit takes it (this is kind {kind})")


def _store(session: Session, runner: FitRunner, observation: uploads.Observation, name: str,
           method: str | None, max_evals: int | None, key: str | None = None, digest: str = "",
           owner_id: int | None = None, location=None) -> FitJob | Response:
    if runner.queue_full(session):
        raise HTTPException(status_code=503, headers={"Retry-After": str(RETRY_AFTER_S)},
                            detail=f"{runner.queue_limit} fits are already waiting; retry "
                                   "later")
    options: dict = {} if max_evals is None else {"max_evals": max_evals}
    source = dict(observation.source)
    if "weights" in source:
        options["weights"] = source.pop("weights")
    job = FitJob(name=name.strip()[:200] or f"{observation.kind} fit", kind=observation.kind,
                 method=method or default_method(observation.kind, observation.points),
                 state="queued", progress={"evaluations": 0, "best_error": None, "fraction": 0.0},
                 source={**source, "options": options}, owner_id=owner_id)
    job.set_observation(observation.points)
    session.add(job)
    session.flush()
    runner.announce(session)  # every server hears of it when this commits
    if key is not None:
        idempotency.remember(session, "createFit", key, digest, status.HTTP_202_ACCEPTED,
                             FitOut.model_validate(job).model_dump(mode="json"),
                             {"Location": location(job.id)})
    if (replayed := idempotency.commit_or_replay(session, "createFit", key, digest)) is not None:
        return replayed
    runner.wake()
    return job


@router.get("/fits", operation_id="listFits", response_model=FitList)
def list_fits(session: SessionDep, user: SignedInUser, state: State | None = None,
              offset: Offset = 0,
              limit: Annotated[int, Query(ge=1, le=1000)] = 100) -> FitList:
    """Fits, newest first; ``state=done`` lists the fitted targets."""
    query = select(FitJob)
    if state is not None:
        query = query.where(FitJob.state == state)
    total = session.scalar(select(func.count()).select_from(query.subquery()))
    jobs = session.scalars(query.order_by(FitJob.id.desc()).offset(offset).limit(limit))
    return FitList(fits=[FitOut.model_validate(j) for j in jobs], total=total)


@router.get("/fits/{fit_id}", operation_id="getFit", response_model=FitOut)
def get_fit(fit_id: RecordId, session: SessionDep, user: SignedInUser) -> FitJob:
    """One fit: its state and progress, and once done its target (``params``) and report."""
    return get_fit_record(session, fit_id)


@router.get("/fits/{fit_id}/events", operation_id="streamFitEvents",
            response_class=StreamingResponse,
            responses={200: {"content": {"text/event-stream": {}},
                             "description": "progress events, then one done or failed event"}})
def stream_fit_events(fit_id: RecordId, session: SessionDep,
                      user: SignedInUser) -> StreamingResponse:
    """Server-sent events: ``progress`` (the job's state and progress) whenever its row
    changes, then one ``done`` or ``failed`` event with the whole job, then the stream ends."""
    get_fit_record(session, fit_id)
    return StreamingResponse(_events(fit_id), media_type="text/event-stream",
                             headers={"Cache-Control": "no-cache", "X-Accel-Buffering": "no"})


def _snapshot(fit_id: int) -> dict | None:
    with Session(get_engine()) as session:
        job = session.get(FitJob, fit_id)
        return None if job is None else FitOut.model_validate(job).model_dump(mode="json")


def _event(name: str, data: dict) -> str:
    return f"event: {name}\ndata: {json.dumps(data)}\n\n"


async def _events(fit_id: int):
    last = None
    quiet = 0.0
    while True:
        job = await run_in_threadpool(_snapshot, fit_id)
        if job is None:
            yield _event("failed", {"id": fit_id, "state": "failed",
                                    "message": "the fit was deleted"})
            return
        seen = (job["state"], job["progress"])
        if seen != last:
            last, quiet = seen, 0.0
            yield _event("progress", {"id": fit_id, "state": job["state"],
                                      "progress": job["progress"]})
        if job["state"] in ("done", "failed"):
            yield _event(job["state"], job)
            return
        await asyncio.sleep(EVENT_POLL_S)
        quiet += EVENT_POLL_S
        if quiet >= KEEP_ALIVE_S:
            quiet = 0.0
            yield ": keep-alive\n\n"


@router.delete("/fits/{fit_id}", operation_id="deleteFit", status_code=status.HTTP_204_NO_CONTENT)
def delete_fit(fit_id: RecordId, session: SessionDep, user: Maker) -> Response:
    """Delete a fit and its target; a fit still running stops at its next progress write."""
    job = get_fit_record(session, fit_id)
    check_owner(user, job, "fit")
    session.delete(job)
    session.commit()
    return Response(status_code=status.HTTP_204_NO_CONTENT)
