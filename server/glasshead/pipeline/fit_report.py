"""Build step: the fit report, the 2D fit of every JD3 shape with an overlay plot each.

Writes, under the assets directory:

- ``fit-report.json`` (``FIT_REPORT_FILE``, format ``FIT_REPORT_FORMAT_VERSION``): per shape, in
  the observations document's order, its name and a label a person reads, the fit's misfit
  (``rms_mm``, ``max_error_mm``), cost (``evaluations``, ``seconds``, ``method``, ``stop``),
  ``volume_change_pct`` and ``at_limit``; every rig parameter at the start (``start_params``) and
  after the fit (``params``); the rays' ``origin`` (x, y, 0); the compared part of the observed
  outline (``outline``, root to tip, one point per ray) and the signed error on each ray
  (``errors``, mm, +: the rig lies outside); and the plot's path;
- ``fit-plots/<name>.svg`` (``FIT_PLOTS_DIR``): the overlay (``pipeline.overlay_svg``);
- ``fit-report.html`` (``FIT_REPORT_PAGE``): a page with the table and every plot
  (``pipeline.fit_report_html``).

The fits are ``fit2d.fit_shape``'s (BOBYQA, the sagittal parameters and the widths free from
neutral, the jaw from VTL's JA, default weights): the same fits ``bench/fit2d.py`` times. The
rays, their origin and the per-ray errors are read from an ``Objective2D`` made with the fit's own
start, so the errors are those the fit minimised, at the fitted values.

The step is skipped when the SHA-256 of its inputs (the built rig and observations, and the code
of this module, the fit and its objective, the optimiser, the tongue surface and the two
writers) is the one the report records and every plot and the page are there.
"""

import hashlib
import inspect
import json
import sys
import time
from pathlib import Path
from urllib.parse import quote

import numpy as np

from glasshead import phonemes as phoneme_inventory
from glasshead.constants import (
    FIT_PLOTS_DIR,
    FIT_REPORT_FILE,
    FIT_REPORT_FORMAT_VERSION,
    FIT_REPORT_PAGE,
    TONGUE_RIG_FILE,
    VTL_OBSERVATIONS_FILE,
)
from glasshead.fitting import fit2d, objective2d, optimizer, vtl_mapping
from glasshead.fitting.objective2d import MidSagittalSection, Objective2D
from glasshead.geometry import midsagittal, tongue_surface
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.pipeline import fit_report_html, overlay_svg
from glasshead.pipeline.forked import WORKERS, forked_map
from glasshead.pipeline.outputs import current_output, write_json

#: Bump when the output changes in a way that must rebuild it.
BUILDER = 1
METHOD = "bobyqa"
SOURCE = "vtl-jd3"
#: Built files read.
INPUT_FILES = (TONGUE_RIG_FILE, VTL_OBSERVATIONS_FILE)
#: The modules whose code shapes the output; their text is part of the cache key.
CODE = (fit2d, objective2d, optimizer, tongue_surface, overlay_svg, fit_report_html, vtl_mapping,
        midsagittal)
#: Digits kept of the outline points and per-ray errors (mm): 0.1 micrometre.
DIGITS = 4


def shape_label(shape: dict) -> str:
    """What a person calls a JD3 shape, e.g. "JD3 /t d n/ alveolar closure in /a/ context" or
    "JD3 vowel /a/ (SAMPA)"; the phonemes are those of the inventory fitted to it."""
    kind = shape.get("class", {})
    if kind.get("kind") == "vowel":
        raw = ", VTL's raw version" if kind["raw"] else ""
        return f"JD3 vowel /{kind['vowel']}/ (SAMPA{raw})"
    if kind.get("kind") == "consonant":
        stem = shape["name"].split("(")[0]
        symbols = [p.ipa for p in phoneme_inventory.INVENTORY if p.shape == stem]
        which = f"/{' '.join(symbols)}/ " if symbols else ""
        return (f"JD3 {which}{kind['place']} {kind['manner']} ({kind['articulator']}) in "
                f"/{kind['context']}/ context")
    return f"JD3 shape {shape['name']}"


def plot_path(name: str) -> str:
    """The plot of shape ``name``, relative to the assets directory."""
    return f"{FIT_PLOTS_DIR}/{name}.svg"


def plot_href(name: str) -> str:
    """``plot_path`` as a relative URL (shape names hold ``(``, ``:`` and ``@``)."""
    return quote(plot_path(name))


def start_values(rig: TongueRig, shape: dict) -> np.ndarray:
    """The fit's start (P,): ``fit2d.fit_shape``'s, neutral with the jaw from VTL's JA."""
    base = rig.neutral.copy()
    base[rig.jaw_parameter] = vtl_mapping.jaw_opening_from_vtl(shape, rig)
    return base


class Context:
    """The rig, its mid-sagittal section and the shapes, shared by every fit."""

    def __init__(self, assets_dir: Path):
        self.rig = TongueRig(json.loads((assets_dir / TONGUE_RIG_FILE).read_text()))
        self.section = MidSagittalSection(self.rig)
        self.shapes = json.loads((assets_dir / VTL_OBSERVATIONS_FILE).read_text())["shapes"]


def _rounded(array) -> list:
    return np.round(np.asarray(array, dtype=np.float64), DIGITS).tolist()


def fit_entry(ctx: Context, shape: dict) -> tuple[dict, dict | None]:
    """One shape's report entry, and what its plot draws besides (the fitted and starting
    outlines); a shape that cannot be fitted gets an entry with ``error`` and no plot."""
    rig = ctx.rig
    entry = {"name": shape["name"], "label": shape_label(shape), "source": SOURCE}
    base = start_values(rig, shape)
    try:
        objective = Objective2D(rig, shape["tongue_outline"], fit2d.outline_parameters(rig),
                                base=base, section=ctx.section)
        report = fit2d.fit_shape(rig, shape, fit2d.ShapeFit(method=METHOD, section=ctx.section))
    except ValueError as exc:
        return {**entry, "error": str(exc), "rms_mm": None}, None
    fitted = np.array([report.params[n] for n in rig.parameter_names])
    held = np.ones(len(base), dtype=bool)
    held[objective.index] = False
    if not np.array_equal(fitted[held], base[held]):
        raise RuntimeError(f"{shape['name']}: the fit held other values than the report's start")
    errors = objective.errors(fitted[objective.index])
    entry.update({
        "rms_mm": report.rms_mm, "max_error_mm": report.max_error_mm,
        "evaluations": report.evaluations, "seconds": round(report.seconds, 4),
        "method": report.method, "stop": report.stop,
        "volume_change_pct": round(report.volume_change_pct, 4), "at_limit": report.at_limit,
        "rays": report.rays,
        "start_params": {n: float(v) for n, v in zip(rig.parameter_names, base, strict=True)},
        "params": report.params,
        "origin": [float(objective.origin[0]), float(objective.origin[1]), 0.0],
        "outline": _rounded(objective.rays.points),
        "errors": _rounded(errors),
        "plot": plot_path(shape["name"]),
    })
    drawing = {"observed": np.asarray(shape["tongue_outline"], dtype=np.float64),
               "fitted": ctx.section.outline(fitted), "start": ctx.section.outline(base)}
    return entry, drawing


def plot_svg(entry: dict, drawing: dict) -> str:
    """The overlay of one fitted entry (``fit_entry``)."""
    title = (f"{entry['name']}: RMS {entry['rms_mm']:.2f} mm, {entry['evaluations']} "
             f"evaluations, {entry['seconds']:.2f} s")
    subtitle = (f"{entry['label']}; max {entry['max_error_mm']:.2f} mm, volume "
                f"{entry['volume_change_pct']:+.1f} %, {entry['method']}")
    return overlay_svg.svg_overlay(
        observed=drawing["observed"], compared=entry["outline"], errors=entry["errors"],
        origin=entry["origin"][:2], fitted=drawing["fitted"], start=drawing["start"],
        title=title, subtitle=subtitle)


def _fit_and_plot(ctx: Context, index: int) -> tuple[dict, str | None]:
    entry, drawing = fit_entry(ctx, ctx.shapes[index])
    return entry, None if drawing is None else plot_svg(entry, drawing)


def fit_every_shape(ctx: Context, workers: int = WORKERS) -> list[tuple[dict, str | None]]:
    """(entry, plot SVG or None) of every shape, in order, over ``workers`` forked processes
    that share the context (one process where fork is missing). The fits are deterministic, so
    only their ``seconds`` depend on the workers."""
    return forked_map(_fit_and_plot, range(len(ctx.shapes)), ctx, workers)


def input_key(assets_dir: Path) -> str:
    digest = hashlib.sha256()
    for name in INPUT_FILES:
        digest.update(name.encode() + b"\0" + (assets_dir / name).read_bytes() + b"\0")
    for module in (*CODE, sys.modules[__name__]):
        digest.update(inspect.getsource(module).encode())
    digest.update(f"{FIT_REPORT_FORMAT_VERSION}/{BUILDER}".encode())
    return digest.hexdigest()


def summary(entries: list[dict]) -> dict:
    """Median and worst RMS, and how many shapes are within 1 mm, over the fitted entries."""
    fitted = [e for e in entries if e["rms_mm"] is not None]
    rms = np.array([e["rms_mm"] for e in fitted])
    worst = max(fitted, key=lambda e: e["rms_mm"]) if fitted else None
    return {"shapes": len(entries), "fitted": len(fitted),
            "median_rms_mm": round(float(np.median(rms)), 4) if fitted else None,
            "within_1mm": int(np.sum(rms <= 1.0)),
            "worst": {"name": worst["name"], "rms_mm": round(worst["rms_mm"], 4)} if worst
            else None,
            "median_evaluations": int(np.median([e["evaluations"] for e in fitted]))
            if fitted else None,
            "fit_seconds": round(float(sum(e["seconds"] for e in fitted)), 3)}


def _outputs_present(assets_dir: Path, document: dict) -> bool:
    return (assets_dir / FIT_REPORT_PAGE).is_file() and all(
        (assets_dir / e["plot"]).is_file() for e in document["shapes"] if "plot" in e)


def build_fit_report(assets_dir, force=False, workers=WORKERS):
    """Write the report, the plots and the page; returns (document, skipped)."""
    assets_dir = Path(assets_dir)
    out_path = assets_dir / FIT_REPORT_FILE
    digest = input_key(assets_dir)
    existing = None if force else current_output(out_path, digest, BUILDER,
                                                 FIT_REPORT_FORMAT_VERSION)
    if existing is not None and _outputs_present(assets_dir, existing):
        return existing, True
    started = time.perf_counter()
    made = fit_every_shape(Context(assets_dir), workers)
    plots = assets_dir / FIT_PLOTS_DIR
    plots.mkdir(parents=True, exist_ok=True)
    written = set()
    for entry, svg in made:
        if svg is not None:
            path = assets_dir / entry["plot"]
            temporary = path.with_name(path.name + ".tmp")
            temporary.write_text(svg, encoding="utf-8")
            temporary.replace(path)
            written.add(path.name)
    for stale in plots.glob("*.svg"):
        if stale.name not in written:
            stale.unlink()
    entries = [entry for entry, _ in made]
    document = {
        "format_version": FIT_REPORT_FORMAT_VERSION,
        "builder": BUILDER,
        "source": {"sha256": digest, "inputs": list(INPUT_FILES)},
        "method": METHOD,
        "objective": {"volume_weight": fit2d.VOLUME_WEIGHT,
                      "neutral_weight": fit2d.NEUTRAL_WEIGHT,
                      "width_weight": fit2d.WIDTH_WEIGHT,
                      "volume_bound_pct": fit2d.VOLUME_BOUND_PCT,
                      "root_cut_deg": objective2d.ROOT_CUT_DEG,
                      "spacing_mm": objective2d.SPACING_MM, "jaw": "from VTL's JA"},
        "count": len(entries),
        "summary": summary(entries),
        "shapes": entries,
        "workers": workers,
        "build_seconds": round(time.perf_counter() - started, 3),
    }
    page = fit_report_html.page(document, plot_href)
    (assets_dir / FIT_REPORT_PAGE).write_text(page, encoding="utf-8")
    write_json(out_path, document)
    return document, False


def build_step(ctx) -> dict:
    """``glasshead build`` step: the summary, the step's wall time and each shape's RMS,
    evaluations and seconds."""
    started = time.perf_counter()
    document, skipped = build_fit_report(ctx.assets_dir)
    return {"step": "fit-report", "skipped": skipped, "count": document["count"],
            "build_seconds": document["build_seconds"],
            "wall_seconds": round(time.perf_counter() - started, 3),
            "summary": document["summary"],
            "shapes": {e["name"]: {"rms_mm": e["rms_mm"], "evaluations": e.get("evaluations"),
                                   "seconds": e.get("seconds")} for e in document["shapes"]}}
