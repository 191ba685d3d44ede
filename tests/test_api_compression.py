"""Compressed responses: built files sent as their precompressed gzip siblings when the request
allows it, JSON answers gzipped by the middleware above its threshold, streams left alone."""

import asyncio
import gzip
import os
import shutil

import pytest

from glasshead.api.compression import MINIMUM_SIZE, CompressionMiddleware, accepts_gzip
from glasshead.pipeline.precompress import precompress
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


def run_asgi(app, accept="gzip"):
    """The messages ``app`` sends for a GET with ``Accept-Encoding: accept``."""
    sent = []

    async def receive():
        return {"type": "http.request", "body": b"", "more_body": False}

    async def send(message):
        sent.append(message)

    scope = {"type": "http", "method": "GET", "path": "/", "headers": [
        (b"accept-encoding", accept.encode())]}
    asyncio.run(CompressionMiddleware(app)(scope, receive, send))
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


def test_a_json_body_already_compressed_or_streamed_is_not_compressed_again():
    body = gzip.compress(b'{"a": "' + b"y" * 5000 + b'"}')

    async def encoded(scope, receive, send):
        await send({"type": "http.response.start", "status": 200, "headers": [
            (b"content-type", b"application/json"), (b"content-encoding", b"gzip")]})
        await send({"type": "http.response.body", "body": body})

    sent = run_asgi(encoded)
    assert sent[1]["body"] == body

    async def streamed(scope, receive, send):
        await send({"type": "http.response.start", "status": 200,
                    "headers": [(b"content-type", b"application/json")]})
        await send({"type": "http.response.body", "body": b"[" + b"1," * 3000, "more_body": True})
        await send({"type": "http.response.body", "body": b"1]"})

    sent = run_asgi(streamed)
    assert sent[1]["body"].startswith(b"[1,1,")
    assert (b"content-encoding", b"gzip") not in sent[0]["headers"]


@pytest.mark.parametrize(("header", "allowed"), [
    ("gzip, deflate, br", True), ("GZIP", True), ("br;q=1.0, gzip;q=0.5", True),
    ("gzip;q=0", False), ("identity", False), ("", False), ("*", True), ("*;q=0", False),
    ("gzip;q=0, *", False), ("deflate, *;q=0.1", True), ("gzip;q=x", False)])
def test_accept_encoding_allows_gzip_only_with_a_quality_above_zero(header, allowed):
    assert accepts_gzip(header) is allowed


def test_a_large_answer_is_gzipped_off_the_event_loop(monkeypatch):
    """A stream of large answers (tongue surfaces) once held /health up: gzip ran on the event
    loop. A body from THREAD_SIZE on is compressed in a thread while the loop goes on: here gzip
    waits until the loop has run a step of another task, which it never could if gzip held the
    loop (the wait would give up after a minute)."""
    import threading

    from glasshead.api import compression

    body = b'{"v": [' + b"1.25," * (compression.THREAD_SIZE // 5 + 10) + b"0]}"
    plain_compress = gzip.compress
    compressing, loop_ran = threading.Event(), threading.Event()
    wait_s = 60.0
    during = {}

    def waiting(data, **options):
        compressing.set()
        during["loop ran while gzip worked"] = loop_ran.wait(timeout=wait_s)
        return plain_compress(data, **options)

    monkeypatch.setattr(compression.gzip, "compress", waiting)

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
        await asyncio.gather(CompressionMiddleware(large)(scope, receive, send), other_task())
        return sent

    sent = asyncio.run(both())
    assert gzip.decompress(sent[1]["body"]) == body
    assert during == {"loop ran while gzip worked": True}
