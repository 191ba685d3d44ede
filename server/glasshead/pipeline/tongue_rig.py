"""Build step: fit the tongue rig's rest shape to the MRI tongue; write the tongue-rig.json asset.

``build_tongue_rig(data_dir, out_dir)`` reads ``anatomy/artisynth-badin/tongue.obj`` (the rest
tongue) and ``jaw.obj`` (for the temporomandibular pivot), converts them into the project frame,
fits the rest shape (``pipeline.tongue_fit``), measures it against the MRI with closest-point
distances both ways, and writes the definition with the fit report in it. It skips the work when
the output already records the same inputs (the SHA-256 of the sources and of the code).
"""

import hashlib
import inspect
import json
import time
from pathlib import Path
from typing import Any

import numpy as np
import trimesh

from glasshead.constants import BADIN_TO_PROJECT_AXES, TONGUE_RIG_FILE, TONGUE_RIG_FORMAT_VERSION
from glasshead.geometry import bspline, tongue_parameters
from glasshead.geometry import jaw as jaw_module
from glasshead.geometry import tongue_rig as rig_template
from glasshead.geometry.frame import badin_to_project, fix_winding
from glasshead.geometry.jaw import estimate_condyle, jaw_definition
from glasshead.geometry.mesh_volume import mesh_volume
from glasshead.geometry.meshio import read_obj
from glasshead.geometry.tongue_rig import HUB_MM, build_definition
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.pipeline import tongue_fit

BADIN_DIR = Path("anatomy") / "artisynth-badin"
OUTPUT_NAME = TONGUE_RIG_FILE
#: Bump when the fit or the definition changes in a way that must rebuild the output.
FIT_REVISION = 1
#: Surface samples per triangle-mesh for the distance report (plus every vertex).
DISTANCE_SAMPLES = 20000
DISTANCE_SEED = 20240


def load_badin_mesh(data_dir, name):
    """A Badin mesh in the project frame: vertices (n, 3) float64 mm, triangles (m, 3) int64."""
    vertices, triangles = read_obj(Path(data_dir) / BADIN_DIR / f"{name}.obj")
    return badin_to_project(vertices), fix_winding(triangles, BADIN_TO_PROJECT_AXES)


def _sha256(path):
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


#: Modules whose code shapes the output; their text is part of the cache key.
CODE = (tongue_fit, rig_template, tongue_parameters, jaw_module, bspline)


def input_key(data_dir):
    """What the output depends on: the two source files and the code that builds the rig."""
    base = Path(data_dir) / BADIN_DIR
    code = hashlib.sha256()
    for module in CODE:
        code.update(Path(inspect.getfile(module)).read_bytes())
    return {"tongue.obj": _sha256(base / "tongue.obj"), "jaw.obj": _sha256(base / "jaw.obj"),
            "code": code.hexdigest(), "fit_revision": FIT_REVISION,
            "format_version": TONGUE_RIG_FORMAT_VERSION}


def surface_distances(vertices_a, triangles_a, vertices_b, triangles_b,
                      samples=DISTANCE_SAMPLES, seed=DISTANCE_SEED):
    """Closest-point distances, mm, from surface a to b and from b to a.

    Each surface is represented by its vertices plus ``samples`` area-uniform points.
    Returns {"a_to_b": {"mean", "max", "rms"}, "b_to_a": {...}, "mean": mean of both means}.
    """
    a = trimesh.Trimesh(vertices_a, triangles_a, process=False)
    b = trimesh.Trimesh(vertices_b, triangles_b, process=False)
    report: dict[str, Any] = {}
    for key, source, target, offset in (("a_to_b", a, b, 0), ("b_to_a", b, a, 1)):
        points, _ = trimesh.sample.sample_surface(source, samples, seed=seed + offset)
        points = np.vstack([source.vertices, points])
        distance = trimesh.proximity.closest_point(target, points)[1]
        report[key] = {"mean": float(distance.mean()), "max": float(distance.max()),
                       "rms": float(np.sqrt(np.mean(distance**2)))}
    report["mean"] = 0.5 * (report["a_to_b"]["mean"] + report["b_to_a"]["mean"])
    return report


def fit_definition(data_dir):
    """Fit the rig to the MRI tongue; returns the definition (with its fit report)."""
    started = time.perf_counter()
    mri_vertices, mri_triangles = load_badin_mesh(data_dir, "tongue")
    jaw_vertices, _ = load_badin_mesh(data_dir, "jaw")
    jaw = jaw_definition(estimate_condyle(jaw_vertices), source={
        "mesh": str(BADIN_DIR / "jaw.obj"),
        "pivot": "mean of the top 5 mm of the condyles (back half of the mandible)"})

    problem = tongue_fit.RestShapeProblem(mri_vertices, mri_triangles)
    positions, weights, ratios, pole = problem.unpack(problem.solve())

    # Sample the fitted surface finely once to spread the final stations and page angles.
    fine_phi = np.linspace(-90.0, 90.0, 721)
    common = {"sagittal_positions": positions, "section_weights": weights, "ratios": ratios,
              "pole_half_width": pole, "jaw": jaw, "hub": HUB_MM}
    stations = tongue_fit.station_params(positions)
    probe = TongueRig(build_definition(station_params=stations, page_angles_deg=fine_phi[1:-1],
                                       **common))
    _hub, _s, _d, radii, _stretch = probe.page_radii(probe.neutral)
    pages = tongue_fit.page_angles_deg(radii, fine_phi[1:-1])

    definition = build_definition(station_params=stations, page_angles_deg=pages, **common)
    rig = TongueRig(definition)
    rest = rig.vertices(rig.neutral)
    distances = surface_distances(rest, rig.triangles, mri_vertices, mri_triangles)
    definition["fit"] = {
        "target": str(BADIN_DIR / "tongue.obj"),
        "method": "radial least squares about the hub (scipy trust region), see "
                  "glasshead.pipeline.tongue_fit",
        "distance_mm": {"rig_to_mri": distances["a_to_b"], "mri_to_rig": distances["b_to_a"],
                        "mean_both_ways": distances["mean"]},
        "volume_mm3": {"rig": mesh_volume(rest, rig.triangles),
                       "mri": mesh_volume(mri_vertices, mri_triangles)},
        "seconds": time.perf_counter() - started,
    }
    definition["source"] = {"inputs": input_key(data_dir),
                            "credit": "Badin et al. MRI tongue via the ArtiSynth project "
                                      "(ArtiSynth Models licence)"}
    return definition


def build_tongue_rig(data_dir, out_dir):
    """Write ``out_dir/tongue-rig.json`` unless it is up to date; returns the build report.

    Report: {"step": "tongue-rig", "file", "skipped", "vertices", "triangles", "fit": {...}}.
    """
    out = Path(out_dir) / OUTPUT_NAME
    key = input_key(data_dir)
    if out.is_file():
        try:
            existing = json.loads(out.read_text())
        except json.JSONDecodeError:
            existing = None
        if existing and existing.get("source", {}).get("inputs") == key:
            return _report(out, existing, skipped=True)
    definition = fit_definition(data_dir)
    out.parent.mkdir(parents=True, exist_ok=True)
    temporary = out.with_suffix(".json.tmp")
    temporary.write_text(json.dumps(definition, indent=1))
    temporary.replace(out)
    return _report(out, definition, skipped=False)


def _report(path, definition, skipped):
    surface = definition["surface"]
    return {"step": "tongue-rig", "file": str(path), "skipped": skipped,
            "vertices": surface["vertex_count"], "triangles": surface["triangle_count"],
            "fit": definition.get("fit", {})}
