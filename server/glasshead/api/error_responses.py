"""What the API answers when a request fails, and an OpenAPI document that says so.

Every error body is ``{"detail": "<one readable sentence>"}`` (a 503 for a missing asset adds
the asset, file, problem and rebuild command): ``app.py``'s handlers make it so, including for
validation errors, whose ``detail`` FastAPI would otherwise send as an array. FastAPI's generated
document declares that array (``HTTPValidationError``) and leaves out every other error, so
``install_error_responses`` has it rewritten once, when it is first asked for:

- the one ``Error`` schema for every 4xx and 5xx it documents;
- 400 on every operation (a Host not allowed, a body that cannot be parsed); 401 on every
  operation that needs a bearer token and 403 on every one limited to some roles
  (``api/auth.py``'s dependencies); 403 on every write (a cross-site Origin,
  ``api/security.py``); 422 on every operation that takes a
  parameter or a body; 404 on every operation with a path parameter (the id or name may name
  nothing); 413 on every operation with a body (past its limit, ``api/limits.py``); 503 on every
  operation that needs the built assets or the compute pool; 502 and 504 on every operation
  of the compute pool (a worker that died, a computation past its limit);
- a route's own ``responses`` (409, 412, 415, a 503 for a full queue) keep their descriptions
  and gain the schema.

A known path with a method it does not take answers 405 with ``Allow`` (``method_not_allowed``),
not the 404 of a path that names nothing.
"""

import importlib
from typing import Any

from fastapi import FastAPI, HTTPException, Request
from fastapi.routing import APIRoute
from starlette.routing import Match

#: The name of the shared error schema in ``components.schemas``.
ERROR_SCHEMA_NAME = "Error"
#: A route's ``responses``: by status code, what the OpenAPI document says of the answer.
Responses = dict[int | str, dict[str, Any]]

ERROR_SCHEMA = {
    "title": ERROR_SCHEMA_NAME,
    "type": "object",
    "required": ["detail"],
    "properties": {"detail": {"type": "string", "description": (
        "what was wrong, naming the field, frame or resource, e.g. \"body.params.tip_height: "
        "Input should be a valid number\"")}},
}

#: The generic errors and when an operation can answer them.
DESCRIPTIONS = {
    "400": "the Host is not one the server answers to (GLASSHEAD_ALLOWED_HOSTS), or the body "
           "cannot be read as its media type (JSON that is not UTF-8, a broken multipart form)",
    "401": "no valid bearer token: missing, unknown, expired or revoked (sign in with POST "
           "/auth/sessions, or POST /auth/child-sessions for a child); WWW-Authenticate: Bearer",
    "403": "a write from another site: its Origin is not this server's (docs/api.md)",
    "404": "nothing has that id or name",
    "413": "the body is past the operation's size limit (docs/api.md), refused as it streams in",
    "422": "a parameter or the body is not valid; detail names the field and the problem",
    "502": "the worker process that served the request died before it answered (a fault in "
           "native code, a signal, out of memory); detail names what it was doing. It has "
           "been replaced: retry, or change the request if it fails again",
    "504": "the computation ran past its time limit and was stopped with its worker",
    "503": "a built asset the operation needs is missing or corrupt (rebuild with glasshead "
           "build), or the compute queue is full (Retry-After gives the seconds to wait)",
}

#: Dependencies (by function name) whose operations can answer 503: the asset store raises
#: AssetUnavailableError for a missing asset; the compute pool refuses work when it is full.
UNAVAILABLE_DEPENDENCIES = frozenset({"get_asset_store", "get_compute_pool"})
#: Dependencies whose operations run in a worker process: 502 when it dies, 504 past its limit.
WORKER_DEPENDENCIES = frozenset({"get_compute_pool"})

#: Operations that read the asset store without failing: /health reports a missing asset in its
#: body, with 200.
NEVER_UNAVAILABLE = frozenset({"getHealth"})
#: Dependencies (by function name) that take a bearer token: their operations can answer 401.
TOKEN_DEPENDENCIES = frozenset({"current_token", "current_child_token", "current_person"})
#: The 403 of an operation limited to some roles (``allow`` and ``require_role`` name their
#: dependencies allow_... and require_...).
ROLE_FORBIDDEN = ("the signed-in caller's role may not do this (detail names who may), or the "
                  "record is another's to change; on a write also: its Origin is not this "
                  "server's (docs/api.md)")
#: Methods that a cross-site request may not use (api/security.py answers 403).
WRITE_METHODS = frozenset({"POST", "PUT", "PATCH", "DELETE"})
#: FastAPI's validation-error schemas, replaced by ``Error``.
_FASTAPI_ERROR_SCHEMAS = ("HTTPValidationError", "ValidationError")


def install_error_responses(app: FastAPI, prefix: str, module_names: list[str]) -> None:
    """Document the errors in ``app.openapi()`` and let ``unknown_path_error`` tell 405 from
    404; the API routes are the ``router`` of each module under glasshead.api.routes, included
    under ``prefix``."""
    routes = [route for name in module_names
              for route in importlib.import_module(f"glasshead.api.routes.{name}").router.routes
              if isinstance(route, APIRoute)]
    app.state.api_routes = (prefix, routes)
    generate = app.openapi

    def openapi() -> dict:
        if app.openapi_schema is None:
            document = generate()
            _rewrite(document, {(prefix + route.path_format, method.lower()): route
                                for route in routes for method in route.methods})
            app.openapi_schema = document
        return app.openapi_schema

    app.openapi = openapi  # type: ignore[method-assign]


def _rewrite(document: dict, routes: dict[tuple[str, str], APIRoute]) -> None:
    schemas = document.setdefault("components", {}).setdefault("schemas", {})
    for name in _FASTAPI_ERROR_SCHEMAS:
        schemas.pop(name, None)
    schemas[ERROR_SCHEMA_NAME] = ERROR_SCHEMA
    for path, operations in document.get("paths", {}).items():
        for method, operation in operations.items():
            route = routes.get((path, method))
            for status in _generic_errors(operation, route):
                operation["responses"].setdefault(status, {"description": DESCRIPTIONS[status]})
            for status, response in operation["responses"].items():
                if status[:1] in ("4", "5"):
                    response["content"] = {"application/json": {
                        "schema": {"$ref": f"#/components/schemas/{ERROR_SCHEMA_NAME}"}}}


def _generic_errors(operation: dict, route: APIRoute | None) -> list[str]:
    parameters = operation.get("parameters", [])
    has_body = "requestBody" in operation
    errors = ["400"]  # any request: the Host allow-list (api/security.py)
    if route is not None and _depends_on(route.dependant, TOKEN_DEPENDENCIES):
        errors.append("401")
    if route is not None and _limited_to_roles(route.dependant):
        operation["responses"].setdefault("403", {"description": ROLE_FORBIDDEN})
    if route is not None and route.methods & WRITE_METHODS:
        errors.append("403")
    if any(p.get("in") == "path" for p in parameters):
        errors.append("404")
    if has_body:
        errors.append("413")
    if parameters or has_body:
        errors.append("422")
    if (route is not None and operation.get("operationId") not in NEVER_UNAVAILABLE
            and _depends_on(route.dependant, UNAVAILABLE_DEPENDENCIES)):
        errors.append("503")
    if route is not None and _depends_on(route.dependant, WORKER_DEPENDENCIES):
        errors.extend(["502", "504"])
    return errors


def _depends_on(dependant, names: frozenset[str]) -> bool:
    return any(getattr(d.call, "__name__", None) in names or _depends_on(d, names)
               for d in dependant.dependencies)


def _limited_to_roles(dependant) -> bool:
    return any(getattr(d.call, "__name__", "").startswith(("allow_", "require_"))
               or _limited_to_roles(d) for d in dependant.dependencies)


def allowed_methods(app: FastAPI, path: str) -> list[str]:
    """The methods of the API routes whose path matches ``path`` (none: the path is unknown)."""
    prefix, routes = app.state.api_routes
    if not path.startswith(prefix):
        return []
    scope = {"type": "http", "path": path[len(prefix):], "method": "GET", "root_path": ""}
    methods: set[str] = set()
    for route in routes:
        if route.matches(scope)[0] != Match.NONE:
            methods |= route.methods
    return sorted(methods)


def unknown_path_error(app: FastAPI, request: Request) -> HTTPException:
    """405 with ``Allow`` for a known path and another method, else 404 naming the path (for
    the catch-all route that answers whatever no other API route takes)."""
    path = request.url.path
    allowed = allowed_methods(app, path)
    if allowed:
        return HTTPException(status_code=405, headers={"Allow": ", ".join(allowed)},
                             detail=f"{request.method} is not allowed on {path}; "
                                    f"use {', '.join(allowed)}")
    return HTTPException(status_code=404, detail=f"no API resource at {path}")
