"""Static files: GLB assets with caching headers, and the built web app.

A file with a fresh ``.gz`` sibling (written at build time by ``glasshead.precompress``)
is sent as that sibling with ``Content-Encoding: gzip`` when the request's ``Accept-Encoding``
allows it. Every file that has a sibling answers with ``Vary: Accept-Encoding``, and the two
encodings have different ETags (the gzip one ends in ``-gzip``), so that no cache confuses them.
"""

import hashlib
import mimetypes
from functools import lru_cache
from pathlib import Path
from urllib.parse import quote

from fastapi import FastAPI, HTTPException, Request
from fastapi.responses import FileResponse, HTMLResponse, Response

from glasshead.api.compression import accepts_gzip
from glasshead.precompress import fresh_sibling

#: Content-hashed asset URLs never change, so browsers may keep them for a year.
IMMUTABLE = "public, max-age=31536000, immutable"
#: An asset URL is content-hashed when its ``?v=`` is the first HASH_PREFIX (or more) hex digits
#: of the sha256 of the file's bytes (``hashed_url`` makes such URLs); any other ``v`` is ignored.
HASH_PREFIX = 16
#: Unversioned asset URLs must be revalidated (cheap: the ETag is the content hash).
REVALIDATE = "no-cache"

MEDIA_TYPES = {".glb": "model/gltf-binary", ".json": "application/json",
               ".bin": "application/octet-stream", ".svg": "image/svg+xml",
               ".html": "text/html; charset=utf-8"}


def _etag(path: Path) -> str:
    stat = path.stat()
    key = f"{path.name}:{stat.st_size}:{stat.st_mtime_ns}".encode()
    return '"' + hashlib.sha256(key).hexdigest()[:32] + '"'


@lru_cache(maxsize=1024)
def _content_sha256(path: Path, size: int, mtime_ns: int) -> str:
    digest = hashlib.sha256()
    with path.open("rb") as file:
        for block in iter(lambda: file.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def content_sha256(path: Path) -> str:
    """The sha256 of the file's bytes, read again only when its size or mtime changes."""
    stat = path.stat()
    return _content_sha256(path, stat.st_size, stat.st_mtime_ns)


def is_content_hashed(path: Path, version: str | None) -> bool:
    """Whether ``version`` (a URL's ``v``) names these exact bytes."""
    return (version is not None and HASH_PREFIX <= len(version) <= 64
            and content_sha256(path).startswith(version.lower()))


def hashed_url(assets_dir: Path, name: str) -> str:
    """The immutable URL of the built asset ``name`` (relative to the assets directory); the
    plain URL while the file is missing (it answers 404 until a build makes it)."""
    path = Path(assets_dir) / name
    if not path.is_file():
        return f"/assets/build/{quote(name)}"
    return f"/assets/build/{quote(name)}?v={content_sha256(path)[:HASH_PREFIX]}"


def _safe_child(root: Path, relative: str) -> Path:
    """The file ``relative`` under ``root``; 404 for anything outside it or missing."""
    root = root.resolve()
    if "\0" in relative:  # no file name holds one; the OS refuses it
        raise HTTPException(status_code=404, detail=f"no asset named {relative!r}")
    candidate = (root / relative).resolve()
    if root not in candidate.parents or not candidate.is_file():
        raise HTTPException(status_code=404, detail=f"no asset named {relative!r}")
    return candidate


def encoded_file(path: Path, request: Request) -> tuple[Path, dict[str, str]]:
    """The file to send for ``path`` (its fresh ``.gz`` sibling when the request allows gzip)
    and the headers that say so; ``{}`` for a file without a sibling."""
    gz = fresh_sibling(path)
    if gz is None:
        return path, {}
    if accepts_gzip(request.headers.get("accept-encoding", "")):
        return gz, {"Content-Encoding": "gzip", "Vary": "Accept-Encoding"}
    return path, {"Vary": "Accept-Encoding"}


def file_response(path: Path, request: Request, headers: dict[str, str],
                  media_type: str | None = None) -> Response:
    """``path`` (or its gzip sibling) with ``headers`` and an ETag of the encoding sent; 304 when
    the request's If-None-Match names that ETag."""
    sent, encoding = encoded_file(path, request)
    etag = _etag(path)
    if "Content-Encoding" in encoding:
        etag = etag[:-1] + '-gzip"'
    headers = {**headers, **encoding, "ETag": etag}
    if request.headers.get("if-none-match") == etag:
        return Response(status_code=304, headers=headers)
    media_type = media_type or mimetypes.guess_type(path.name)[0] or "application/octet-stream"
    return FileResponse(sent, media_type=media_type, headers=headers)


def mount_static(app: FastAPI, settings) -> None:
    @app.get("/assets/build/{name:path}", include_in_schema=False)
    async def built_asset(name: str, request: Request):
        path = _safe_child(settings.assets_dir, name)
        cache = IMMUTABLE if is_content_hashed(path, request.query_params.get("v")) else REVALIDATE
        media_type = MEDIA_TYPES.get(path.suffix, "application/octet-stream")
        return file_response(path, request, {"Cache-Control": cache}, media_type)

    @app.get("/{name:path}", include_in_schema=False)
    async def web_app(name: str, request: Request):
        dist = settings.web_dist_dir
        index = dist / "index.html"
        if "\0" in name:
            raise HTTPException(status_code=404, detail=f"no file named {name!r}")
        if name:
            candidate = (dist / name).resolve()
            if dist.resolve() in candidate.parents and candidate.is_file():
                cache = IMMUTABLE if name.startswith("assets/") else REVALIDATE
                return file_response(candidate, request, {"Cache-Control": cache})
            if "." in Path(name).name:
                raise HTTPException(status_code=404, detail=f"no file named {name!r}")
        if not index.is_file():
            return HTMLResponse(
                "<h1>Glasshead</h1>"
                "<p>The web app is not built yet: run <code>npm start</code>.</p>",
                status_code=503,
            )
        return file_response(index, request, {"Cache-Control": REVALIDATE})
