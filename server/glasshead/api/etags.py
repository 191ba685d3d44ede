"""ETags and If-Match for stored records: no silent lost updates.

A record's ETag is its kind, id and version (``store.base.Versioned``), e.g. ``"pose-3-v7"``:
it changes with every update. Reads and writes answer with it in the ``ETag`` header. A write
(PUT, PATCH, DELETE) that sends ``If-Match`` goes ahead only while the record is still at one of
the versions named there (``*`` matches any), else 412; the version check is repeated inside the
UPDATE itself, so of two writers who read the same version only one succeeds. A write without
``If-Match`` is allowed and overwrites what is there (docs: "Concurrent edits").
"""

from fastapi import HTTPException, Response
from sqlalchemy.orm import Session
from sqlalchemy.orm.exc import StaleDataError

from glasshead.api.error_responses import Responses

PRECONDITION_FAILED = 412
#: The 412 of a conditional write, for a route's ``responses``.
PRECONDITION: Responses = {PRECONDITION_FAILED: {
    "description": "If-Match names a version the record is no longer at; the ETag header gives "
                   "the current one"}}


def etag(kind: str, record) -> str:
    """The strong ETag of ``record`` (a Versioned row) of ``kind``."""
    return f'"{kind}-{record.id}-v{record.version}"'


def set_etag(response: Response, kind: str, record) -> None:
    response.headers["ETag"] = etag(kind, record)


def _listed(header: str) -> list[str]:
    return [tag.strip().removeprefix("W/") for tag in header.split(",") if tag.strip()]


def check_if_match(if_match: str | None, kind: str, record, what: str) -> None:
    """412 naming the current ETag when ``If-Match`` names no version the record is at."""
    if if_match is None:
        return
    tags = _listed(if_match)
    current = etag(kind, record)
    if "*" not in tags and current not in tags:
        raise HTTPException(status_code=PRECONDITION_FAILED,
                            detail=f"{what} changed since it was read: If-Match {if_match} "
                                   f"but it is now {current}; read it again and reapply "
                                   "the change",
                            headers={"ETag": current})


def commit_versioned(session: Session, kind: str, record, what: str) -> None:
    """Commit, turning a lost race on the version (another writer first) into a 412."""
    try:
        session.commit()
    except StaleDataError:
        session.rollback()
        raise HTTPException(status_code=PRECONDITION_FAILED,
                            detail=f"{what} was changed by another request at the same time; "
                                   "read it again and reapply the change") from None
