"""`glasshead build`: every generated asset, rebuilt only when an input has changed.

Steps run in order; each is a function ``step(ctx) -> dict`` (its report) registered in
``STEPS``. The anatomy step comes first and writes the manifest; later steps (tongue rig,
collision tables, EPG layout, face rig) read the meshes it wrote and skip themselves when their
own inputs are unchanged.

Inputs are the reference data files and the package's own source, hashed together: when that
hash matches the one recorded in ``manifest.json``, the build returns at once.
"""

import hashlib
import json
import shutil
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from glasshead.constants import MANIFEST_FILE, MANIFEST_FORMAT_VERSION
from glasshead.pipeline import sources
from glasshead.pipeline.outputs import read_json, write_json
from glasshead.pipeline.report_paths import portable
from glasshead.precompress import precompress

MANIFEST = MANIFEST_FILE
REPORT = "build-report.json"
PACKAGE_DIR = Path(__file__).resolve().parents[1]


@dataclass
class BuildContext:
    data_dir: Path
    assets_dir: Path
    log: Callable[[str], None] = print
    reports: dict = field(default_factory=dict)


#: The sources the anatomy meshes depend on; a change elsewhere does not rebuild them.
ANATOMY_SOURCES = ["constants.py", "geometry/frame.py", "geometry/meshio.py", "pipeline/sources.py",
                   "pipeline/anatomy.py", "pipeline/face_skin.py", "pipeline/head_shell.py",
                   "geometry/register_cbct.py", "pipeline/maxilla_lods.py",
                   "geometry/surface_distance.py", "pipeline/tract.py", "pipeline/tract_checks.py",
                   "pipeline/larynx.py", "pipeline/quantized_glb.py", "pipeline/neck.py",
                   "pipeline/seam_fairing.py"]


def inputs_digest(data_dir, package_files=None):
    """sha256 over the data files the build reads and the package's Python sources (all of them,
    or the ``package_files`` given relative to the package)."""
    digest = hashlib.sha256()
    code = (sorted(PACKAGE_DIR.rglob("*.py")) if package_files is None
            else [PACKAGE_DIR / name for name in package_files])
    for path in sources.input_files(data_dir) + code:
        digest.update(str(path.name).encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()


def anatomy_step(ctx):
    """Build the meshes into a staging directory, then move them in and write the manifest last,
    so a failed build never leaves a manifest that names missing or half-written files."""
    from glasshead.pipeline.anatomy import build_anatomy  # heavy imports only when building

    anatomy_digest = inputs_digest(ctx.data_dir, ANATOMY_SOURCES)
    previous = read_manifest(ctx.assets_dir)
    if previous and previous.get("anatomy_sha256") == anatomy_digest and all(
            (ctx.assets_dir / m["file"]).is_file() for m in previous["meshes"]):
        ctx.log("    meshes up to date")
        return read_json(ctx.assets_dir / REPORT).get("anatomy", {"skipped": True})
    ctx.assets_dir.mkdir(parents=True, exist_ok=True)
    stage = Path(tempfile.mkdtemp(prefix=".stage-", dir=ctx.assets_dir))
    try:
        entries, report = build_anatomy(ctx.data_dir, stage, log=ctx.log)
        for item in stage.iterdir():
            item.replace(ctx.assets_dir / item.name)
    finally:
        shutil.rmtree(stage, ignore_errors=True)
    manifest = {
        "format_version": MANIFEST_FORMAT_VERSION,
        "frame": {"units": "mm", "axes": {"x": "anterior", "y": "superior", "z": "left"},
                  "origin": "Badin (0.080, 0, 0.100) m, inside the oral cavity"},
        "inputs_sha256": None,  # written by run() once every step has succeeded
        "anatomy_sha256": anatomy_digest,
        "meshes": entries,
    }
    write_json(ctx.assets_dir / MANIFEST, manifest)
    return report


def tongue_rig_step(ctx):
    from glasshead.pipeline.tongue_rig import build_tongue_rig
    return build_tongue_rig(ctx.data_dir, ctx.assets_dir)


def collision_tables_step(ctx):
    from glasshead.pipeline.collision_tables import build_step
    return build_step(ctx.assets_dir)


def epg_layout_step(ctx):
    from glasshead.pipeline.epg_layout import build_step
    return build_step(ctx.assets_dir)


def face_rig_step(ctx):
    from glasshead.pipeline.face_rig import build_step
    return build_step(ctx)


def velum_rig_step(ctx):
    from glasshead.pipeline.velum_rig import build_step
    return build_step(ctx)


def tract_collision_step(ctx):
    from glasshead.pipeline.tract_collision_check import build_step
    return build_step(ctx)


def vtl_observations_step(ctx):
    from glasshead.pipeline.vtl_observations import build_vtl_observations
    document, skipped = build_vtl_observations(ctx.assets_dir)
    registration = document["registration"]
    return {"step": "vtl-observations", "skipped": skipped, "shapes": document["shape_count"],
            "registration_midline_mm": registration["midline"],
            "registration_rms_mm": registration["icp_trimmed_rms_mm"]}


def phoneme_targets_step(ctx):
    from glasshead.pipeline.phoneme_targets import build_step
    return build_step(ctx)


def fit_report_step(ctx):
    from glasshead.pipeline.fit_report import build_step
    return build_step(ctx)


def vowel_norms_step(ctx):
    from glasshead.pipeline.vowel_norms import build_step
    return build_step(ctx)


def tract_section_step(ctx):
    from glasshead.pipeline.tract_section import build_step
    return build_step(ctx)


def inversion_codebook_step(ctx):
    from glasshead.pipeline.inversion_codebook import build_step
    return build_step(ctx)


def landmarks_step(ctx):
    from glasshead.pipeline.landmarks import build_step
    return build_step(ctx.assets_dir)


#: (name, step) in the order they run.
STEPS = [
    ("anatomy", anatomy_step),
    ("tongue-rig", tongue_rig_step),
    ("collision-tables", collision_tables_step),
    ("epg-layout", epg_layout_step),
    ("face-rig", face_rig_step),
    ("velum-rig", velum_rig_step),
    ("tract-collision", tract_collision_step),
    ("landmarks", landmarks_step),
    ("vtl-observations", vtl_observations_step),
    ("phoneme-targets", phoneme_targets_step),
    ("fit-report", fit_report_step),
    ("vowel-norms", vowel_norms_step),
    ("tract-section", tract_section_step),
    ("inversion-codebook", inversion_codebook_step),
]


def read_manifest(assets_dir):
    return read_json(Path(assets_dir) / MANIFEST) or None


def is_up_to_date(assets_dir, digest):
    manifest = read_manifest(assets_dir)
    return bool(manifest) and manifest.get("inputs_sha256") == digest and all(
        (Path(assets_dir) / m["file"]).is_file() for m in manifest.get("meshes", []))


def _make_report_portable(assets_dir, data_dir):
    report = read_json(assets_dir / REPORT)
    if report:
        fixed = portable(report, assets_dir=assets_dir, data_dir=data_dir)
        if fixed != report:
            write_json(assets_dir / REPORT, fixed)


def run(data_dir, assets_dir, force=False, log=print):
    """Build what is stale. Returns the report dict (``{"up_to_date": True}`` when nothing was)."""
    data_dir, assets_dir = Path(data_dir), Path(assets_dir)
    sources.check_data_dir(data_dir)
    digest = inputs_digest(data_dir)
    if not force and is_up_to_date(assets_dir, digest):
        _make_report_portable(assets_dir, data_dir)  # one written before reports were
        precompress(assets_dir)  # the .gz siblings the server sends (glasshead/precompress.py)
        log(f"assets up to date in {assets_dir}")
        return {"up_to_date": True}
    ctx = BuildContext(data_dir=data_dir, assets_dir=assets_dir, log=log)
    started = time.perf_counter()
    for name, step in STEPS:
        log(f"==> {name}")
        step_started = time.perf_counter()
        ctx.reports[name] = step(ctx)
        log(f"    {name} done in {time.perf_counter() - step_started:.1f} s")
    ctx.reports["total_s"] = round(time.perf_counter() - started, 3)
    write_json(assets_dir / REPORT, portable(ctx.reports, assets_dir=assets_dir,
                                             data_dir=data_dir))
    manifest = json.loads((assets_dir / MANIFEST).read_text())
    manifest["inputs_sha256"] = digest
    write_json(assets_dir / MANIFEST, manifest)
    precompress(assets_dir)
    log(f"built {len(manifest['meshes'])} meshes and {len(STEPS) - 1} tables in "
        f"{ctx.reports['total_s']:.1f} s; report in {assets_dir / REPORT}")
    return ctx.reports
