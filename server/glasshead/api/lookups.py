"""Stored records by id, for the routes: a 404 naming the resource when there is none.

Ids and offsets are bounded by the largest key a database holds (SQLite's INTEGER and
PostgreSQL's BIGINT are signed 64-bit), so a larger number is a 422 naming the field rather than
an overflow inside the driver.
"""

from typing import Annotated

from fastapi import HTTPException, Path, Query
from sqlalchemy.orm import Session

from glasshead.store.models import EpgRecording, SavedPose

#: The largest key SQLite and PostgreSQL store (2**63 - 1); ids start at 1.
MAX_ID = 2**63 - 1

#: A record id in a route's path.
RecordId = Annotated[int, Path(ge=1, le=MAX_ID, description="the record's id")]
#: How many records a listing skips.
Offset = Annotated[int, Query(ge=0, le=MAX_ID, description="records to skip")]


def get_record(session: Session, recording_id: int) -> EpgRecording:
    """The EPG recording ``recording_id``; 404 when there is none."""
    record = session.get(EpgRecording, recording_id)
    if record is None:
        raise HTTPException(status_code=404, detail=f"no EPG recording with id {recording_id}")
    return record


def get_pose_record(session: Session, pose_id: int) -> SavedPose:
    """The saved pose ``pose_id``; 404 when there is none."""
    pose = session.get(SavedPose, pose_id)
    if pose is None:
        raise HTTPException(status_code=404, detail=f"no saved pose with id {pose_id}")
    return pose
