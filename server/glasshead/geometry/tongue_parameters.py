"""The tongue rig's design: its control points, coronal controls, hub and surface resolution, and
the articulation parameters that move them (Cohen, Beskow and Massaro 1998, section 3). These
tables are what ``geometry.tongue_rig.build_definition`` writes into the rig definition (the
rest shape is fitted to the MRI tongue by ``pipeline.tongue_fit``); the evaluators read only
the definition.
"""

import math

from glasshead.geometry.bspline import clamped_knots, greville_abscissae

SAGITTAL_DEGREE = 3
CORONAL_DEGREE = 3

#: Section names, in the order of ``section_weights``.
SECTIONS = ("front", "middle", "back")

#: Sagittal control points: letter, role, direction from the hub in degrees (the rest-shape fit
#: moves each point only along this ray, which keeps the control polygon star-shaped about the
#: hub), jaw weight, and the blend of sections it carries (None: fitted to the MRI tongue).
SAGITTAL_POINTS = (
    ("A", "tip, underside", 13.0, 1.0, (1.0, 0.0, 0.0)),
    ("B", "tip", 22.0, 1.0, (1.0, 0.0, 0.0)),
    ("C", "blade, front", 33.0, 1.0, (1.0, 0.0, 0.0)),
    ("D", "blade, back", 46.0, 1.0, None),
    ("E", "dorsum, front", 62.0, 0.95, None),
    ("F", "dorsum, front-centre", 79.0, 0.9, None),
    ("G", "dorsum, centre", 97.0, 0.85, (0.0, 1.0, 0.0)),
    ("H", "dorsum, back-centre", 115.0, 0.85, None),
    ("I", "dorsum, back", 133.0, 0.9, None),
    ("J", "root, top", 152.0, 0.95, None),
    ("K", "root", 170.0, 1.0, (0.0, 0.0, 1.0)),
    ("L", "root, low", 188.0, 1.0, None),
    ("M", "root, base", 208.0, 1.0, None),
    ("N", "floor, back", 228.0, 1.0, None),
    ("O", "floor", 255.0, 1.0, None),
    ("P", "floor, front", 281.0, 1.0, None),
    ("Q", "underside, low", 304.0, 1.0, None),
    ("R", "underside, front", 326.0, 1.0, None),
    ("S", "underside, behind the tip", 348.0, 1.0, (1.0, 0.0, 0.0)),
)

#: How much the coronal offsets (groove, edges, bulge) act at each sagittal control point: fully
#: on the upper surface, tip to root; not on the floor and the underside, which have no groove
#: or lateral edges (the sections' width stretch acts everywhere).
CORONAL_WEIGHTS = {"A": 0.5, "B": 1.0, "C": 1.0, "D": 1.0, "E": 1.0, "F": 1.0, "G": 1.0,
                   "H": 1.0, "I": 1.0, "J": 1.0, "K": 1.0, "L": 0.6, "M": 0.0, "N": 0.0,
                   "O": 0.0, "P": 0.0, "Q": 0.0, "R": 0.0, "S": 0.0}

#: Blend a fit starts from for the points whose blend is fitted.
DEFAULT_SECTION_WEIGHTS = {
    "D": (0.8, 0.2, 0.0), "E": (0.4, 0.6, 0.0), "F": (0.1, 0.9, 0.0), "H": (0.0, 0.9, 0.1),
    "I": (0.0, 0.6, 0.4), "J": (0.0, 0.2, 0.8), "L": (0.0, 0.0, 1.0), "M": (0.0, 0.0, 1.0),
    "N": (0.0, 0.2, 0.8), "O": (0.0, 0.5, 0.5), "P": (0.3, 0.5, 0.2), "Q": (0.6, 0.3, 0.1),
    "R": (0.9, 0.1, 0.0),
}

#: The hub, mm, project frame. Chosen on the MRI tongue (tests/test_tongue_fit.py checks it):
#: every direction from it but a few crosses the MRI surface once, and it sees every segment of
#: the mid-sagittal outline at more than 9 degrees from grazing.
HUB_MM = (-19.0, -15.0)
#: How much the hub follows the jaw.
HUB_JAW_WEIGHT = 0.95
#: How far the hub moves (forward, up; mm per unit of the parameter, before the jaw) with the
#: parameters that carry the body of the tongue. The root drawn in toward a hub that stays put
#: leaves it a few mm behind the surface, where its pages can no longer hold a root pushed
#: forward round its midline with the sides behind (VocalTractLab's /i/ and the velar closure in
#: /i/, docs/fitting-3d-fits.md); a hub that comes forward and up with the root keeps the body
#: about it.
HUB_FOLLOWS = (("root_advancement", (0.5, 0.5)),)
#: Share of the turn between neighbouring stations, seen from the hub that has not followed,
#: which every such turn keeps when the hub follows: the hub takes only as much of its move as
#: that allows, so the pages stay in order wherever they were in order about the unmoved hub.
HUB_KEEP = 0.5

#: Inner knots of the coronal radial B-spline, degrees of page angle (denser near the lateral
#: edges of the dorsum, where the tongue's cross-section turns fastest).
CORONAL_INNER_KNOTS_DEG = (-66.0, -46.0, -32.0, -22.0, -12.0, 0.0, 12.0, 22.0, 32.0, 46.0, 66.0)
#: Coronal control values, right pole to left pole (their page angles are the Greville abscissae).
CORONAL_CONTROLS = (
    "right pole", "right pole ring", "right lower side", "right side", "right upper side",
    "right edge", "right paramedian", "midline", "left paramedian", "left edge",
    "left upper side", "left side", "left lower side", "left pole ring", "left pole",
)
#: Controls pinned to the pole half-width (two at each end: the surface meets the pole at a
#: right angle, so it is smooth there).
POLE_CONTROLS = (0, 1, 13, 14)

#: Surface resolution: stations along the sagittal curve, and page samples between the poles.
STATIONS = 96
PAGE_SAMPLES = 31


def _along_rays(weights):
    """Sagittal moves along each point's ray from the hub (outward per unit for a positive
    weight): the ray's direction is fixed in ``SAGITTAL_POINTS`` (the rest-shape fit moves the
    points along it), so these moves are table data. A move along its ray leaves the point's page
    angle as it is; only the moves across the rays of the other parameters can fold the pages."""
    angles = {name: angle for name, _role, angle, _jaw, _blend in SAGITTAL_POINTS}
    return tuple((name, (round(w * math.cos(math.radians(angles[name])), 6),
                         round(w * math.sin(math.radians(angles[name])), 6)))
                 for name, w in weights)


def _radial(weights):
    """Moves along each point's own ray from the hub, mm per unit, outward for a positive weight
    (see ``geometry.tongue_surface``): the point keeps its direction from the hub whatever the
    other parameters did to it, so no such move can turn one point past another. Moved along
    their rest rays instead (``_along_rays``), points that a straight move had already carried
    off their rays were pushed across them, and the pages folded."""
    return tuple({"point": name, "radial": w} for name, w in weights)


def _turns(weights):
    """Moves that turn points about the hub, degrees per unit (see
    ``geometry.tongue_surface``): a turn keeps each point's distance from the hub, so points that
    turn by the same angle keep their pages in order whatever the other parameters did to them."""
    return tuple({"point": name, "turn": w} for name, w in weights)


# --- The articulation parameters -------------------------------------------------------------
# (name, unit, min, max, description, moves); neutral is 0 for every tongue parameter (values
# are displacements from the rest shape, so the table stays valid when the rest shape is refit).
# Sagittal moves: (point, (dx, dy)) in mm per unit, {"point", "radial"} in mm per unit along
# the point's own ray from the hub (``_radial``), or {"point", "turn"} in degrees per unit
# about the hub (``_turns``). Coronal moves: (control, offset), radial mm
# per unit along the control's page direction, given for one section and applied to each.
#
# The sagittal ranges cover what the mid-sagittal fits to VocalTractLab's JD3 shapes reach for
# (docs/fitting.md): the root comes up to 24 mm toward the hub for /i/-like shapes, the tip drops
# 18 mm and thins for the back rounded vowels and /i/, the back of the dorsum drops 16 mm toward
# the hub where the root comes forward and rises 20 mm up and back for /o/ and the uvulars. The
# back of the dorsum and the root move along the hub's rays (``_along_rays``): moved straight up
# and forward they turned round the hub toward each other and folded the pages at 10 and 18 mm.
# Each range is as wide as it can be while every corner of the sagittal and jaw ranges still
# keeps the pages in order (tests/test_tongue_surface.py): the dorsum and blade advancements,
# the blade height and the back dorsum's drop are held there, not by the shapes. The front of
# /i/ and the palatals needs the blade and the front of the dorsum higher and further forward at
# once than those corners allow, so ``dorsum_front_height`` moves C to G out along their rays:
# it only raises (0..20 mm), since lowering them along the rays against a retracted blade
# folded the pages at every negative value tried. The back vowels, the velars in /a u/ and the
# uvulars want the whole body of the tongue drawn back and down into the pharynx, about 10 to 25
# degrees round the hub (their fits sat at the backward limit of ``dorsum_advancement`` and the
# lower limit of ``body_height``). Made of straight moves that folded the pages wherever another
# parameter had drawn a point near the hub; ``tongue_retraction`` turns the points instead
# (``_turns``): D to M together, tapering to nothing at the blade and along the floor, so only
# the taper changes the angles between pages. Two shapes still missed with those: /O/ wants the
# front of the dorsum 2 mm lower than ``blade_height``, ``dorsum_front_height`` and
# ``body_height`` at their floors allow, and /a/ and the velar closure in /a/ want the base of
# the root drawn in where VTL's root turns forward to the hyoid. Both move points toward the hub
# along each point's own ray (``_radial``), which keeps every point's direction from the hub, so
# they fold no corner (the same moves along the rest rays folded 24 to 1,024 corners at a few
# mm): ``dorsum_front_lowering`` 0..6 mm (at 8 mm, 16 corners fold) and
# ``root_base_advancement`` 0..24 mm (no corner folds there; /i/'s 3D fit takes all of it).

SAGITTAL_PARAMETERS = (
    ("tip_advancement", "mm", -4.0, 14.0, "Moves the tip pair (A, B) forward.",
     (("A", (1.0, 0.0)), ("B", (1.0, 0.0)), ("C", (0.4, 0.0)), ("S", (0.5, 0.0)))),
    ("tip_height", "mm", -18.0, 8.0, "Raises the tip pair (A, B).",
     (("A", (0.0, 1.0)), ("B", (0.0, 1.0)), ("C", (0.0, 0.6)), ("D", (0.0, 0.2)),
      ("S", (0.0, 0.5)), ("R", (0.0, 0.2)))),
    ("tip_thickness", "mm", -6.0, 3.0,
     "Moves the tip pair apart vertically (negative: toward each other).",
     (("A", (0.0, -0.5)), ("B", (0.0, 0.5)))),
    ("blade_advancement", "mm", -4.0, 8.0, "Moves the blade (C, D) forward; the tip follows.",
     (("A", (0.8, 0.0)), ("B", (0.8, 0.0)), ("C", (1.0, 0.0)), ("D", (0.6, 0.0)))),
    ("blade_height", "mm", -4.0, 10.0, "Raises the blade (C, D).",
     (("C", (0.0, 1.0)), ("D", (0.0, 0.7)), ("E", (0.0, 0.2)))),
    ("dorsum_advancement", "mm", -6.0, 6.0, "Moves the dorsum (E to H) forward.",
     (("C", (0.2, 0.0)), ("D", (0.5, 0.0)), ("E", (0.8, 0.0)), ("F", (1.0, 0.0)),
      ("G", (1.0, 0.0)),
      ("H", (0.5, 0.0)))),
    ("dorsum_height", "mm", -6.0, 12.0, "Raises the centre of the dorsum (E to H).",
     (("E", (0.0, 0.4)), ("F", (0.0, 1.0)), ("G", (0.0, 1.0)), ("H", (0.0, 0.5)))),
    ("dorsum_front_height", "mm", 0.0, 20.0,
     "Raises the front of the dorsum and the blade (C to G) up and forward, away from the hub.",
     _along_rays((("C", 0.3), ("D", 0.7), ("E", 1.0), ("F", 0.8), ("G", 0.3)))),
    ("back_dorsum_height", "mm", -16.0, 20.0,
     "Raises the back of the dorsum (H to J) up and back, away from the hub.",
     _along_rays((("H", 0.5), ("I", 1.0), ("J", 0.4)))),
    ("root_advancement", "mm", -8.0, 24.0,
     "Moves the root (J to M) forward, toward the hub.",
     _along_rays((("J", -0.4), ("K", -1.0), ("L", -1.0), ("M", -0.6)))),
    ("body_height", "mm", -5.0, 8.0, "Raises the whole upper surface, tip to root.",
     (("S", (0.0, 0.5)), ("A", (0.0, 1.0)), ("B", (0.0, 1.0)), ("C", (0.0, 1.0)),
      ("D", (0.0, 1.0)),
      ("E", (0.0, 1.0)), ("F", (0.0, 1.0)), ("G", (0.0, 1.0)), ("H", (0.0, 1.0)),
      ("I", (0.0, 1.0)), ("J", (0.0, 1.0)), ("K", (0.0, 0.6)), ("L", (0.0, 0.3)))),
    ("tongue_retraction", "deg", 0.0, 25.0,
     "Turns the body of the tongue back about the hub: the dorsum back, the root down into the "
     "pharynx.",
     _turns((("C", 0.2), ("D", 0.5), ("E", 0.8), ("F", 1.0), ("G", 1.0), ("H", 1.0), ("I", 1.0),
             ("J", 1.0), ("K", 1.0), ("L", 1.0), ("M", 1.0), ("N", 0.6), ("O", 0.2)))),
    ("dorsum_front_lowering", "mm", 0.0, 6.0,
     "Lowers the front of the dorsum (D to G) toward the hub, each point along its own ray.",
     _radial((("D", -0.5), ("E", -1.0), ("F", -0.8), ("G", -0.3)))),
    ("root_base_advancement", "mm", 0.0, 24.0,
     "Draws the base of the root and the back of the floor (M to O) in toward the hub, each "
     "point along its own ray.",
     _radial((("M", -1.0), ("N", -0.6), ("O", -0.2)))),
)

#: A coronal move that stretches the section sideways instead of moving a control: a page point
#: at angle phi and radius lambda gets z = lambda sin(phi) (1 + stretch (1 - sin(phi)^4)). The
#: stretch fades to nothing at the poles, which every page shares, with zero slope there (the
#: poles stay smooth), and for -1 < stretch < 1/4 it keeps each page's rays in order (the
#: derivative of tan(phi) (1 + stretch (1 - sin(phi)^4)) is at least 1 - 4 stretch), so nothing
#: folds. The width range keeps the stretch within -10 / 32 and 7.5 / 32.
STRETCH = None
#: Full width of the tongue body at the hub, mm: a stretch of 1 / WIDTH_REFERENCE_MM per mm of
#: ``width`` widens the body by about 1 mm per mm.
WIDTH_REFERENCE_MM = 32.0

CORONAL_PARAMETERS = (
    ("width", "mm", -10.0, 7.5, "Widens the section, about 1 mm of width per mm.",
     ((STRETCH, 1.0 / WIDTH_REFERENCE_MM),)),
    # -1.35 at the midline: the B-spline spreads a control's move over its neighbours, so this
    # lowers the surface's midline by 1 mm per mm where the section applies fully.
    ("groove_depth", "mm", -3.0, 10.0,
     "Lowers the midline: a central groove (negative: a ridge).",
     (("midline", -1.35), ("right paramedian", -0.35), ("left paramedian", -0.35))),
    ("groove_width", "mm", -4.0, 8.0, "Lowers the paramedian pair: widens the groove.",
     (("right paramedian", -1.0), ("left paramedian", -1.0), ("right edge", -0.3),
      ("left edge", -0.3))),
    ("left_edge_height", "mm", -8.0, 8.0, "Raises the left lateral edge.",
     (("left edge", 1.0), ("left upper side", 0.5), ("left paramedian", 0.25))),
    ("right_edge_height", "mm", -8.0, 8.0, "Raises the right lateral edge.",
     (("right edge", 1.0), ("right upper side", 0.5), ("right paramedian", 0.25))),
    ("asymmetry", "mm", -4.0, 4.0, "Rolls the section: left side out, right side in.",
     (("left paramedian", 0.25), ("left edge", 0.5), ("left upper side", 0.5),
      ("left side", 0.35), ("left lower side", 0.2), ("right paramedian", -0.25),
      ("right edge", -0.5), ("right upper side", -0.5), ("right side", -0.35),
      ("right lower side", -0.2))),
    ("side_bulge", "mm", -6.0, 8.0, "Pushes the lower sides out.",
     (("right lower side", 1.0), ("right side", 0.6), ("left side", 0.6),
      ("left lower side", 1.0))),
)

JAW_PARAMETER = ("jaw_opening", "deg", 0.0, 10.0,
                 "Opens the jaw: rotation about the temporomandibular axis with a forward slide.")

GROUP_SAGITTAL = "tongue sagittal"
GROUP_JAW = "jaw"


def coronal_knots_deg():
    """Clamped knot vector of the coronal radial B-spline, degrees, (19,) float64."""
    return clamped_knots(CORONAL_INNER_KNOTS_DEG, CORONAL_DEGREE, -90.0, 90.0)


def coronal_control_angles_deg():
    """Page angle where each coronal control has the most weight (Greville), (15,) float64."""
    return greville_abscissae(coronal_knots_deg(), CORONAL_DEGREE)


def parameter_table():
    """The parameter list of the definition (without the rest shape), as JSON-ready dicts."""
    table = []
    for name, unit, low, high, text, moves in SAGITTAL_PARAMETERS:
        table.append(_parameter(name, unit, low, high, GROUP_SAGITTAL, text,
                                [dict(m) if isinstance(m, dict) else {"point": m[0],
                                                                      "by": list(m[1])}
                                 for m in moves]))
    for section in SECTIONS:
        for name, unit, low, high, text, weights in CORONAL_PARAMETERS:
            table.append(_parameter(f"{section}_{name}", unit, low, high,
                                    f"tongue coronal {section}", text,
                                    [{"section": section, "stretch": by} if c is STRETCH
                                     else {"section": section, "control": c, "by": by}
                                     for c, by in weights]))
    name, unit, low, high, text = JAW_PARAMETER
    table.append(_parameter(name, unit, low, high, GROUP_JAW, text, []))
    return table


def _parameter(name, unit, low, high, group, text, moves):
    return {"name": name, "unit": unit, "min": low, "max": high, "neutral": 0.0, "group": group,
            "description": text, "moves": moves}
