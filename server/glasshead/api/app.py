"""The FastAPI application: the JSON API under /api/v1, the GLB assets and the web app."""

import importlib
from contextlib import asynccontextmanager

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse
from starlette.exceptions import HTTPException as StarletteHTTPException

from glasshead import __version__
from glasshead.api.compression import GZipUnlessETagMiddleware
from glasshead.api.error_responses import install_error_responses, unknown_path_error
from glasshead.api.limits import BodyLimitMiddleware
from glasshead.api.security import install_safe_defaults
from glasshead.api.static import mount_static
from glasshead.asset_store import AssetStore, AssetUnavailableError
from glasshead.jobs.compute import ComputePool
from glasshead.jobs.fit_runner import FitRunner
from glasshead.settings import get_settings

API_PREFIX = "/api/v1"

#: Route modules under glasshead.api.routes, each exposing ``router``; included under API_PREFIX.
ROUTE_MODULES = ["health", "site", "anatomy", "recordings", "epg_compare", "epg_coarticulated",
                 "epg_indices", "ema", "poses",
                 "collision", "tongue", "epg", "face", "landmarks", "velum",
                 "phonemes", "observations", "fits", "utterances", "tract", "auth", "users",
                 "lessons", "classes", "class_staff", "practice", "practice_audio",
                 "child_records"]

#: Functions run once at start-up (e.g. database migrations), as "module:function".
STARTUP_HOOKS: list[str] = ["glasshead.store.db:upgrade_to_head"]


@asynccontextmanager
async def lifespan(app: FastAPI):
    for hook in STARTUP_HOOKS:
        module_name, function_name = hook.split(":")
        getattr(importlib.import_module(module_name), function_name)()
    # Every built asset is read once, here; a missing or corrupt one is reported, not fatal.
    app.state.assets.load_all()
    # Fit jobs run in worker processes, taken from the queue in the database; the jobs a
    # server that died left running are failed.
    app.state.fits.start()
    app.state.compute.start()
    yield
    app.state.compute.shutdown()
    app.state.fits.shutdown()


def create_app() -> FastAPI:
    settings = get_settings()
    app = FastAPI(
        title="Glasshead",
        version=__version__,
        summary="A talking head with transparent skin, a parametric tongue and synthetic EPG.",
        openapi_url=f"{API_PREFIX}/openapi.json",
        docs_url=None,  # served by glasshead.api.docs_pages, without a CDN
        redoc_url=None,
        lifespan=lifespan,
    )
    app.state.assets = AssetStore(settings.assets_dir)
    app.state.fits = FitRunner(settings.database_url, settings.assets_dir,
                               workers=settings.fit_workers, queue_limit=settings.fit_queue_limit)
    app.state.compute = ComputePool(settings.assets_dir, workers=settings.compute_workers,
                                    queue_limit=settings.compute_queue_limit)
    app.add_middleware(BodyLimitMiddleware)  # 413 while the body streams in
    app.add_middleware(GZipUnlessETagMiddleware)  # gzip JSON answers; never events or files
    for name in ROUTE_MODULES:
        module = importlib.import_module(f"glasshead.api.routes.{name}")
        app.include_router(module.router, prefix=API_PREFIX)
    install_safe_defaults(app, settings, API_PREFIX)

    @app.api_route(
        API_PREFIX + "/{rest:path}",
        methods=["GET", "POST", "PUT", "PATCH", "DELETE"],
        include_in_schema=False,
    )
    async def unknown_api_path(request: Request, rest: str):
        # request.app, not a closure: FastAPI's cache of routes' callables would keep the app.
        raise unknown_path_error(request.app, request)

    @app.exception_handler(StarletteHTTPException)
    async def json_http_error(request: Request, exc: StarletteHTTPException):
        return JSONResponse({"detail": exc.detail}, status_code=exc.status_code,
                            headers=getattr(exc, "headers", None))

    @app.exception_handler(AssetUnavailableError)
    async def asset_unavailable(request: Request, exc: AssetUnavailableError):
        return JSONResponse(exc.to_json(), status_code=503, headers={"Retry-After": "60"})

    @app.exception_handler(RequestValidationError)
    async def json_validation_error(request: Request, exc: RequestValidationError):
        return JSONResponse({"detail": _describe_validation_errors(exc.errors())},
                            status_code=422)

    install_error_responses(app, API_PREFIX, ROUTE_MODULES)  # {detail: string}; 404, 405
    mount_static(app, settings)
    return app


def _describe_validation_errors(errors) -> str | list:
    """One readable sentence per error, e.g. "body.params.tip_height: value is not a number"."""
    messages = []
    for error in errors:
        location = ".".join(str(part) for part in error.get("loc", ()))
        messages.append(f"{location}: {error.get('msg', 'invalid')}" if location else error["msg"])
    return "; ".join(messages)


app = create_app()
