"""Build step: the velum rig definition ``assets/build/velum-rig.json``.

It holds what ``velum_opening`` needs on both sides (``geometry.velum``, ``web/src/core/velum.js``):

- the parameter, in the tongue rig's table format: 0 raised (port closed), 1 lowered, neutral r;
- the three measured poses' vertex positions (mm, the velum GLBs' vertex order), placed at 0, r
  and 1, where r is the rest pose's share of the raised -> lowered path by mean vertex
  displacement;
- the nasal port's samples: fixed points of the raised velum's posterior surface (triangle and
  barycentric weights), on cuts across the passage at and above the palatal plane, over the
  width of the posterior pharyngeal wall, with the wall's normal at each (docs/velum.md).
"""

import hashlib
import json
from pathlib import Path
from typing import Any

import numpy as np

from glasshead.constants import (
    MANIFEST_FILE,
    VELUM_PARAMETER,
    VELUM_POSES,
    VELUM_RIG_FILE,
    VELUM_RIG_FORMAT_VERSION,
)
from glasshead.geometry import velum as evaluator
from glasshead.pipeline.outputs import load_built_meshes, read_json

OUTPUT_NAME = VELUM_RIG_FILE
#: Bump when the build changes in a way that must rebuild the output.
BUILD_REVISION = 1
#: The meshes the rig is made from (built by the anatomy step).
MESHES = ("velum_raised", "velum_rest", "velum_lowered", "pharynx")
#: Decimals kept: positions and the wall (1e-5 mm), weights and normals (1e-6).
POSITION_DECIMALS = 5
WEIGHT_DECIMALS = 6
#: mm. Spacing of the port's samples across the passage (z) and between its cuts (y).
SAMPLE_STEP_MM = 1.0
#: mm. Band below the top of the measured pharyngeal wall (at the midline) whose lateral extent
#: gives the port's width.
WALL_BAND_MM = 6.0
#: mm. Half-width of the strip about the midline in which the velum's front edge (its joint with
#: the hard palate) and the pharyngeal wall's top are read.
MIDLINE_MM = 2.0
#: mm. Depth behind the velum's front-most point that counts as its joint with the hard palate.
JOINT_DEPTH_MM = 2.0
#: Openings at which the build checks that the port area never shrinks.
CHECK_OPENINGS = 201


def load_meshes(assets_dir):
    """dict name -> (vertices (n, 3) float64, faces (m, 3) int64, sha256) of MESHES, from the
    manifest in assets_dir. ValueError naming a mesh that is not there."""
    return load_built_meshes(assets_dir, MESHES)


def rest_share(raised, rest, lowered):
    """r: the rest pose's share of the raised -> rest -> lowered path, by mean vertex
    displacement; with the two means (mm)."""
    first = float(np.linalg.norm(rest - raised, axis=1).mean())
    second = float(np.linalg.norm(lowered - rest, axis=1).mean())
    return first / (first + second), first, second


def first_hits_along_x(vertices, faces, y, z):
    """The first crossing of the line (t, y, z), t growing from -inf (posterior to anterior),
    with the mesh: (triangle index, barycentric weights (3,), x) or None when it misses."""
    tri = vertices[faces]
    a, b, c = tri[:, 0, 1:], tri[:, 1, 1:], tri[:, 2, 1:]
    e1, e2, p = b - a, c - a, np.array([y, z]) - a
    det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    ok = np.abs(det) > 1e-12
    safe = np.where(ok, det, 1.0)
    v = (p[:, 0] * e2[:, 1] - p[:, 1] * e2[:, 0]) / safe
    w = (e1[:, 0] * p[:, 1] - e1[:, 1] * p[:, 0]) / safe
    inside = ok & (v >= 0) & (w >= 0) & (v + w <= 1)
    if not inside.any():
        return None
    candidates = np.flatnonzero(inside)
    weights = np.stack([1 - v[candidates] - w[candidates], v[candidates], w[candidates]], 1)
    x = np.einsum("ij,ij->i", weights, tri[candidates, :, 0])
    k = int(np.argmin(x))
    return int(candidates[k]), weights[k], float(x[k])


def palatal_level(raised):
    """mm: the height of the velum's joint with the hard palate (its front edge at the
    midline), where the palatal plane meets the velum."""
    mid = raised[np.abs(raised[:, 2]) < MIDLINE_MM]
    front = mid[:, 0].max()
    return float(mid[mid[:, 0] > front - JOINT_DEPTH_MM][:, 1].mean())


def wall_width(pharynx):
    """mm: the lateral extent (z) of the measured pharyngeal wall in the band WALL_BAND_MM
    below its top at the midline; with that top's height."""
    mid = pharynx[np.abs(pharynx[:, 2]) < MIDLINE_MM]
    top = float(mid[:, 1].max())
    band = pharynx[(pharynx[:, 1] > top - WALL_BAND_MM) & (pharynx[:, 1] <= top)]
    return float(band[:, 2].max() - band[:, 2].min()), top


def port_samples(raised, faces, width, level):
    """The port's samples on the raised velum's posterior surface: cuts at level, level + 1 mm,
    ... while every one of the cut's samples (spaced across ``width``, centred on the midline)
    lies on the velum. Returns dict of vertices (k, 3), weights (k, 3), normals (k, 3), rows (k,),
    row heights, the width a sample stands for and the z of the samples."""
    count = max(1, int(round(width / SAMPLE_STEP_MM)))
    step = width / count
    zs = -width / 2 + step * (np.arange(count) + 0.5)
    vertices: list = []
    weights: list = []
    normals: list = []
    rows: list = []
    heights: list = []
    y = level
    while True:
        hits = [first_hits_along_x(raised, faces, y, z) for z in zs]
        if any(hit is None for hit in hits):
            break
        for triangle, w, _ in hits:
            corners = faces[triangle]
            a, b, c = raised[corners]
            normal = np.cross(b - a, c - a)
            normal /= np.linalg.norm(normal)
            if normal[0] > 0:  # toward the pharynx (posterior)
                normal = -normal
            vertices.append(corners)
            weights.append(w)
            normals.append(normal)
            rows.append(len(heights))
        heights.append(y)
        y += SAMPLE_STEP_MM
    if not heights:
        raise ValueError(f"the raised velum has no full cut of width {width:.1f} mm at "
                         f"y = {level:.1f} mm")
    return {"vertices": np.array(vertices), "weights": np.array(weights),
            "normals": np.array(normals), "rows": np.array(rows), "heights": heights,
            "width_mm": step, "z_mm": zs}


def _flat(array, decimals):
    return [round(float(v), decimals) for v in np.asarray(array).ravel()]


def build_velum_rig(assets_dir):
    """The definition document (without ``inputs_sha256``) and its report."""
    meshes = load_meshes(assets_dir)
    raised, faces, _ = meshes["velum_raised"]
    rest, lowered = meshes["velum_rest"][0], meshes["velum_lowered"][0]
    r, first, second = rest_share(raised, rest, lowered)
    r = round(r, WEIGHT_DECIMALS)
    positions = {name: _flat(meshes[f"velum_{name}"][0], POSITION_DECIMALS)
                 for name in VELUM_POSES}
    width, wall_top = wall_width(meshes["pharynx"][0])
    level = palatal_level(np.array(positions["raised"]).reshape(-1, 3))
    raised_stored = np.array(positions["raised"]).reshape(-1, 3)
    samples = port_samples(raised_stored, faces, width, level)
    definition: dict[str, Any] = {
        "format_version": VELUM_RIG_FORMAT_VERSION,
        "description": "The velum (soft palate) as one mesh in three measured poses blended by "
                       "velum_opening, and the samples of the nasal port (docs/velum.md).",
        "frame": {"units": "mm", "axes": {"x": "anterior", "y": "superior", "z": "left"},
                  "name": "project"},
        "parameters": [{
            "name": VELUM_PARAMETER, "unit": "ratio", "min": 0.0, "max": 1.0, "neutral": r,
            "group": "velum",
            "description": "0 raised (nasal port closed, oral sounds), r rest, 1 lowered "
                           "(port open, nasals); blends the three measured poses piecewise"}],
        "poses": {
            "names": list(VELUM_POSES), "at": [0.0, r, 1.0],
            "vertex_count": len(raised), "triangle_count": len(faces),
            "meshes": {name: f"velum_{name}" for name in VELUM_POSES},
            "rest_share": {"value": r, "rule": "mean vertex displacement raised -> rest over "
                                               "raised -> rest plus rest -> lowered",
                           "raised_to_rest_mm": round(first, 4),
                           "rest_to_lowered_mm": round(second, 4)},
            "positions": positions},
        "port": {
            "description": "samples of the raised velum's posterior surface (the wall where it "
                           "closes the port): a triangle's vertices and barycentric weights, "
                           "the wall's unit normal toward the pharynx, and the cut across the "
                           "passage each lies on. gap = max(0, (wall - posed) . normal); cut "
                           "area = sum of gaps * width_mm; port area = the smallest cut.",
            "vertices": [int(v) for v in samples["vertices"].ravel()],
            "weights": _flat(samples["weights"], WEIGHT_DECIMALS),
            "normals": _flat(samples["normals"], WEIGHT_DECIMALS),
            "rows": [int(v) for v in samples["rows"]],
            "row_count": len(samples["heights"]),
            "row_heights_mm": [round(h, 3) for h in samples["heights"]],
            "width_mm": round(samples["width_mm"], WEIGHT_DECIMALS),
            "samples_per_row": len(samples["z_mm"]),
            "palatal_level_mm": round(level, 3),
            "wall_width_mm": round(width, 3),
            "pharynx_top_mm": round(wall_top, 3)},
    }
    rig = evaluator.prepare_velum(definition)
    report = port_report(rig)
    definition["port"]["areas_mm2"] = report["areas_mm2"]
    return definition, report


def port_report(rig):
    """Port areas at a few openings, and the check that the area never shrinks as the velum
    lowers (ValueError when it does)."""
    openings = np.linspace(0.0, 1.0, CHECK_OPENINGS)
    areas = np.array([evaluator.nasal_port_area(rig, o) for o in openings])
    if areas[0] != 0.0 or np.any(np.diff(areas) < 0):
        worst = int(np.argmin(np.diff(areas)))
        raise ValueError(f"the nasal port area shrinks from opening {openings[worst]:.3f} to "
                         f"{openings[worst + 1]:.3f} ({areas[worst]:.3f} -> "
                         f"{areas[worst + 1]:.3f} mm^2) or is not 0 when raised")
    r = rig.rest_share
    named = {"0": 0.0, "0.25": 0.25, "0.5": 0.5, "r": r, "0.75": 0.75, "1": 1.0}
    return {"rest_share": r,
            "areas_mm2": {k: round(evaluator.nasal_port_area(rig, o), 3)
                          for k, o in named.items()},
            "monotonic_over": CHECK_OPENINGS}


def input_key(assets_dir):
    """sha256 over the meshes' content hashes, this step's sources and its revision."""
    manifest = json.loads((Path(assets_dir) / MANIFEST_FILE).read_text())
    entries = {m["name"]: m.get("sha256") for m in manifest.get("meshes", [])}
    digest = hashlib.sha256(f"velum-rig {BUILD_REVISION}".encode())
    for name in MESHES:
        digest.update(f"{name}={entries.get(name)}".encode())
    for module in (__file__, evaluator.__file__):
        digest.update(Path(module).read_bytes())
    return digest.hexdigest()


def build_step(ctx):
    """The `glasshead build` step: write ``velum-rig.json`` unless it records the same inputs."""
    assets_dir = Path(ctx.assets_dir)
    out = assets_dir / OUTPUT_NAME
    key = input_key(assets_dir)
    existing = read_json(out)
    if existing.get("inputs_sha256") == key:
        return {"step": "velum-rig", "file": str(out), "skipped": True,
                **existing.get("report", {})}
    definition, report = build_velum_rig(assets_dir)
    definition["report"] = report
    definition["inputs_sha256"] = key
    temporary = out.with_name(out.name + ".tmp")
    temporary.write_text(json.dumps(definition, separators=(",", ":")))
    temporary.replace(out)
    return {"step": "velum-rig", "file": str(out), "skipped": False, **report}
