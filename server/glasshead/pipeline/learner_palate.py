"""A learner's own palate: a scan of their upper jaw (STL, PLY or OBJ, as intraoral scanners and
digitised dental casts give it) placed on the head and made into that learner's collision tables
and EPG electrode layout, so that contact is computed on the palate that is theirs.

1. Reading (``read_scan``). The scan must be a triangle mesh of at most ``MAX_TRIANGLES``
   triangles (the count is read from a binary STL's header before its triangles are). Scanners
   write millimetres; a scan whose extent is under ``METRES_BELOW`` is taken to be in metres.
2. Registration (``register_scan``). First onto the head's whole maxilla as the build registers
   the CBCT maxilla (``geometry.register_cbct``: the 24 axis orientations, then trimmed
   similarity ICP, so a scan upside down or turned is found), then refined by a trimmed
   similarity ICP of the head's mouth-facing surface alone (``maxilla_lods.mouth_facing``: the
   vault, the ridge and the teeth's inner faces, what the tongue touches and the electrodes lie
   on) onto the scan, ``REFINE_TRIM`` of the worst pairs left out. The residual is measured on
   that surface, head to scan. A residual over ``MAX_RESIDUAL_RMS_MM`` is not a palate of this
   head (a lower jaw, a scan of something else): it is refused with the figure and a picture
   of the scan as placed over the head's palate, cut down the middle (``residual_picture``).
3. Rebuilding (``build_learner_palate``): the placed scan's collision tables
   (``pipeline.collision_tables``) and electrode layout (``pipeline.epg_layout``, the Reading
   rules placed on that palate), written with the placed mesh and a report into a new folder
   that replaces the old one only once everything is written: a failed rebuild leaves the
   previous palate in use.
"""

import io
import json
import shutil
import struct
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from xml.sax.saxutils import escape

import numpy as np
import trimesh
from scipy.spatial import cKDTree

from glasshead.asset_store import read_glb_mesh
from glasshead.constants import COLLISION_TABLES_FILE, EPG_LAYOUT_FILE
from glasshead.geometry.midsagittal import midline_section
from glasshead.geometry.register_cbct import icp, register_cbct
from glasshead.geometry.surface_distance import SurfaceDistance, sample_surface, summarise
from glasshead.pipeline.anatomy import write_glb
from glasshead.pipeline.collision_tables import build_collision_tables, load_scene_maxilla
from glasshead.pipeline.epg_layout import build_epg_layout
from glasshead.pipeline.maxilla_lods import mouth_facing, mouth_point

#: The file types a scan may be.
SCAN_TYPES = ("stl", "ply", "obj")
#: Largest scan, triangles (an intraoral scan of an upper jaw is 100,000 to 1,000,000).
MAX_TRIANGLES = 2_000_000
#: A scan whose largest extent is under this is in metres (an upper jaw is 40 to 80 mm across).
METRES_BELOW = 1.0
#: Fraction of the worst pairs left out of the refining ICP (the scan's gums and the head's
#: teeth need not match).
REFINE_TRIM = 0.1
#: Iterations of the refining ICP.
REFINE_ITERATIONS = 60
#: Above this residual on the mouth-facing surface the scan is not taken, mm.
MAX_RESIDUAL_RMS_MM = 2.5
#: What the palate folder holds besides the tables and the layout.
PALATE_MESH, REPORT_FILE = "palate.glb", "palate-report.json"


class ScanError(ValueError):
    """A scan that cannot become a palate; the message says why, in words. ``picture``: an SVG
    of the scan as placed over the head's palate, when it was placed but did not fit."""

    def __init__(self, message: str, picture: str | None = None):
        super().__init__(message)
        self.picture = picture


#: The residual picture's scale at most, px per mm, its width at most, px, and its margin round
#: the head's palate, mm.
PICTURE_PX_PER_MM, PICTURE_WIDTH_PX, PICTURE_MARGIN_MM = 8.0, 640.0, 15.0
PICTURE_COLOURS = {"head": "#9a8a6e", "scan": "#1565c0"}


def residual_picture(maxilla_vertices, maxilla_faces, placed_vertices, placed_faces,
                     residual: dict) -> str:
    """An SVG of the mid-sagittal cuts of the head's maxilla and of the scan as placed on it,
    lips to the left, with the residual in its title: what a clinician looks at when a scan is
    refused."""
    cuts = {}
    for name, (v, f) in (("head", (maxilla_vertices, maxilla_faces)),
                         ("scan", (placed_vertices, placed_faces))):
        try:
            cuts[name] = midline_section(v, f)
        except ValueError:  # a scan placed off the mid-sagittal plane: only the head is drawn
            cuts[name] = []
    # Framed on the head's palate: a scan placed far off runs out of the picture.
    points = np.vstack(cuts["head"])
    low, high = points.min(axis=0) - PICTURE_MARGIN_MM, points.max(axis=0) + PICTURE_MARGIN_MM
    scale = min(PICTURE_PX_PER_MM, PICTURE_WIDTH_PX / (high[0] - low[0]))
    width, height = (high - low) * scale

    def path(line):
        # Anterior (+x) on the left, as the head's profile is drawn; +y up.
        xy = [f"{(high[0] - x) * scale:.1f},{(high[1] - y) * scale:.1f}" for x, y in line]
        return f'<polyline points="{" ".join(xy)}" fill="none" />'

    groups = [f'<g class="{name}" stroke="{PICTURE_COLOURS[name]}" stroke-width="1.5">'
              + "".join(path(line) for line in lines) + "</g>" for name, lines in cuts.items()]
    title = (f"The scan (blue) on the head's palate (brown), cut down the middle: "
             f"{residual['rms_mm']:.1f} mm RMS on the palate and teeth")
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0f}" '
            f'height="{height + 24:.0f}" viewBox="0 -24 {width:.0f} {height + 24:.0f}" '
            'overflow="hidden">'
            f"<title>{escape(title)}</title>"
            f'<text x="4" y="-8" font-size="11" font-family="sans-serif">{escape(title)}</text>'
            + "".join(groups) + "</svg>")


def read_scan(data: bytes, file_type: str) -> tuple[np.ndarray, np.ndarray, dict]:
    """(vertices (n, 3) mm, faces (m, 3), notes) of a scan file's bytes; ScanError when it is
    not a mesh, is empty or too large."""
    kind = file_type.lower().lstrip(".")
    if kind not in SCAN_TYPES:
        raise ScanError(f"a scan must be {', '.join(t.upper() for t in SCAN_TYPES)}, not {kind!r}")
    if kind == "stl" and len(data) >= 84 and not data[:5].lower().startswith(b"solid"):
        count = struct.unpack_from("<I", data, 80)[0]
        if count > MAX_TRIANGLES:
            raise ScanError(f"the scan has {count:,} triangles; at most {MAX_TRIANGLES:,} are "
                            "taken (decimate it in the scanner's software)")
    try:
        mesh = trimesh.load(io.BytesIO(data), file_type=kind, force="mesh", process=False)
    except Exception as exc:  # trimesh raises many kinds for a bad file
        raise ScanError(f"the file is not a readable {kind.upper()} mesh: {exc}") from None
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        raise ScanError(f"the file holds no triangles: it is not a {kind.upper()} mesh of a jaw")
    if len(mesh.faces) > MAX_TRIANGLES:
        raise ScanError(f"the scan has {len(mesh.faces):,} triangles; at most "
                        f"{MAX_TRIANGLES:,} are taken (decimate it in the scanner's software)")
    vertices = np.asarray(mesh.vertices, dtype=np.float64)
    if not np.all(np.isfinite(vertices)):
        raise ScanError("the scan has vertices that are not numbers")
    extent = float(np.ptp(vertices, axis=0).max())
    if extent <= 0:
        raise ScanError("the scan is flat: all its points are one")
    notes = {"triangles": int(len(mesh.faces)), "vertices": int(len(vertices)),
             "extent": round(extent, 6), "units": "mm"}
    if extent < METRES_BELOW:
        vertices = vertices * 1000.0
        notes["units"] = "m (scaled to mm)"
    return vertices, np.asarray(mesh.faces, dtype=np.int64), notes


def register_scan(scan_vertices, scan_faces, maxilla_vertices, maxilla_faces
                  ) -> tuple[np.ndarray, np.ndarray, dict]:
    """Place a scan (mm, its own axes) on the head's maxilla (project frame): (vertices,
    faces, report with the residual on the mouth-facing surface); ScanError when the residual
    passes ``MAX_RESIDUAL_RMS_MM``."""
    placed, faces, coarse = register_cbct(scan_vertices, scan_faces, maxilla_vertices,
                                          maxilla_faces)
    point = mouth_point(maxilla_vertices)
    arch = (maxilla_vertices.min(axis=0), maxilla_vertices.max(axis=0))
    facing = np.asarray(maxilla_faces)[mouth_facing(maxilla_vertices, maxilla_faces, point, arch)]
    source, _ = sample_surface(maxilla_vertices, facing, seed=6)
    target, _ = sample_surface(placed, faces, seed=7)
    scale, rot, shift, trimmed = icp(source, cKDTree(target), target, REFINE_ITERATIONS,
                                     trim=REFINE_TRIM)
    # The scan takes the inverse of the head-to-scan similarity.
    placed = (placed - shift) @ rot / scale
    check, _ = sample_surface(maxilla_vertices, facing, seed=5)
    residual = summarise(SurfaceDistance(placed, faces).distance(check))
    report = {"axes": coarse["axes_cbct_to_badin"], "scale": round(coarse["scale"] / scale, 5),
              "whole_maxilla_icp_trimmed_rms_mm": coarse["icp_trimmed_rms_mm"],
              "refined_trimmed_rms_mm": round(float(trimmed), 3),
              "mouth_facing_residual": residual}
    if residual["rms_mm"] > MAX_RESIDUAL_RMS_MM:
        raise ScanError(
            f"the scan does not fit this head's palate: {residual['rms_mm']:.1f} mm RMS on the "
            f"palate and teeth after registration (at most {MAX_RESIDUAL_RMS_MM} mm is taken). "
            "Is it a scan of the upper jaw?",
            picture=residual_picture(maxilla_vertices, maxilla_faces, placed, faces, residual))
    return placed, faces, report


def build_learner_palate(data: bytes, file_type: str, assets_dir, out_dir,
                         progress: Callable[[str, float], None] = lambda step, share: None
                         ) -> dict:
    """Read, register and rebuild a learner's palate into ``out_dir`` (replaced only when
    everything is written); returns the report. ``progress(step, share 0..1)`` as it goes."""
    started = time.perf_counter()
    progress("reading the scan", 0.0)
    vertices, faces, notes = read_scan(data, file_type)
    progress("registering it on the head's palate", 0.1)
    maxilla_vertices, maxilla_faces = load_scene_maxilla(assets_dir)
    placed, faces, registration = register_scan(vertices, faces, maxilla_vertices, maxilla_faces)
    out = Path(out_dir)
    out.parent.mkdir(parents=True, exist_ok=True)
    stage = Path(tempfile.mkdtemp(prefix=f".{out.name}-", dir=out.parent))
    try:
        # The tables and the electrodes are made from the mesh as written (quantised, as the
        # browser reads it), as the build makes the head's from its maxilla's GLB.
        write_glb(stage / PALATE_MESH, placed, faces)
        placed, faces = read_glb_mesh((stage / PALATE_MESH).read_bytes())
        progress("building the collision tables", 0.5)
        tables = build_collision_tables(placed, faces, stage)
        progress("placing the electrodes", 0.9)
        layout = build_epg_layout(placed, faces, stage, source={"mesh": "learner's scan"})
        report = {"scan": notes, "registration": registration,
                  "tables": {"file": COLLISION_TABLES_FILE, "sha256": tables["sha256"],
                             "stats": tables["stats"]},
                  "layout": {"file": EPG_LAYOUT_FILE,
                             "electrodes": {name: len(grid["electrodes"])
                                            for name, grid in layout["grids"].items()}},
                  "seconds": round(time.perf_counter() - started, 1)}
        (stage / REPORT_FILE).write_text(json.dumps(report, indent=1) + "\n")
        old = out.with_name(f".{out.name}-old")
        shutil.rmtree(old, ignore_errors=True)
        if out.exists():
            out.rename(old)
        stage.rename(out)
        shutil.rmtree(old, ignore_errors=True)
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise
    progress("done", 1.0)
    return report
