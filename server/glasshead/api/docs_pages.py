"""The API's docs pages, Swagger UI at ``/api/v1/docs`` and ReDoc at ``/api/v1/redoc``, with
their scripts, styles and icon served from the installed ``fastapi-offline`` package (so they
work offline and under a Content-Security-Policy that allows only this origin)."""

from functools import lru_cache
from pathlib import Path

import fastapi_offline
from fastapi import FastAPI, HTTPException
from fastapi.openapi.docs import get_redoc_html, get_swagger_ui_html
from fastapi.responses import FileResponse, HTMLResponse, Response

from glasshead.api.security import docs_policy

#: swagger-ui-bundle.js, swagger-ui.css, redoc.standalone.js and favicon.png.
STATIC_DIR = Path(fastapi_offline.__file__).parent / "static"
STATIC_FILES = {"swagger-ui-bundle.js": "text/javascript; charset=utf-8",
                "swagger-ui.css": "text/css; charset=utf-8",
                "redoc.standalone.js": "text/javascript; charset=utf-8",
                "favicon.png": "image/png"}


#: The one outside URL ReDoc's bundle loads by itself (its footer's logo).
REDOC_LOGO = "https://cdn.redoc.ly/redoc/logo-mini.svg"


@lru_cache(maxsize=1)
def _redoc_bundle(logo_url: str) -> bytes:
    """ReDoc's bundle with its footer logo read from here instead of Redocly's CDN."""
    return (STATIC_DIR / "redoc.standalone.js").read_bytes().replace(
        REDOC_LOGO.encode(), logo_url.encode())


def mount_docs(app: FastAPI, prefix: str) -> dict[str, str]:
    """Add the two pages and their static files; returns {page path: its CSP}."""
    static = f"{prefix}/docs/static"
    openapi_url = app.openapi_url
    swagger = get_swagger_ui_html(
        openapi_url=openapi_url, title=f"{app.title} API", swagger_js_url=f"{static}/"
        "swagger-ui-bundle.js", swagger_css_url=f"{static}/swagger-ui.css",
        swagger_favicon_url=f"{static}/favicon.png",
        # no badge from validator.swagger.io, which would be sent this document's URL
        swagger_ui_parameters={"validatorUrl": None}).body.decode()
    redoc = get_redoc_html(
        openapi_url=openapi_url, title=f"{app.title} API",
        redoc_js_url=f"{static}/redoc.standalone.js", redoc_favicon_url=f"{static}/favicon.png",
        with_google_fonts=False).body.decode()

    @app.get(f"{prefix}/docs", include_in_schema=False)
    async def swagger_ui():
        return HTMLResponse(swagger)

    @app.get(f"{prefix}/redoc", include_in_schema=False)
    async def redoc_page():
        return HTMLResponse(redoc)

    @app.get(static + "/{name}", include_in_schema=False)
    async def docs_static(name: str):
        if name not in STATIC_FILES:
            raise HTTPException(status_code=404, detail=f"no docs file named {name!r}")
        if name == "redoc.standalone.js":
            return Response(_redoc_bundle(f"{static}/favicon.png"), media_type=STATIC_FILES[name],
                            headers={"Cache-Control": "no-cache"})
        return FileResponse(STATIC_DIR / name, media_type=STATIC_FILES[name],
                            headers={"Cache-Control": "no-cache"})

    return {f"{prefix}/docs": docs_policy(swagger), f"{prefix}/redoc": docs_policy(redoc)}
