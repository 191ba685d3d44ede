"""One child's records as a whole: the practice history as CSV for the adult who follows the
child, and, for an admin, everything stored about the child as one JSON document, and its
deletion.

A school or clinic must be able to answer two requests about a child: "show me everything you
keep about them" and "forget them". ``GET /children/{id}/export`` gathers the child, their
class, the assignments that name them or their class, their practice, their EPG recordings
with every frame, the recordings of their attempts (each WAV file in base64) with every change
of the switch that let them be kept, and that sign-in tokens existed (when made, until when,
whether revoked; never a token or its hash). ``DELETE /children/{id}/data`` removes the child
with all of that in one transaction: recordings are deleted explicitly, never left behind as
reference recordings, and the import answers kept for retries that list them go too. The CSV is
for the adults who follow the child (the owner of the child's class, or an admin); another
class's child is a 404, so that nobody learns that it exists.
"""

import base64
import csv
import io
from datetime import datetime
from typing import Annotated

from fastapi import APIRouter, Depends, HTTPException, Response
from pydantic import BaseModel
from sqlalchemy import delete, or_, select
from sqlalchemy.orm import Session, undefer

from glasshead.api.auth import FORBIDDEN, UNAUTHENTICATED, AdminUser, Person, require_role
from glasshead.api.error_responses import Responses
from glasshead.api.etags import PRECONDITION, check_if_match, etag
from glasshead.api.lookups import RecordId
from glasshead.api.ownership import child_of
from glasshead.api.people import ChildOut
from glasshead.api.records import IfMatch
from glasshead.epg.sequence import rows_to_strings
from glasshead.store.idempotency_keys import IdempotencyKey
from glasshead.store.lessons import Assignment, Child, Lesson, PracticeRecord, SchoolClass
from glasshead.store.models import EpgRecording
from glasshead.store.practice_audio import AudioRecordingSwitch, PracticeAudio, switch_history
from glasshead.store.session import SessionDep
from glasshead.store.users import ChildToken, User

router = APIRouter(tags=["child records"])

#: The version of the export's layout, carried in it (2: the attempts' audio and its switch).
EXPORT_VERSION = 2
#: The attempt's measures, each a column of the practice CSV (empty when not measured).
MEASURE_COLUMNS = ("f0", "f1", "f2", "f3", "f3_minus_f2", "centroid", "duration_s", "verdict",
                   "target_vowel")
#: The columns of the practice CSV, in order.
CSV_COLUMNS = ("practice_id", "child_id", "child", "lesson_id", "lesson", "item_index",
               "target_kind", "target", "practised_at", "replays", "rating", "rated_by",
               *(f"measured_{name}" for name in MEASURE_COLUMNS))
#: Characters that make a spreadsheet read a cell as a formula (OWASP, "CSV injection").
FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")
#: The operation whose kept answers can list a child's recordings (routes/recordings.py).
RECORDING_IMPORT = "createRecordings"

Follower = Annotated[User, Depends(require_role("teacher", "clinician", "admin"))]
NOT_FOUND: Responses = {
    404: {"description": "no such child, or a child of a class that is not yours"}}


class TokenTrace(BaseModel):
    """That a sign-in token existed, without the token or its hash."""

    created_at: datetime
    expires_at: datetime
    revoked_at: datetime | None


class ChildExport(BaseModel):
    """Everything stored about one child."""

    export_version: int
    exported_at: datetime
    child: ChildOut
    school_class: dict
    assignments: list[dict]
    practice: list[dict]
    recordings: list[dict]
    audio: list[dict]
    audio_recording_switches: list[dict]
    tokens: list[TokenTrace]


class DeletedCounts(BaseModel):
    """How many rows of each kind the deletion removed."""

    child_id: int
    children: int
    practice_records: int
    assignments: int
    recordings: int
    practice_audio: int
    audio_recording_switches: int
    child_tokens: int
    idempotency_keys: int


def _cell(value) -> str:
    text = "" if value is None else str(value)
    return "'" + text if text.startswith(FORMULA_STARTS) else text


def _target(lesson: Lesson | None, index: int) -> tuple[str, str]:
    if lesson is None or not 0 <= index < len(lesson.items):
        return "", ""
    target = lesson.items[index].get("target", {})
    return target.get("kind", ""), target.get("text", "")


def practice_rows(session: Session, child: Child) -> list[list[str]]:
    """The child's practice records, oldest first, one CSV row each (``CSV_COLUMNS``)."""
    records = session.scalars(select(PracticeRecord).where(PracticeRecord.child_id == child.id)
                              .order_by(PracticeRecord.practised_at, PracticeRecord.id))
    lessons: dict[int, Lesson | None] = {}
    rows = []
    for record in records:
        if record.lesson_id not in lessons:
            lessons[record.lesson_id] = session.get(Lesson, record.lesson_id)
        lesson = lessons[record.lesson_id]
        kind, text = _target(lesson, record.item_index)
        rows.append([_cell(v) for v in (
            record.id, child.id, child.display_name, record.lesson_id,
            lesson.title if lesson else "", record.item_index, kind, text,
            record.practised_at.isoformat().replace("+00:00", "Z"), record.replays,
            record.rating, record.rated_by,
            *((record.measures or {}).get(name) for name in MEASURE_COLUMNS))])
    return rows


@router.get("/children/{child_id}/practice.csv", operation_id="exportChildPractice",
            response_class=Response,
            responses={200: {"content": {"text/csv": {}}}, **UNAUTHENTICATED, **FORBIDDEN,
                       **NOT_FOUND})
def export_child_practice(child_id: RecordId, session: SessionDep, user: Follower) -> Response:
    """The child's practice history as CSV (UTF-8, a header row, oldest first): the item's
    target, when, replays and rating, for a spreadsheet or a report."""
    child = child_of(session, Person(user=user), child_id)
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\r\n")
    writer.writerow(CSV_COLUMNS)
    writer.writerows(practice_rows(session, child))
    return Response(out.getvalue(), media_type="text/csv; charset=utf-8", headers={
        "Content-Disposition": f'attachment; filename="child-{child_id}-practice.csv"'})


def _child_or_404(session: Session, child_id: int) -> Child:
    child = session.get(Child, child_id)
    if child is None:
        raise HTTPException(status_code=404, detail=f"no child with id {child_id}")
    return child


def _columns(record) -> dict:
    """A row's columns as JSON values (bytes left out: recordings carry their frames apart)."""
    values = {}
    for column in record.__table__.columns:
        value = getattr(record, column.key)
        if isinstance(value, bytes):
            continue
        values[column.key] = value.isoformat() if isinstance(value, datetime) else value
    return values


def _recordings(session: Session, child: Child) -> list[EpgRecording]:
    return list(session.scalars(select(EpgRecording).where(EpgRecording.child_id == child.id)
                                .order_by(EpgRecording.id)))


def _recording_json(record: EpgRecording) -> dict:
    sequence = record.to_sequence()
    return {**_columns(record), "export_url": f"/api/v1/epg/recordings/{record.id}/export",
            "t_s": sequence.t_s.tolist(),
            "frames": [rows_to_strings(frame) for frame in sequence.frames]}


def _audio_json(audio: PracticeAudio) -> dict:
    return {**_columns(audio), "wav_base64": base64.b64encode(audio.wav).decode("ascii"),
            "audio_url": f"/api/v1/practice/{audio.practice_id}/audio"}


def _audio(session: Session, child: Child) -> list[PracticeAudio]:
    return list(session.scalars(select(PracticeAudio).where(PracticeAudio.child_id == child.id)
                                .options(undefer(PracticeAudio.wav)).order_by(PracticeAudio.id)))


def _assignments(session: Session, child: Child) -> list[Assignment]:
    return list(session.scalars(select(Assignment).where(or_(
        Assignment.child_id == child.id, Assignment.class_id == child.class_id)
    ).order_by(Assignment.id)))


@router.get("/children/{child_id}/export", operation_id="exportChildData",
            response_model=ChildExport,
            responses={**UNAUTHENTICATED, **FORBIDDEN, 404: {"description": "no such child"}})
def export_child_data(child_id: RecordId, session: SessionDep, admin: AdminUser,
                      response: Response) -> ChildExport:
    """Everything stored about one child, as one JSON document: the child, their class,
    the assignments that reach them (theirs and their class's), every practice record, every
    EPG recording with its frames, every kept recording of an attempt (its WAV in base64) and
    every change of the switch that kept them, and the sign-in tokens they were given (times
    only)."""
    child = _child_or_404(session, child_id)
    practice = session.scalars(select(PracticeRecord).where(PracticeRecord.child_id == child.id)
                               .order_by(PracticeRecord.practised_at, PracticeRecord.id))
    tokens = session.scalars(select(ChildToken).where(ChildToken.child_id == child.id)
                             .order_by(ChildToken.id))
    response.headers["ETag"] = etag("child", child)
    response.headers["Content-Disposition"] = f'attachment; filename="child-{child_id}.json"'
    return ChildExport(
        export_version=EXPORT_VERSION, exported_at=datetime.now().astimezone(),
        child=ChildOut.model_validate(child),
        school_class=_columns(session.get(SchoolClass, child.class_id)),
        assignments=[_columns(a) for a in _assignments(session, child)],
        practice=[_columns(p) for p in practice],
        recordings=[_recording_json(r) for r in _recordings(session, child)],
        audio=[_audio_json(a) for a in _audio(session, child)],
        audio_recording_switches=[_columns(c) for c in switch_history(session, child.id,
                                                                     newest_first=False)],
        tokens=[TokenTrace(created_at=t.created_at, expires_at=t.expires_at,
                           revoked_at=t.revoked_at) for t in tokens])


def _kept_answers_listing(session: Session, recording_ids: set[int]) -> list[IdempotencyKey]:
    """The kept import answers (for retries) that list any of ``recording_ids``."""
    if not recording_ids:
        return []
    kept = session.scalars(select(IdempotencyKey)
                           .where(IdempotencyKey.operation == RECORDING_IMPORT))
    return [row for row in kept
            if any(r.get("id") in recording_ids
                   for r in (row.response or {}).get("recordings", []))]


@router.delete("/children/{child_id}/data", operation_id="deleteChildData",
               response_model=DeletedCounts,
               responses={**UNAUTHENTICATED, **FORBIDDEN, **PRECONDITION,
                          404: {"description": "no such child"}})
def delete_child_data(child_id: RecordId, session: SessionDep, admin: AdminUser,
                      if_match: IfMatch = None) -> DeletedCounts:
    """Forget a child: their recordings, the audio of their attempts and its switch, practice,
    own assignments, sign-in tokens and the child, in one transaction; answers how many rows
    of each went. ``If-Match`` takes the
    child's ETag (``GET /children/{id}``)."""
    child = _child_or_404(session, child_id)
    check_if_match(if_match, "child", child, f"child {child_id}")
    recording_ids = set(session.scalars(select(EpgRecording.id)
                                        .where(EpgRecording.child_id == child_id)))
    kept = _kept_answers_listing(session, recording_ids)
    for row in kept:
        session.delete(row)
    # Each table explicitly, not by the children's ON DELETE CASCADE: the counts are exact, and
    # nothing depends on a database enforcing its foreign keys.
    counts = DeletedCounts(
        child_id=child_id, children=1, idempotency_keys=len(kept), recordings=session.execute(
            delete(EpgRecording).where(EpgRecording.child_id == child_id)).rowcount,
        practice_audio=session.execute(
            delete(PracticeAudio).where(PracticeAudio.child_id == child_id)).rowcount,
        audio_recording_switches=session.execute(
            delete(AudioRecordingSwitch)
            .where(AudioRecordingSwitch.child_id == child_id)).rowcount,
        practice_records=session.execute(
            delete(PracticeRecord).where(PracticeRecord.child_id == child_id)).rowcount,
        assignments=session.execute(
            delete(Assignment).where(Assignment.child_id == child_id)).rowcount,
        child_tokens=session.execute(
            delete(ChildToken).where(ChildToken.child_id == child_id)).rowcount)
    session.flush()
    session.delete(child)
    session.commit()
    return counts

