"""Users: admins add, list, change and remove the people who sign in.

A username is unique after trimming and lower-casing. A new password revokes the user's tokens,
so a changed password signs them out everywhere. The last admin can neither be removed nor given
another role (409), so the server always has someone who can manage it; ``glasshead user create
--role admin`` makes the first one.
"""

from typing import Annotated

from fastapi import APIRouter, Header, HTTPException, Query, Response, status
from pydantic import BaseModel, ConfigDict, Field, StringConstraints
from sqlalchemy import func, select
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Session

from glasshead.accounts import (
    MAX_PASSWORD_LENGTH,
    MIN_PASSWORD_LENGTH,
    AccountError,
    count_admins,
    create_user,
    hash_password,
    revoke_all,
)
from glasshead.api.auth import FORBIDDEN, UNAUTHENTICATED, AdminUser
from glasshead.api.error_responses import Responses
from glasshead.api.etags import PRECONDITION, check_if_match, commit_versioned, set_etag
from glasshead.api.lookups import Offset, RecordId
from glasshead.api.people import Role, UserOut
from glasshead.store.session import SessionDep
from glasshead.store.users import MAX_DISPLAY_NAME_LENGTH, MAX_USERNAME_LENGTH, User

router = APIRouter(tags=["users"])

KIND = "user"
Password = Annotated[str, Field(min_length=MIN_PASSWORD_LENGTH, max_length=MAX_PASSWORD_LENGTH)]
DisplayName = Annotated[str, StringConstraints(strip_whitespace=True, min_length=1,
                                               max_length=MAX_DISPLAY_NAME_LENGTH)]
IfMatch = Annotated[str | None, Header(description="the ETag last read: the write goes ahead "
                                                  "only while the user is still at it (412 "
                                                  "otherwise); leave out to overwrite")]
ADMIN_ONLY: Responses = {**UNAUTHENTICATED, **FORBIDDEN}
#: The 409s: a username already taken, the last admin removed or demoted.
CONFLICT: Responses = {
    409: {"description": "the username is taken, or the change would leave no admin"}}


class UserIn(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={"examples": [
        {"username": "ann@school.example", "display_name": "Ann Teacher", "role": "teacher",
         "password": "correct horse battery"}]})
    username: str = Field(min_length=1, max_length=MAX_USERNAME_LENGTH,
                          description="unique; an email address will do; no spaces")
    display_name: DisplayName | None = None
    role: Role
    password: Password


class UserPatch(BaseModel):
    model_config = ConfigDict(extra="forbid", json_schema_extra={"examples": [
        {"display_name": "Ann Clinician", "role": "clinician"}]})
    display_name: DisplayName | None = None
    role: Role | None = None
    password: Password | None = Field(None, description="a new password; signs the user out "
                                                        "everywhere")


class UserList(BaseModel):
    users: list[UserOut]
    total: int


def _get_user(session: Session, user_id: int) -> User:
    user = session.get(User, user_id)
    if user is None:
        raise HTTPException(status_code=404, detail=f"no user with id {user_id}")
    return user


def _keep_an_admin(session: Session, user: User, what: str) -> None:
    if user.role == "admin" and count_admins(session) <= 1:
        raise HTTPException(status_code=409, detail=f"{user.username} is the only admin and "
                                                    f"cannot be {what}; make another admin first")


@router.post("/users", operation_id="createUser", status_code=status.HTTP_201_CREATED,
             response_model=UserOut, responses={**ADMIN_ONLY, **CONFLICT})
def create(new: UserIn, session: SessionDep, admin: AdminUser, response: Response) -> User:
    try:
        user = create_user(session, new.username, new.password, new.role, new.display_name)
        session.commit()
    except AccountError as error:
        session.rollback()
        code = 409 if "taken" in str(error) else 422
        raise HTTPException(status_code=code, detail=f"field username: {error}") from None
    except IntegrityError:  # a simultaneous create of the same username
        session.rollback()
        raise HTTPException(status_code=409, detail=f"field username: {new.username!r} is "
                                                    "taken") from None
    set_etag(response, KIND, user)
    return user


@router.get("/users", operation_id="listUsers", response_model=UserList, responses=ADMIN_ONLY)
def list_users(session: SessionDep, admin: AdminUser, role: Role | None = None,
               offset: Offset = 0,
               limit: Annotated[int, Query(ge=1, le=1000)] = 100) -> UserList:
    """Users in username order; ``role`` selects those with that role."""
    query = select(User)
    if role is not None:
        query = query.where(User.role == role)
    total = session.scalar(select(func.count()).select_from(query.subquery()))
    users = session.scalars(query.order_by(User.username).offset(offset).limit(limit))
    return UserList(users=[UserOut.model_validate(u) for u in users], total=total)


@router.get("/users/{user_id}", operation_id="getUser", response_model=UserOut,
            responses=ADMIN_ONLY)
def get_user(user_id: RecordId, session: SessionDep, admin: AdminUser,
             response: Response) -> User:
    user = _get_user(session, user_id)
    set_etag(response, KIND, user)
    return user


@router.patch("/users/{user_id}", operation_id="updateUser", response_model=UserOut,
              responses={**ADMIN_ONLY, **PRECONDITION, **CONFLICT})
def update_user(user_id: RecordId, patch: UserPatch, session: SessionDep, admin: AdminUser,
                response: Response, if_match: IfMatch = None) -> User:
    user = _get_user(session, user_id)
    check_if_match(if_match, KIND, user, f"user {user_id}")
    changes = patch.model_dump(exclude_unset=True)
    for field, value in changes.items():
        if value is None:
            raise HTTPException(status_code=422, detail=f"field {field}: may not be null")
    if changes.get("role", user.role) != user.role:
        _keep_an_admin(session, user, "given another role")
        user.role = changes["role"]
    if "display_name" in changes:
        user.display_name = changes["display_name"]
    if "password" in changes:
        user.password_hash = hash_password(changes["password"])
        revoke_all(session, user)
    commit_versioned(session, KIND, user, f"user {user_id}")
    set_etag(response, KIND, user)
    return user


@router.delete("/users/{user_id}", operation_id="deleteUser",
               status_code=status.HTTP_204_NO_CONTENT,
               responses={**ADMIN_ONLY, **PRECONDITION, **CONFLICT})
def delete_user(user_id: RecordId, session: SessionDep, admin: AdminUser,
                if_match: IfMatch = None) -> Response:
    """Remove a user and their tokens."""
    user = _get_user(session, user_id)
    check_if_match(if_match, KIND, user, f"user {user_id}")
    _keep_an_admin(session, user, "removed")
    session.delete(user)
    commit_versioned(session, KIND, user, f"user {user_id}")
    return Response(status_code=status.HTTP_204_NO_CONTENT)
