"""Electrode layouts on the palate: the Reading 62-electrode palate and a denser 96-electrode grid.

The placement rule (Cohen, Beskow and Massaro 1998 place the electrodes "on the palate surface";
the Reading palate runs its rows from just behind the upper incisors to the junction of the hard
and soft palate, Hardcastle, Gibbon and Jones 1991). It is measured on the maxilla the scene shows:

1. **Midline.** The mid-sagittal section (z = 0) of the maxilla, found from the vault (its lowest
   crossing with the vertical line through the middle of the dental arch) and followed forward
   to the lingual gingival margin of the incisors, where the tooth weight of ``epg.dental`` (the
   head view's own tooth rule) reaches one half (or where the gum's curve ends against teeth
   that are separate shells of the mesh), and backward to its most posterior point: the
   posterior edge of the hard palate in the mesh, taken as the junction of the hard and soft
   palate.
2. **Rows.** The midline from that margin to the posterior edge is cut into ``rows`` intervals
   of equal arc length; row r sits at the middle of interval r (R1 at the front). The Reading
   palate has 8 rows; the dense grid 12.
3. **Arc.** At each row, the maxilla is cut by the plane through the row's midline point that is
   perpendicular to the midline there (its tangent is the chord over +-``TANGENT_HALF_SPAN_MM``).
   The section is followed from the midline to each side up to the lingual gingival margin of the
   teeth (tooth weight one half again); where no tooth lies on that side of the section, up to the
   lowest point of the section on that side (the crest of the alveolar ridge).
4. **Columns.** That arc, from the subject's left margin to the right one, is cut into 8 intervals
   of equal arc length; column c sits at the middle of interval c. Column 1 is the subject's
   left, column 8 the right: a palatogram drawn with the front at the top and column 1 on the
   left is the palate seen from below, from the tongue. R1 of the Reading palate keeps columns
   2 to 7 (6 electrodes): the front of the arch is narrow.
5. **Normal.** Each electrode's normal is the area-weighted mean of the face normals of the
   maxilla within ``NORMAL_RADIUS_MM`` of it, turned to face the tongue (into the mouth).

Rows, columns and ids follow the emuR frames: row 1 is the front, ids read ``R3C5``.
"""

import hashlib
from typing import TypedDict

import numpy as np

from glasshead.constants import (
    EPG_CONTACT_BEHIND_MM,
    EPG_CONTACT_TOLERANCE_MM,
    EPG_LAYOUT_FORMAT_VERSION,
)
from glasshead.epg.dental import LAYOUT_TIP_BAND_MM, tooth_weights
from glasshead.epg.palate_section import Section, crossing_arc, point_at


class GridSpec(TypedDict):
    """One electrode grid: rows x columns cells, row-major from R1; missing cells are empty."""

    rows: int
    columns: int
    missing_cells: tuple[int, ...]
    description: str


#: The grids: rows, columns, and the flat cells (row * columns + column) left without an electrode.
GRIDS: dict[str, GridSpec] = {
    "reading62": {"rows": 8, "columns": 8, "missing_cells": (0, 7),
                  "description": "Reading 62-electrode palate: 8 rows, R1 has columns 2-7"},
    "dense96": {"rows": 12, "columns": 8, "missing_cells": (),
                "description": "dense grid: 12 rows of 8 electrodes"},
}
DEFAULT_GRID = "reading62"
#: Tooth weight at which the teeth begin (the gingival margin).
MARGIN_WEIGHT = 0.5
#: The midline tangent at a row is the chord between the points this far before and after it, mm.
TANGENT_HALF_SPAN_MM = 2.0
#: Face normals within this distance of an electrode are averaged for its normal, mm (an
#: electrode is a disc about 1.4 mm across).
NORMAL_RADIUS_MM = 1.5
#: A point this far into the mouth from a row's midline point is used to turn normals toward the
#: tongue, mm.
INSIDE_DEPTH_MM = 20.0
#: The vault is looked for this far above the lowest point of the maxilla (the incisal edges), mm.
VAULT_CLEARANCE_MM = 4.0
#: Where the gum's midline curve ends (teeth that are separate shells of the mesh), its front end
#: is the margin if a tooth lies within this distance of it, mm.
SEPARATE_TOOTH_MM = 3.0


class LayoutError(ValueError):
    """The maxilla does not allow the placement rule (e.g. no midline behind the incisors)."""


def _check_mesh(vertices, faces):
    v = np.asarray(vertices, dtype=np.float64)
    f = np.asarray(faces)
    if v.ndim != 2 or v.shape[1] != 3 or len(v) < 3 or not np.all(np.isfinite(v)):
        raise ValueError(f"maxilla vertices must be finite with shape (n, 3), got {v.shape}")
    if f.ndim != 2 or f.shape[1] != 3 or len(f) == 0 or not np.issubdtype(f.dtype, np.integer):
        raise ValueError(f"maxilla faces must be (m, 3) integers, got {f.shape} {f.dtype}")
    if f.min() < 0 or f.max() >= len(v):
        raise ValueError("maxilla faces refer to vertices that do not exist")
    return v, f.astype(np.int64)


def midline(vertices, faces, teeth=None):
    """The palate's midline (step 1 of the rule).

    Returns a dict: ``polyline`` (the oral profile at z = 0, ordered from front to back),
    ``arc`` (its cumulative arc lengths), ``start_s`` (arc length at the incisors' lingual gingival
    margin) and ``end_s`` (at the posterior edge of the hard palate).

    The profile is found from the vault: the lowest crossing of the mid-sagittal section with the
    vertical line through the middle of the dental arch (the palate, seen from the mouth). From
    there it is followed forward to the gingival margin (tooth weight one half; or the front end
    of the curve, where the gum meets teeth that are separate shells of the mesh) and backward to
    its most posterior point.
    """
    v, f = _check_mesh(vertices, faces)
    teeth = tooth_weights(v, tip_band=LAYOUT_TIP_BAND_MM) if teeth is None else teeth
    section = Section(v, f, origin=(0.0, 0.0, 0.0), normal=(0.0, 0.0, 1.0))
    if section.empty:
        raise LayoutError("the maxilla does not cross the mid-sagittal plane z = 0")
    is_tooth = teeth > MARGIN_WEIGHT
    if not is_tooth.any():
        raise LayoutError("no teeth found on the maxilla (is it upside down?)")
    arch_x = 0.5 * (v[is_tooth, 0].min() + v[is_tooth, 0].max())
    segment = _vault_segment(section, arch_x, v[:, 1].min() + VAULT_CLEARANCE_MM)
    profile = section.polyline_through(segment)
    vault = np.array([arch_x, 0.0, 0.0])
    vault[1] = section.node_points[section.links[segment], 1].mean()
    if profile.closed:  # open the loop opposite the vault
        k = len(profile.points)
        profile = _rotate_loop(profile, (_nearest(profile, vault) + k // 2) % k)
    arc = profile.arc_lengths()
    here = _nearest(profile, vault)
    # Orient the curve front to back: x falls along it at the vault.
    if _x_at(profile, arc, arc[here] + TANGENT_HALF_SPAN_MM) > \
            _x_at(profile, arc, arc[here] - TANGENT_HALF_SPAN_MM):
        profile = profile.reversed()
        arc = profile.arc_lengths()
        here = _nearest(profile, vault)
    weights = profile.interpolate(teeth)
    start_s = crossing_arc(arc, weights, MARGIN_WEIGHT, start=here, step=-1)
    if start_s is None:
        front = profile.points[0]
        if np.min(np.linalg.norm(v[is_tooth] - front, axis=1)) > SEPARATE_TOOTH_MM:
            raise LayoutError("no lingual gingival margin found behind the incisors on the "
                              "midline")
        start_s = 0.0
    end = here + int(np.argmin(profile.points[here:, 0]))
    if not start_s < arc[end]:
        raise LayoutError("the midline from the incisors to the back of the palate is empty")
    return {"polyline": profile, "arc": arc, "start_s": float(start_s), "end_s": float(arc[end])}


def _vault_segment(section, x, above_y):
    """The section segment crossing the vertical line at ``x`` lowest above ``above_y``."""
    a = section.node_points[section.links[:, 0]]
    b = section.node_points[section.links[:, 1]]
    crosses = (a[:, 0] - x) * (b[:, 0] - x) <= 0.0
    span = np.where(a[:, 0] != b[:, 0], b[:, 0] - a[:, 0], 1.0)
    y = a[:, 1] + (x - a[:, 0]) / span * (b[:, 1] - a[:, 1])
    candidates = np.flatnonzero(crosses & (y > above_y))
    if not len(candidates):
        raise LayoutError(f"no palate above the middle of the dental arch (x = {x:.1f} mm) on "
                          "the midline")
    return int(candidates[np.argmin(y[candidates])])


def _nearest(polyline, point):
    return int(np.argmin(np.linalg.norm(polyline.points - point, axis=1)))


def _rotate_loop(polyline, start):
    """A closed polyline re-started at point ``start``."""
    from glasshead.epg.palate_section import Polyline

    k = len(polyline.points)
    order = (np.arange(k) + start) % k
    return Polyline(polyline.points[order], polyline.edges[order], polyline.weights[order],
                    np.roll(polyline.triangles, -start), closed=True)


def _x_at(polyline, arc, s):
    return point_at(polyline, arc, s)[0][0]


def _row_frame(line, s):
    """Midline point (3,), backward unit tangent (3,) and unit normal into the mouth (3,) at s."""
    polyline, arc = line["polyline"], line["arc"]
    point, _ = point_at(polyline, arc, s)
    before, _ = point_at(polyline, arc, s - TANGENT_HALF_SPAN_MM)
    after, _ = point_at(polyline, arc, s + TANGENT_HALF_SPAN_MM)
    tangent = after - before
    tangent[2] = 0.0
    tangent /= np.linalg.norm(tangent)
    into_mouth = np.cross([0.0, 0.0, 1.0], tangent)  # the backward tangent turned downward
    return point, tangent, into_mouth


def _side_margin(arc, weights, heights, centre, step):
    """Arc length of the gingival margin walking from index ``centre`` by ``step`` (+1 or -1):
    where the tooth weight reaches one half; else the lowest point of that side."""
    s = crossing_arc(arc, weights, MARGIN_WEIGHT, start=centre, step=step)
    if s is not None:
        return s, "teeth"
    side = np.arange(centre, len(arc)) if step > 0 else np.arange(0, centre + 1)
    return float(arc[side[np.argmin(heights[side])]]), "ridge"


def row_arc(vertices, faces, teeth, point, tangent):
    """Section of the palate at one row (step 3 of the rule).

    Returns (polyline, arc lengths, left_s, right_s, (left end kind, right end kind)): the arc
    runs from arc length ``left_s`` (the subject's left margin) to ``right_s`` along the
    polyline, in either order; an end kind is "teeth" or "ridge".
    """
    section = Section(vertices, faces, origin=point, normal=tangent)
    if section.empty:
        raise LayoutError(f"the section at {np.round(point, 2).tolist()} misses the maxilla")
    profile = section.polyline_through(section.nearest_segment(point))
    centre = int(np.argmin(np.linalg.norm(profile.points - point, axis=1)))
    if profile.closed:  # open the loop opposite the midline point
        profile = _rotate_loop(profile, (centre + len(profile.points) // 2)
                               % len(profile.points))
        centre = int(np.argmin(np.linalg.norm(profile.points - point, axis=1)))
    arc = profile.arc_lengths()
    # Which way along the curve is the subject's left (+z), seen at the midline.
    after, _ = point_at(profile, arc, arc[centre] + TANGENT_HALF_SPAN_MM)
    before, _ = point_at(profile, arc, arc[centre] - TANGENT_HALF_SPAN_MM)
    left_step = 1 if after[2] > before[2] else -1
    weights = profile.interpolate(teeth)
    heights = profile.points[:, 1]
    left_s, left_kind = _side_margin(arc, weights, heights, centre, left_step)
    right_s, right_kind = _side_margin(arc, weights, heights, centre, -left_step)
    if abs(right_s - left_s) < 1e-6:
        raise LayoutError(f"the palate's arc at {np.round(point, 2).tolist()} is empty")
    return profile, arc, left_s, right_s, (left_kind, right_kind)


def electrode_normals(vertices, faces, positions, inside_points):
    """Unit normals (k, 3) at ``positions`` (k, 3): area-weighted face normals within
    NORMAL_RADIUS_MM, each turned toward its ``inside_points`` row (k, 3)."""
    tri = vertices[faces]
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])  # length = 2 * area
    centroids = tri.mean(axis=1)
    normals = np.empty_like(positions)
    for k, p in enumerate(positions):
        near = np.linalg.norm(centroids - p, axis=1) <= NORMAL_RADIUS_MM
        if not near.any():
            near = np.linalg.norm(centroids - p, axis=1) <= np.min(
                np.linalg.norm(centroids - p, axis=1)) + 1e-9
        total = cross[near].sum(axis=0)
        length = np.linalg.norm(total)
        if length == 0:
            raise LayoutError(f"no surface normal at electrode {k}")
        n = total / length
        if np.dot(n, inside_points[k] - p) < 0:
            n = -n
        normals[k] = n
    return normals


def build_layout(vertices, faces, grid=DEFAULT_GRID, line=None, teeth=None):
    """Electrodes of ``grid`` on the maxilla (vertices (n, 3) float mm, faces (m, 3) int).

    Returns a dict: ``grid``, ``rows``, ``columns``, ``cells``, ``missing_cells``, and
    ``electrodes``: a list of {``id``, ``row``, ``column`` (1-based), ``cell`` (row-major,
    0-based), ``position`` [x, y, z] mm, ``normal`` [x, y, z] unit, toward the tongue}; plus
    ``rows_detail`` with each row's midline point and arc length.
    """
    if grid not in GRIDS:
        raise ValueError(f"unknown electrode grid {grid!r}; choose from {', '.join(GRIDS)}")
    spec = GRIDS[grid]
    v, f = _check_mesh(vertices, faces)
    teeth = tooth_weights(v, tip_band=LAYOUT_TIP_BAND_MM) if teeth is None else teeth
    line = midline(v, f, teeth) if line is None else line
    rows, columns = spec["rows"], spec["columns"]
    length = line["end_s"] - line["start_s"]
    electrodes: list[dict] = []
    points: list[np.ndarray] = []
    inside: list[np.ndarray] = []
    rows_detail: list[dict] = []
    for r in range(rows):
        s = line["start_s"] + (r + 0.5) * length / rows
        point, tangent, into_mouth = _row_frame(line, s)
        profile, arc, left_s, right_s, ends = row_arc(v, f, teeth, point, tangent)
        width = right_s - left_s  # signed: the polyline may run either way
        rows_detail.append({"row": r + 1, "midline_point": point.tolist(),
                            "midline_s_mm": s - line["start_s"], "arc_mm": abs(width),
                            "margins": list(ends)})
        for c in range(columns):
            cell = r * columns + c
            if cell in spec["missing_cells"]:
                continue
            position, _ = point_at(profile, arc, left_s + (c + 0.5) * width / columns)
            electrodes.append({"id": f"R{r + 1}C{c + 1}", "row": r + 1, "column": c + 1,
                               "cell": cell})
            points.append(position)
            inside.append(point + INSIDE_DEPTH_MM * into_mouth)
    positions = np.array(points)
    normals = electrode_normals(v, f, positions, np.array(inside))
    for e, p, n in zip(electrodes, positions, normals, strict=True):
        e["position"] = p.tolist()
        e["normal"] = n.tolist()
    return {"grid": grid, "description": spec["description"], "rows": rows, "columns": columns,
            "cells": rows * columns, "missing_cells": list(spec["missing_cells"]),
            "electrodes": electrodes, "rows_detail": rows_detail}


def layout_document(vertices, faces, source=None):
    """The layout file's content: every grid on one maxilla, with the rule's figures.

    ``source`` (optional dict) says which mesh it was built from; the mesh's sha256 is added.
    """
    v, f = _check_mesh(vertices, faces)
    teeth = tooth_weights(v, tip_band=LAYOUT_TIP_BAND_MM)
    line = midline(v, f, teeth)
    grids = {name: build_layout(v, f, name, line=line, teeth=teeth) for name in GRIDS}
    step = max(1, len(line["polyline"].points) // 200)
    start, _ = point_at(line["polyline"], line["arc"], line["start_s"])
    end, _ = point_at(line["polyline"], line["arc"], line["end_s"])
    digest = hashlib.sha256(np.ascontiguousarray(v).tobytes()
                            + np.ascontiguousarray(f).tobytes()).hexdigest()
    return {
        "format_version": EPG_LAYOUT_FORMAT_VERSION,
        "kind": "glasshead-epg-layout",
        "frame": {"name": "project", "units": "mm",
                  "axes": {"x": "anterior", "y": "superior", "z": "left"}},
        "source": {**(source or {}), "vertices": len(v), "faces": len(f), "sha256": digest},
        "contact": {"tolerance_mm": EPG_CONTACT_TOLERANCE_MM,
                    "behind_mm": EPG_CONTACT_BEHIND_MM},
        "midline": {"start": start.tolist(), "end": end.tolist(),
                    "length_mm": line["end_s"] - line["start_s"],
                    "points": line["polyline"].points[::step].tolist()},
        "grids": grids,
    }


def validate_layout_document(document):
    """Check a layout document read from JSON; LayoutError naming the first problem."""
    if not isinstance(document, dict):
        raise LayoutError("an electrode layout must be a JSON object")
    version = document.get("format_version")
    if version != EPG_LAYOUT_FORMAT_VERSION:
        raise LayoutError(f"layout format_version {version!r} is not {EPG_LAYOUT_FORMAT_VERSION}")
    grids = document.get("grids")
    if not isinstance(grids, dict):
        raise LayoutError("the layout has no 'grids'")
    missing = [name for name in GRIDS if name not in grids]
    if missing:
        raise LayoutError(f"the layout lacks the grids {', '.join(missing)}")
    for name in GRIDS:
        electrodes = grids[name].get("electrodes") if isinstance(grids[name], dict) else None
        if not isinstance(electrodes, list) or not electrodes:
            raise LayoutError(f"grid {name} has no electrodes")
    for key in ("contact", "midline", "frame", "source"):
        if not isinstance(document.get(key), dict):
            raise LayoutError(f"the layout has no '{key}'")
    return document
