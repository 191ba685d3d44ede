"""gzip for the responses made per request: the JSON API's answers, above a size threshold.

Static files are compressed once, at build time (``glasshead.precompress`` writes ``.gz``
siblings that ``api/static.py`` serves); Starlette's ``GZipMiddleware`` compresses what cannot
be: the JSON documents the routes return (``GET /tongue/rig`` is about 90 kB, a third of that
gzipped), when the request's ``Accept-Encoding`` names gzip. With the options below it leaves
alone bodies under ``MINIMUM_SIZE``, a response that already has a ``Content-Encoding`` (a
precompressed file), a 206, and the types of ``EXCLUDED_TYPES``: the server-sent events of
``GET /fits/{id}/events`` (``text/event-stream``), and types that do not shrink (GLB, octet
streams, images, audio).
"""

from starlette.datastructures import Headers
from starlette.middleware.gzip import DEFAULT_EXCLUDED_CONTENT_TYPES, GZipMiddleware
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
#: Starlette's own list (text/event-stream, PNG, JPEG, audio/*, zip...) and the binary files
#: the server sends.
EXCLUDED_TYPES = (*DEFAULT_EXCLUDED_CONTENT_TYPES, "model/gltf-binary", "application/octet-stream")


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


class GZipUnlessETagMiddleware:
    """``GZipMiddleware`` with the options above, except that a response with an ``ETag`` is
    sent as the app made it.

    Why: an ETag names one representation. ``api/static.py`` gives a file's gzip sibling its own
    ETag (``...-gzip"``) and answers ``If-None-Match`` by comparing exactly; a file without a
    sibling (under 1 KiB, a suffix ``precompress`` skips, a sibling saving under 5 % or older
    than the file) and the records' JSON (``api/etags.py``) carry one ETag for their only
    encoding. Gzipped here, the gzip body would go out under the identity body's ETag.
    """

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        async def app(scope: Scope, receive: Receive, gzip_send: Send) -> None:
            target = gzip_send

            async def send_to_target(message: Message) -> None:
                nonlocal target
                if message["type"] == "http.response.start" and "etag" in Headers(
                        raw=message.get("headers", [])):
                    target = send  # past GZipMiddleware, which then sees nothing of it
                await target(message)

            await self.app(scope, receive, send_to_target)

        gzip = GZipMiddleware(app, minimum_size=MINIMUM_SIZE, compresslevel=LEVEL,
                              thread_minimum_size=THREAD_SIZE,
                              exclude_content_types=EXCLUDED_TYPES)
        await gzip(scope, receive, send)
