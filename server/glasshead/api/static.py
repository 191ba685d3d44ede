"""Static files: GLB assets with caching headers, and the built web app."""

import hashlib
from functools import lru_cache
from pathlib import Path
from urllib.parse import quote

from fastapi import FastAPI, HTTPException, Request
from fastapi.responses import FileResponse, HTMLResponse, Response

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


def mount_static(app: FastAPI, settings) -> None:
    @app.get("/assets/build/{name:path}", include_in_schema=False)
    async def built_asset(name: str, request: Request):
        path = _safe_child(settings.assets_dir, name)
        etag = _etag(path)
        cache = IMMUTABLE if is_content_hashed(path, request.query_params.get("v")) else REVALIDATE
        headers = {"ETag": etag, "Cache-Control": cache}
        if request.headers.get("if-none-match") == etag:
            return Response(status_code=304, headers=headers)
        media_type = MEDIA_TYPES.get(path.suffix, "application/octet-stream")
        return FileResponse(path, media_type=media_type, headers=headers)

    @app.get("/{name:path}", include_in_schema=False)
    async def web_app(name: str):
        dist = settings.web_dist_dir
        index = dist / "index.html"
        if "\0" in name:
            raise HTTPException(status_code=404, detail=f"no file named {name!r}")
        if name:
            candidate = (dist / name).resolve()
            if dist.resolve() in candidate.parents and candidate.is_file():
                cache = IMMUTABLE if name.startswith("assets/") else REVALIDATE
                return FileResponse(candidate, headers={"Cache-Control": cache})
            if "." in Path(name).name:
                raise HTTPException(status_code=404, detail=f"no file named {name!r}")
        if not index.is_file():
            return HTMLResponse(
                "<h1>Glasshead</h1>"
                "<p>The web app is not built yet: run <code>npm start</code>.</p>",
                status_code=503,
            )
        return FileResponse(index, headers={"Cache-Control": REVALIDATE})
