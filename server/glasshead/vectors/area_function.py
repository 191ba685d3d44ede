"""area-function.json: tracts of known shape through the area function, with the width at
every station and the tube that comes out.

pytest (tests/test_area_function.py) checks that the file is what this module makes, and
``tests/js/areaFunction.test.js`` that the JavaScript twin gives the same numbers. The tracts
are drawn by hand, so that each number can be checked by eye: a straight channel between two
walls 10 mm apart; the same with a round tongue pressed into the roof (stations inside it are
shut); and a bent tract (a pharynx down, a mouth forward) with solid lips that are parted,
then pressed together, then rounded.
"""

import math

import numpy as np

from glasshead.acoustics.area_function import area_function, chain_part, nasal_branch
from glasshead.constants import (
    TRACT_AREA_LAWS,
    TRACT_LARYNX_TUBE,
    TRACT_MIN_AREA_MM2,
    TRACT_STATION_STEP_MM,
)
from glasshead.vectors.common import case, document, tolerance

NAME = "area-function.json"
FORMAT_VERSION = 1
TOLERANCES = {"mm": tolerance(1e-9, "mm", "distances from the same few operations"),
              "area": tolerance(1e-9, "relative", "a power of a width")}


#: A made-up nose for the nasal branch of every case, and the port it is given, mm².
NOSE = {"port_length_mm": 6.0, "length_mm": [6.0, 6.0, 6.0], "area_mm2": [100.0, 300.0, 80.0]}
PORT_MM2 = 40.0


def _circle(cx, cy, radius, count=24):
    angle = 2.0 * math.pi * np.arange(count) / count
    return np.column_stack([cx + radius * np.cos(angle), cy + radius * np.sin(angle)])


def _line(*points):
    return np.asarray(points, dtype=np.float64)


def _channel():
    stations = np.column_stack([np.arange(-60.0, 21.0, TRACT_STATION_STEP_MM * 2),
                                np.zeros(21)])
    floor = [(_line((-70.0, -5.0), (40.0, -5.0)), False)]
    roof = [(_line((-70.0, 5.0), (40.0, 5.0)), False)]
    return stations, floor, roof


def _bent():
    down = np.column_stack([np.full(15, -40.0), np.linspace(-60.0, -4.0, 15)])
    forward = np.column_stack([np.linspace(-36.0, 20.0, 15), np.zeros(15)])
    stations = np.vstack([down, forward])
    roof = [(_line((-48.0, -70.0), (-48.0, 8.0), (40.0, 8.0)), False)]
    floor = [(_line((-32.0, -70.0), (-32.0, -8.0), (40.0, -8.0)), False)]
    return stations, floor, roof


def _lips(gap_mm):
    upper = _line((22.0, 8.0), (34.0, 8.0), (36.0, gap_mm / 2), (22.0, gap_mm / 2))
    lower = _line((22.0, -gap_mm / 2), (36.0, -gap_mm / 2), (34.0, -8.0), (22.0, -8.0))
    return (upper, True), (lower, True)


def _tract_case(description, stations, floor, roof, *, incisor_x, uvula_y, lip_front_x,
                lip_rounding):
    result = area_function(stations, [chain_part(p, c) for p, c in floor],
                           [chain_part(p, c) for p, c in roof], incisor_x=incisor_x,
                           uvula_y=uvula_y, lip_front_x=lip_front_x, lip_rounding=lip_rounding)
    return case(description,
                {"stations": np.asarray(stations).ravel().tolist(),
                 "floor": [{"points": np.asarray(p).ravel().tolist(), "closed": c}
                           for p, c in floor],
                 "roof": [{"points": np.asarray(p).ravel().tolist(), "closed": c}
                          for p, c in roof],
                 "incisor_x": incisor_x, "uvula_y": uvula_y, "lip_front_x": lip_front_x,
                 "lip_rounding": lip_rounding},
                {"length_mm": result["length_mm"].tolist(),
                 "area_mm2": result["area_mm2"].tolist(),
                 "position_mm": result["position_mm"].tolist(),
                 "width_mm": [None if np.isnan(w) else float(w) for w in result["width_mm"]],
                 "region": [int(r) for r in result["region"]], "closed": result["closed"],
                 "nasal": nasal_branch(result["region"], NOSE, PORT_MM2)})


def build_document():
    stations, floor, roof = _channel()
    cases = [
        _tract_case("a straight channel 10 mm high, all mouth", stations, floor, roof,
                    incisor_x=30.0, uvula_y=-100.0, lip_front_x=20.0, lip_rounding=0.0),
        _tract_case("the channel with its front as lips, reaching 9 mm ahead", stations, floor,
                    roof, incisor_x=0.0, uvula_y=-100.0, lip_front_x=29.0, lip_rounding=2.0),
        _tract_case("the channel with a round tongue of radius 8 pressed 4 mm into the roof",
                    stations, floor + [(_circle(-20.0, 1.0, 8.0), True)], roof,
                    incisor_x=30.0, uvula_y=-100.0, lip_front_x=20.0, lip_rounding=0.0),
    ]
    stations, floor, roof = _bent()
    for gap, rounding, what in ((4.0, 0.0, "parted 4 mm"), (0.0, 0.0, "pressed together"),
                                (3.0, 8.0, "rounded, 3 mm apart")):
        upper, lower = _lips(gap)
        cases.append(_tract_case(
            f"a bent tract (pharynx, then mouth) with solid lips {what}", stations,
            floor + [lower], roof + [upper], incisor_x=22.0, uvula_y=-10.0, lip_front_x=36.0,
            lip_rounding=rounding))
    return document(
        NAME, "Hand-drawn tracts through the area function: stations (x y, mm) from the larynx "
              "to the incisors, the floor's and the roof's polylines (closed: a solid), and the "
              "tube, glottis first: section lengths, areas, middles from the glottis, mean "
              "widths (null for the larynx tube), regions (-1 larynx, 0 pharynx, 1 mouth, "
              "2 lips), whether a section is shut, and the nasal branch that the fixtures' nose "
              "behind a port of port_mm2 makes of it (at: the sections before the junction)",
        FORMAT_VERSION, cases,
        constants={"laws": TRACT_AREA_LAWS, "larynx": TRACT_LARYNX_TUBE,
                   "min_area_mm2": TRACT_MIN_AREA_MM2, "step_mm": TRACT_STATION_STEP_MM},
        fixtures={"nose": NOSE, "port_mm2": PORT_MM2},
        tolerances=TOLERANCES)


def files():
    return {NAME: build_document()}
