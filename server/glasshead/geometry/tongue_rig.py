"""The tongue rig definition: what the JSON holds, how it is built, and how it is checked.

The tongue follows Cohen, Beskow and Massaro (1998), section 3: a polygon surface built from a
sagittal B-spline curve and coronal B-spline sections whose control points move, singly and in
pairs, under named articulation parameters. Here:

- The **sagittal curve** is a closed cubic B-spline in the mid-sagittal plane (z = 0) with the
  control points A, B, C, ... lettered from the tip over the dorsum to the root, then along the
  floor and the underside back to the tip.
- Every point of the surface is seen from one **hub** H, a point inside the tongue on the
  mid-sagittal plane. A station u of the sagittal curve defines a *page*: the half-plane through
  the z-parallel line of H that contains S(u). Pages never cross each other except on that line,
  so the surface cannot fold through itself.
- In each page the **coronal section** is a radial B-spline: the distance from H along the
  direction at page angle phi (phi = -90 deg: toward the subject's right, 0: toward S(u),
  +90: toward the left). With w = ``pole_half_width``, R = |S(u) - H| and R0 its rest value,
  a control value is ``w + (R0 - w) * ratio + (R - R0) * follow + offset``: the rest section
  spans from the poles (ratio 0) to the sagittal curve (ratio 1, the midline); when the curve
  moves, each control follows it by ``follow`` = cos(its page angle), so the section moves with
  the curve rather than swelling; articulation offsets are in mm. The two controls at each end
  equal w: every page meets the z-line of H at the same two poles, so the surface is a closed
  sphere-like shell.
- Three sections (front, middle, back) are **blended** along the tongue by weights that each
  sagittal control point carries (``section_weights``), interpolated with the sagittal basis;
  the coronal offsets are further weighted by each point's ``coronal_weight`` (1 on the upper
  surface, 0 on the floor and underside, see ``CORONAL_WEIGHTS``).
- **Parameters** displace control points linearly: ``point = rest + (value - neutral) * by``,
  and may then turn them about the hub by ``(value - neutral) * turn`` degrees;
  a section's ``stretch`` (its width) scales its pages sideways, see ``STRETCH``.
  ``jaw_opening`` instead poses the jaw (see ``geometry.jaw``); the tongue rides on it, each
  sagittal control point and the hub by its ``jaw_weight``.
- The **hub follows** some parameters (``hub.follows``: ``(value - neutral) * by`` mm, before the
  jaw), but only as far as every turn between neighbouring stations, seen from it, keeps the
  share ``hub.keep`` of what it is from the hub that has not followed. That turn's cross product
  is linear in the share of the move taken, so the share is found exactly, and the pages stay
  in order wherever they are in order about the unmoved hub.

``build_definition`` assembles the JSON document from the design's tables
(``geometry.tongue_parameters``); ``validate_definition`` checks one that was read back. Both
evaluators (``geometry.tongue_surface`` and ``web/src/core/tongue.js``) are generic interpreters
of this document: no parameter has code of its own.
"""

import copy
import math

import numpy as np

from glasshead.constants import FRAME_AXES, TONGUE_RIG_FORMAT_VERSION
from glasshead.geometry.bspline import periodic_knots
from glasshead.geometry.tongue_parameters import (
    CORONAL_CONTROLS,
    CORONAL_DEGREE,
    CORONAL_WEIGHTS,
    HUB_FOLLOWS,
    HUB_JAW_WEIGHT,
    HUB_KEEP,
    HUB_MM,
    POLE_CONTROLS,
    SAGITTAL_DEGREE,
    SAGITTAL_POINTS,
    SECTIONS,
    coronal_control_angles_deg,
    coronal_knots_deg,
    parameter_table,
)


def build_definition(*, sagittal_positions, section_weights, ratios, pole_half_width,
                     station_params, page_angles_deg, jaw, hub=HUB_MM, fit=None, source=None):
    """Assemble the rig definition document.

    sagittal_positions : (18, 2) float, rest control points A..R, mm.
    section_weights : (18, 3) float, the blend each control point carries (rows sum to 1).
    ratios : mapping section -> (15,) float, rest control ratios (pole entries are ignored).
    pole_half_width : float, mm.
    station_params : (STATIONS,) float in [0, 1), increasing: where the surface samples the curve.
    page_angles_deg : (PAGE_SAMPLES,) float in (-90, 90), increasing: page samples between poles.
    jaw : the jaw block (``geometry.jaw.jaw_definition``).
    """
    positions = np.asarray(sagittal_positions, dtype=np.float64)
    weights = np.asarray(section_weights, dtype=np.float64)
    if positions.shape != (len(SAGITTAL_POINTS), 2):
        raise ValueError(f"sagittal_positions must be ({len(SAGITTAL_POINTS)}, 2)")
    if weights.shape != (len(SAGITTAL_POINTS), len(SECTIONS)):
        raise ValueError(f"section_weights must be ({len(SAGITTAL_POINTS)}, {len(SECTIONS)})")
    points = [
        {"name": name, "role": role, "position": _floats(positions[k]),
         "jaw_weight": jaw_weight, "coronal_weight": CORONAL_WEIGHTS[name],
         "section_weights": _floats(weights[k])}
        for k, (name, role, _angle, jaw_weight, _blend) in enumerate(SAGITTAL_POINTS)
    ]
    ratio_lists = {}
    for section in SECTIONS:
        values = np.asarray(ratios[section], dtype=np.float64).copy()
        values[list(POLE_CONTROLS)] = 0.0
        ratio_lists[section] = _floats(values)
    definition = {
        "format_version": TONGUE_RIG_FORMAT_VERSION,
        "kind": "glasshead tongue rig",
        "units": "mm",
        "frame": {"name": "project", "axes": dict(FRAME_AXES), "mid_sagittal_plane": "z = 0"},
        "source": source or {},
        "hub": {"position": _floats(hub), "jaw_weight": HUB_JAW_WEIGHT,
                "follows": [{"parameter": name, "by": _floats(by)} for name, by in HUB_FOLLOWS],
                "keep": HUB_KEEP},
        "sagittal": {
            "degree": SAGITTAL_DEGREE,
            "closed": True,
            "knots": _floats(periodic_knots(len(SAGITTAL_POINTS), SAGITTAL_DEGREE)),
            "control_points": points,
        },
        "coronal": {
            "degree": CORONAL_DEGREE,
            "parameter": "page angle, degrees: -90 subject's right pole, 0 the sagittal curve, "
                         "+90 left pole",
            "knots": _floats(coronal_knots_deg()),
            "controls": list(CORONAL_CONTROLS),
            "control_angles_deg": _floats(coronal_control_angles_deg()),
            "follow": _floats(np.cos(np.radians(coronal_control_angles_deg()))),
            "pole_controls": list(POLE_CONTROLS),
            "pole_half_width": float(pole_half_width),
            "sections": list(SECTIONS),
            "ratios": ratio_lists,
        },
        "jaw": copy.deepcopy(jaw),
        "surface": {
            "station_params": _floats(station_params),
            "page_angles_deg": _floats(page_angles_deg),
            "vertex_count": 2 + len(station_params) * len(page_angles_deg),
            "triangle_count": 2 * len(station_params) * len(page_angles_deg),
            "layout": "vertex 0 is the right pole, vertex 1 the left pole, then one ring per "
                      "station (page samples right to left); triangles wind counter-clockwise "
                      "seen from outside",
        },
        "parameters": parameter_table(),
        "fit": fit or {},
    }
    validate_definition(definition)
    return definition


def _floats(values):
    return [float(v) for v in np.asarray(values, dtype=np.float64).reshape(-1)]


def validate_definition(definition):
    """Check a rig definition read from JSON; raise ValueError naming the first problem."""
    if not isinstance(definition, dict):
        raise TypeError("a rig definition must be a JSON object")
    version = definition.get("format_version")
    if version != TONGUE_RIG_FORMAT_VERSION:
        raise ValueError(f"rig format_version {version!r} is not {TONGUE_RIG_FORMAT_VERSION}")
    for key in ("hub", "sagittal", "coronal", "jaw", "surface", "parameters"):
        if key not in definition:
            raise ValueError(f"rig definition has no '{key}'")
    sagittal, coronal, surface = (definition[k] for k in ("sagittal", "coronal", "surface"))
    points = sagittal["control_points"]
    names = [p["name"] for p in points]
    _unique(names, "sagittal control point")
    degree = sagittal["degree"]
    if len(sagittal["knots"]) != len(points) + 2 * degree + 1:
        raise ValueError("closed sagittal curve needs len(points) + 2 * degree + 1 knots")
    sections = coronal["sections"]
    for p in points:
        if len(p["position"]) != 2 or not all(map(math.isfinite, p["position"])):
            raise ValueError(f"sagittal point {p['name']}: position must be 2 finite numbers")
        if not 0 <= p["coronal_weight"] <= 1 or not 0 <= p["jaw_weight"] <= 1:
            raise ValueError(f"sagittal point {p['name']}: jaw_weight and coronal_weight must "
                             "lie in [0, 1]")
        w = p["section_weights"]
        if len(w) != len(sections) or min(w) < 0 or abs(sum(w) - 1.0) > 1e-9:
            raise ValueError(f"sagittal point {p['name']}: section_weights must be "
                             f"{len(sections)} non-negative numbers summing to 1")
    controls = coronal["controls"]
    _unique(controls, "coronal control")
    if len(coronal["knots"]) != len(controls) + coronal["degree"] + 1:
        raise ValueError("coronal knots must number len(controls) + degree + 1")
    if len(coronal["follow"]) != len(controls):
        raise ValueError(f"coronal follow needs {len(controls)} values")
    for section in sections:
        if len(coronal["ratios"][section]) != len(controls):
            raise ValueError(f"coronal section {section}: needs {len(controls)} ratios")
    if not coronal["pole_half_width"] > 0:
        raise ValueError("coronal pole_half_width must be positive")
    params = np.asarray(surface["station_params"], dtype=np.float64)
    if params.size < 3 or np.any(np.diff(params) <= 0) or params[0] < 0 or params[-1] >= 1:
        raise ValueError("surface station_params must increase strictly within [0, 1)")
    angles = np.asarray(surface["page_angles_deg"], dtype=np.float64)
    if angles.size < 2 or np.any(np.diff(angles) <= 0) or angles[0] <= -90 or angles[-1] >= 90:
        raise ValueError("surface page_angles_deg must increase strictly within (-90, 90)")
    _validate_parameters(definition, set(names), set(controls), set(sections))


def _validate_parameters(definition, point_names, control_names, section_names):
    table = definition["parameters"]
    _unique([p["name"] for p in table], "parameter")
    poles = {definition["coronal"]["controls"][i] for i in definition["coronal"]["pole_controls"]}
    jaw_name = definition["jaw"]["parameter"]
    for p in table:
        name = p["name"]
        if p["unit"] not in ("mm", "deg", "ratio"):
            raise ValueError(f"parameter {name}: unit must be mm, deg or ratio")
        if not p["min"] <= p["neutral"] <= p["max"] or p["min"] == p["max"]:
            raise ValueError(f"parameter {name}: needs min <= neutral <= max and min < max")
        for move in p["moves"]:
            if "turn" in move:
                if move["point"] not in point_names or not isinstance(move["turn"], (int, float)):
                    raise ValueError(f"parameter {name}: bad turn {move}")
            elif "radial" in move:
                if move["point"] not in point_names \
                        or not isinstance(move["radial"], (int, float)):
                    raise ValueError(f"parameter {name}: bad radial move {move}")
            elif "point" in move:
                if move["point"] not in point_names or len(move["by"]) != 2:
                    raise ValueError(f"parameter {name}: bad sagittal move {move}")
            elif move.get("section") in section_names and move.get("control") in control_names:
                if move["control"] in poles:
                    raise ValueError(f"parameter {name}: pole controls cannot move")
            elif move.get("section") in section_names and "stretch" in move:
                if not isinstance(move["stretch"], (int, float)):
                    raise ValueError(f"parameter {name}: stretch must be a number")
            else:
                raise ValueError(f"parameter {name}: bad move {move}")
    parameter_names = {p["name"] for p in table}
    if jaw_name not in parameter_names:
        raise ValueError(f"the jaw parameter {jaw_name!r} is not in the parameter table")
    hub = definition["hub"]
    if not isinstance(hub.get("follows"), list) or not isinstance(hub.get("keep"), (int, float)):
        raise ValueError("the hub needs 'follows' (a list) and 'keep' (a number)")
    for follow in hub["follows"]:
        if follow.get("parameter") not in parameter_names:
            raise ValueError(f"the hub follows {follow.get('parameter')!r}, which is not in the "
                             "parameter table")
        if len(follow.get("by", ())) != 2 or not all(map(math.isfinite, follow["by"])):
            raise ValueError(f"the hub's follow of {follow['parameter']}: by must be 2 finite "
                             "numbers")
    if not 0 <= hub["keep"] < 1:
        raise ValueError("the hub's keep must lie in [0, 1)")


def _unique(names, what):
    seen = set()
    for name in names:
        if name in seen:
            raise ValueError(f"duplicate {what} name {name!r}")
        seen.add(name)
