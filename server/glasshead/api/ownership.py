"""Whose records a caller may see and change: the ownership half of the role table.

``api/auth.py`` says who is asking and whether their role may call a route at all (401, 403);
this module says which records they reach. A class (a teacher's class or a clinician's
caseload) is its owner's: its children, their assignments, practice records and EPG recordings
go with it. The owner may share it with other teachers and clinicians (its staff, so that a
clinician follows a teacher's pupil): staff reach it and everything in it as the owner does, but
only the owner (or an admin) deletes the class or changes its staff, a 403 to staff. Someone
else's class, child, assignment, practice record or recording is a 404, the
answer for one that does not exist, so nobody learns that it does; in a body it is the 422 of a
reference to nothing (``api/records.py``). Content that every signed-in adult reads (lessons,
saved poses, fitted targets) is changed only by its owner or an admin: another's is a 403, since
it is no secret that it exists. Admins reach everything. docs/auth.md has the table.
"""

from fastapi import HTTPException
from sqlalchemy import Select, false, or_, select
from sqlalchemy.orm import Session

from glasshead.api.auth import Person
from glasshead.store.lessons import (
    Assignment,
    Child,
    ClassStaff,
    Lesson,
    PracticeRecord,
    SchoolClass,
)
from glasshead.store.models import EpgRecording
from glasshead.store.users import User


def _not_found(what: str, record_id: int) -> HTTPException:
    return HTTPException(status_code=404, detail=f"no {what} with id {record_id}")


def _not_in_body(field: str, what: str, record_id: int) -> HTTPException:
    return HTTPException(status_code=422, detail=f"body.{field}: no {what} with id {record_id}")


# Classes and children: the owner's and their staff's, or an admin's.

def staffed_class_ids(user: User) -> Select:
    """The ids of the classes shared with ``user`` (a subquery)."""
    return select(ClassStaff.class_id).where(ClassStaff.user_id == user.id)


def kept_class_ids(user: User) -> Select:
    """The ids of the classes ``user`` owns or is staff of (a subquery)."""
    return select(SchoolClass.id).where(or_(SchoolClass.owner_id == user.id,
                                            SchoolClass.id.in_(staffed_class_ids(user))))


def kept_child_ids(user: User) -> Select:
    """The ids of the children in classes ``user`` owns or is staff of (a subquery)."""
    return select(Child.id).where(Child.class_id.in_(kept_class_ids(user)))


def owns_class(user: User, school_class: SchoolClass) -> bool:
    return user.role == "admin" or school_class.owner_id == user.id


def keeps_class(session: Session, user: User, school_class: SchoolClass) -> bool:
    """Whether ``user`` owns ``school_class``, is its staff or is an admin."""
    return owns_class(user, school_class) or session.scalar(
        staffed_class_ids(user).where(ClassStaff.class_id == school_class.id)) is not None


def class_of(session: Session, user: User, class_id: int) -> SchoolClass:
    """Class ``class_id`` when ``user`` owns it, is its staff or is an admin; 404 otherwise."""
    record = session.get(SchoolClass, class_id)
    if record is None or not keeps_class(session, user, record):
        raise _not_found("class", class_id)
    return record


def check_class_owner(user: User, school_class: SchoolClass) -> None:
    """403 unless ``user`` owns ``school_class`` or is an admin: staff, who reach the class,
    neither delete it nor change who it is shared with."""
    if not owns_class(user, school_class):
        raise HTTPException(status_code=403, detail=f"class {school_class.id} is shared with "
                                                    "you: only its owner or an admin deletes it "
                                                    "or changes who it is shared with")


def child_of(session: Session, person: Person, child_id: int) -> Child:
    """Child ``child_id`` when ``person`` is that child, keeps their class (owner or staff) or is
    an admin; 404 otherwise."""
    record = session.get(Child, child_id)
    if record is None or not _reaches_child(session, person, record):
        raise _not_found("child", child_id)
    return record


def _reaches_child(session: Session, person: Person, child: Child) -> bool:
    if person.child is not None:
        return child.id == person.child.id
    return keeps_class(session, person.user, session.get(SchoolClass, child.class_id))


def check_class_reference(session: Session, user: User, class_id: int | None,
                          field: str = "class_id") -> None:
    """422 naming ``field`` when ``class_id`` is not a class ``user`` keeps."""
    if class_id is None:
        return
    record = session.get(SchoolClass, class_id)
    if record is None or not keeps_class(session, user, record):
        raise _not_in_body(field, "class", class_id)


def check_child_reference(session: Session, person: Person, child_id: int | None,
                          field: str = "child_id") -> None:
    """422 naming ``field`` when ``child_id`` is not a child ``person`` reaches."""
    if child_id is None:
        return
    record = session.get(Child, child_id)
    if record is None or not _reaches_child(session, person, record):
        raise _not_in_body(field, "child", child_id)


def visible_classes(query: Select, user: User) -> Select:
    return query if user.role == "admin" else query.where(SchoolClass.id.in_(kept_class_ids(user)))


def visible_children(query: Select, user: User) -> Select:
    if user.role == "admin":
        return query
    return query.where(Child.class_id.in_(kept_class_ids(user)))


# Lessons: every adult reads them; a child reads those assigned to them or to their class.

def assigned_lesson_ids(child: Child) -> Select:
    return select(Assignment.lesson_id).where(or_(Assignment.child_id == child.id,
                                                  Assignment.class_id == child.class_id))


def visible_lessons(query: Select, person: Person) -> Select:
    if person.child is None:
        return query
    return query.where(Lesson.id.in_(assigned_lesson_ids(person.child)))


def lesson_for(session: Session, person: Person, lesson_id: int) -> Lesson:
    """Lesson ``lesson_id`` when ``person`` may read it; 404 otherwise (a child's unassigned
    lesson too)."""
    record = session.get(Lesson, lesson_id)
    if record is None or (person.child is not None and session.scalar(
            assigned_lesson_ids(person.child).where(Assignment.lesson_id == lesson_id)
            .limit(1)) is None):
        raise _not_found("lesson", lesson_id)
    return record


def check_owner(user: User, record, what: str) -> None:
    """403 unless ``user`` owns ``record`` (content every adult reads: lessons, saved poses,
    fits) or is an admin; a record without an owner (a starter lesson, a pose saved before
    owners) is an admin's to change."""
    if user.role == "admin" or (record.owner_id is not None and record.owner_id == user.id):
        return
    whose = "has no owner: only an admin changes it" if record.owner_id is None else \
        "is another user's: only they or an admin change it"
    raise HTTPException(status_code=403, detail=f"{what} {record.id} {whose}")


# Assignments and practice: those of the caller's classes, or a child's own.

def _class_or_its_children(user: User, class_column, child_column):
    return or_(class_column.in_(kept_class_ids(user)), child_column.in_(kept_child_ids(user)))


def visible_assignments(query: Select, person: Person) -> Select:
    if person.child is not None:
        return query.where(or_(Assignment.child_id == person.child.id,
                               Assignment.class_id == person.child.class_id))
    if person.is_admin:
        return query
    return query.where(_class_or_its_children(person.user, Assignment.class_id,
                                              Assignment.child_id))


def assignment_for(session: Session, person: Person, assignment_id: int) -> Assignment:
    record = session.get(Assignment, assignment_id)
    if record is None or session.scalar(visible_assignments(
            select(Assignment.id).where(Assignment.id == assignment_id), person)) is None:
        raise _not_found("assignment", assignment_id)
    return record


def visible_practice(query: Select, person: Person) -> Select:
    if person.child is not None:
        return query.where(PracticeRecord.child_id == person.child.id)
    if person.is_admin:
        return query
    return query.where(PracticeRecord.child_id.in_(kept_child_ids(person.user)))


def practice_for(session: Session, person: Person, record_id: int) -> PracticeRecord:
    record = session.get(PracticeRecord, record_id)
    if record is None or session.scalar(visible_practice(
            select(PracticeRecord.id).where(PracticeRecord.id == record_id), person)) is None:
        raise _not_found("practice record", record_id)
    return record


# EPG recordings: reference recordings and those of the children of a clinician's own or shared
# classes, or an admin's.

def visible_recordings(query: Select, user: User) -> Select:
    if user.role == "admin":
        return query
    if user.role != "clinician":
        return query.where(false())
    return query.where(or_(EpgRecording.child_id.is_(None),
                           EpgRecording.child_id.in_(kept_child_ids(user))))


def recording_for(session: Session, user: User, recording_id: int) -> EpgRecording:
    """Recording ``recording_id`` when ``user`` may read it; 404 otherwise."""
    record = session.get(EpgRecording, recording_id)
    if record is None or session.scalar(visible_recordings(
            select(EpgRecording.id).where(EpgRecording.id == recording_id), user)) is None:
        raise HTTPException(status_code=404, detail=f"no EPG recording with id {recording_id}")
    return record


def check_uploader(user: User, record: EpgRecording) -> None:
    """403 unless ``user`` imported ``record`` or is an admin."""
    if user.role != "admin" and record.uploaded_by != user.id:
        raise HTTPException(status_code=403, detail=f"EPG recording {record.id} was imported by "
                                                    "another user: only they or an admin "
                                                    "delete it")

