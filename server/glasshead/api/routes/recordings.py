"""EPG recordings: import (emuR JSON, CSV, SSFF), list, read for playback, export, delete.

POST /epg/recordings takes either a multipart upload (``file``, optional ``format`` and ``name``)
or a JSON body ``{"format", "content" | "content_base64", "name"}``. A file is checked whole before
anything is stored: one bad frame and nothing of the file is kept (422 naming the frame and field).
Playback needs ``t_s`` (each frame's own time, seconds) and ``frame_rate_hz``, both in the detail.

A recording is a child's (``child_id``, a child in one of the importing clinician's classes) or a
reference recording (no child). Clinicians and admins import them; a clinician reads reference
recordings and those of the children of their own caseload (another's is a 404) and deletes
those they imported (403 otherwise); admins reach all (``api/ownership.py``).
"""

import base64
import binascii
import json
from datetime import datetime
from typing import Annotated, Literal

from fastapi import (
    APIRouter,
    Depends,
    File,
    Form,
    Header,
    HTTPException,
    Query,
    Request,
    Response,
    UploadFile,
    status,
)
from fastapi.concurrency import run_in_threadpool
from pydantic import BaseModel, ConfigDict, Field, ValidationError
from sqlalchemy import func, select
from sqlalchemy.orm import Session

from glasshead.api import idempotency
from glasshead.api.auth import Person, require_role
from glasshead.api.etags import PRECONDITION, check_if_match, commit_versioned, set_etag
from glasshead.api.examples import EMUR_EXAMPLE
from glasshead.api.lookups import MAX_ID, Offset, RecordId
from glasshead.api.ownership import (
    check_child_reference,
    check_uploader,
    recording_for,
    visible_recordings,
)
from glasshead.epg import formats
from glasshead.epg.indices import epg_indices
from glasshead.epg.sequence import EpgFormatError, rows_to_strings
from glasshead.store.models import EpgRecording
from glasshead.store.session import SessionDep
from glasshead.store.users import User

router = APIRouter(tags=["epg recordings"])

#: The kind in a recording's ETag (api/etags.py).
KIND = "recording"
#: The operation an import's Idempotency-Key belongs to (api/idempotency.py).
IMPORT_OPERATION = "createRecordings"

#: Largest upload accepted, bytes. Every export must import again: the largest recording
#: (MAX_FRAMES, every contact on, long times) exports as 20.9 MiB of emuR JSON, 23.4 MiB when
#: sent as a JSON string in ``content``, 16.3 MiB of CSV and 0.9 MiB of SSFF.
MAX_UPLOAD_BYTES = 32 * 1024 * 1024
FormatName = Literal["emur-json", "csv", "ssff"]
#: Who imports and reads recordings.
Clinician = Annotated[User, Depends(require_role("clinician", "admin"))]
CHILD_ID = ("the child it was recorded from, in one of your classes; leave out for a reference "
            "recording")


class RecordingUpload(BaseModel):
    """A recording file sent as JSON: text or JSON in ``content``, binary (ssff) in base64."""

    model_config = ConfigDict(json_schema_extra={"examples": [
        {"format": "emur-json", "content": EMUR_EXAMPLE, "name": "sp1bescan s->k"}]})
    format: FormatName
    content: str | dict | list | None = Field(
        None, description="csv: the file's text; emur-json: the document or its text")
    content_base64: str | None = Field(None, description="the file's bytes in base64 (ssff)")
    name: str | None = Field(None, max_length=200, description="overrides the file's name")
    child_id: int | None = Field(None, ge=1, le=MAX_ID, description=CHILD_ID)


class RecordingSummary(BaseModel):
    id: int
    name: str
    child_id: int | None = Field(None, description="the child it was recorded from; None for a "
                                                   "reference recording")
    uploaded_by: int | None = Field(None, description="the user who imported it")
    source_format: str
    frame_rate_hz: float | None = Field(description="frames per second of the recording")
    n_frames: int
    start_s: float = Field(description="time of the first frame, seconds")
    duration_s: float = Field(description="last frame time minus first frame time, seconds")
    meta: dict
    created_at: datetime


class RecordingDetail(RecordingSummary):
    t_s: list[float] = Field(description="each frame's time, seconds")
    frames: list[list[str]] = Field(
        description="per frame 8 strings of '0'/'1', R1 (front) first; character c = column c+1")


class RecordingList(BaseModel):
    recordings: list[RecordingSummary]
    total: int


class IndexTracks(BaseModel):
    recording_id: int
    t_s: list[float]
    indices: dict[str, list[float]]


def summary(record: EpgRecording) -> RecordingSummary:
    return RecordingSummary(
        id=record.id, name=record.name, child_id=record.child_id,
        uploaded_by=record.uploaded_by, source_format=record.source_format,
        frame_rate_hz=record.frame_rate_hz, n_frames=record.n_frames, start_s=record.first_t_s,
        duration_s=record.last_t_s - record.first_t_s, meta=record.meta or {},
        created_at=record.created_at)


@router.post(
    "/epg/recordings", operation_id=IMPORT_OPERATION, status_code=status.HTTP_201_CREATED,
    response_model=RecordingList,
    responses={415: {"description": "the body is neither multipart/form-data nor JSON"}},
    # The multipart form comes from the parameters below; the JSON alternative is added here.
    openapi_extra={"requestBody": {"required": True, "content": {
        "application/json": {"schema": RecordingUpload.model_json_schema()},
        "multipart/form-data": {"example": {"file": json.dumps(EMUR_EXAMPLE),
                                            "format": "emur-json", "name": "sp1bescan s->k"}},
    }}},
)
async def create_recordings(
    request: Request,
    session: SessionDep,
    user: Clinician,
    idempotency_key: idempotency.IdempotencyKeyHeader = None,
    file: Annotated[UploadFile | None, File(description="the recording file (multipart)")] = None,
    format: Annotated[FormatName | None, Form(
        description="the file's format; detected from its name and content when left out")] = None,
    name: Annotated[str | None, Form(max_length=200,
                                     description="overrides the file's name")] = None,
    child_id: Annotated[int | None, Form(ge=1, le=MAX_ID, description=CHILD_ID)] = None,
) -> RecordingList:
    """Import a file; emuR JSON with several segments makes one recording per segment. A retry
    with the same ``Idempotency-Key`` gets the first answer and stores nothing new."""
    content_type = request.headers.get("content-type", "").split(";")[0].strip().lower()
    declared = request.headers.get("content-length", "")
    if declared.isdigit() and int(declared) > MAX_UPLOAD_BYTES + 64 * 1024:
        raise _too_large()
    if content_type == "multipart/form-data":
        content, fmt = await _read_upload(file, format)
        name = name or None
    elif content_type == "application/json":
        content, fmt, name, child_id = _read_json_upload(await _read_body(request))
    else:
        raise HTTPException(status_code=415, detail="send multipart/form-data (a file) or "
                                                    "application/json (format and content)")
    return await run_in_threadpool(_import, session, content, fmt, name, idempotency_key,
                                   user, child_id)


def _import(session: Session, content: bytes, fmt: str | None, name: str | None,
            key: str | None = None, user: User | None = None, child_id: int | None = None):
    # The importer is part of the request: another user's retry with the same key is not it.
    digest = idempotency.upload_digest(content, fmt, name, child_id,
                                       user.id if user is not None else None)
    if (replayed := idempotency.replay(session, IMPORT_OPERATION, key, digest)) is not None:
        return replayed
    if user is not None:
        check_child_reference(session, Person(user=user), child_id)
    try:
        fmt = fmt or formats.detect_format(content)
        sequences = formats.parse(content, fmt, name=name)
    except EpgFormatError as error:
        raise HTTPException(status_code=422, detail=str(error)) from None
    records = [EpgRecording.from_sequence(seq, fmt) for seq in sequences]
    for record in records:
        record.child_id, record.uploaded_by = child_id, user.id if user is not None else None
    session.add_all(records)
    session.flush()
    result = RecordingList(recordings=[summary(r) for r in records], total=len(records))
    idempotency.remember(session, IMPORT_OPERATION, key, digest, status.HTTP_201_CREATED,
                         result.model_dump(mode="json"))
    return idempotency.commit_or_replay(session, IMPORT_OPERATION, key, digest) or result


async def _read_body(request: Request) -> bytes:
    body = bytearray()
    async for chunk in request.stream():
        body += chunk
        if len(body) > MAX_UPLOAD_BYTES:
            raise _too_large()
    return bytes(body)


async def _read_upload(upload: UploadFile | None, fmt: str | None) -> tuple[bytes, str]:
    if upload is None:
        raise HTTPException(status_code=422, detail="field file: the upload has no file part")
    content = await upload.read(MAX_UPLOAD_BYTES + 1)
    if len(content) > MAX_UPLOAD_BYTES:
        raise _too_large()
    if fmt is None:
        try:
            fmt = formats.detect_format(content, upload.filename)
        except EpgFormatError as error:
            raise HTTPException(status_code=422, detail=str(error)) from None
    return content, fmt


def _read_json_upload(body: bytes) -> tuple[bytes, str, str | None, int | None]:
    try:
        upload = RecordingUpload.model_validate_json(body)
    except ValidationError as error:
        problems = "; ".join(f"field {'.'.join(str(p) for p in e['loc']) or 'body'}: {e['msg']}"
                             for e in error.errors())
        raise HTTPException(status_code=422, detail=problems) from None
    if (upload.content is None) == (upload.content_base64 is None):
        raise HTTPException(status_code=422,
                            detail="field content: give exactly one of content, content_base64")
    if upload.content_base64 is not None:
        try:
            content = base64.b64decode(upload.content_base64, validate=True)
        except (binascii.Error, ValueError):
            raise HTTPException(status_code=422,
                                detail="field content_base64: not valid base64") from None
    elif isinstance(upload.content, str):
        content = upload.content.encode()
    else:
        content = json.dumps(upload.content).encode()
    return content, upload.format, upload.name, upload.child_id


def _too_large() -> HTTPException:
    return HTTPException(status_code=413, detail=f"field file: larger than the "
                                                 f"{MAX_UPLOAD_BYTES // (1024 * 1024)} MiB limit")


@router.get("/epg/recordings", operation_id="listRecordings", response_model=RecordingList)
def list_recordings(session: SessionDep, user: Clinician, offset: Offset = 0,
                    limit: Annotated[int, Query(ge=1, le=1000)] = 100,
                    child_id: Annotated[int | None, Query(ge=1, le=MAX_ID, description=(
                        "only this child's recordings"))] = None) -> RecordingList:
    """Recordings the caller may read (reference recordings and their caseload's), newest
    first, without their frames."""
    query = visible_recordings(select(EpgRecording), user)
    if child_id is not None:
        query = query.where(EpgRecording.child_id == child_id)
    total = session.scalar(select(func.count()).select_from(query.subquery()))
    records = session.scalars(query.order_by(EpgRecording.id.desc()).offset(offset).limit(limit))
    return RecordingList(recordings=[summary(r) for r in records], total=total)


@router.get("/epg/recordings/{recording_id}", operation_id="getRecording",
            response_model=RecordingDetail)
def get_recording(recording_id: RecordId, session: SessionDep, user: Clinician,
                  response: Response) -> RecordingDetail:
    """One recording with every frame and its time, for playback at its own frame rate."""
    record = recording_for(session, user, recording_id)
    set_etag(response, KIND, record)
    sequence = record.to_sequence()
    return RecordingDetail(**summary(record).model_dump(), t_s=sequence.t_s.tolist(),
                           frames=[rows_to_strings(f) for f in sequence.frames])


@router.get("/epg/recordings/{recording_id}/indices", operation_id="getRecordingIndices",
            response_model=IndexTracks)
def get_recording_indices(recording_id: RecordId, session: SessionDep,
                          user: Clinician) -> IndexTracks:
    """The emuR indices of every frame (see POST /epg/indices for their names)."""
    sequence = recording_for(session, user, recording_id).to_sequence()
    return IndexTracks(recording_id=recording_id, t_s=sequence.t_s.tolist(),
                       indices={k: v.tolist() for k, v in epg_indices(sequence.frames).items()})


@router.get("/epg/recordings/{recording_id}/export", operation_id="exportRecording",
            response_class=Response,
            responses={200: {"content": {t: {} for t in set(formats.MEDIA_TYPES.values())}},
                       409: {"description": "ssff of unevenly spaced frames, or an export "
                                            "larger than the import limit"}})
def export_recording(recording_id: RecordId, session: SessionDep, user: Clinician,
                     format: Annotated[FormatName, Query()] = "csv") -> Response:
    """The recording as a file in ``format``; ssff needs evenly spaced frames (else 409), and
    an export larger than the import limit is refused (409) rather than sent."""
    record = recording_for(session, user, recording_id)
    try:
        content = formats.serialise([record.to_sequence()], format)
    except EpgFormatError as error:
        raise HTTPException(status_code=409, detail=str(error)) from None
    if len(content) > MAX_UPLOAD_BYTES:
        # Only metadata can make it so (frames are bounded): refuse what could not come back.
        raise HTTPException(status_code=409, detail=(
            f"the {format} export is {len(content) / 2**20:.1f} MiB, more than the "
            f"{MAX_UPLOAD_BYTES // 2**20} MiB an import takes; export as ssff, which keeps "
            f"only the name, label, utterance, word, start_s and end_s"))
    stem = "".join(ch if ch.isalnum() or ch in "-_." else "_" for ch in record.name)[:80]
    filename = f"{stem or 'recording'}{formats.EXTENSIONS[format]}"
    return Response(content, media_type=formats.MEDIA_TYPES[format],
                    headers={"Content-Disposition": f'attachment; filename="{filename}"'})


@router.delete("/epg/recordings/{recording_id}", operation_id="deleteRecording",
               status_code=status.HTTP_204_NO_CONTENT, responses=PRECONDITION)
def delete_recording(
    recording_id: RecordId, session: SessionDep, user: Clinician,
    if_match: Annotated[str | None, Header(description="the ETag last read: delete only while "
                                                       "the recording is still at it")] = None,
) -> Response:
    record = recording_for(session, user, recording_id)
    check_uploader(user, record)
    check_if_match(if_match, KIND, record, f"recording {recording_id}")
    session.delete(record)
    commit_versioned(session, KIND, record, f"recording {recording_id}")
    return Response(status_code=status.HTTP_204_NO_CONTENT)
