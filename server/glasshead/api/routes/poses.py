"""Saved poses: named parameter sets saved from the workbench, the targets EPG is compared with.

A pose's ``params`` map articulation parameter names (as in the tongue, face and velum rigs) to
numbers; a value outside its rig's range is refused (422 naming the parameter and the range),
names no rig has are kept. Pose names are unique, so a pose can be found by name
(``GET /poses?name=...``).

Poses are content shared within a school: every signed-in adult reads them; authors, clinicians
and admins save them; a pose is changed or deleted only by whoever saved it, or an admin (403
otherwise; a pose saved before poses had owners is an admin's).
"""

import math
import re
from datetime import datetime
from typing import Annotated

from fastapi import APIRouter, Depends, Header, HTTPException, Query, Response, status
from pydantic import BaseModel, ConfigDict, Field, StringConstraints, field_validator
from pydantic.json_schema import JsonDict, SkipJsonSchema
from sqlalchemy import func, select
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Session

from glasshead.api.auth import SignedInUser, require_role
from glasshead.api.deps import AssetsDep
from glasshead.api.error_responses import Responses
from glasshead.api.etags import PRECONDITION, check_if_match, commit_versioned, set_etag
from glasshead.api.lookups import Offset, RecordId, get_pose_record
from glasshead.api.ownership import check_owner
from glasshead.api.params import check_known_params
from glasshead.store.models import SavedPose
from glasshead.store.session import SessionDep
from glasshead.store.users import User

router = APIRouter(tags=["poses"])

KIND = "pose"
#: The 409 of a write that would give a pose another pose's name.
NAME_CONFLICT: Responses = {409: {"description": "a pose with that name already exists"}}
IfMatch = Annotated[str | None, Header(description="the ETag last read: the write goes ahead "
                                                  "only while the pose is still at it (412 "
                                                  "otherwise); leave out to overwrite")]

PARAM_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_.]{0,63}$")
MAX_PARAMS = 256
#: The document states the rules _check_params holds a map to, so that a client (or a request
#: generator) knows which names and how many are taken before it is refused.
PARAMS_SCHEMA: JsonDict = {"propertyNames": {"pattern": PARAM_NAME.pattern},
                           "maxProperties": MAX_PARAMS}
#: Who saves poses and targets.
Maker = Annotated[User, Depends(require_role("author", "clinician", "admin"))]
PoseName = Annotated[str, StringConstraints(strip_whitespace=True, min_length=1, max_length=120)]


def _check_params(params: dict[str, float]) -> dict[str, float]:
    if len(params) > MAX_PARAMS:
        raise ValueError(f"{len(params)} parameters is more than {MAX_PARAMS}")
    for name, value in params.items():
        if not PARAM_NAME.match(name):
            raise ValueError(f"{name!r} is not a parameter name (a letter, then letters, "
                             "digits, '_' or '.')")
        if not math.isfinite(value):
            raise ValueError(f"{name}: {value} is not a finite number")
    return params


class PoseIn(BaseModel):
    # The /t/ target's main tongue and jaw parameters (assets/build/phoneme-targets.json).
    model_config = ConfigDict(extra="forbid", json_schema_extra={"examples": [
        {"name": "t alveolar closure", "description": "tip and blade up to the alveolar ridge",
         "params": {"tip_advancement": 0.28, "tip_height": 5.79, "blade_advancement": 1.7,
                    "blade_height": 8.28, "dorsum_height": 9.44, "body_height": -5.0,
                    "jaw_opening": 0.0}}]})
    name: PoseName
    description: str = Field("", max_length=2000)
    params: dict[str, float] = Field(description="parameter name -> value, in the rig's units",
                                     json_schema_extra=PARAMS_SCHEMA)

    @field_validator("params")
    @classmethod
    def _params(cls, params):
        return _check_params(params)


class PosePatch(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={"examples": [
        {"description": "tip a little higher", "params": {"tip_height": 6.0,
                                                          "blade_height": 8.28}}]})
    # Each field may be left out, never null: the document has no null among the types, and
    # update_pose refuses a null by the field's name.
    name: PoseName | SkipJsonSchema[None] = None
    # The length bound sits on the string: on the union it would be applied to a null too.
    description: Annotated[str, StringConstraints(max_length=2000)] | SkipJsonSchema[None] = None
    params: dict[str, float] | SkipJsonSchema[None] = Field(None,
                                                            json_schema_extra=PARAMS_SCHEMA)

    @field_validator("params")
    @classmethod
    def _params(cls, params):
        return None if params is None else _check_params(params)


class PoseOut(BaseModel):
    model_config = ConfigDict(from_attributes=True)
    id: int
    name: str
    description: str
    params: dict[str, float]
    owner_id: int | None = Field(description="the user who saved it (None: an admin's)")
    created_at: datetime
    updated_at: datetime


class PoseList(BaseModel):
    poses: list[PoseOut]
    total: int


def _commit(session: Session, name: str, record: SavedPose | None = None) -> None:
    try:
        if record is None:
            session.commit()
        else:
            commit_versioned(session, KIND, record, f"pose {record.id}")
    except IntegrityError:
        session.rollback()
        raise HTTPException(status_code=409, detail=f"field name: a pose named {name!r} "
                                                    "already exists") from None


@router.post("/poses", operation_id="createPose", status_code=status.HTTP_201_CREATED,
             response_model=PoseOut, responses=NAME_CONFLICT)
def create_pose(pose: PoseIn, session: SessionDep, assets: AssetsDep, user: Maker,
                response: Response) -> SavedPose:
    check_known_params(assets, pose.params)
    record = SavedPose(name=pose.name, description=pose.description, params=pose.params,
                       owner_id=user.id)
    session.add(record)
    _commit(session, pose.name)
    set_etag(response, KIND, record)
    return record


@router.get("/poses", operation_id="listPoses", response_model=PoseList)
def list_poses(session: SessionDep, user: SignedInUser, name: str | None = None,
               offset: Offset = 0,
               limit: Annotated[int, Query(ge=1, le=1000)] = 100) -> PoseList:
    """Poses in name order; ``name`` selects the one pose of that name."""
    query = select(SavedPose)
    if name is not None:
        query = query.where(SavedPose.name == name.strip())
    total = session.scalar(select(func.count()).select_from(query.subquery()))
    poses = session.scalars(query.order_by(SavedPose.name).offset(offset).limit(limit))
    return PoseList(poses=[PoseOut.model_validate(p) for p in poses], total=total)


@router.get("/poses/{pose_id}", operation_id="getPose", response_model=PoseOut)
def get_pose(pose_id: RecordId, session: SessionDep, user: SignedInUser,
             response: Response) -> SavedPose:
    record = get_pose_record(session, pose_id)
    set_etag(response, KIND, record)
    return record


@router.put("/poses/{pose_id}", operation_id="replacePose", response_model=PoseOut,
            responses={**PRECONDITION, **NAME_CONFLICT})
def replace_pose(pose_id: RecordId, pose: PoseIn, session: SessionDep, assets: AssetsDep,
                 user: Maker, response: Response, if_match: IfMatch = None) -> SavedPose:
    record = get_pose_record(session, pose_id)
    check_owner(user, record, KIND)
    check_if_match(if_match, KIND, record, f"pose {pose_id}")
    check_known_params(assets, pose.params)
    record.name, record.description, record.params = pose.name, pose.description, pose.params
    _commit(session, pose.name, record)
    set_etag(response, KIND, record)
    return record


@router.patch("/poses/{pose_id}", operation_id="updatePose", response_model=PoseOut,
              responses={**PRECONDITION, **NAME_CONFLICT})
def update_pose(pose_id: RecordId, patch: PosePatch, session: SessionDep, assets: AssetsDep,
                user: Maker, response: Response, if_match: IfMatch = None) -> SavedPose:
    record = get_pose_record(session, pose_id)
    check_owner(user, record, KIND)
    check_if_match(if_match, KIND, record, f"pose {pose_id}")
    if patch.params is not None:
        check_known_params(assets, patch.params)
    for field, value in patch.model_dump(exclude_unset=True).items():
        if value is None:
            raise HTTPException(status_code=422, detail=f"field {field}: may not be null")
        setattr(record, field, value)
    _commit(session, record.name, record)
    set_etag(response, KIND, record)
    return record


@router.delete("/poses/{pose_id}", operation_id="deletePose",
               status_code=status.HTTP_204_NO_CONTENT, responses=PRECONDITION)
def delete_pose(pose_id: RecordId, session: SessionDep, user: Maker,
                if_match: IfMatch = None) -> Response:
    record = get_pose_record(session, pose_id)
    check_owner(user, record, KIND)
    check_if_match(if_match, KIND, record, f"pose {pose_id}")
    session.delete(record)
    commit_versioned(session, KIND, record, f"pose {pose_id}")
    return Response(status_code=status.HTTP_204_NO_CONTENT)
