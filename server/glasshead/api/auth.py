"""Who is asking: the bearer-token dependencies of the routes that need a signed-in user.

``CurrentUser`` is the user whose token came in ``Authorization: Bearer <token>``; a token that
is missing, unknown, expired or revoked is a 401 with ``WWW-Authenticate: Bearer`` (RFC 6750
section 3), and the same sentence for all four, so a caller learns nothing about other people's
tokens. ``require_role(*roles)`` narrows it to those roles, with a 403 that names them.
``CurrentChild`` is the same for a child signed in with their class's join code.

Only the routes that manage users and sessions use these for now; the other routes stay open
until each is given its roles (docs/auth.md).
"""

from typing import Annotated

from fastapi import Depends, HTTPException
from fastapi.security import HTTPAuthorizationCredentials, HTTPBearer

from glasshead.accounts import valid_child_token, valid_token
from glasshead.store.lessons import Child
from glasshead.store.session import SessionDep
from glasshead.store.users import AuthToken, ChildToken, User

#: The security scheme in the OpenAPI document; a missing or malformed header is our own 401.
bearer = HTTPBearer(auto_error=False, scheme_name="bearerToken",
                    description="a token from POST /auth/sessions")

#: The 401 of a route that needs a signed-in user, for its ``responses``.
UNAUTHENTICATED = {401: {
    "description": "no valid bearer token: missing, unknown, expired or revoked (sign in again "
                   "with POST /auth/sessions)",
    "headers": {"WWW-Authenticate": {"description": "Bearer", "schema": {"type": "string"}}}}}
#: The 403 of a route limited to some roles.
FORBIDDEN = {403: {"description": "the signed-in user's role may not do this (detail names the "
                                  "roles that may), or a write from another site"}}

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


def require_role(*roles: str):
    """A dependency giving the current user when their role is one of ``roles``, else 403."""
    if not roles:
        raise ValueError("require_role needs at least one role")

    def user_with_role(user: CurrentUser) -> User:
        if user.role not in roles:
            raise HTTPException(status_code=403,
                                detail=f"this needs the role {' or '.join(roles)}; "
                                       f"{user.username} is {user.role}")
        return user

    user_with_role.__name__ = f"require_{'_or_'.join(roles)}"
    return user_with_role


AdminUser = Annotated[User, Depends(require_role("admin"))]


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
