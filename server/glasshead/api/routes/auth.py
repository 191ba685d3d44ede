"""Signing in and out: a username and password for a bearer token, and the token revoked.

``POST /auth/sessions`` answers a wrong password and an unknown username with the same 401, so
nobody learns which usernames exist. A child signs in with their class's join code and their
own id (``POST /auth/child-sessions``), for a token that names the child, after finding their
name and avatar in the class's roster (``POST /auth/class-roster``, open: a child has no token
yet). Failed attempts are limited per username and per client address (``api/attempts.py``):
past the limit the answer is 429 with Retry-After.
"""

from datetime import datetime
from typing import Literal

from fastapi import APIRouter, HTTPException, Request, Response, status
from pydantic import BaseModel, ConfigDict, Field
from sqlalchemy import select

from glasshead.accounts import MAX_PASSWORD_LENGTH, revoke, sign_in, sign_in_child
from glasshead.api import attempts
from glasshead.api.auth import (
    UNAUTHENTICATED,
    CurrentChild,
    CurrentChildToken,
    CurrentToken,
    CurrentUser,
)
from glasshead.api.lookups import MAX_ID
from glasshead.api.people import ChildOut, UserOut
from glasshead.store.lessons import Child, SchoolClass
from glasshead.store.session import SessionDep
from glasshead.store.users import MAX_USERNAME_LENGTH

router = APIRouter(tags=["auth"])

WRONG_CREDENTIALS = "unknown username or wrong password"
WRONG_CHILD = "no child with that id in the class with that code"
WRONG_CODE = "no class with that code"


class SignIn(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={
        "examples": [{"username": "ann@school.example", "password": "correct horse battery"}]})
    username: str = Field(min_length=1, max_length=MAX_USERNAME_LENGTH)
    password: str = Field(min_length=1, max_length=MAX_PASSWORD_LENGTH)


class SessionOut(BaseModel):
    token: str = Field(description="send as Authorization: Bearer <token>; shown only once")
    token_type: Literal["bearer"] = "bearer"
    expires_at: datetime
    user: UserOut


@router.post("/auth/sessions", operation_id="signIn", status_code=status.HTTP_201_CREATED,
             response_model=SessionOut,
             responses={401: {"description": WRONG_CREDENTIALS}, **attempts.TOO_MANY})
def create_session(credentials: SignIn, session: SessionDep, request: Request) -> SessionOut:
    """Sign in: a new bearer token for this username and password."""
    keys = (attempts.username_key(credentials.username), attempts.address_key(request))
    attempts.check(session, *keys)
    issued = sign_in(session, credentials.username, credentials.password)
    if issued is None:
        attempts.record_failure(session, *keys)
        raise HTTPException(status_code=401, detail=WRONG_CREDENTIALS,
                            headers={"WWW-Authenticate": "Bearer"})
    attempts.clear(session, keys[0])
    return SessionOut(token=issued.token, expires_at=issued.expires_at,
                      user=UserOut.model_validate(issued.user))


@router.delete("/auth/sessions/current", operation_id="signOut",
               status_code=status.HTTP_204_NO_CONTENT, responses=UNAUTHENTICATED)
def delete_session(token: CurrentToken, session: SessionDep) -> Response:
    """Sign out: the token sent is revoked and refused from now on."""
    revoke(token)
    session.commit()
    return Response(status_code=status.HTTP_204_NO_CONTENT)


@router.get("/auth/me", operation_id="getCurrentUser", response_model=UserOut,
            responses=UNAUTHENTICATED)
def get_me(user: CurrentUser):
    """The signed-in user."""
    return user


class ChildSignIn(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={
        "examples": [{"join_code": "7KQ4MX", "child_id": 12}]})
    join_code: str = Field(min_length=1, max_length=40, description="the class's code, any case")
    child_id: int = Field(ge=1, le=MAX_ID, description="the child, as picked by name and avatar "
                                                       "from the class's children")


class ChildSessionOut(BaseModel):
    token: str = Field(description="send as Authorization: Bearer <token>; shown only once")
    token_type: Literal["bearer"] = "bearer"
    expires_at: datetime
    child: ChildOut


@router.post("/auth/child-sessions", operation_id="signInChild",
             status_code=status.HTTP_201_CREATED, response_model=ChildSessionOut,
             responses={401: {"description": WRONG_CHILD}, **attempts.TOO_MANY})
def create_child_session(body: ChildSignIn, session: SessionDep,
                         request: Request) -> ChildSessionOut:
    """A child signs in: a bearer token for the child with this id in the class with this code."""
    key = attempts.address_key(request, "join-code-address")
    attempts.check(session, key)
    issued = sign_in_child(session, body.join_code, body.child_id)
    if issued is None:
        attempts.record_failure(session, key)
        raise HTTPException(status_code=401, detail=WRONG_CHILD,
                            headers={"WWW-Authenticate": "Bearer"})
    return ChildSessionOut(token=issued.token, expires_at=issued.expires_at,
                           child=ChildOut.model_validate(issued.child))


@router.get("/auth/child-sessions/current", operation_id="getCurrentChild",
            response_model=ChildOut, responses=UNAUTHENTICATED)
def get_current_child(child: CurrentChild):
    """The signed-in child."""
    return child


@router.delete("/auth/child-sessions/current", operation_id="signOutChild",
               status_code=status.HTTP_204_NO_CONTENT, responses=UNAUTHENTICATED)
def delete_child_session(token: CurrentChildToken, session: SessionDep) -> Response:
    """A child signs out: the token sent is revoked."""
    revoke(token)
    session.commit()
    return Response(status_code=status.HTTP_204_NO_CONTENT)


class RosterRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={
        "examples": [{"join_code": "7KQ4MX"}]})
    join_code: str = Field(min_length=1, max_length=40, description="the class's code, any case")


class RosterChild(BaseModel):
    model_config = ConfigDict(from_attributes=True)
    id: int
    display_name: str
    avatar: str


class Roster(BaseModel):
    class_name: str
    children: list[RosterChild] = Field(description="in name order, for the child to pick")


@router.post("/auth/class-roster", operation_id="getClassRoster", response_model=Roster,
             responses={404: {"description": WRONG_CODE}, **attempts.TOO_MANY})
def class_roster(body: RosterRequest, session: SessionDep, request: Request) -> Roster:
    """The names and avatars of the children of the class with this code, so that a child can
    pick themselves before signing in (POST /auth/child-sessions). Open, as a child has no
    token yet; the code is asked in a body, not a URL, so that it stays out of logs. Unknown
    codes count against the client's address like wrong passwords."""
    key = attempts.address_key(request, "join-code-address")
    attempts.check(session, key)
    code = "".join(body.join_code.split()).upper()
    school_class = session.scalar(select(SchoolClass).where(SchoolClass.join_code == code))
    if school_class is None:
        attempts.record_failure(session, key)
        raise HTTPException(status_code=404, detail=WRONG_CODE)
    children = session.scalars(select(Child).where(Child.class_id == school_class.id)
                               .order_by(Child.display_name, Child.id))
    return Roster(class_name=school_class.name,
                  children=[RosterChild.model_validate(c) for c in children])
