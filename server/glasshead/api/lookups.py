"""Stored records by id, for the routes: a 404 naming the resource when there is none."""

from fastapi import HTTPException
from sqlalchemy.orm import Session

from glasshead.store.models import EpgRecording, SavedPose


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
