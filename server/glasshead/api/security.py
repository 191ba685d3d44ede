"""Safe defaults for a server that anyone's browser can reach on loopback.

Every HTTP request passes, in this order:

1. **Host allow-list** (DNS rebinding; Starlette's ``TrustedHostMiddleware``): a page on
   ``evil.example`` whose name is re-pointed at 127.0.0.1 reaches this server with
   ``Host: evil.example``. Only the names in ``settings.allowed_hosts`` are served (default: the
   loopback names and the configured host); any other host gets 400, as JSON like every error.
2. **Cross-site writes** (CSRF; ``SecurityMiddleware``, plain ASGI, so that streamed bodies pass
   through untouched): a form on another site can POST to this server without any script. A
   state-changing request (POST, PUT, PATCH, DELETE) whose ``Origin`` is not this server's own
   origin (the same host and port as its ``Host``), or that has no ``Origin`` but
   ``Sec-Fetch-Site: cross-site``, gets 403. A client that sends neither (curl, scripts) passes.
3. **Headers on every response** (``SecurityMiddleware``; the host refusal sends them itself): a
   Content-Security-Policy that allows only this origin (``frame-ancestors 'none'`` among it),
   ``X-Content-Type-Options: nosniff``, ``X-Frame-Options: DENY`` and
   ``Referrer-Policy: same-origin``.

The API's docs pages (Swagger UI and ReDoc) load their scripts and styles from the
``fastapi-offline`` package, served here, never from a CDN; their one inline script is allowed
by its hash (``docs_routes``), so the policy for them adds no ``'unsafe-inline'`` scripts.
"""

import base64
import hashlib
import json
import re
from urllib.parse import urlsplit

from starlette.datastructures import Headers
from starlette.middleware.trustedhost import TrustedHostMiddleware

#: The policy for every response but the docs pages: this origin only. Images may be data: URLs
#: (the page's empty favicon), and sound blob: URLs (a kept attempt, fetched with the page's
#: token, plays in an <audio> element); no plugins, no <base> elsewhere, forms post here, never
#: framed.
CSP = ("default-src 'self'; img-src 'self' data:; media-src 'self' blob:; object-src 'none'; "
       "base-uri 'self'; form-action 'self'; frame-ancestors 'none'")
#: Methods that change state, and so are refused from another site.
UNSAFE_METHODS = frozenset({"POST", "PUT", "PATCH", "DELETE"})
#: Names that always reach this machine's loopback interface.
LOOPBACK_HOSTS = ("localhost", "127.0.0.1", "::1")


def allowed_host_names(settings) -> frozenset[str]:
    """The host names served: ``settings.allowed_hosts`` when set, else the loopback names and
    the configured host (unless that is a wildcard address such as 0.0.0.0)."""
    names = [name.strip().lower() for name in settings.allowed_hosts.split(",") if name.strip()]
    if not names:
        names = [*LOOPBACK_HOSTS]
        if settings.host not in ("0.0.0.0", "::", ""):
            names.append(settings.host.lower())
    return frozenset(name.strip("[]") for name in names)


def _origin_netloc(origin: str) -> str | None:
    """``host:port`` of an Origin header as a browser sends it, default ports dropped;
    None for ``null`` or anything that is not an http(s) origin."""
    try:
        parts = urlsplit(origin.strip())
        port = parts.port
    except ValueError:
        return None
    if parts.scheme not in ("http", "https") or not parts.hostname:
        return None
    default = 443 if parts.scheme == "https" else 80
    name = f"[{parts.hostname}]" if ":" in parts.hostname else parts.hostname
    return name if port in (None, default) else f"{name}:{port}"


def _netloc_of_host(host_header: str) -> str:
    host = host_header.strip().lower()
    for default in (":80", ":443"):
        if host.endswith(default):
            return host[: -len(default)]
    return host


class SecurityMiddleware:
    """See the module docstring. ``policies`` maps a path to its own CSP (the docs pages)."""

    def __init__(self, app, policies: dict[str, str]):
        self.app = app
        self.policies = policies

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        headers = {key.decode("latin-1").lower(): value.decode("latin-1")
                   for key, value in scope["headers"]}
        host = headers.get("host", "")
        policy = self.policies.get(scope["path"], CSP)
        refusal = self._refusal(scope["method"], host, headers)
        if refusal is not None:
            status, detail = refusal
            await _send_json(send, status, {"detail": detail}, policy)
            return

        async def send_with_headers(message):
            if message["type"] == "http.response.start":
                message["headers"] = [*message.get("headers", []), *_safe_headers(policy)]
            await send(message)

        await self.app(scope, receive, send_with_headers)

    def _refusal(self, method: str, host: str, headers: dict) -> tuple[int, str] | None:
        if method not in UNSAFE_METHODS:
            return None
        origin = headers.get("origin")
        if origin is not None:
            if _origin_netloc(origin) != _netloc_of_host(host):
                return 403, (f"cross-site request refused: Origin {origin!r} is not this "
                             "server's origin")
        elif headers.get("sec-fetch-site") == "cross-site":
            return 403, "cross-site request refused: Sec-Fetch-Site is cross-site"
        return None


class JSONTrustedHostMiddleware(TrustedHostMiddleware):
    """Starlette's host allow-list, www-redirect off, whose refusal is the API's JSON error
    (``{"detail": ...}``, 400, the safe headers) instead of its plain-text "Invalid host header".

    Starlette sends that refusal itself, so the ``send`` it is given is a ``_HostRefusal``, which
    answers JSON whatever the refusal sends; the app behind it, called only for an allowed host,
    gets the server's own ``send`` back (``_serve``).
    """

    def __init__(self, app, allowed_hosts: frozenset[str]):
        # Starlette compares the Host's name as written, an IPv6 literal in brackets.
        patterns = [f"[{name}]" if ":" in name else name for name in sorted(allowed_hosts)]
        super().__init__(self._serve, allowed_hosts=patterns, www_redirect=False)
        self.served = app

    async def __call__(self, scope, receive, send):
        await super().__call__(scope, receive, _HostRefusal(scope, send))

    async def _serve(self, scope, receive, refusal: "_HostRefusal"):
        await self.served(scope, receive, refusal.send)


class _HostRefusal:
    def __init__(self, scope, send):
        self.scope, self.send = scope, send

    async def __call__(self, message):
        if message["type"] == "http.response.start":
            host = Headers(scope=self.scope).get("host", "")
            await _send_json(self.send, 400, {"detail": (
                f"host {host!r} is not served here; set GLASSHEAD_ALLOWED_HOSTS to the names "
                "this server is reached by")}, CSP)


def _safe_headers(policy: str) -> list[tuple[bytes, bytes]]:
    return [(b"content-security-policy", policy.encode()),
            (b"x-content-type-options", b"nosniff"),
            (b"x-frame-options", b"DENY"),
            (b"referrer-policy", b"same-origin")]


async def _send_json(send, status: int, body: dict, policy: str) -> None:
    data = json.dumps(body).encode()
    await send({"type": "http.response.start", "status": status,
                "headers": [(b"content-type", b"application/json"),
                            (b"content-length", str(len(data)).encode()), *_safe_headers(policy)]})
    await send({"type": "http.response.body", "body": data})


def install_safe_defaults(app, settings, api_prefix: str) -> None:
    """Mount the docs pages under ``api_prefix`` and wrap ``app`` in ``SecurityMiddleware``, and
    that in the host allow-list, so that a request for another host goes no further."""
    from glasshead.api.docs_pages import mount_docs

    policies = mount_docs(app, api_prefix)
    app.add_middleware(SecurityMiddleware, policies=policies)
    app.add_middleware(JSONTrustedHostMiddleware, allowed_hosts=allowed_host_names(settings))


def inline_script_hashes(html: str) -> list[str]:
    """CSP source expressions (``'sha256-...'``) for each inline <script> of ``html``."""
    hashes = []
    for body in re.findall(r"<script>(.*?)</script>", html, flags=re.DOTALL):
        digest = base64.b64encode(hashlib.sha256(body.encode()).digest()).decode()
        hashes.append(f"'sha256-{digest}'")
    return hashes


def docs_policy(html: str) -> str:
    """The docs pages' policy: scripts from here and their own inline script by hash; styles
    inline too (both UIs inject <style> elements); data: images (Swagger UI's icons); ReDoc's
    search runs in a blob: worker."""
    scripts = " ".join(["'self'", *inline_script_hashes(html)])
    return (f"default-src 'self'; script-src {scripts}; style-src 'self' 'unsafe-inline'; "
            "img-src 'self' data:; worker-src 'self' blob:; object-src 'none'; "
            "base-uri 'self'; form-action 'self'; frame-ancestors 'none'")
