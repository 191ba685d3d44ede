"""Compressed responses: built files sent as their precompressed gzip siblings when the request
allows it, JSON answers gzipped by Starlette's GZipMiddleware above its threshold, server-sent
events and binary types left alone, and nothing gzipped under the identity body's ETag."""

import asyncio
import gzip
import os
import shutil
import zlib

import pytest

from glasshead.api.compression import MINIMUM_SIZE, GZipUnlessETagMiddleware, accepts_gzip
from glasshead.precompress import precompress
from glasshead.settings import get_settings

#: The largest built file the head view loads, the one the issue's figures were measured on.
TABLES = "collision-tables.bin"
MESH = "maxilla.glb"


@pytest.fixture
def compressed_assets(tmp_path):
    """A copy of two real built files, precompressed as the build does."""
    built = get_settings().assets_dir
    assets = tmp_path / "assets"
    assets.mkdir()
    for name in (TABLES, MESH):
        if not (built / name).is_file():
            pytest.fail(f"built asset missing: {built / name} (run `glasshead build`)")
        shutil.copy2(built / name, assets / name)
    summary = precompress(assets)
    assert summary["written"] == 2
    return assets


def test_a_built_file_comes_back_gzipped_when_asked_and_identical_after_decoding(
        compressed_assets, start_app):
    _, client = start_app(compressed_assets)
    plain = (compressed_assets / TABLES).read_bytes()
    response = client.get(f"/assets/build/{TABLES}", headers={"Accept-Encoding": "gzip"})
    assert response.status_code == 200
    assert response.headers["content-encoding"] == "gzip"
    assert response.headers["vary"] == "Accept-Encoding"
    assert int(response.headers["content-length"]) < 0.6 * len(plain)
    assert response.content == plain  # decoded by the client
    assert response.headers["content-type"] == "application/octet-stream"


def test_a_built_file_comes_back_plain_when_gzip_is_not_asked_for(compressed_assets, start_app):
    _, client = start_app(compressed_assets)
    for accept in ("identity", "gzip;q=0", "br"):
        response = client.get(f"/assets/build/{MESH}", headers={"Accept-Encoding": accept})
        assert response.status_code == 200
        assert "content-encoding" not in response.headers, accept
        assert response.headers["vary"] == "Accept-Encoding"
        assert response.content == (compressed_assets / MESH).read_bytes()
        assert response.headers["content-type"] == "model/gltf-binary"


def test_each_encoding_has_its_own_etag_and_revalidates_to_304(compressed_assets, start_app):
    _, client = start_app(compressed_assets)
    url = f"/assets/build/{MESH}"
    gzipped = client.get(url, headers={"Accept-Encoding": "gzip"}).headers["etag"]
    plain = client.get(url, headers={"Accept-Encoding": "identity"}).headers["etag"]
    assert gzipped != plain and gzipped.endswith('-gzip"')
    again = client.get(url, headers={"Accept-Encoding": "gzip", "If-None-Match": gzipped})
    assert again.status_code == 304
    crossed = client.get(url, headers={"Accept-Encoding": "identity", "If-None-Match": gzipped})
    assert crossed.status_code == 200


def test_a_sibling_older_than_its_file_is_never_served(compressed_assets, start_app):
    _, client = start_app(compressed_assets)
    path = compressed_assets / MESH
    stat = path.stat()
    os.utime(path.with_name(MESH + ".gz"), ns=(stat.st_atime_ns, stat.st_mtime_ns - 10**9))
    response = client.get(f"/assets/build/{MESH}", headers={"Accept-Encoding": "gzip"})
    assert "content-encoding" not in response.headers
    assert response.content == path.read_bytes()


def test_a_large_json_answer_is_gzipped_and_a_small_one_is_not(compressed_assets, start_app):
    _, client = start_app(compressed_assets)
    large = client.get("/api/v1/openapi.json", headers={"Accept-Encoding": "gzip"})
    assert len(large.content) > MINIMUM_SIZE
    assert large.headers["content-encoding"] == "gzip"
    assert int(large.headers["content-length"]) < len(large.content) / 3
    assert large.json()["openapi"].startswith("3.")
    plain = client.get("/api/v1/openapi.json", headers={"Accept-Encoding": "identity"})
    assert "content-encoding" not in plain.headers and plain.content == large.content
    assert plain.headers["vary"] == "Accept-Encoding"
    small = client.get("/api/v1/no-such-route", headers={"Accept-Encoding": "gzip"})
    assert small.status_code == 404
    assert len(small.content) < MINIMUM_SIZE
    assert "content-encoding" not in small.headers


def test_a_built_file_without_a_sibling_is_never_gzipped_under_its_identity_etag(
        compressed_assets, start_app):
    """precompress skips files under 1 KiB, other suffixes and siblings saving under 5 %, and a
    stale sibling is not served: such a file keeps its one encoding and its one ETag."""
    name = "no-sibling.json"
    (compressed_assets / name).write_text('{"v": [' + "1.25, " * 2000 + "0]}")
    _, client = start_app(compressed_assets)
    gzip_asked = client.get(f"/assets/build/{name}", headers={"Accept-Encoding": "gzip"})
    plain = client.get(f"/assets/build/{name}", headers={"Accept-Encoding": "identity"})
    assert gzip_asked.status_code == 200 and "content-encoding" not in gzip_asked.headers
    assert gzip_asked.headers["etag"] == plain.headers["etag"]
    assert gzip_asked.content == plain.content == (compressed_assets / name).read_bytes()


def run_asgi(app, accept="gzip"):
    """The messages ``app`` sends for a GET with ``Accept-Encoding: accept``."""
    sent = []

    async def receive():
        return {"type": "http.request", "body": b"", "more_body": False}

    async def send(message):
        sent.append(message)

    scope = {"type": "http", "method": "GET", "path": "/", "headers": [
        (b"accept-encoding", accept.encode())]}
    asyncio.run(GZipUnlessETagMiddleware(app)(scope, receive, send))
    return sent


def test_a_stream_of_server_sent_events_passes_through_untouched():
    event = b"event: progress\ndata: " + b"x" * 4000 + b"\n\n"

    async def events(scope, receive, send):
        await send({"type": "http.response.start", "status": 200,
                    "headers": [(b"content-type", b"text/event-stream")]})
        await send({"type": "http.response.body", "body": event, "more_body": True})
        await send({"type": "http.response.body", "body": b"", "more_body": False})

    sent = run_asgi(events)
    assert [m.get("body") for m in sent[1:]] == [event, b""]
    assert all(name != b"content-encoding" for name, _ in sent[0]["headers"])


def one_body(content_type, body, *headers):
    """An app that answers ``body`` as ``content_type`` in one message, with ``headers``."""
    async def app(scope, receive, send):
        await send({"type": "http.response.start", "status": 200,
                    "headers": [(b"content-type", content_type), *headers]})
        await send({"type": "http.response.body", "body": body})
    return app


def test_a_json_body_already_compressed_or_with_an_etag_is_not_compressed():
    body = gzip.compress(b'{"a": "' + b"y" * 5000 + b'"}')
    sent = run_asgi(one_body(b"application/json", body, (b"content-encoding", b"gzip")))
    assert sent[1]["body"] == body

    record = b'{"a": "' + b"y" * 5000 + b'"}'  # a record's JSON, as api/etags.py tags it
    sent = run_asgi(one_body(b"application/json", record, (b"etag", b'"lesson-1-v2"')))
    assert sent[1]["body"] == record
    assert all(name != b"content-encoding" for name, _ in sent[0]["headers"])


def test_a_streamed_json_body_is_gzipped_chunk_by_chunk():
    """Starlette compresses a stream too, flushing after each chunk so that each reaches the
    client as it is sent (no route streams JSON today; files carry ETags, events are excluded)."""
    first = b"[" + b"1," * 3000

    async def streamed(scope, receive, send):
        await send({"type": "http.response.start", "status": 200,
                    "headers": [(b"content-type", b"application/json")]})
        await send({"type": "http.response.body", "body": first, "more_body": True})
        await send({"type": "http.response.body", "body": b"1]"})

    sent = run_asgi(streamed)
    assert (b"content-encoding", b"gzip") in sent[0]["headers"]
    assert zlib.decompressobj(16 + zlib.MAX_WBITS).decompress(sent[1]["body"]) == first
    assert gzip.decompress(sent[1]["body"] + sent[2]["body"]) == first + b"1]"


@pytest.mark.parametrize(("content_type", "compressed"), [
    (b"application/json", True), (b"image/svg+xml", True), (b"text/html; charset=utf-8", True),
    (b"model/gltf-binary", False), (b"application/octet-stream", False), (b"image/png", False),
    (b"audio/wav", False)])
def test_only_types_that_shrink_are_gzipped(content_type, compressed):
    body = b"<" + b"0123" * 2000 + b">"
    sent = run_asgi(one_body(content_type, body))
    assert ((b"content-encoding", b"gzip") in sent[0]["headers"]) is compressed
    assert (gzip.decompress(sent[1]["body"]) if compressed else sent[1]["body"]) == body


@pytest.mark.parametrize(("header", "compressed"), [
    ("gzip, deflate, br", True), ("br;q=1.0, gzip;q=0.5", True), ("gzip;q=0", True),
    ("identity", False), ("", False), ("*", False), ("br", False)])
def test_json_answers_are_gzipped_when_accept_encoding_names_gzip(header, compressed):
    """Starlette's documented rule: gzip for any request whose Accept-Encoding contains "gzip".
    It reads no q-values, so "gzip;q=0" (which no browser sends) gets gzip, and "*" alone does
    not. api/static.py chooses a file's sibling by the full rule (accepts_gzip, below)."""
    body = b'{"v": "' + b"z" * 5000 + b'"}'
    sent = run_asgi(one_body(b"application/json", body), accept=header)
    assert ((b"content-encoding", b"gzip") in sent[0]["headers"]) is compressed


@pytest.mark.parametrize(("header", "allowed"), [
    ("gzip, deflate, br", True), ("GZIP", True), ("br;q=1.0, gzip;q=0.5", True),
    ("gzip;q=0", False), ("identity", False), ("", False), ("*", True), ("*;q=0", False),
    ("gzip;q=0, *", False), ("deflate, *;q=0.1", True), ("gzip;q=x", False)])
def test_a_sibling_is_chosen_only_when_accept_encoding_allows_gzip_above_q0(header, allowed):
    assert accepts_gzip(header) is allowed


def test_a_large_answer_is_gzipped_off_the_event_loop(monkeypatch):
    """A stream of large answers (tongue surfaces) once held /health up: gzip ran on the event
    loop. A body from THREAD_SIZE on is compressed in a thread while the loop goes on (Starlette's
    thread_minimum_size): here gzip waits until the loop has run a step of another task, which it
    never could if gzip held the loop (the wait would give up after a minute)."""
    import threading

    from starlette.middleware.gzip import GZipResponder

    from glasshead.api import compression

    body = b'{"v": [' + b"1.25," * (compression.THREAD_SIZE // 5 + 10) + b"0]}"
    plain_compress = GZipResponder._compress_body
    compressing, loop_ran = threading.Event(), threading.Event()
    wait_s = 60.0
    during = {}

    def waiting(responder, data, more_body):
        compressing.set()
        during["loop ran while gzip worked"] = loop_ran.wait(timeout=wait_s)
        return plain_compress(responder, data, more_body)

    monkeypatch.setattr(GZipResponder, "_compress_body", waiting)

    async def large(scope, receive, send):
        await send({"type": "http.response.start", "status": 200,
                    "headers": [(b"content-type", b"application/json")]})
        await send({"type": "http.response.body", "body": body})

    async def both():
        sent = []

        async def receive():
            return {"type": "http.request", "body": b"", "more_body": False}

        async def send(message):
            sent.append(message)

        async def other_task():
            # A step of the loop once gzip has begun (or, if it never does, after a minute).
            for _ in range(int(wait_s / 0.01)):
                if compressing.is_set():
                    break
                await asyncio.sleep(0.01)
            if compressing.is_set():
                loop_ran.set()

        scope = {"type": "http", "method": "GET", "path": "/",
                 "headers": [(b"accept-encoding", b"gzip")]}
        await asyncio.gather(GZipUnlessETagMiddleware(large)(scope, receive, send), other_task())
        return sent

    sent = asyncio.run(both())
    assert gzip.decompress(sent[1]["body"]) == body
    assert during == {"loop ran while gzip worked": True}
