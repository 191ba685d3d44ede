"""Who is asking: the bearer-token dependencies of the routes that need a signed-in user.

``CurrentUser`` is the user whose token came in ``Authorization: Bearer <token>``; a token that
is missing, unknown, expired or revoked is a 401 with ``WWW-Authenticate: Bearer`` (RFC 6750
section 3), and the same sentence for all four, so a caller learns nothing about other people's
tokens. ``require_role(*roles)`` narrows it to those roles, with a 403 that names them.
``CurrentChild`` is the same for a child signed in with their class's join code.

``CurrentPerson`` takes either token: a user's or a child's, for the routes both may use, and
``allow(*callers)`` narrows it to some roles and, with ``"child"``, to children (a 403 naming
who may). Which record of a resource a caller may see or change is the business of
``api/ownership.py``; the role table is docs/auth.md's.
"""

from dataclasses import dataclass
from typing import Annotated

from fastapi import Depends, HTTPException
from fastapi.security import HTTPAuthorizationCredentials, HTTPBearer

from glasshead.accounts import valid_child_token, valid_token
from glasshead.api.error_responses import Responses
from glasshead.store.lessons import Child
from glasshead.store.session import SessionDep
from glasshead.store.users import ROLES, AuthToken, ChildToken, User

#: The security scheme in the OpenAPI document; a missing or malformed header is our own 401.
bearer = HTTPBearer(auto_error=False, scheme_name="bearerToken",
                    description="a token from POST /auth/sessions")

#: The 401 of a route that needs a signed-in user, for its ``responses``.
UNAUTHENTICATED: Responses = {401: {
    "description": "no valid bearer token: missing, unknown, expired or revoked (sign in again "
                   "with POST /auth/sessions)",
    "headers": {"WWW-Authenticate": {"description": "Bearer", "schema": {"type": "string"}}}}}
#: The 403 of a route limited to some roles.
FORBIDDEN: Responses = {403: {
    "description": "the signed-in user's role may not do this (detail names the roles that may), "
                   "or a write from another site"}}

NOT_SIGNED_IN = "not signed in: send Authorization: Bearer <token> from POST /auth/sessions; " \
                "a token that has expired or was signed out is refused too"


def current_token(session: SessionDep,
                  credentials: Annotated[HTTPAuthorizationCredentials | None,
                                         Depends(bearer)]) -> AuthToken:
    """The stored token the request came with; 401 when there is no valid one."""
    record = valid_token(session, credentials.credentials) if credentials else None
    if record is None:
        raise HTTPException(status_code=401, detail=NOT_SIGNED_IN,
                            headers={"WWW-Authenticate": "Bearer"})
    return record


CurrentToken = Annotated[AuthToken, Depends(current_token)]


def current_user(token: CurrentToken) -> User:
    return token.user


CurrentUser = Annotated[User, Depends(current_user)]


NOT_SIGNED_IN_CHILD = "not signed in as a child: send Authorization: Bearer <token> from " \
                      "POST /auth/child-sessions; a token that has expired or was signed out " \
                      "is refused too"


def current_child_token(session: SessionDep,
                        credentials: Annotated[HTTPAuthorizationCredentials | None,
                                               Depends(bearer)]) -> ChildToken:
    """The stored child's token the request came with; 401 when there is no valid one (a
    user's token is not a child's)."""
    record = valid_child_token(session, credentials.credentials) if credentials else None
    if record is None:
        raise HTTPException(status_code=401, detail=NOT_SIGNED_IN_CHILD,
                            headers={"WWW-Authenticate": "Bearer"})
    return record


CurrentChildToken = Annotated[ChildToken, Depends(current_child_token)]


def current_child(token: CurrentChildToken) -> Child:
    return token.child


CurrentChild = Annotated[Child, Depends(current_child)]


#: Every role of a user: any signed-in adult.
ADULTS = ROLES
#: Who may call a route: a user's role, or ``"child"`` for a child signed in with a join code.
CALLERS = (*ROLES, "child")


@dataclass(frozen=True)
class Person:
    """Who sent the request: a user or a child (exactly one)."""

    user: User | None = None
    child: Child | None = None

    @property
    def role(self) -> str:
        return "child" if self.child is not None else self.user.role

    @property
    def is_admin(self) -> bool:
        return self.user is not None and self.user.role == "admin"

    def describe(self) -> str:
        if self.child is not None:
            return f"child {self.child.id}"
        return f"{self.user.username} is {self.user.role}"


def current_person(session: SessionDep,
                   credentials: Annotated[HTTPAuthorizationCredentials | None,
                                          Depends(bearer)]) -> Person:
    """The user or the child whose token the request came with; 401 when there is neither."""
    if credentials is not None:
        if (token := valid_token(session, credentials.credentials)) is not None:
            return Person(user=token.user)
        if (child_token := valid_child_token(session, credentials.credentials)) is not None:
            return Person(child=child_token.child)
    raise HTTPException(status_code=401, detail=NOT_SIGNED_IN,
                        headers={"WWW-Authenticate": "Bearer"})


CurrentPerson = Annotated[Person, Depends(current_person)]


def allow(*callers: str):
    """A dependency giving the current person when they are one of ``callers`` (roles, and
    ``"child"``), else 403 naming who may."""
    unknown = set(callers) - set(CALLERS)
    if not callers or unknown:
        raise ValueError(f"allow needs callers from {CALLERS}, not {sorted(unknown)}")

    def person_allowed(person: CurrentPerson) -> Person:
        if person.role not in callers:
            raise HTTPException(status_code=403,
                                detail=f"this needs the role {' or '.join(callers)}; "
                                       f"{person.describe()}")
        return person

    person_allowed.__name__ = f"allow_{'_or_'.join(callers)}"
    return person_allowed


def require_role(*roles: str):
    """A dependency giving the current user when their role is one of ``roles``, else 403 (a
    child's token too: it is valid, only not for this)."""
    if not roles or set(roles) - set(ROLES):
        raise ValueError(f"require_role needs roles from {ROLES}, not {roles}")
    allowed = allow(*roles)

    def user_with_role(person: Annotated[Person, Depends(allowed)]) -> User:
        return person.user

    user_with_role.__name__ = f"require_{'_or_'.join(roles)}"
    return user_with_role


AdminUser = Annotated[User, Depends(require_role("admin"))]


#: Any signed-in adult (a user of any role).
SignedInUser = Annotated[User, Depends(require_role(*ADULTS))]
