"""Sharing a class: the teachers and clinicians it is shared with besides its owner (its staff).

A child who practises in a teacher's class may also be seen by a clinician: the teacher shares
the class with the clinician by username, and the clinician then reaches the class and its
children as the teacher does (their practice, and as a clinician their EPG recordings), without
a second copy of the child in a caseload of their own. Staff neither delete the class nor change
its staff (a 403); removing someone takes their access away at once. Only teachers and
clinicians are shared with: an unknown username, an author's and an admin's are all the same
422, so that sharing tells nobody which usernames exist. The rule itself is in
``api/ownership.py``.
"""

from datetime import datetime
from typing import Annotated

from fastapi import APIRouter, Depends, HTTPException, Response, status
from pydantic import BaseModel, ConfigDict, Field
from sqlalchemy import select
from sqlalchemy.exc import IntegrityError

from glasshead.api.auth import require_role
from glasshead.api.error_responses import Responses
from glasshead.api.lookups import RecordId
from glasshead.api.ownership import check_class_owner, class_of
from glasshead.api.people import Role
from glasshead.store.lessons import ClassStaff
from glasshead.store.session import SessionDep
from glasshead.store.users import MAX_USERNAME_LENGTH, User

router = APIRouter(tags=["classes"])

#: Who keeps classes: teachers, clinicians and admins (as in ``routes/classes.py``).
Keeper = Annotated[User, Depends(require_role("teacher", "clinician", "admin"))]
#: The roles a class may be shared with.
STAFF_ROLES = ("teacher", "clinician")
ALREADY_SHARED: Responses = {409: {"description": "the class is already shared with that user"}}


class StaffIn(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={
        "examples": [{"username": "cleo@clinic.example"}]})
    username: str = Field(min_length=1, max_length=MAX_USERNAME_LENGTH,
                          description="the teacher's or clinician's username (any case)")


class StaffMember(BaseModel):
    user_id: int
    username: str
    display_name: str
    role: Role
    #: When the class was shared with them; None for the owner.
    added_at: datetime | None = None


class StaffList(BaseModel):
    #: Who made the class (None once that user is removed).
    owner: StaffMember | None
    staff: list[StaffMember]


def _member(user: User, added_at: datetime | None = None) -> StaffMember:
    return StaffMember(user_id=user.id, username=user.username, display_name=user.display_name,
                       role=user.role, added_at=added_at)


@router.post("/classes/{class_id}/staff", operation_id="addClassStaff",
             status_code=status.HTTP_201_CREATED, response_model=StaffMember,
             responses=ALREADY_SHARED)
def add_class_staff(class_id: RecordId, body: StaffIn, session: SessionDep,
                    user: Keeper) -> StaffMember:
    """Share the class with a teacher or clinician, who then reaches it as its owner does
    (except deleting it or changing its staff). Owner or admin only."""
    school_class = class_of(session, user, class_id)
    check_class_owner(user, school_class)
    name = body.username.strip().lower()
    member = session.scalar(select(User).where(User.username == name))
    if member is None or member.role not in STAFF_ROLES:
        raise HTTPException(status_code=422, detail="body.username: no such user among "
                                                    "teachers and clinicians")
    if member.id == school_class.owner_id:
        raise HTTPException(status_code=422, detail="body.username: that is the class's owner, "
                                                    "who keeps it already")
    row = ClassStaff(class_id=class_id, user_id=member.id)
    session.add(row)
    try:
        session.commit()
    except IntegrityError:
        session.rollback()
        raise HTTPException(status_code=409, detail=f"class {class_id} is already shared with "
                                                    f"{member.username}") from None
    return _member(member, row.added_at)


@router.get("/classes/{class_id}/staff", operation_id="listClassStaff", response_model=StaffList)
def list_class_staff(class_id: RecordId, session: SessionDep, user: Keeper) -> StaffList:
    """The class's owner and the users it is shared with, in the order they were added; its
    owner, its staff and admins read it."""
    school_class = class_of(session, user, class_id)
    owner = session.get(User, school_class.owner_id) if school_class.owner_id else None
    rows = session.execute(select(User, ClassStaff.added_at).join(
        ClassStaff, ClassStaff.user_id == User.id).where(ClassStaff.class_id == class_id)
        .order_by(ClassStaff.id)).all()
    return StaffList(owner=_member(owner) if owner else None,
                     staff=[_member(member, added_at) for member, added_at in rows])


@router.delete("/classes/{class_id}/staff/{user_id}", operation_id="removeClassStaff",
               status_code=status.HTTP_204_NO_CONTENT)
def remove_class_staff(class_id: RecordId, user_id: RecordId, session: SessionDep,
                       user: Keeper) -> Response:
    """Stop sharing the class with ``user_id``: they no longer reach it or its children. Owner
    or admin only; 404 when the class is not shared with that user."""
    school_class = class_of(session, user, class_id)
    check_class_owner(user, school_class)
    row = session.scalar(select(ClassStaff).where(ClassStaff.class_id == class_id,
                                                  ClassStaff.user_id == user_id))
    if row is None:
        raise HTTPException(status_code=404, detail=f"class {class_id} is not shared with a "
                                                    f"user with id {user_id}")
    session.delete(row)
    session.commit()
    return Response(status_code=status.HTTP_204_NO_CONTENT)
