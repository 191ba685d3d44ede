"""What the lesson, class and practice routes share: records by id, paged listings, id
references in a body, conditional writes and the If-Match header.

Every resource here is ``Versioned``: reads answer with an ETag, and PUT, PATCH and DELETE take
``If-Match`` (412 when the record moved on, ``api/etags.py``). A body that names another record
(``class_id``, ``lesson_id``, ``child_id``) that does not exist is a 422 naming the field, not
a 404: the path named something that exists, the body did not.
"""

from typing import Annotated, Any, TypeVar

from fastapi import Header, HTTPException, Query, Response
from pydantic import BaseModel, Field
from sqlalchemy import Select, func, select
from sqlalchemy.orm import Session

from glasshead.api.etags import check_if_match, commit_versioned, set_etag
from glasshead.api.lookups import MAX_ID

Record = TypeVar("Record")

IfMatch = Annotated[str | None, Header(description="the ETag last read: the write goes ahead "
                                                  "only while the record is still at it (412 "
                                                  "otherwise); leave out to overwrite")]
#: How many records a listing returns at most.
Limit = Annotated[int, Query(ge=1, le=1000, description="records to return at most")]
#: A record id in a query string (a filter).
IdFilter = Annotated[int | None, Query(ge=1, le=MAX_ID, description="only records of this id")]
#: A record id in a body.
BodyId = Annotated[int, Field(ge=1, le=MAX_ID)]


def get_or_404(session: Session, model: type[Record], record_id: int, what: str) -> Record:
    """The ``model`` row ``record_id``; 404 naming ``what`` and the id when there is none."""
    record = session.get(model, record_id)
    if record is None:
        raise HTTPException(status_code=404, detail=f"no {what} with id {record_id}")
    return record


def check_reference(session: Session, model: type, record_id: int | None, field: str,
                    what: str) -> None:
    """422 naming the body's ``field`` when it names a ``model`` row that does not exist."""
    if record_id is not None and session.get(model, record_id) is None:
        raise HTTPException(status_code=422, detail=f"body.{field}: no {what} with id "
                                                    f"{record_id}")


def page(session: Session, query: Select, order, offset: int, limit: int) -> tuple[list, int]:
    """One page of ``query`` in ``order`` (a column or a tuple of them), and how many rows the
    whole query has."""
    total = session.scalar(select(func.count()).select_from(query.subquery()))
    ordered = query.order_by(*order) if isinstance(order, tuple) else query.order_by(order)
    return list(session.scalars(ordered.offset(offset).limit(limit))), total or 0


def apply_patch(record, patch: BaseModel) -> dict[str, Any]:
    """Set the fields a PATCH gave; a field given as null is a 422 naming it."""
    changes = patch.model_dump(exclude_unset=True)
    for field, value in changes.items():
        if value is None:
            raise HTTPException(status_code=422, detail=f"body.{field}: may not be null")
        setattr(record, field, value)
    return changes


def conditional_write(session: Session, response: Response | None, kind: str, record,
                      what: str) -> None:
    """Commit a write already checked against If-Match; a lost race is a 412."""
    commit_versioned(session, kind, record, what)
    if response is not None:
        set_etag(response, kind, record)


def delete_record(session: Session, kind: str, record, what: str, if_match: str | None) -> None:
    check_if_match(if_match, kind, record, what)
    session.delete(record)
    commit_versioned(session, kind, record, what)
