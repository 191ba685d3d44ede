"""Lessons: create, read, replace, update and delete, list, and import and export as JSON.

A lesson's body is the published lesson format (``glasshead.lessons.schema``, served at
``GET /lessons/schema``); its items are validated whole, so an unknown phoneme symbol is a 422
naming the item and the symbol. An export is exactly what an import takes, so a lesson moves
between servers unchanged. Writes take If-Match (412 when stale).

Every signed-in adult reads every lesson; a child reads only the lessons assigned to them or to
their class (another is a 404). Authors and admins make lessons; a lesson is changed only by
its author or an admin (403 otherwise). The starter lessons have no owner: admins change them,
and an author who wants another version exports one and imports it as their own.
"""

from datetime import datetime
from typing import Annotated

from fastapi import APIRouter, Depends, Response, status
from pydantic import BaseModel, ConfigDict, Field
from sqlalchemy import select
from sqlalchemy.orm import Session

from glasshead.api.auth import ADULTS, Person, SignedInUser, allow, require_role
from glasshead.api.etags import PRECONDITION, check_if_match, set_etag
from glasshead.api.lookups import Offset, RecordId
from glasshead.api.ownership import check_owner, lesson_for, visible_lessons
from glasshead.api.records import (
    IfMatch,
    Limit,
    apply_patch,
    conditional_write,
    delete_record,
    get_or_404,
    page,
)
from glasshead.lessons.schema import (
    MAX_ITEMS,
    Description,
    Item,
    LanguageTag,
    LessonContent,
    Text,
    json_schema,
)
from glasshead.store.lessons import Lesson
from glasshead.store.session import SessionDep
from glasshead.store.users import User

router = APIRouter(tags=["lessons"])

KIND = "lesson"
#: Who writes lessons.
Author = Annotated[User, Depends(require_role("author", "admin"))]
#: Who reads them: any adult, and a child (their assigned lessons).
Reader = Annotated[Person, Depends(allow(*ADULTS, "child"))]


class LessonPatch(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={"examples": [
        {"title": "/s/ and /ʃ/, slowly", "items": [
            {"target": {"kind": "phoneme", "text": "s"}, "speed": 0.5},
            {"target": {"kind": "word", "text": "ship"}, "speed": 0.5}]}]})
    title: Text | None = None
    language: LanguageTag | None = None
    description: Description | None = None
    items: Annotated[list[Item], Field(min_length=1, max_length=MAX_ITEMS)] | None = None


class LessonOut(LessonContent):
    model_config = ConfigDict(from_attributes=True, extra="ignore")
    id: int
    created_at: datetime
    updated_at: datetime


class LessonSummary(BaseModel):
    model_config = ConfigDict(from_attributes=True)
    id: int
    title: str
    language: str
    description: str
    n_items: int
    updated_at: datetime


class LessonList(BaseModel):
    lessons: list[LessonSummary]
    total: int


def _out(record: Lesson) -> LessonOut:
    return LessonOut(id=record.id, title=record.title, language=record.language,
                     description=record.description, items=record.items,
                     created_at=record.created_at, updated_at=record.updated_at)


def _items(lesson: LessonContent | LessonPatch) -> list[dict]:
    return [item.model_dump(mode="json") for item in lesson.items]


def _create(lesson: LessonContent, session: Session, user: User,
            response: Response) -> LessonOut:
    record = Lesson(title=lesson.title, language=lesson.language,
                    description=lesson.description, items=_items(lesson), owner_id=user.id)
    session.add(record)
    session.commit()
    set_etag(response, KIND, record)
    return _out(record)


@router.post("/lessons", operation_id="createLesson", status_code=status.HTTP_201_CREATED,
             response_model=LessonOut)
def create_lesson(lesson: LessonContent, session: SessionDep, user: Author,
                  response: Response) -> LessonOut:
    """A new lesson, owned by the caller."""
    return _create(lesson, session, user, response)


@router.get("/lessons", operation_id="listLessons", response_model=LessonList)
def list_lessons(session: SessionDep, person: Reader, offset: Offset = 0,
                 limit: Limit = 100) -> LessonList:
    """Lessons in id order (the order they were made), without their items; a child's list
    has only the lessons assigned to them or to their class."""
    records, total = page(session, visible_lessons(select(Lesson), person), Lesson.id, offset,
                          limit)
    return LessonList(total=total, lessons=[
        LessonSummary(id=r.id, title=r.title, language=r.language, description=r.description,
                      n_items=len(r.items), updated_at=r.updated_at) for r in records])


@router.get("/lessons/schema", operation_id="getLessonSchema")
def get_lesson_schema() -> dict:
    """The JSON Schema of a lesson as imported and exported (docs/lesson.schema.json)."""
    return json_schema()


@router.post("/lessons/import", operation_id="importLesson",
             status_code=status.HTTP_201_CREATED, response_model=LessonOut)
def import_lesson(lesson: LessonContent, session: SessionDep, user: Author,
                  response: Response) -> LessonOut:
    """A lesson as exported (by this server or another): stored as a new lesson, the caller's."""
    return _create(lesson, session, user, response)


@router.get("/lessons/{lesson_id}", operation_id="getLesson", response_model=LessonOut)
def get_lesson(lesson_id: RecordId, session: SessionDep, person: Reader,
               response: Response) -> LessonOut:
    record = lesson_for(session, person, lesson_id)
    set_etag(response, KIND, record)
    return _out(record)


@router.get("/lessons/{lesson_id}/export", operation_id="exportLesson",
            response_model=LessonContent)
def export_lesson(lesson_id: RecordId, session: SessionDep, user: SignedInUser,
                  response: Response) -> LessonContent:
    """The lesson in the published format, as a download that ``POST /lessons/import`` takes."""
    record = get_or_404(session, Lesson, lesson_id, KIND)
    set_etag(response, KIND, record)
    response.headers["Content-Disposition"] = f'attachment; filename="lesson-{lesson_id}.json"'
    return LessonContent(title=record.title, language=record.language,
                         description=record.description, items=record.items)


@router.put("/lessons/{lesson_id}", operation_id="replaceLesson", response_model=LessonOut,
            responses=PRECONDITION)
def replace_lesson(lesson_id: RecordId, lesson: LessonContent, session: SessionDep,
                   user: Author, response: Response, if_match: IfMatch = None) -> LessonOut:
    record = get_or_404(session, Lesson, lesson_id, KIND)
    check_owner(user, record, KIND)
    check_if_match(if_match, KIND, record, f"lesson {lesson_id}")
    record.title, record.language = lesson.title, lesson.language
    record.description, record.items = lesson.description, _items(lesson)
    conditional_write(session, response, KIND, record, f"lesson {lesson_id}")
    return _out(record)


@router.patch("/lessons/{lesson_id}", operation_id="updateLesson", response_model=LessonOut,
              responses=PRECONDITION)
def update_lesson(lesson_id: RecordId, patch: LessonPatch, session: SessionDep, user: Author,
                  response: Response, if_match: IfMatch = None) -> LessonOut:
    record = get_or_404(session, Lesson, lesson_id, KIND)
    check_owner(user, record, KIND)
    check_if_match(if_match, KIND, record, f"lesson {lesson_id}")
    apply_patch(record, patch)
    if patch.items is not None:
        record.items = _items(patch)
    conditional_write(session, response, KIND, record, f"lesson {lesson_id}")
    return _out(record)


@router.delete("/lessons/{lesson_id}", operation_id="deleteLesson",
               status_code=status.HTTP_204_NO_CONTENT, responses=PRECONDITION)
def delete_lesson(lesson_id: RecordId, session: SessionDep, user: Author,
                  if_match: IfMatch = None) -> Response:
    """The lesson, its assignments and its practice records."""
    record = get_or_404(session, Lesson, lesson_id, KIND)
    check_owner(user, record, KIND)
    delete_record(session, KIND, record, f"lesson {lesson_id}", if_match)
    return Response(status_code=status.HTTP_204_NO_CONTENT)
