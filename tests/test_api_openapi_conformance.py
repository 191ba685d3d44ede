"""Generated requests against the OpenAPI document: the server answers as the document says.

schemathesis (4.x) reads /api/v1/openapi.json from the app in this process and sends each
operation requests made from its schema, valid and invalid ones. Every answer is checked: no
server error, a documented status code, a documented content type, and a body that matches the
documented schema (every error is ``{"detail": string}``, api/error_responses.py). Bounded and
repeatable: at most MAX_EXAMPLES cases per operation, derandomized, so each run sends the same
requests. The app runs on the built assets and a fresh SQLite database, as the server does.

The operations that need a token are called with one (tests/route_roles.json says who may): a
new admin's for each operation (so that a case that signs out, demotes or removes its caller
leaves the next operation its own), a child's for the child's session routes; the open
operations without one, as the head calls them. Answers without a token are the role test's
(tests/test_api_roles.py).

Left out, because a unit test cannot read it to the end: GET /fits/{fit_id}/events, a
server-sent events stream that stays open while its fit runs (tests/test_api_fits.py covers it).
"""

import json
from pathlib import Path

import pytest
import schemathesis
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from schemathesis import GenerationMode
from schemathesis.checks import not_a_server_error
from schemathesis.python.asgi import shutdown_lifespans
from schemathesis.specs.openapi.checks import (
    content_type_conformance,
    response_schema_conformance,
    status_code_conformance,
)
from sqlalchemy.orm import Session

from accounts_support import add_user, child_token_for, header, token_for
from glasshead.settings import get_settings
from glasshead.store.db import engine_for, upgrade_to_head
from glasshead.store.lessons import Child, SchoolClass

#: Cases per operation, valid and invalid together; about 40 operations.
MAX_EXAMPLES = 25
CHECKS = [not_a_server_error, status_code_conformance, content_type_conformance,
          response_schema_conformance]
#: Seconds a request may take: the first one to a compute route starts its worker process
#: (numpy imported at niceness +10), which took over 10 s, schemathesis' default, on busy cores.
REQUEST_TIMEOUT_S = 60
#: Operations that cannot run in a unit test (see the module's docstring).
EXCLUDED = {"streamFitEvents"}
CONTRACT = json.loads((Path(__file__).parent / "api-contract.json").read_text())
ROLE_TABLE = json.loads((Path(__file__).parent / "route_roles.json").read_text())
OPERATION_IDS = sorted({op["operationId"] for op in CONTRACT["operations"]} - EXCLUDED)


@pytest.fixture(scope="module")
def api_schema(tmp_path_factory, built_assets):
    from glasshead.api.app import create_app

    folder = tmp_path_factory.mktemp("schemathesis")
    with pytest.MonkeyPatch.context() as env:
        env.setenv("GLASSHEAD_ASSETS_DIR", str(built_assets))
        url = f"sqlite:///{folder / 'app.sqlite3'}"
        env.setenv("GLASSHEAD_DATABASE_URL", url)
        env.setenv("GLASSHEAD_WEB_DIST_DIR", str(folder / "no-web"))
        env.setenv("GLASSHEAD_SPEECH_CACHE_DIR", str(folder / "utterances"))
        env.setenv("GLASSHEAD_COMPUTE_WORKERS", "1")
        get_settings.cache_clear()
        app = create_app()
        upgrade_to_head(engine_for(url))  # as the app's start does, for the callers below
        yield schemathesis.openapi.from_asgi("/api/v1/openapi.json", app), engine_for(url)
        shutdown_lifespans()  # the app's lifespan (fit and compute workers) ends here
        get_settings.cache_clear()


def caller_headers(operation_id: str, engine) -> dict:
    """The Authorization header to call ``operation_id`` with: none for an open operation, a
    child's for a child's, else a new admin's."""
    allowed = ROLE_TABLE[operation_id]
    if allowed == "open":
        return {}
    if allowed == ["child"]:
        with Session(engine) as session:
            school_class = SchoolClass(name=operation_id, join_code=operation_id[:6].upper())
            session.add(school_class)
            session.flush()
            child = Child(class_id=school_class.id, display_name="Ada", avatar="owl")
            session.add(child)
            session.commit()
            return header(child_token_for(child.id, engine))
    return header(token_for(add_user("admin", engine=engine), engine))


def test_every_operation_the_server_documents_is_generated_for_or_excluded(api_schema):
    api_schema, _ = api_schema
    served = {result.ok().label: result.ok() for result in api_schema.get_all_operations()}
    ids = {operation.definition.raw.get("operationId") for operation in served.values()}
    assert ids == set(OPERATION_IDS) | EXCLUDED


@pytest.mark.parametrize("operation_id", OPERATION_IDS)
def test_every_generated_request_is_answered_as_the_openapi_document_says(api_schema,
                                                                         operation_id):
    api_schema, engine = api_schema
    operation = api_schema.find_operation_by_id(operation_id)
    headers = caller_headers(operation_id, engine)
    cases = st.one_of(operation.as_strategy(GenerationMode.POSITIVE),
                      operation.as_strategy(GenerationMode.NEGATIVE))

    @given(case=cases)
    @settings(max_examples=MAX_EXAMPLES, derandomize=True, deadline=None, database=None,
              suppress_health_check=list(HealthCheck))
    def answered_as_documented(case):
        case.call_and_validate(checks=CHECKS, headers=headers, timeout=REQUEST_TIMEOUT_S)

    answered_as_documented()
