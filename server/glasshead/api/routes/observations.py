"""GET /observations: the measured tongue shapes the rig is fitted to, with each one's 2D fit
error; GET /observations/{name}: one of them, as the workbench overlays it on the tongue.

Built by `glasshead build`: the shapes by ``pipeline.vtl_observations`` (docs/observations.md),
their fits, rays and plots by ``pipeline.fit_report`` (docs/fitting.md, "The fit report"); both
read through the asset store. The fit's rays start at ``origin``; the browser finds where each
ray through an ``outline`` point crosses the tongue it shows, so the error vectors follow the
sliders from the ``before`` pose to the ``after`` one.
"""

from urllib.parse import quote

import numpy as np
from fastapi import APIRouter, HTTPException
from pydantic import BaseModel, Field

from glasshead.api.deps import AssetsDep, BuiltUrlDep
from glasshead.asset_store import AssetUnavailableError
from glasshead.constants import FIT_REPORT_FILE

router = APIRouter(tags=["observations"])

#: Most observed surface vertices one observation returns (subsampled evenly beyond it).
MAX_SURFACE_VERTICES = 1500


class ObservationSummary(BaseModel):
    name: str = Field(description="the shape's name in its source, e.g. tt-alveolar-closure(a)")
    source: str = Field(description="where it was measured: vtl-jd3 (VocalTractLab's JD3)")
    label: str = Field(description="what a person calls it")
    has_surface: bool = Field(description="whether an observed 3D tongue surface comes with it")
    rms_mm: float | None = Field(description="the 2D fit's RMS ray error after the fit, mm; "
                                             "null when the shape has no fit")
    url: str


class ObservationList(BaseModel):
    observations: list[ObservationSummary]


class Pose(BaseModel):
    params: dict[str, float] = Field(description="every parameter of the tongue rig (tongue and "
                                                 "jaw)")


class FitResult(Pose):
    rms_mm: float = Field(description="RMS of the per-ray errors, mm")
    max_error_mm: float
    evaluations: int
    seconds: float
    method: str
    volume_change_pct: float = Field(description="the tongue's volume against rest, percent")
    at_limit: list[str] = Field(description="parameters that ended at a range limit")


class Observation(BaseModel):
    name: str
    source: str
    label: str
    origin: list[float] = Field(description="[x, y, z] mm, project frame: the rays' origin, the "
                                            "rig's hub at the fit's start")
    outline: list[list[float]] = Field(description="[[x, y], ...] mm, z = 0: the part of the "
                                                   "observed mid-sagittal outline the 2D error "
                                                   "compares, root to tip, one point per ray")
    surface: list[list[float]] = Field(description="[[x, y, z], ...] mm: observed 3D tongue "
                                                   "surface vertices, at most 1,500, subsampled "
                                                   "evenly; [] when there is none")
    before: Pose = Field(description="the fit's starting pose")
    after: FitResult = Field(description="the 2D fit's result")
    plot_url: str = Field(description="the overlay plot (SVG): observed against fitted outline "
                                      "with the error vectors")


def evenly(points: list, limit: int = MAX_SURFACE_VERTICES) -> list:
    """At most ``limit`` of ``points``, evenly spaced along the list, the first and last kept."""
    if len(points) <= limit:
        return points
    keep = np.unique(np.round(np.linspace(0, len(points) - 1, limit)).astype(int))
    return [points[k] for k in keep]


def _shapes(assets) -> dict:
    """The observed shapes by name, in the document's order."""
    return assets.derived("vtl_observations", "by_name",
                          lambda document: {s["name"]: s for s in document["shapes"]})


def _fits(assets) -> dict:
    return assets.derived("fit_report", "by_name",
                          lambda document: {s["name"]: s for s in document["shapes"]})


def _url(name: str) -> str:
    return f"/api/v1/observations/{quote(name, safe='')}"


@router.get("/observations", operation_id="listObservations", response_model=ObservationList)
def list_observations(assets: AssetsDep) -> dict:
    """Every observed shape, in the observations document's order, with its 2D fit's error."""
    shapes, fits = _shapes(assets), _fits(assets)
    listed = []
    for name, shape in shapes.items():
        fit = fits.get(name, {})
        listed.append({"name": name, "source": fit.get("source", "vtl-jd3"),
                       "label": fit.get("label", name),
                       "has_surface": bool(shape["tongue_surface_vertices"]),
                       "rms_mm": fit.get("rms_mm"), "url": _url(name)})
    return {"observations": listed}


@router.get("/observations/{name}", operation_id="getObservation", response_model=Observation)
def get_observation(name: str, assets: AssetsDep, built_url: BuiltUrlDep) -> dict:
    """One observed shape: the rays' origin, the compared outline, the observed surface, the
    fit's start and result, and the URL of its overlay plot."""
    shapes, fits = _shapes(assets), _fits(assets)
    shape = shapes.get(name)
    if shape is None:
        raise HTTPException(status_code=404, detail=(
            f"no observed shape {name!r}; GET /api/v1/observations lists them"))
    fit = fits.get(name)
    if fit is None or fit["rms_mm"] is None:
        reason = fit.get("error") if fit else "it lists no such shape"
        raise AssetUnavailableError("fit_report", FIT_REPORT_FILE, "stale",
                                    f"no fit of {name!r}: {reason}")
    return {
        "name": name, "source": fit["source"], "label": fit["label"],
        "origin": fit["origin"], "outline": fit["outline"],
        "surface": evenly(shape["tongue_surface_vertices"]),
        "before": {"params": fit["start_params"]},
        "after": {key: fit[key] for key in ("params", "rms_mm", "max_error_mm", "evaluations",
                                            "seconds", "method", "volume_change_pct",
                                            "at_limit")},
        "plot_url": built_url(fit["plot"]),
    }
