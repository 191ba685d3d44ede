"""Build step: the tract's still mid-sagittal section and its stations, written to
``tract-section.json`` for the area function (``glasshead.acoustics.area_function``) on both
sides.

- ``stations``: points along the rest airway's midline, ``TRACT_STATION_STEP_MM`` apart, from the
  airway's lower (laryngeal) end forward to the upper incisors' edge. The midline is the
  airway's upper wall with each point moved halfway to the nearest point of its lower wall (as
  ``core/constriction.js`` draws it).
- ``still``: the parts that do not move, as polylines with their side of the air: the roof is
  the maxilla (palate and upper teeth) and the pharyngeal wall; the floor is the airway's lower
  wall below the rest tongue (the larynx's entrance) and what stands inside the airway (the
  epiglottis's tip).
- ``mandible``: its section at rest, posed by the jaw on each side.
- ``incisor_x`` and ``uvula_y``: where the lips' sections begin (in front of the upper incisors'
  edge) and the pharynx's (below the uvula), from the landmarks.
- ``nose``: the nasal branch's sections after its port (the nose of VocalTractLab's JD3
  speaker, ``vtl_speaker.nose_tube``): the head's CT has no nasal cavity.

Each polyline is ``{"points": [[x, y], ...], "closed": bool}`` in mm, project frame.
"""

import hashlib
import json
from pathlib import Path

import numpy as np

from glasshead.acoustics.area_function import nearest_on_segments
from glasshead.constants import (
    LANDMARKS_FILE,
    TRACT_SECTION_FILE,
    TRACT_SECTION_FORMAT_VERSION,
    TRACT_STATION_STEP_MM,
)
from glasshead.geometry.midsagittal import midline_section, point_to_polylines, resample
from glasshead.pipeline import vtl_speaker
from glasshead.pipeline.outputs import current_output, load_built_meshes, write_json

#: Bumped whenever the section is computed differently.
BUILDER = 2
#: The meshes read, by their manifest names.
MESHES = ("airway", "maxilla", "pharynx", "mandible", "tongue_rest")
#: Section points closer than this (mm) are the same point (a chain closes on itself).
CLOSE_MM = 1e-3


def _chains(vertices, faces):
    """The mesh's z = 0 section: [(points (k, 2), closed)], a closed chain without its repeat."""
    out = []
    for chain in midline_section(vertices, faces):
        closed = len(chain) > 2 and np.linalg.norm(chain[0] - chain[-1]) < CLOSE_MM
        out.append((chain[:-1] if closed else chain, bool(closed)))
    return out


def airway_walls(chains):
    """The airway's (upper, lower) walls, each from its laryngeal end to the lip opening, and
    its closed loops; as ``core/sectionPolygon.js airwayPolygon`` finds them."""
    open_chains = sorted((p for p, closed in chains if not closed), key=len, reverse=True)
    if len(open_chains) < 2:
        raise ValueError(f"the airway's section has {len(open_chains)} open walls; it needs two")
    a, b = (c if c[0, 0] <= c[-1, 0] else c[::-1] for c in open_chains[:2])
    distance = np.linalg.norm(a[:, None] - b[None], axis=2)
    distance[a[:, 0] <= 0.0] = np.inf
    distance[:, b[:, 0] <= 0.0] = np.inf
    i, j = np.unravel_index(int(np.argmin(distance)), distance.shape)
    upper, lower = a[:i + 1], b[:j + 1]
    if upper[-1, 1] < lower[-1, 1]:
        upper, lower = lower, upper
    loops = [p for p, closed in chains if closed]
    return upper, lower, loops


def midline_stations(upper, lower, incisor_x, step_mm=TRACT_STATION_STEP_MM):
    """Stations (n, 2) along the airway's midline from its laryngeal end to ``incisor_x``."""
    dense = resample(upper, 0.5)
    _, nearest = nearest_on_segments(dense, lower[:-1], lower[1:])
    midline = (dense + nearest) / 2.0
    ahead = np.flatnonzero(midline[:, 0] >= incisor_x)
    if len(ahead) == 0 or ahead[0] < 2:
        raise ValueError(f"the airway's midline does not reach the incisors at x = {incisor_x}")
    cut = int(ahead[0])
    before, after = midline[cut - 1], midline[cut]
    share = (incisor_x - before[0]) / (after[0] - before[0])
    end = before + share * (after - before)
    return resample(np.vstack([midline[:cut], end]), step_mm)


def _polylines(chains):
    return [{"points": np.round(p, 4).tolist(), "closed": bool(closed)} for p, closed in chains]


def build_tract_section(assets_dir: Path) -> tuple[dict, bool]:
    """(document, skipped)."""
    assets_dir = Path(assets_dir)
    meshes = load_built_meshes(assets_dir, MESHES)
    landmarks = json.loads((assets_dir / LANDMARKS_FILE).read_text())
    digest = hashlib.sha256("".join(meshes[n][2] for n in MESHES).encode()
                            + vtl_speaker.speaker_file().read_bytes()
                            + json.dumps(landmarks, sort_keys=True).encode()).hexdigest()
    path = assets_dir / TRACT_SECTION_FILE
    existing = current_output(path, digest, BUILDER, TRACT_SECTION_FORMAT_VERSION)
    if existing is not None:
        return existing, True
    marks = {m["name"]: m["position"] for m in landmarks["landmarks"]}
    incisor_x, uvula_y = float(marks["upper_incisor_edge"][0]), float(marks["uvula"][1])
    sections = {name: _chains(*meshes[name][:2]) for name in MESHES}
    upper, lower, loops = airway_walls(sections["airway"])
    stations = midline_stations(upper, lower, incisor_x)
    # The larynx's entrance: the lower wall below the rest tongue's lowest point.
    tongue_bottom = min(float(p[:, 1].min()) for p, _ in sections["tongue_rest"])
    entrance = lower[lower[:, 1] < tongue_bottom]
    floor = [(entrance, False)] if len(entrance) >= 2 else []
    floor += [(loop, True) for loop in loops]
    roof = sections["maxilla"] + sections["pharynx"]
    clearance = point_to_polylines(stations, [p for p, _ in roof])
    document = {
        "format_version": TRACT_SECTION_FORMAT_VERSION, "builder": BUILDER,
        "source": {"sha256": digest, "meshes": list(MESHES), "landmarks": LANDMARKS_FILE},
        "step_mm": TRACT_STATION_STEP_MM,
        "incisor_x": round(incisor_x, 4), "uvula_y": round(uvula_y, 4),
        "stations": np.round(stations, 4).tolist(),
        "length_mm": round(float(np.linalg.norm(np.diff(stations, axis=0), axis=1).sum()), 2),
        "still": {"floor": _polylines(floor), "roof": _polylines(roof)},
        "mandible": _polylines(sections["mandible"]),
        "nose": {**vtl_speaker.nose_tube(), "source": "VocalTractLab JD3 speaker's nose"},
        "roof_clearance_mm": {"min": round(float(clearance.min()), 2),
                              "max": round(float(clearance.max()), 2)},
    }
    write_json(path, document)
    return document, False


def build_step(ctx) -> dict:
    """``glasshead build`` step: the stations and the midline's length."""
    document, skipped = build_tract_section(ctx.assets_dir)
    return {"step": "tract-section", "skipped": skipped, "stations": len(document["stations"]),
            "length_mm": document["length_mm"]}
