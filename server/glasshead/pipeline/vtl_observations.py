"""Build step: VocalTractLab's JD3 shapes as observations in the project frame.

``build_vtl_observations(assets_dir, out_path)`` reads every stored vocal tract shape of the
speaker the ``vocaltractlab-cython`` bindings ship (``vtl_speaker``), registers VTL's hard palate
and upper incisor onto the built maxilla (``vtl_registration``), moves every outline and
surface into the project frame and writes one JSON (default ``assets/build/vtl-observations.json``)
with the registration's residuals and the SHA-256 of its inputs. It skips the work when the
output already records the same inputs. ``glasshead build`` runs it as its step
``vtl-observations``.
"""

import hashlib
import inspect
import time
from importlib import metadata
from pathlib import Path

import numpy as np

from glasshead.constants import FRAME_AXES, FRAME_UNITS, VTL_OBSERVATIONS_FILE
from glasshead.geometry import midsagittal, register_cbct, surface_distance
from glasshead.geometry.frame import fix_winding
from glasshead.pipeline import vtl_registration
from glasshead.pipeline import vtl_speaker as vtl
from glasshead.pipeline.outputs import current_output, load_built_meshes, write_json

FORMAT_VERSION = 1
#: Bump when the output changes in a way that must rebuild it.
BUILDER = 1
#: Decimals kept for coordinates (mm): 1 micrometre, far below VTL's own precision.
DECIMALS = 3
#: Modules whose code shapes the output; their text is part of the cache key.
CODE = (vtl, vtl_registration, midsagittal, register_cbct, surface_distance)
CREDIT = ("Vocal tract shapes of the JD3 speaker of VocalTractLab (Peter Birkholz, "
          "www.vocaltractlab.de), read through the vocaltractlab-cython bindings (Paul Krug); "
          "both GPL-3.0.")


def _round(points):
    return np.round(np.asarray(points, dtype=np.float64), DECIMALS).tolist()


def input_key(maxilla_sha256):
    """SHA-256 over the speaker file, the bindings' version, the built maxilla and the code."""
    digest = hashlib.sha256()
    digest.update(vtl.speaker_file().read_bytes())
    digest.update(_package_version().encode())
    digest.update(str(maxilla_sha256).encode())
    for module in CODE:
        digest.update(inspect.getsource(module).encode())
    digest.update(f"{FORMAT_VERSION}/{BUILDER}".encode())
    return digest.hexdigest()


def _package_version():
    try:
        return metadata.version("vocaltractlab-cython")
    except metadata.PackageNotFoundError:
        return "unknown"


def _surface(transform, vertices, triangles):
    """A VTL surface in the project frame; the z mirror reverses the winding back."""
    faces = fix_winding(triangles, vtl_registration.VTL_TO_PROJECT_AXES)
    return {"vertices": _round(transform.apply(vertices)), "triangles": faces.tolist()}


def _shape_record(record, transform):
    vertices, _ = record["tongue_surface"]
    outline = transform.apply(record["tongue_outline"])
    return {
        "name": record["name"],
        "class": record["class"],
        "params": {k: round(v, 6) for k, v in record["params"].items()},
        "settings": record["settings"],
        "constriction": record["constriction"],
        "tongue_length_mm": round(vtl.tongue_length(outline), 2),
        "tongue_outline": _round(outline),
        "upper_outline": _round(transform.apply(record["upper_outline"])),
        "lower_outline": _round(transform.apply(record["lower_outline"])),
        "tongue_surface_vertices": _round(transform.apply(vertices)),
    }


def observe_all(maxilla_vertices, maxilla_faces):
    """Every shape in the project frame: (document body without source/timing, transform)."""
    palate = vtl.palate_geometry()
    section = midsagittal.midline_section(maxilla_vertices, maxilla_faces)
    transform, report = vtl_registration.register_palate(palate["registration_outline"],
                                                         section)
    report["palate_surface_to_maxilla"] = vtl_registration.surface_residual(
        transform, [palate["palate_surface"]], maxilla_vertices, maxilla_faces)
    report["upper_teeth_surface_to_maxilla"] = vtl_registration.surface_residual(
        transform, [palate["upper_teeth_surface"]], maxilla_vertices, maxilla_faces)
    records = vtl.observations()
    triangles = fix_winding(records[0]["tongue_surface"][1],
                            vtl_registration.VTL_TO_PROJECT_AXES)
    body = {
        "registration": {"transform": transform.to_json(), **report},
        "palate": {
            "vault_outline": _round(transform.apply(palate["vault_outline"])),
            "incisor_outline": _round(transform.apply(palate["incisor_outline"])),
            "maxilla_midline": [_round(p) for p in section],
            "palate_surface": _surface(transform, *palate["palate_surface"]),
            "upper_teeth_surface": _surface(transform, *palate["upper_teeth_surface"]),
        },
        "tongue_surface_triangles": triangles.tolist(),
        "shapes": [_shape_record(record, transform) for record in records],
    }
    return body, transform


def build_vtl_observations(assets_dir, out_path=None, force=False):
    """Write the observations; returns (document, skipped)."""
    assets_dir = Path(assets_dir)
    out_path = Path(out_path) if out_path else assets_dir / VTL_OBSERVATIONS_FILE
    vertices, faces, maxilla_sha = load_built_meshes(assets_dir, ["maxilla"])["maxilla"]
    digest = input_key(maxilla_sha)
    existing = None if force else current_output(out_path, digest, BUILDER, FORMAT_VERSION)
    if existing is not None:
        return existing, True
    started = time.perf_counter()
    body, _ = observe_all(vertices, faces)
    document = {
        "format_version": FORMAT_VERSION,
        "builder": BUILDER,
        "frame": {"units": FRAME_UNITS, "axes": FRAME_AXES},
        "source": {
            "sha256": digest,
            "package": f"vocaltractlab-cython {_package_version()}",
            "api_version": vtl.api().get_version(),
            "speaker_file": vtl.speaker_file().name,
            "speaker_sha256": hashlib.sha256(vtl.speaker_file().read_bytes()).hexdigest(),
            "maxilla_sha256": maxilla_sha,
        },
        "credit": CREDIT,
        "shape_count": len(body["shapes"]),
        **body,
        "build_seconds": round(time.perf_counter() - started, 3),
    }
    out_path.parent.mkdir(parents=True, exist_ok=True)
    write_json(out_path, document)
    return document, False
