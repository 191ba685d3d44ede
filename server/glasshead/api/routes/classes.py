"""Classes (or a clinician's caseload) and the children in them.

A class gets a join code when it is made: six characters from an alphabet without look-alikes
(no 0/O, 1/I/L, 2/Z, 5/S, 8/B), unique, which children type to join; it never changes with the
class's name. Children are pseudonymous: a display name and one of a fixed list of avatars
(``GET /children/avatars``), nothing that names them. Writes take If-Match (412 when stale);
deleting a class deletes its children and their practice.

A class is its owner's: the teacher, clinician or admin who made it. Only they, the teachers and
clinicians they share it with (its staff, ``routes/class_staff.py``) and admins list, read and
change it and its children; to anyone else another's class or child is a 404
(``api/ownership.py``). Staff do not delete the class (a 403).
"""

import secrets
from datetime import datetime
from typing import Annotated, Literal

from fastapi import APIRouter, Depends, Query, Response, status
from pydantic import BaseModel, ConfigDict, StringConstraints
from sqlalchemy import select
from sqlalchemy.exc import IntegrityError

from glasshead.api.auth import Person, require_role
from glasshead.api.etags import PRECONDITION, check_if_match, set_etag
from glasshead.api.lookups import Offset, RecordId
from glasshead.api.ownership import (
    check_class_owner,
    check_class_reference,
    child_of,
    class_of,
    visible_children,
    visible_classes,
)
from glasshead.api.people import ChildOut
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
from glasshead.store.lessons import (
    AVATARS,
    JOIN_CODE_ALPHABET,
    JOIN_CODE_LENGTH,
    Child,
    SchoolClass,
)
from glasshead.store.session import SessionDep
from glasshead.store.users import User

router = APIRouter(tags=["classes"])

CLASS, CHILD = "class", "child"
#: Tries at a fresh join code before giving up (25**6 codes: a clash is already rare).
JOIN_CODE_TRIES = 8

ClassName = Annotated[str, StringConstraints(strip_whitespace=True, min_length=1, max_length=120)]
DisplayName = Annotated[str, StringConstraints(strip_whitespace=True, min_length=1,
                                               max_length=40)]
Avatar = Literal[AVATARS]  # type: ignore[valid-type]
#: Who keeps classes and children: teachers (a class), clinicians (a caseload) and admins.
Keeper = Annotated[User, Depends(require_role("teacher", "clinician", "admin"))]
JoinCode = Annotated[str | None, Query(description="only the class with this join code (any "
                                                   "case)", max_length=40)]


class ClassIn(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={"examples": [{"name": "Year 2"}]})
    name: ClassName


class ClassPatch(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={"examples": [{"name": "Year 3"}]})
    name: ClassName | None = None


class ClassOut(BaseModel):
    model_config = ConfigDict(from_attributes=True)
    id: int
    name: str
    join_code: str
    created_at: datetime
    updated_at: datetime


class ClassList(BaseModel):
    classes: list[ClassOut]
    total: int


class ChildIn(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={
        "examples": [{"class_id": 1, "display_name": "Ada", "avatar": "owl"}]})
    class_id: BodyId
    display_name: DisplayName
    avatar: Avatar


class ChildPatch(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={"examples": [
        {"display_name": "Ada", "avatar": "fox"}]})
    class_id: BodyId | None = None
    display_name: DisplayName | None = None
    avatar: Avatar | None = None


class ChildList(BaseModel):
    children: list[ChildOut]
    total: int


def new_join_code() -> str:
    return "".join(secrets.choice(JOIN_CODE_ALPHABET) for _ in range(JOIN_CODE_LENGTH))


@router.post("/classes", operation_id="createClass", status_code=status.HTTP_201_CREATED,
             response_model=ClassOut)
def create_class(body: ClassIn, session: SessionDep, user: Keeper,
                 response: Response) -> SchoolClass:
    """A new class owned by the caller, with a fresh join code."""
    for _ in range(JOIN_CODE_TRIES):
        record = SchoolClass(name=body.name, join_code=new_join_code(), owner_id=user.id)
        session.add(record)
        try:
            session.commit()
            break
        except IntegrityError:  # the code is taken: draw another
            session.rollback()
    else:
        raise RuntimeError(f"no free join code in {JOIN_CODE_TRIES} tries")
    set_etag(response, CLASS, record)
    return record


@router.get("/classes", operation_id="listClasses", response_model=ClassList)
def list_classes(session: SessionDep, user: Keeper, join_code: JoinCode = None,
                 offset: Offset = 0, limit: Limit = 100) -> ClassList:
    """The caller's classes, their own and those shared with them (an admin's: all) in id
    order; ``join_code`` finds one by its code (a child finds theirs with the open POST
    /auth/class-roster)."""
    query = visible_classes(select(SchoolClass), user)
    if join_code is not None:
        query = query.where(SchoolClass.join_code == join_code.strip().upper())
    records, total = page(session, query, SchoolClass.id, offset, limit)
    return ClassList(classes=[ClassOut.model_validate(r) for r in records], total=total)


@router.get("/classes/{class_id}", operation_id="getClass", response_model=ClassOut)
def get_class(class_id: RecordId, session: SessionDep, user: Keeper,
              response: Response) -> SchoolClass:
    record = class_of(session, user, class_id)
    set_etag(response, CLASS, record)
    return record


@router.put("/classes/{class_id}", operation_id="replaceClass", response_model=ClassOut,
            responses=PRECONDITION)
def replace_class(class_id: RecordId, body: ClassIn, session: SessionDep, user: Keeper,
                  response: Response, if_match: IfMatch = None) -> SchoolClass:
    """A new name; the join code stays."""
    record = class_of(session, user, class_id)
    check_if_match(if_match, CLASS, record, f"class {class_id}")
    record.name = body.name
    conditional_write(session, response, CLASS, record, f"class {class_id}")
    return record


@router.patch("/classes/{class_id}", operation_id="updateClass", response_model=ClassOut,
              responses=PRECONDITION)
def update_class(class_id: RecordId, patch: ClassPatch, session: SessionDep, user: Keeper,
                 response: Response, if_match: IfMatch = None) -> SchoolClass:
    record = class_of(session, user, class_id)
    check_if_match(if_match, CLASS, record, f"class {class_id}")
    apply_patch(record, patch)
    conditional_write(session, response, CLASS, record, f"class {class_id}")
    return record


@router.delete("/classes/{class_id}", operation_id="deleteClass",
               status_code=status.HTTP_204_NO_CONTENT, responses=PRECONDITION)
def delete_class(class_id: RecordId, session: SessionDep, user: Keeper,
                 if_match: IfMatch = None) -> Response:
    record = class_of(session, user, class_id)
    check_class_owner(user, record)
    delete_record(session, CLASS, record, f"class {class_id}", if_match)
    return Response(status_code=status.HTTP_204_NO_CONTENT)


@router.get("/children/avatars", operation_id="listAvatars")
def list_avatars() -> list[str]:
    """The avatar ids a child may pick."""
    return list(AVATARS)


@router.post("/children", operation_id="createChild", status_code=status.HTTP_201_CREATED,
             response_model=ChildOut)
def create_child(body: ChildIn, session: SessionDep, user: Keeper, response: Response) -> Child:
    """A child in one of the caller's classes."""
    check_class_reference(session, user, body.class_id)
    record = Child(**body.model_dump())
    session.add(record)
    session.commit()
    set_etag(response, CHILD, record)
    return record


@router.get("/children", operation_id="listChildren", response_model=ChildList)
def list_children(session: SessionDep, user: Keeper, class_id: IdFilter = None,
                  offset: Offset = 0, limit: Limit = 100) -> ChildList:
    """Children of the caller's classes in id order, of one class with ``class_id``."""
    query = visible_children(select(Child), user)
    if class_id is not None:
        query = query.where(Child.class_id == class_id)
    records, total = page(session, query, Child.id, offset, limit)
    return ChildList(children=[ChildOut.model_validate(r) for r in records], total=total)


@router.get("/children/{child_id}", operation_id="getChild", response_model=ChildOut)
def get_child(child_id: RecordId, session: SessionDep, user: Keeper,
              response: Response) -> Child:
    record = child_of(session, Person(user=user), child_id)
    set_etag(response, CHILD, record)
    return record


@router.put("/children/{child_id}", operation_id="replaceChild", response_model=ChildOut,
            responses=PRECONDITION)
def replace_child(child_id: RecordId, body: ChildIn, session: SessionDep, user: Keeper,
                  response: Response, if_match: IfMatch = None) -> Child:
    record = child_of(session, Person(user=user), child_id)
    check_if_match(if_match, CHILD, record, f"child {child_id}")
    check_class_reference(session, user, body.class_id)
    for field, value in body.model_dump().items():
        setattr(record, field, value)
    conditional_write(session, response, CHILD, record, f"child {child_id}")
    return record


@router.patch("/children/{child_id}", operation_id="updateChild", response_model=ChildOut,
              responses=PRECONDITION)
def update_child(child_id: RecordId, patch: ChildPatch, session: SessionDep, user: Keeper,
                 response: Response, if_match: IfMatch = None) -> Child:
    record = child_of(session, Person(user=user), child_id)
    check_if_match(if_match, CHILD, record, f"child {child_id}")
    check_class_reference(session, user, patch.class_id)
    apply_patch(record, patch)
    conditional_write(session, response, CHILD, record, f"child {child_id}")
    return record


@router.delete("/children/{child_id}", operation_id="deleteChild",
               status_code=status.HTTP_204_NO_CONTENT, responses=PRECONDITION)
def delete_child(child_id: RecordId, session: SessionDep, user: Keeper,
                 if_match: IfMatch = None) -> Response:
    """The child, their assignments, practice records and EPG recordings."""
    record = child_of(session, Person(user=user), child_id)
    delete_record(session, CHILD, record, f"child {child_id}", if_match)
    return Response(status_code=status.HTTP_204_NO_CONTENT)
