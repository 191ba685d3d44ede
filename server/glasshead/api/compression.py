"""gzip for the responses made per request: the JSON API's answers, above a size threshold.

The first load of ``/`` used to transfer every byte uncompressed. Static files are compressed
once, at build time (``glasshead.precompress`` writes ``.gz`` siblings that ``api/static.py``
serves); this middleware compresses what cannot be: the JSON documents the routes return
(``GET /tongue/rig`` is about 90 kB, a third of that gzipped). It is a pure ASGI middleware, like
``api/limits.py`` and ``api/security.py`` (a ``BaseHTTPMiddleware`` would buffer every stream),
and it leaves alone:

- a response whose first body message says more follows (``more_body``): a stream, such as the
  server-sent events of ``GET /fits/{id}/events``, which must reach the client as it is sent;
- a response that already has a ``Content-Encoding`` (a precompressed file), or an ``ETag``
  (``api/static.py`` chooses the encoding of its files itself, with an ETag per encoding);
- types that do not shrink (GLB, PNG, octet streams), and bodies under ``MINIMUM_SIZE``;
- a 204, 206 or 304, and a request whose ``Accept-Encoding`` does not allow gzip.

A response of a compressible type carries ``Vary: Accept-Encoding`` whether or not this request
got it compressed, so that a cache never hands the gzipped body to a client that did not ask.
"""

import gzip
from functools import partial

import anyio
from starlette.datastructures import Headers, MutableHeaders
from starlette.types import ASGIApp, Message, Receive, Scope, Send

#: Bodies smaller than this are sent as they are: below about a kilobyte gzip's header and the
#: extra header lines cost more than they save.
MINIMUM_SIZE = 1024
#: zlib's level 6, its default: within a few per cent of level 9's size at a third of the time.
LEVEL = 6
#: Bodies from this size on are compressed in a worker thread (zlib lets go of the GIL), so that
#: a stream of large answers (a tongue surface is about 300 kB of JSON, 5-10 ms to gzip) does not
#: hold up /health and the cheap routes on the event loop.
THREAD_SIZE = 64 * 1024
#: Media types (without parameters) worth compressing; ``text/event-stream`` is a stream.
COMPRESSIBLE_TYPES = frozenset({"application/json", "application/problem+json",
                                "application/javascript", "text/javascript", "text/html",
                                "text/css", "text/plain", "text/csv", "image/svg+xml",
                                "model/gltf+json", "application/xml", "text/xml"})
#: Statuses whose body must not be re-encoded (no body, a byte range of the identity, unchanged).
UNTOUCHED_STATUSES = frozenset({204, 206, 304})


def accepts_gzip(accept_encoding: str) -> bool:
    """Whether an ``Accept-Encoding`` value allows gzip (``gzip`` or ``*`` with a q above 0)."""
    allowed = {}
    for item in accept_encoding.split(","):
        name, _, params = item.strip().partition(";")
        quality = 1.0
        for param in params.split(";"):
            key, _, value = param.strip().partition("=")
            if key.strip().lower() == "q":
                try:
                    quality = float(value)
                except ValueError:
                    quality = 0.0
        allowed[name.strip().lower()] = quality
    return allowed.get("gzip", allowed.get("*", 0.0)) > 0.0


def is_compressible(media_type: str | None) -> bool:
    """Whether a ``Content-Type`` value names a type that ``COMPRESSIBLE_TYPES`` holds."""
    return bool(media_type) and media_type.split(";")[0].strip().lower() in COMPRESSIBLE_TYPES


class CompressionMiddleware:
    """gzip a whole (single-message) response body of a compressible type when asked."""

    def __init__(self, app: ASGIApp, minimum_size: int = MINIMUM_SIZE, level: int = LEVEL):
        self.app = app
        self.minimum_size = minimum_size
        self.level = level

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        wanted = accepts_gzip(Headers(scope=scope).get("accept-encoding", ""))
        held: Message | None = None  # the response start, held until the first body message

        async def send_compressed(message: Message) -> None:
            nonlocal held
            if message["type"] == "http.response.start":
                headers = Headers(raw=message.get("headers", []))
                if (message["status"] in UNTOUCHED_STATUSES or "content-encoding" in headers
                        or "etag" in headers or not is_compressible(headers.get("content-type"))):
                    await send(message)
                    return
                MutableHeaders(scope=message).add_vary_header("Accept-Encoding")
                if not wanted:
                    await send(message)
                    return
                held = message
                return
            if held is None or message["type"] != "http.response.body":
                await send(message)
                return
            start, held = held, None
            body = message.get("body", b"")
            if not message.get("more_body", False) and len(body) >= self.minimum_size:
                compress = partial(gzip.compress, body, compresslevel=self.level, mtime=0)
                compressed = (await anyio.to_thread.run_sync(compress)
                              if len(body) >= THREAD_SIZE else compress())
                if len(compressed) < len(body):
                    headers = MutableHeaders(scope=start)
                    headers["Content-Encoding"] = "gzip"
                    headers["Content-Length"] = str(len(compressed))
                    message = {**message, "body": compressed}
            await send(start)
            await send(message)

        await self.app(scope, receive, send_compressed)
