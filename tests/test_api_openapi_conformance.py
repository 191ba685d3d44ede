"""Generated requests against the OpenAPI document: the server answers as the document says.

schemathesis (4.x) reads /api/v1/openapi.json from the app in this process and runs its engine,
the one behind ``schemathesis run``, with its phases:

- examples: the document's own examples;
- coverage: each parameter and body field at its boundaries and just past them (the longest
  string, one character more, the largest integer, a missing required field, a wrong type, a
  method the path does not take...), the phase that once found that 60 digits of text killed
  the server;
- fuzzing: random requests, valid and invalid;
- stateful: sequences that follow the links between operations, which schemathesis infers from
  the responses' fields (``POST /poses`` answers ``id``, which ``PATCH /poses/{pose_id}`` takes),
  so that the operations that take an id are called with a real one. They are made within each
  of STATEFUL_GROUPS, after ``seed`` has sent the documented examples of the group's creating
  operations (a generated body makes no EPG recording or fit).

Every answer is checked: no server error (no 5xx at all: a worker that died is a 502, a
computation past its limit a 504), a documented status code, a documented content type, and a
body that matches the documented schema (every error is ``{"detail": string}``,
api/error_responses.py). A request left without an answer, an error inside the engine (an
exception out of the app), or a phase that could not run fails the test as well.

Callers: no token, each role of tests/route_roles.json (author, teacher, clinician, admin) and a
child. Each runs every phase on the operations it may call (the open ones without a token), and
the examples and a few random requests on every other operation: its refusal (401 or 403) is
checked like any other answer, and an open operation answers it as it answers anyone. A caller's
token is renewed whenever a request has ended it (signed it out, deleted or demoted its user,
deleted its child), so that one operation does not leave the next ones unauthorised. The child
is in a class with an assignment.

Repeatable: generation is derandomized with a fixed seed, so each run sends the same requests
(answers may still differ where the server draws at random: tokens, join codes). Bounded: SUITE
takes under 3 minutes of one core. To stay there it leaves out, in the coverage phase, the
invalid requests of the author, teacher and clinician (validation refuses them as it refuses the
admin's, whose run sends them to every operation a role may call) and the unexpected methods
with a token (the 405 comes before the token is read). BENCH is the scale of a longer run,
without these cuts. The app runs on the built assets, a new SQLite database, one compute
worker and no fit worker (fits are queued, not run; tests/test_api_fits.py runs them); of GET
/fits/{fit_id}/events, whose stream stays open while its fit waits, the first event is read.

Texts are narrowed here to MAX_TEXT_CHARS characters: a text of 500 digits takes about 3 s of
CPU to speak, and random requests would spend much of this suite's time speaking; 60 digits,
the text that once killed the server, is within the bound. BENCH sends them at full length.
"""

import contextlib
import copy
import json
import time
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

import pytest
import schemathesis
from schemathesis.engine import events, from_schema
from schemathesis.python import asgi
from schemathesis.python.asgi import shutdown_lifespans
from sqlalchemy.orm import Session

from accounts_support import add_user, child_token_for, token_for
from glasshead import accounts
from glasshead.api.routes.classes import new_join_code
from glasshead.jobs.compute import TASK_TIMEOUT_S
from glasshead.settings import get_settings
from glasshead.store.db import engine_for, upgrade_to_head
from glasshead.store.lessons import Assignment, Child, Lesson, SchoolClass
from glasshead.store.users import User

OPENAPI = "/api/v1/openapi.json"
CONTRACT = json.loads((Path(__file__).parent / "api-contract.json").read_text())
ROLE_TABLE = json.loads((Path(__file__).parent / "route_roles.json").read_text())
OPERATION_IDS = sorted(op["operationId"] for op in CONTRACT["operations"])
#: operationId -> the first segment of its path after /api/v1/.
OPERATION_GROUPS = {op["operationId"]: op["path"].split("/")[3] for op in CONTRACT["operations"]}
CALLERS = ("anonymous", "author", "teacher", "clinician", "admin", "child")
PHASES = ("examples", "coverage", "fuzzing", "stateful")
CHECKS = ("not_a_server_error", "status_code_conformance", "content_type_conformance",
          "response_schema_conformance")
SEED = 27
#: Longest text sent to POST /utterances (see the module docstring).
MAX_TEXT_CHARS = 100
#: Seconds a request may take: past the compute pool's own limit, after which the server answers
#: 504 itself; so a request without an answer is the server's fault, not a slow machine's.
REQUEST_TIMEOUT_S = TASK_TIMEOUT_S + 30
#: Events of GET /fits/{fit_id}/events read (checked, then the stream is closed): its first,
#: sent at once, is the fit's state; the stream stays open while the fit waits.
STREAM_EVENTS = 1
#: The operations whose answers feed each other's requests, by the first segment of their path
#: (stateful sequences are made within each group, so that they are long enough to reach the
#: operations that take an id).
STATEFUL_GROUPS = {
    "poses": {"poses"},
    "EPG recordings": {"epg"},
    "fits": {"fits", "observations"},
    "utterances": {"utterances"},
    "accounts": {"auth", "users"},
    "lessons": {"lessons"},
    "classes": {"classes", "children"},
    "assignments and practice": {"assignments", "practice"},
}
#: The methods the coverage phase sends where they are not taken (a 405 with Allow), as no
#: token only: the answer comes before the token is read.
UNEXPECTED_METHODS = ["GET", "PUT", "POST", "DELETE", "OPTIONS", "PATCH", "TRACE"]
#: How many records of each kind ``seed`` makes before a group's stateful sequences.
SEED_COPIES = 3

# An attempt's recording (PUT /practice/{id}/audio): the body is the WAV file's bytes. Generated
# bodies are bytes (the schema's binary string); the document's example, text that says what the
# bytes are, is sent as its UTF-8 bytes, which the server refuses as no WAV. tests/
# test_api_practice_audio.py sends real WAV files, good and bad.
@schemathesis.serializer("audio/wav")
def _wav_body(_context, value) -> bytes:
    return value if isinstance(value, bytes) else str(value).encode()


@dataclass(frozen=True)
class Scale:
    """How much to send: ``examples`` cases per operation and phase on the operations a caller
    is tested in full on (``is_tested_in_full``), ``other_examples`` on the others, ``scenarios``
    stateful sequences of at most ``steps`` requests per caller and group of STATEFUL_GROUPS."""

    examples: int
    other_examples: int
    scenarios: int
    steps: int = 8
    #: The callers whose coverage phase sends invalid requests too (the others', valid ones
    #: only: an invalid request is refused by the same validation whoever sends it, which the
    #: admin's run covers on every operation a role may call).
    invalid_coverage: tuple = CALLERS
    narrow_text: bool = True


SUITE = Scale(examples=6, other_examples=2, scenarios=8,
              invalid_coverage=("anonymous", "admin", "child"))
BENCH = Scale(examples=200, other_examples=5, scenarios=50, steps=12, narrow_text=False)


def is_tested_in_full(caller: str, operation_id: str) -> bool:
    """Whether ``caller`` runs every phase on ``operation_id``: the open operations without a
    token, the others for the roles route_roles.json names (the operations it may call)."""
    allowed = ROLE_TABLE[operation_id]
    if caller == "anonymous":
        return allowed == "open"
    return allowed != "open" and caller in allowed


@dataclass
class Outcome:
    """What one caller's run sent and found."""

    caller: str
    operations: set = field(default_factory=set)
    cases: Counter = field(default_factory=Counter)  # requests sent, by phase
    statuses: Counter = field(default_factory=Counter)
    #: (operation label, status) of the stateful steps that took a parameter from an earlier
    #: answer (a link).
    linked: Counter = field(default_factory=Counter)
    failures: dict = field(default_factory=dict)  # (operation, title, status) -> description
    errors: dict = field(default_factory=dict)  # (where, title, message) -> description
    seconds: float = 0.0

    def problems(self) -> list[str]:
        return [*self.failures.values(), *self.errors.values()]

    def error(self, where: str, title: str, message: str = "", sample: str | None = None):
        self.errors.setdefault((where, title, message), f"[{self.caller}] {where}: {title}"
                               + (f": {message}" if message else "")
                               + (f"\n{sample}" if sample else ""))

    def reached(self) -> set:
        """The operations a stateful step called with a value from an earlier answer and got
        a 2xx from."""
        return {label for label, status in self.linked if 200 <= status < 300}


def id_operations(caller: str) -> set:
    """The labels ("PATCH /api/v1/poses/{pose_id}") of the operations with a path parameter
    that ``caller`` is tested in full on."""
    return {f"{op['method']} {op['path']}" for op in CONTRACT["operations"]
            if "{" in op["path"] and is_tested_in_full(caller, op["operationId"])}


class CallerTokens:
    """A valid bearer token of one caller, renewed when a request has ended the last one."""

    def __init__(self, caller: str, engine):
        self.caller = caller
        self.engine = engine
        self.token: str | None = None
        self.class_id: int | None = None

    def current(self) -> str:
        with Session(self.engine) as session:
            if self.caller == "child":
                record = self.token and accounts.valid_child_token(session, self.token)
                alive = record is not None and session.get(Child, record.child_id) is not None
            else:
                record = self.token and accounts.valid_token(session, self.token)
                user = record and session.get(User, record.user_id)
                alive = user is not None and user.role == self.caller
        if not alive:
            self.token = (child_token_for(self._new_child(), self.engine)
                          if self.caller == "child"
                          else token_for(add_user(self.caller, engine=self.engine), self.engine))
        return self.token

    def _new_child(self) -> int:
        """A new child in this caller's class (made with a teacher and an assignment of the first
        lesson the first time, or again if it was deleted)."""
        with Session(self.engine) as session:
            if self.class_id is None or session.get(SchoolClass, self.class_id) is None:
                teacher = add_user("teacher", engine=self.engine)
                school_class = SchoolClass(name="Owls", join_code=new_join_code(),
                                           owner_id=teacher)
                session.add(school_class)
                session.flush()
                lesson = session.query(Lesson).order_by(Lesson.id).first()
                if lesson is not None:
                    session.add(Assignment(lesson_id=lesson.id, class_id=school_class.id))
                self.class_id = school_class.id
            child = Child(class_id=self.class_id, display_name="Ada", avatar="owl")
            session.add(child)
            session.commit()
            return child.id


@contextlib.contextmanager
def app_for_fuzzing(folder: Path, assets_dir: Path):
    """(app, database engine): the app on ``assets_dir`` and a new SQLite database in
    ``folder``, as the server starts it; its lifespan (started by the first request) is ended
    on leaving."""
    from glasshead.api.app import create_app

    with pytest.MonkeyPatch.context() as env:
        url = f"sqlite:///{folder / 'app.sqlite3'}"
        for name, value in {"ASSETS_DIR": str(assets_dir), "DATABASE_URL": url,
                            "WEB_DIST_DIR": str(folder / "no-web"),
                            "SPEECH_CACHE_DIR": str(folder / "utterances"),
                            "COMPUTE_WORKERS": "1", "FIT_WORKERS": "0",
                            "FIT_QUEUE_LIMIT": "10000",
                            "ALLOWED_HOSTS": "testserver"}.items():
            env.setenv(f"GLASSHEAD_{name}", value)
        get_settings.cache_clear()
        try:
            app = create_app()
            engine = engine_for(url)
            upgrade_to_head(engine)  # as the app's start does, for the tokens made here
            yield app, engine
        finally:
            shutdown_lifespans()
            get_settings.cache_clear()


def _document(app, scale: Scale) -> dict:
    document = json.loads(json.dumps(app.openapi()))
    if scale.narrow_text:
        text = document["components"]["schemas"]["UtteranceRequest"]["properties"]["text"]
        for option in text["anyOf"]:
            if option.get("type") == "string":
                option["maxLength"] = MAX_TEXT_CHARS
    return document


def _config(caller: str, scale: Scale, phases: tuple, operation_ids: list) -> schemathesis.Config:
    others = [op for op in OPERATION_IDS if not is_tested_in_full(caller, op)]
    left_out = [op for op in OPERATION_IDS if op not in operation_ids]
    operations = [{"include-operation-id": "streamFitEvents", "max-stream-events": STREAM_EVENTS}]
    if left_out:
        operations.append({"include-operation-id": left_out, "enabled": False})
    if others:
        operations.append({"include-operation-id": others,
                           "generation": {"max-examples": scale.other_examples},
                           "phases": {"coverage": {"enabled": False}}})
    return schemathesis.Config.from_dict({
        "seed": SEED,
        "workers": 1,
        "request-timeout": REQUEST_TIMEOUT_S,
        "generation": {"max-examples": scale.examples, "deterministic": True,
                       "database": "none"},
        "checks": {"enabled": False, **{name: {"enabled": True} for name in CHECKS}},
        "phases": {name: {"enabled": name in phases} for name in PHASES}
        | {"coverage": {"enabled": "coverage" in phases,
                        "unexpected-methods": UNEXPECTED_METHODS if caller == "anonymous" else [],
                        "generation": {"mode": "all" if caller in scale.invalid_coverage
                                       else "positive"}},
           "stateful": {"enabled": "stateful" in phases, "max-steps": scale.steps,
                        "generation": {"max-examples": scale.scenarios,
                                       "mode": "positive"}}},
        "operations": operations,
    })


def fuzz(app, engine, caller: str, scale: Scale, phases: tuple = PHASES) -> Outcome:
    """Run the schemathesis engine as ``caller`` at ``scale``: the unit phases of ``phases``
    on every operation (all of them on those ``caller`` may call, the examples and fuzzing on
    the others), then the stateful phase on each of STATEFUL_GROUPS, limited to the operations
    ``caller`` may call, after seeding the group (``seed``)."""
    outcome = Outcome(caller)
    started = time.process_time()
    tokens = None if caller == "anonymous" else CallerTokens(caller, engine)
    document = _document(app, scale)
    unit = tuple(p for p in phases if p != "stateful")
    if unit:
        _run(app, document, _config(caller, scale, unit, OPERATION_IDS), tokens, outcome)
    if "stateful" in phases:
        for group in STATEFUL_GROUPS.values():
            members = [op for op in OPERATION_IDS
                       if OPERATION_GROUPS[op] in group and is_tested_in_full(caller, op)]
            if members:
                seed(app, document, members, tokens, outcome)
                _run(app, document, _config(caller, scale, ("stateful",), members), tokens,
                     outcome)
    outcome.seconds = time.process_time() - started
    return outcome


def _run(app, document: dict, config, tokens, outcome: Outcome) -> None:
    schema = schemathesis.openapi.from_dict(copy.deepcopy(document), config=config)
    schema.app = app
    schema.location = OPENAPI
    if tokens is not None:
        _sign_requests(schema, tokens)
    for event in from_schema(schema).execute():
        _record(outcome, event)


def seed(app, document: dict, operation_ids: list, tokens, outcome: Outcome) -> None:
    """Send the first documented example of each POST operation among ``operation_ids`` that
    makes a record SEED_COPIES times: records for the stateful sequences to find through the
    list operations, where a generated body would not make one (an EPG recording's or a fit's
    file). A server error among their answers is one of ``outcome``'s problems."""
    headers = {} if tokens is None else {"Authorization": f"Bearer {tokens.current()}"}
    with asgi.get_client(app) as client:
        for path, item in document["paths"].items():
            operation = item.get("post")
            if operation is None or operation["operationId"] not in operation_ids \
                    or "{" in path:
                continue
            request = _example_request(document, operation.get("requestBody", {}))
            for _ in range(SEED_COPIES if request else 0):
                answer = client.post(f"http://{asgi.HOST}{path}", headers=headers, **request)
                if answer.status_code >= 500:
                    outcome.error(f"seed POST {path}", str(answer.status_code), answer.text[:500])


def _example_request(document: dict, body: dict) -> dict:
    """requests' keyword arguments for a request body's first example: JSON, or a form whose
    file fields (contentMediaType) are sent as files; {} without an example."""
    def resolve(schema: dict) -> dict:
        if "$ref" in schema:
            return document["components"]["schemas"][schema["$ref"].split("/")[-1]]
        return schema

    content = body.get("content", {})
    if "application/json" in content:
        examples = resolve(content["application/json"]["schema"]).get("examples", [])
        return {"json": examples[0]} if examples else {}
    form = content.get("multipart/form-data", {})
    if "example" not in form:
        return {}
    fields = resolve(form["schema"]).get("properties", {})
    files, data = {}, {}
    for name, value in form["example"].items():
        options = fields.get(name, {}).get("anyOf", [fields.get(name, {})])
        if any("contentMediaType" in option or option.get("format") == "binary"
               for option in options):
            files[name] = (name, str(value).encode())
        else:
            data[name] = str(value)
    return {"files": files, "data": data}


def _sign_requests(schema, tokens: CallerTokens) -> None:
    @schema.auth(refresh_interval=None)
    class Bearer:
        def get(self, case, context):
            return tokens.current()

        def set(self, case, token, context):
            case.headers = {**(case.headers or {}), "Authorization": f"Bearer {token}"}


def _record(outcome: Outcome, event) -> None:
    if isinstance(event, events.ScenarioFinished) and event.is_test_scenario:
        recorder = event.recorder
        for case_id, interaction in recorder.interactions.items():
            node = recorder.cases.get(case_id)
            label = node.value.operation.label if node else recorder.label
            outcome.operations.add(label)
            outcome.cases[event.phase.value] += 1
            if interaction.response is None:
                outcome.error(label, "no answer", f"{interaction.request.method} "
                              f"{interaction.request.uri} "
                              f"{(interaction.request.body or b'')[:300]!r}")
                continue
            outcome.statuses[interaction.response.status_code] += 1
            if node is not None and node.transition is not None and node.is_transition_applied:
                outcome.linked[(label, interaction.response.status_code)] += 1
        for case_id, checks in recorder.checks.items():
            for check in checks:
                if check.failure_info is None:
                    continue
                failure = check.failure_info.failure
                interaction = recorder.interactions.get(case_id)
                response = interaction.response if interaction else None
                status = response.status_code if response else None
                key = (failure.operation, failure.title, status)
                outcome.failures.setdefault(key, (
                    f"[{outcome.caller}, {event.phase.value}] {failure.operation}: "
                    f"{failure.title} ({status})\n{failure.message}\n"
                    f"{check.failure_info.code_sample}\n"
                    f"-> {(response.content or b'')[:500] if response else b''!r}"))
    elif isinstance(event, events.NonFatalError):
        outcome.error(f"{event.phase and event.phase.value} {event.label}", event.info.title,
                      event.info.message, event.info.code_sample)
    elif isinstance(event, events.FatalError):
        outcome.error("engine", "failed", repr(event.exception))
    elif isinstance(event, events.PhaseFinished) and event.status.name == "ERROR":
        outcome.error(event.phase.name.value, "the phase failed")


@pytest.fixture(scope="module")
def fuzzed_app(tmp_path_factory, built_assets):
    with app_for_fuzzing(tmp_path_factory.mktemp("schemathesis"), built_assets) as app:
        yield app


def test_every_operation_the_server_documents_is_in_the_contract_and_the_role_table(
        fuzzed_app):
    app, _ = fuzzed_app
    served = {op["operationId"] for path in app.openapi()["paths"].values()
              for op in path.values()}
    assert served == set(OPERATION_IDS) == set(ROLE_TABLE)


@pytest.mark.parametrize("caller", CALLERS)
def test_every_generated_request_is_answered_as_the_openapi_document_says(fuzzed_app, caller):
    outcome = fuzz(*fuzzed_app, caller, SUITE)
    assert not outcome.problems(), "\n\n".join(outcome.problems())
    assert len(outcome.operations) == len(OPERATION_IDS), sorted(outcome.operations)
    assert all(outcome.cases[phase] for phase in PHASES), outcome.cases
    reached = outcome.reached()
    assert reached, "no stateful step was answered 2xx with a value from an earlier answer"
    if caller == "admin":
        assert "PATCH /api/v1/poses/{pose_id}" in reached, sorted(reached)
