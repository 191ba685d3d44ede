"""Issue 13, item 2: a body past its route's limit is refused while it streams in, not after.

A 50 MB JSON body to /collision/correct was parsed in full before its 422 (the server grew from
140 to 976 MB), and a 200 MB chunked upload was spooled to disk before the 16 MiB check. The
server here is a real uvicorn on loopback; the client looks for the answer before every chunk
it sends and stops as soon as it comes, so the bytes it sent bound what the server read."""

import json
import re
from pathlib import Path

import pytest
from live_server_support import live_server, send_until_answered

from accounts_support import signed_in
from glasshead.api.limits import BODY_LIMITS, DEFAULT_LIMIT, MIB, body_limit

CHUNK = 64 * 1024
#: Bytes that may leave the client after the server has read as far as the limit: the socket
#: buffers of both ends on loopback (a few MiB each) and what is sent while the answer is written.
IN_FLIGHT_BYTES = 24 * MIB
DOCS = Path(__file__).resolve().parents[2] / "docs" / "api.md"


@pytest.fixture(scope="module")
def server(tmp_path_factory, built_assets):
    with live_server(tmp_path_factory.mktemp("limits"), compute_workers="1") as running:
        yield running


def _head(path: str, content_type: str, length: int | None = None) -> bytes:
    framing = f"Content-Length: {length}" if length is not None else "Transfer-Encoding: chunked"
    return (f"POST {path} HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: {content_type}\r\n"
            f"{framing}\r\n\r\n").encode()


def _chunked(parts):
    for part in parts:
        yield f"{len(part):x}\r\n".encode() + part + b"\r\n"


def _detail(response: bytes) -> str:
    return json.loads(response.partition(b"\r\n\r\n")[2])["detail"]


def test_a_50_mb_json_body_to_collision_correct_is_refused_before_it_is_read(server):
    _, port = server
    total = 50_000_000
    body = (b" " * CHUNK for _ in range(total // CHUNK))
    status, response, sent = send_until_answered(
        port, _head("/api/v1/collision/correct", "application/json", total), body)
    assert status == 413
    assert "2 MiB limit of POST /api/v1/collision/correct" in _detail(response)
    assert sent < total / 5, f"{sent} of {total} bytes were sent before the answer"


def test_a_50_mb_chunked_json_body_is_refused_once_the_count_passes_the_limit(server):
    _, port = server
    total = 50_000_000
    parts = (b'{"vertices": [' if k == 0 else b" " * CHUNK for k in range(total // CHUNK))
    status, response, sent = send_until_answered(
        port, _head("/api/v1/collision/correct", "application/json"), _chunked(parts))
    assert status == 413
    assert "2 MiB limit" in _detail(response)
    assert sent < total / 5, f"{sent} of {total} bytes were sent before the answer"


def test_a_200_mb_chunked_multipart_upload_is_refused_before_it_is_spooled(server):
    _, port = server
    total = 200_000_000
    boundary = "glassheadboundary"
    first = (f"--{boundary}\r\nContent-Disposition: form-data; name=\"file\"; "
             f"filename=\"big.csv\"\r\nContent-Type: text/csv\r\n\r\n").encode()
    line = b"0,00000000,00000000,00000000,00000000,00000000,00000000,00000000,00000000\n"
    block = line * (CHUNK // len(line))
    parts = (first if k == 0 else block for k in range(total // len(block)))
    status, response, sent = send_until_answered(
        port, _head("/api/v1/epg/recordings", f"multipart/form-data; boundary={boundary}"),
        _chunked(parts))
    assert status == 413
    assert "limit of POST /api/v1/epg/recordings" in _detail(response)
    # The route takes 32 MiB and its framing, so the server reads that much before it can know;
    # what loopback's socket buffers hold and what arrives while a loaded machine writes the
    # answer come on top (41.8 MB of the 200 MB had left the client once, with every core busy).
    bound = body_limit("POST", "/api/v1/epg/recordings") + IN_FLIGHT_BYTES
    assert sent < bound < total / 3, f"{sent} of {total} bytes were sent before the answer"


def test_the_server_answers_health_after_refusing_a_body(server):
    base, port = server
    total = 50_000_000
    send_until_answered(port, _head("/api/v1/collision/correct", "application/json", total),
                        (b" " * CHUNK for _ in range(total // CHUNK)))
    status, response, _ = send_until_answered(
        port, b"GET /api/v1/health HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n", ())
    assert status == 200


def _padded_vertices(size: int) -> bytes:
    document = json.dumps({"vertices": [[30.0, 10.0, 0.0]] * 100}).encode()
    return document[:-1] + b" " * (size - len(document)) + b"}"


def test_a_body_just_under_its_limit_is_accepted_and_one_byte_over_is_not(start_app,
                                                                           built_assets):
    _, client = start_app()
    signed_in(client, "admin")
    limit = body_limit("POST", "/api/v1/collision/correct")
    headers = {"Content-Type": "application/json"}
    under = client.post("/api/v1/collision/correct", content=_padded_vertices(limit),
                        headers=headers)
    assert under.status_code == 200 and len(under.json()["vertices"]) == 100
    over = client.post("/api/v1/collision/correct", content=_padded_vertices(limit + 1),
                       headers=headers)
    assert over.status_code == 413
    assert over.json()["detail"] == ("the request body is larger than the 2 MiB limit of "
                                     "POST /api/v1/collision/correct")


def test_a_chunked_body_one_byte_over_its_limit_is_refused(start_app, built_assets):
    _, client = start_app()
    signed_in(client, "admin")
    body = _padded_vertices(DEFAULT_LIMIT + 1)
    response = client.post("/api/v1/poses", headers={"Content-Type": "application/json"},
                           content=(body[k:k + CHUNK] for k in range(0, len(body), CHUNK)))
    assert response.status_code == 413
    assert "1 MiB limit of POST /api/v1/poses" in response.json()["detail"]


def test_every_route_with_a_body_has_its_limit_in_the_api_docs(start_app, built_assets):
    app, _ = start_app()
    documented = {}
    for method, path, size in re.findall(r"^\| (POST|PUT|PATCH) \| `([^`]+)` \| ([^|]+) \|",
                                         DOCS.read_text(), flags=re.M):
        documented[(method, path)] = size.strip()
    operations = [(method.upper(), path)
                  for path, item in app.openapi()["paths"].items()
                  for method, operation in item.items() if "requestBody" in operation]
    assert len(operations) >= 10
    for method, path in operations:
        limit = body_limit(method, path.replace("{", "").replace("}", ""))
        assert documented.get((method, path)) == _written(limit), (method, path)
    assert {(method, path) for method, path, _ in BODY_LIMITS} <= set(documented)


def _written(limit: int) -> str:
    """How docs/api.md writes a limit: "1 MiB", or "16 MiB + 64 KiB" for an upload's form."""
    mib, rest = divmod(limit, MIB)
    return f"{mib} MiB" if rest == 0 else f"{mib} MiB + {rest // 1024} KiB"
