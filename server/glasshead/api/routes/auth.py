"""Signing in and out: a username and password for a bearer token, and the token revoked.

``POST /auth/sessions`` answers a wrong password and an unknown username with the same 401, so
nobody learns which usernames exist. A child signs in with their class's join code and their
own id (``POST /auth/child-sessions``), for a token that names the child. Attempts are not yet
limited in number: a deployment open to the internet puts a rate limit in front of these routes
until the app has one (docs/auth.md).
"""

from datetime import datetime
from typing import Literal

from fastapi import APIRouter, HTTPException, Response, status
from pydantic import BaseModel, ConfigDict, Field

from glasshead.accounts import MAX_PASSWORD_LENGTH, revoke, sign_in, sign_in_child
from glasshead.api.auth import (
    UNAUTHENTICATED,
    CurrentChild,
    CurrentChildToken,
    CurrentToken,
    CurrentUser,
)
from glasshead.api.lookups import MAX_ID
from glasshead.api.people import ChildOut, UserOut
from glasshead.store.session import SessionDep
from glasshead.store.users import MAX_USERNAME_LENGTH

router = APIRouter(tags=["auth"])

WRONG_CREDENTIALS = "unknown username or wrong password"
WRONG_CHILD = "no child with that id in the class with that code"


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
             responses={401: {"description": WRONG_CREDENTIALS}})
def create_session(credentials: SignIn, session: SessionDep) -> SessionOut:
    """Sign in: a new bearer token for this username and password."""
    issued = sign_in(session, credentials.username, credentials.password)
    if issued is None:
        raise HTTPException(status_code=401, detail=WRONG_CREDENTIALS,
                            headers={"WWW-Authenticate": "Bearer"})
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
             responses={401: {"description": WRONG_CHILD}})
def create_child_session(body: ChildSignIn, session: SessionDep) -> ChildSessionOut:
    """A child signs in: a bearer token for the child with this id in the class with this code."""
    issued = sign_in_child(session, body.join_code, body.child_id)
    if issued is None:
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
