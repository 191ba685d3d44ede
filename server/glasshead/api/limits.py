"""Request body limits, enforced before the work: while the body streams in, not after.

A 50 MB JSON body to POST /collision/correct used to be read and parsed in full before the
route refused it (the server went from 140 to 976 MB, and /health stalled for 5.7 s), and a
200 MB chunked upload was spooled to disk before the 16 MiB check. ``BodyLimitMiddleware`` is
a pure ASGI middleware (a ``BaseHTTPMiddleware`` would buffer and hide the stream) that looks up
the request's limit in ``BODY_LIMITS`` (``DEFAULT_LIMIT`` for every other route) and

- answers 413 at once, reading nothing, when ``Content-Length`` is past the limit;
- otherwise counts the bytes as they arrive (a chunked body has no length) and answers 413 as
  soon as the count passes the limit, so at most one more chunk than the limit is ever held.

The 413 names the limit and carries ``Connection: close``: the rest of the body is never read.
Upload routes keep their own, exact checks of the file (recordings 32 MiB, fits 2 or 8 MiB by
kind, EMA files 16 MiB and their labels 1 MiB, TextGrids 1 MiB); their body limit adds
``MULTIPART_SLACK`` for the form's framing. The limits are documented in docs/api.md.
"""

import json
import re

from starlette.exceptions import HTTPException
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from glasshead import uploads
from glasshead.api.routes import ema, practice_audio, recordings, utterances

MIB = 1024 * 1024
#: Room for the multipart framing (boundaries, part headers, small fields) around a file.
MULTIPART_SLACK = 64 * 1024
#: Every route not in ``BODY_LIMITS``: JSON documents of a few hundred kilobytes at most.
DEFAULT_LIMIT = 1 * MIB

#: (method, path, most bytes in the body); a ``{parameter}`` matches one path segment.
BODY_LIMITS: tuple[tuple[str, str, int], ...] = (
    # Uploads: the route's own file limit plus the framing (routes/recordings.py, fits.py,
    # utterances.py; uploads.py).
    ("POST", "/api/v1/epg/recordings", recordings.MAX_UPLOAD_BYTES + MULTIPART_SLACK),
    ("POST", "/api/v1/fits", max(uploads.MAX_BYTES.values()) + MULTIPART_SLACK),
    ("POST", "/api/v1/ema/playback", ema.MAX_FILE_BYTES + ema.MAX_LABEL_BYTES + MULTIPART_SLACK),
    ("POST", "/api/v1/utterances/textgrid", utterances.MAX_TEXTGRID_BYTES + MULTIPART_SLACK),
    # A WAV file sent as the body: 30 s at 48 kHz (routes/practice_audio.py).
    ("PUT", "/api/v1/practice/{record_id}/audio", practice_audio.MAX_AUDIO_BYTES),
    # JSON routes whose largest valid body passes 1 MiB: 20,000 vertices (about 1.2 MB), with
    # 40,000 triangles; 20,000 EPG frames of 8 rows (about 2 MB) with their times.
    ("POST", "/api/v1/collision/correct", 2 * MIB),
    ("POST", "/api/v1/epg/contacts", 4 * MIB),
    ("POST", "/api/v1/epg/indices", 4 * MIB),
    ("POST", "/api/v1/epg/recordings/{recording_id}/compare", 4 * MIB),
    ("POST", "/api/v1/epg/recordings/{recording_id}/compare/plot", 4 * MIB),
)



def _pattern(path: str) -> re.Pattern:
    segments = ("[^/]+" if s.startswith("{") else re.escape(s) for s in path.split("/"))
    return re.compile("^" + "/".join(segments) + "/?$")


_PATTERNS = tuple((method, _pattern(path), limit) for method, path, limit in BODY_LIMITS)


def body_limit(method: str, path: str) -> int:
    """The most bytes a request's body may hold."""
    for pattern_method, pattern, limit in _PATTERNS:
        if method == pattern_method and pattern.match(path):
            return limit
    return DEFAULT_LIMIT


def describe(limit: int) -> str:
    """A limit as people read it: "2 MiB", or "16842752-byte (16.06 MiB)"."""
    if limit % MIB == 0:
        return f"{limit // MIB} MiB"
    return f"{limit}-byte ({limit / MIB:.2f} MiB)"


class BodyTooLargeError(HTTPException):
    """Raised from ``receive`` once the body passes its limit; answered 413 by the app."""

    def __init__(self, method: str, path: str, limit: int):
        super().__init__(status_code=413, headers={"Connection": "close"},
                         detail=f"the request body is larger than the {describe(limit)} limit "
                                f"of {method} {path}")


class BodyLimitMiddleware:
    """Refuses a body past its route's limit as it arrives (see the module docstring)."""

    def __init__(self, app: ASGIApp, limit_for=body_limit):
        self.app = app
        self.limit_for = limit_for

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        method, path = scope["method"], scope["path"]
        limit = self.limit_for(method, path)
        declared = _content_length(scope)
        if declared is not None and declared > limit:
            await _refuse(send, BodyTooLargeError(method, path, limit))
            return
        received = 0
        state = {"started": False, "exceeded": False}

        async def counted_receive() -> Message:
            nonlocal received
            message = await receive()
            if message["type"] == "http.request":
                received += len(message.get("body", b""))
                if received > limit:
                    state["exceeded"] = True
                    raise BodyTooLargeError(method, path, limit)
            return message

        async def closing_send(message: Message) -> None:
            if message["type"] == "http.response.start":
                state["started"] = True
                if state["exceeded"]:  # the rest of the body stays unread: no keep-alive
                    headers = [(k, v) for k, v in message.get("headers", [])
                               if k.lower() != b"connection"]
                    message = {**message, "headers": [*headers, (b"connection", b"close")]}
            await send(message)

        try:
            await self.app(scope, counted_receive, closing_send)
        except BodyTooLargeError as error:
            if state["started"]:
                raise
            await _refuse(send, error)


def _content_length(scope: Scope) -> int | None:
    for key, value in scope.get("headers", ()):
        if key == b"content-length":
            text = value.decode("latin-1").strip()
            return int(text) if text.isascii() and text.isdigit() else None
    return None


async def _refuse(send: Send, error: BodyTooLargeError) -> None:
    body = json.dumps({"detail": error.detail}).encode()
    await send({"type": "http.response.start", "status": 413, "headers": [
        (b"content-type", b"application/json"), (b"content-length", str(len(body)).encode()),
        (b"connection", b"close")]})
    await send({"type": "http.response.body", "body": body})
