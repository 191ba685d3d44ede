"""Assignments of lessons to classes or single children, and the practice records of children.

An assignment names its lesson and exactly one of a class or a child (422 otherwise). A practice
record is one go at one item of a lesson: the child, the lesson and the item's position in it,
the time, how many times the child replayed it, a rating (1 not yet, 2 nearly, 3 got it)
with who gave it (the child or an adult), and what the learner's voice measured
(``api/practice_measures.py``; numbers, never the audio: the recording is kept apart, only while
a clinician's switch for the child is on, ``practice_audio.py``). A record names an item the lesson
has (422 naming ``item_index`` otherwise). Writes take If-Match (412 when stale).

Assignments and practice records are those of a class's owner (the teacher or clinician who
made it) and of admins: another's is a 404, and a body naming another's class or child is a
422, as for one that does not exist (``api/ownership.py``). A child signed in with their join
code reads their own assignments and practice, and writes practice only for themselves and
only on a lesson assigned to them.
"""

from datetime import datetime
from typing import Annotated, Literal

from fastapi import APIRouter, Depends, HTTPException, Response, status
from pydantic import AwareDatetime, BaseModel, ConfigDict, Field, model_validator
from sqlalchemy import select
from sqlalchemy.orm import Session

from glasshead.api.auth import Person, allow
from glasshead.api.etags import PRECONDITION, check_if_match, set_etag
from glasshead.api.lookups import Offset, RecordId
from glasshead.api.ownership import (
    assignment_for,
    check_child_reference,
    check_class_reference,
    lesson_for,
    practice_for,
    visible_assignments,
    visible_practice,
)
from glasshead.api.practice_measures import AttemptMeasures
from glasshead.api.records import (
    BodyId,
    IdFilter,
    IfMatch,
    Limit,
    apply_patch,
    conditional_write,
    delete_record,
    page,
)
from glasshead.lessons.schema import MAX_ITEMS
from glasshead.store.base import utc_now
from glasshead.store.lessons import Assignment, Lesson, PracticeRecord
from glasshead.store.session import SessionDep

router = APIRouter(tags=["practice"])

ASSIGNMENT, PRACTICE = "assignment", "practice"
MAX_REPLAYS = 10_000
ItemIndex = Annotated[int, Field(ge=0, lt=MAX_ITEMS, description="the item's position in the "
                                                                 "lesson, from 0")]
Replays = Annotated[int, Field(ge=0, le=MAX_REPLAYS)]
Rating = Annotated[int, Field(ge=1, le=3, description="1 not yet, 2 nearly, 3 got it")]
RatedBy = Literal["child", "adult"]
#: Who keeps classes, and so their assignments and practice.
Keeper = Annotated[Person, Depends(allow("teacher", "clinician", "admin"))]
#: A class's keeper, or a child for themselves.
KeeperOrChild = Annotated[Person, Depends(allow("teacher", "clinician", "admin", "child"))]


class AssignmentIn(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={
        "examples": [{"lesson_id": 1, "class_id": 1}, {"lesson_id": 2, "child_id": 1}]})
    lesson_id: BodyId
    class_id: BodyId | None = None
    child_id: BodyId | None = None

    @model_validator(mode="after")
    def _one_assignee(self):
        if (self.class_id is None) == (self.child_id is None):
            raise ValueError("give exactly one of class_id and child_id")
        return self


class AssignmentOut(BaseModel):
    model_config = ConfigDict(from_attributes=True)
    id: int
    lesson_id: int
    class_id: int | None
    child_id: int | None
    created_at: datetime
    updated_at: datetime


class AssignmentList(BaseModel):
    assignments: list[AssignmentOut]
    total: int


class PracticeIn(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={
        "examples": [{"child_id": 1, "lesson_id": 1, "item_index": 2, "replays": 1,
                      "rating": 3, "rated_by": "child"}]})
    child_id: BodyId
    lesson_id: BodyId
    item_index: ItemIndex
    practised_at: AwareDatetime | None = Field(None, description="when; now if left out")
    replays: Replays = 0
    rating: Rating | None = None
    rated_by: RatedBy | None = None
    measures: AttemptMeasures | None = Field(None, description="what the learner's voice "
                                                               "measured; never the audio")

    @model_validator(mode="after")
    def _rating_and_rater(self):
        if (self.rating is None) != (self.rated_by is None):
            raise ValueError("rating and rated_by go together: give both or neither")
        return self


class PracticePatch(BaseModel):
    """A later rating (by an adult, say) or a corrected replay count."""

    model_config = ConfigDict(extra="forbid", json_schema_extra={
        "examples": [{"rating": 2, "rated_by": "adult"}]})
    replays: Replays | None = None
    rating: Rating | None = None
    rated_by: RatedBy | None = None

    @model_validator(mode="after")
    def _rating_and_rater(self):
        if ("rating" in self.model_fields_set) != ("rated_by" in self.model_fields_set):
            raise ValueError("rating and rated_by go together: give both or neither")
        return self


class PracticeOut(BaseModel):
    model_config = ConfigDict(from_attributes=True)
    id: int
    child_id: int
    lesson_id: int
    item_index: int
    practised_at: datetime
    replays: int
    rating: int | None
    rated_by: str | None
    measures: AttemptMeasures | None
    has_audio: bool = Field(description="whether the attempt's recording is kept "
                                         "(GET /practice/{id}/audio)")
    created_at: datetime
    updated_at: datetime


class PracticeList(BaseModel):
    records: list[PracticeOut]
    total: int


def _check_assignment(session: Session, person: Person, body: AssignmentIn) -> None:
    if session.get(Lesson, body.lesson_id) is None:
        raise HTTPException(status_code=422, detail=f"body.lesson_id: no lesson with id "
                                                    f"{body.lesson_id}")
    check_class_reference(session, person.user, body.class_id)
    check_child_reference(session, person, body.child_id)


def _check_practice(session: Session, person: Person, body: PracticeIn) -> None:
    if person.child is not None and body.child_id != person.child.id:
        raise HTTPException(status_code=403, detail="a child records only their own practice: "
                                                    f"body.child_id must be {person.child.id}")
    check_child_reference(session, person, body.child_id)
    try:
        lesson = lesson_for(session, person, body.lesson_id)
    except HTTPException:
        raise HTTPException(status_code=422, detail=f"body.lesson_id: no lesson with id "
                                                    f"{body.lesson_id}") from None
    if body.item_index >= len(lesson.items):
        raise HTTPException(status_code=422, detail=f"body.item_index: lesson {lesson.id} has "
                                                    f"{len(lesson.items)} items, numbered from 0")


@router.post("/assignments", operation_id="createAssignment",
             status_code=status.HTTP_201_CREATED, response_model=AssignmentOut)
def create_assignment(body: AssignmentIn, session: SessionDep, person: Keeper,
                      response: Response) -> Assignment:
    """A lesson given to one of the caller's classes or to a child in one of them."""
    _check_assignment(session, person, body)
    record = Assignment(**body.model_dump())
    session.add(record)
    session.commit()
    set_etag(response, ASSIGNMENT, record)
    return record


@router.get("/assignments", operation_id="listAssignments", response_model=AssignmentList)
def list_assignments(session: SessionDep, person: KeeperOrChild, lesson_id: IdFilter = None,
                     class_id: IdFilter = None, child_id: IdFilter = None, offset: Offset = 0,
                     limit: Limit = 100) -> AssignmentList:
    """Assignments of the caller's classes (a child's: their own and their class's) in id
    order, filtered by lesson, class or child."""
    query = visible_assignments(select(Assignment), person)
    for column, value in ((Assignment.lesson_id, lesson_id), (Assignment.class_id, class_id),
                          (Assignment.child_id, child_id)):
        if value is not None:
            query = query.where(column == value)
    records, total = page(session, query, Assignment.id, offset, limit)
    return AssignmentList(assignments=[AssignmentOut.model_validate(r) for r in records],
                          total=total)


@router.get("/assignments/{assignment_id}", operation_id="getAssignment",
            response_model=AssignmentOut)
def get_assignment(assignment_id: RecordId, session: SessionDep, person: KeeperOrChild,
                   response: Response) -> Assignment:
    record = assignment_for(session, person, assignment_id)
    set_etag(response, ASSIGNMENT, record)
    return record


@router.put("/assignments/{assignment_id}", operation_id="replaceAssignment",
            response_model=AssignmentOut, responses=PRECONDITION)
def replace_assignment(assignment_id: RecordId, body: AssignmentIn, session: SessionDep,
                       person: Keeper, response: Response,
                       if_match: IfMatch = None) -> Assignment:
    record = assignment_for(session, person, assignment_id)
    check_if_match(if_match, ASSIGNMENT, record, f"assignment {assignment_id}")
    _check_assignment(session, person, body)
    record.lesson_id, record.class_id, record.child_id = (body.lesson_id, body.class_id,
                                                          body.child_id)
    conditional_write(session, response, ASSIGNMENT, record, f"assignment {assignment_id}")
    return record


@router.delete("/assignments/{assignment_id}", operation_id="deleteAssignment",
               status_code=status.HTTP_204_NO_CONTENT, responses=PRECONDITION)
def delete_assignment(assignment_id: RecordId, session: SessionDep, person: Keeper,
                      if_match: IfMatch = None) -> Response:
    record = assignment_for(session, person, assignment_id)
    delete_record(session, ASSIGNMENT, record, f"assignment {assignment_id}", if_match)
    return Response(status_code=status.HTTP_204_NO_CONTENT)


@router.post("/practice", operation_id="createPracticeRecord",
             status_code=status.HTTP_201_CREATED, response_model=PracticeOut)
def create_practice_record(body: PracticeIn, session: SessionDep, person: KeeperOrChild,
                           response: Response) -> PracticeRecord:
    """A go at an item: by a child for themselves, or by the keeper of the child's class."""
    _check_practice(session, person, body)
    record = PracticeRecord(**body.model_dump(exclude={"practised_at", "measures"}),
                            practised_at=body.practised_at or utc_now(),
                            measures=body.measures.model_dump(exclude_none=True)
                            if body.measures else None)
    session.add(record)
    session.commit()
    set_etag(response, PRACTICE, record)
    return record


@router.get("/practice", operation_id="listPracticeRecords", response_model=PracticeList)
def list_practice_records(session: SessionDep, person: KeeperOrChild, child_id: IdFilter = None,
                          lesson_id: IdFilter = None, offset: Offset = 0,
                          limit: Limit = 100) -> PracticeList:
    """Practice records of the children of the caller's classes (a child's: their own),
    newest first, of one child or one lesson."""
    query = visible_practice(select(PracticeRecord), person)
    if child_id is not None:
        query = query.where(PracticeRecord.child_id == child_id)
    if lesson_id is not None:
        query = query.where(PracticeRecord.lesson_id == lesson_id)
    records, total = page(session, query,
                          (PracticeRecord.practised_at.desc(), PracticeRecord.id.desc()),
                          offset, limit)
    return PracticeList(records=[PracticeOut.model_validate(r) for r in records], total=total)


@router.get("/practice/{record_id}", operation_id="getPracticeRecord",
            response_model=PracticeOut)
def get_practice_record(record_id: RecordId, session: SessionDep, person: KeeperOrChild,
                        response: Response) -> PracticeRecord:
    record = practice_for(session, person, record_id)
    set_etag(response, PRACTICE, record)
    return record


@router.patch("/practice/{record_id}", operation_id="updatePracticeRecord",
              response_model=PracticeOut, responses=PRECONDITION)
def update_practice_record(record_id: RecordId, patch: PracticePatch, session: SessionDep,
                           person: KeeperOrChild, response: Response,
                           if_match: IfMatch = None) -> PracticeRecord:
    record = practice_for(session, person, record_id)
    check_if_match(if_match, PRACTICE, record, f"practice record {record_id}")
    apply_patch(record, patch)
    conditional_write(session, response, PRACTICE, record, f"practice record {record_id}")
    return record


@router.delete("/practice/{record_id}", operation_id="deletePracticeRecord",
               status_code=status.HTTP_204_NO_CONTENT, responses=PRECONDITION)
def delete_practice_record(record_id: RecordId, session: SessionDep, person: Keeper,
                           if_match: IfMatch = None) -> Response:
    record = practice_for(session, person, record_id)
    delete_record(session, PRACTICE, record, f"practice record {record_id}", if_match)
    return Response(status_code=status.HTTP_204_NO_CONTENT)
