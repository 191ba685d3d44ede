"""Static files: GLB assets with caching headers, and the built web app."""

import hashlib
from pathlib import Path

from fastapi import FastAPI, HTTPException, Request
from fastapi.responses import FileResponse, HTMLResponse, Response

#: Content-hashed asset URLs never change, so browsers may keep them for a year.
IMMUTABLE = "public, max-age=31536000, immutable"
#: Unversioned asset URLs must be revalidated (cheap: the ETag is the content hash).
REVALIDATE = "no-cache"

MEDIA_TYPES = {".glb": "model/gltf-binary", ".json": "application/json",
               ".bin": "application/octet-stream", ".svg": "image/svg+xml",
               ".html": "text/html; charset=utf-8"}


def _etag(path: Path) -> str:
    stat = path.stat()
    key = f"{path.name}:{stat.st_size}:{stat.st_mtime_ns}".encode()
    return '"' + hashlib.sha256(key).hexdigest()[:32] + '"'


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
        cache = IMMUTABLE if request.query_params.get("v") else REVALIDATE
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
