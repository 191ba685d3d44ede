"""Response schemas of people that several route modules return: a user (``users`` and ``auth``
routes) and a child (``classes`` and ``auth`` routes). Kept here so that no route module
imports another."""

from datetime import datetime
from typing import Literal

from pydantic import BaseModel, ConfigDict

#: The roles a user can have.
Role = Literal["author", "teacher", "clinician", "admin"]


class UserOut(BaseModel):
    model_config = ConfigDict(from_attributes=True)
    id: int
    username: str
    display_name: str
    role: Role
    created_at: datetime
    updated_at: datetime


class ChildOut(BaseModel):
    model_config = ConfigDict(from_attributes=True)
    id: int
    class_id: int
    display_name: str
    avatar: str
    created_at: datetime
    updated_at: datetime
