"""Signing in and out: a username and password for a bearer token, and the token revoked.

``POST /auth/sessions`` answers a wrong password and an unknown username with the same 401, so
nobody learns which usernames exist. Attempts are not yet limited in number: a deployment open
to the internet puts a rate limit in front of this route until the app has one (docs/auth.md).
"""

from datetime import datetime
from typing import Literal

from fastapi import APIRouter, HTTPException, Response, status
from pydantic import BaseModel, ConfigDict, Field

from glasshead.accounts import MAX_PASSWORD_LENGTH, revoke, sign_in
from glasshead.api.auth import UNAUTHENTICATED, CurrentToken, CurrentUser
from glasshead.api.routes.users import UserOut
from glasshead.store.session import SessionDep
from glasshead.store.users import MAX_USERNAME_LENGTH

router = APIRouter(tags=["auth"])

WRONG_CREDENTIALS = "unknown username or wrong password"


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
