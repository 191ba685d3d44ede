"""The tract's area function: the cross-sections of the air from the glottis to the lips, read
off the mid-sagittal section of the posed head.

The tract is walked at stations along the rest airway's midline (``pipeline.tract_section``
writes them, about ``TRACT_STATION_STEP_MM`` apart, from the airway's lower end to the upper
incisors' edge), then forward between the lips to their front, wherever the posed lips reach.
At each station the mid-sagittal width of the air is the distance to the floor (the tongue,
the lower lip, the jaw, the larynx's entrance) plus the distance to the roof (the palate, the
velum, the upper lip, the pharyngeal wall); inside a closed part (the tongue risen past the
station, the lips pressed together) the distance to the other side less the depth, and 0 where
the other side's nearest point lies inside the solid too (the two overlap). Nearest distances
rather than lines across the tract: they need no direction, so the bend behind the tongue
cannot send a line into the nasopharynx or across its neighbours.

Each section between two stations takes the mean of their widths d and becomes an area: in
the mouth and the pharynx by the power law A = alpha d^beta of area-function studies (Heinz and
Stevens 1964; Soquet et al. 2002 give alpha 1.3 to 2 and beta 1.2 to 1.6), in front of the
incisors as the ellipse between the lips, pi/4 d w, w the mouth's width (narrower as the lips
round); one narrower than ``TRACT_CLOSURE_MM`` is shut and passes only ``TRACT_MIN_AREA_MM2``
(the rigs do not press tissue together, so a stop keeps a gap of under a millimetre).
``TRACT_AREA_LAWS`` holds the coefficients, the exponent Heinz and Stevens's and each alpha
chosen so that the head's vowels fitted to VocalTractLab's JD3 shapes give that model's
formants (docs/acoustics.md); below the airway's lower end a fixed larynx tube
(``TRACT_LARYNX_TUBE``) completes the tract. Pure numpy; the browser's twin is
``web/src/core/areaFunction.js``, held to the same numbers by the shared vectors.

The nasal branch (``nasal_branch``) is the nose of VocalTractLab's JD3 speaker (its sections from
the port to the nostrils, ``tract-section.json``), its first section the velum's port: it leaves
the tract where the pharynx ends and the mouth begins, below the uvula, as VocalTractLab's nose
leaves its tract above its 16th of 40 sections.
"""

import math
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from glasshead.constants import (
    TRACT_AREA_LAWS,
    TRACT_CLOSURE_MM,
    TRACT_LARYNX_TUBE,
    TRACT_MIN_AREA_MM2,
    TRACT_STATION_STEP_MM,
)

Floats = npt.NDArray[np.float64]
#: A part's section: its segments (m, 4) x0 y0 x1 y1 in mm, and whether they close round
#: tissue (a solid: the tongue, a lip, the velum) so that a station can lie inside it.
Part = tuple[npt.ArrayLike, bool]
#: The region of each section, by the law that gives its area.
REGIONS = ("pharynx", "oral", "lips")


def chain_part(points: npt.ArrayLike, closed: bool) -> Part:
    """A polyline (k, 2) as a part: its segments, a solid when it closes on its first point."""
    p = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    b = np.roll(p, -1, axis=0) if closed else p[1:]
    a = p if closed else p[:-1]
    return np.hstack([a, b]), closed


def plane_segments(vertices: npt.ArrayLike, faces: npt.ArrayLike) -> Floats:
    """The z = 0 section of a triangle mesh as segments (m, 4) x0 y0 x1 y1 (unordered)."""
    v = np.asarray(vertices, dtype=np.float64)
    tri = v[np.asarray(faces, dtype=np.int64)]
    above = tri[:, :, 2] >= 0.0
    crossing = above.any(axis=1) & ~above.all(axis=1)
    tri, above = tri[crossing], above[crossing]
    ends = []
    for i, j in ((0, 1), (1, 2), (2, 0)):
        p, q = tri[:, i], tri[:, j]
        cut = above[:, i] != above[:, j]
        t = p[:, 2] / np.where(cut, p[:, 2] - q[:, 2], 1.0)
        ends.append((p[:, :2] + t[:, None] * (q[:, :2] - p[:, :2]), cut))
    points = np.stack([e[0] for e in ends], axis=1)
    cuts = np.stack([e[1] for e in ends], axis=1)
    # Exactly two of a crossing triangle's edges cross; take them in edge order.
    order = np.argsort(~cuts, axis=1, kind="stable")[:, :2]
    rows = np.arange(len(points))[:, None]
    pair = points[rows, order]
    return np.asarray(pair.reshape(-1, 4))


def _segments(parts: Sequence[Part]) -> tuple[Floats, Floats, list[tuple[int, int]]]:
    """Every segment's ends (m, 2) and (m, 2), and the range of segments of each solid."""
    starts, ends, solids = [], [], []
    count = 0
    for segments, solid in parts:
        s = np.asarray(segments, dtype=np.float64).reshape(-1, 4)
        if not len(s):
            continue
        starts.append(s[:, :2])
        ends.append(s[:, 2:])
        if solid:
            solids.append((count, count + len(s)))
        count += len(s)
    if not starts:
        return np.zeros((0, 2)), np.zeros((0, 2)), []
    return np.vstack(starts), np.vstack(ends), solids


def nearest_on_segments(points: Floats, a: Floats, b: Floats) -> tuple[Floats, Floats]:
    """Distance (n,) from each point to the nearest segment (inf without segments), and that
    nearest point (n, 2)."""
    if len(a) == 0:
        return np.full(len(points), np.inf), np.asarray(points, dtype=np.float64).copy()
    ab = b - a
    t = np.einsum("nmj,mj->nm", points[:, None] - a[None], ab) / np.maximum(
        np.einsum("mj,mj->m", ab, ab), 1e-12)
    closest = a[None] + np.clip(t, 0.0, 1.0)[..., None] * ab[None]
    distance = np.linalg.norm(points[:, None] - closest, axis=2)
    best = distance.argmin(axis=1)
    rows = np.arange(len(points))
    return np.asarray(distance[rows, best]), np.asarray(closest[rows, best])


def _inside(points: Floats, a: Floats, b: Floats, closed: list[tuple[int, int]]) -> npt.NDArray:
    """(n,) bool: the point lies inside one of the solids (crossings of a ray toward +x, counted
    per solid: the segments' order does not matter)."""
    inside = np.zeros(len(points), dtype=bool)
    x, y = points[:, 0, None], points[:, 1, None]
    for first, last in closed:
        x0, y0, x1, y1 = a[first:last, 0], a[first:last, 1], b[first:last, 0], b[first:last, 1]
        spans = (y0 > y) != (y1 > y)
        dy = np.where(y1 == y0, 1.0, y1 - y0)
        crosses = spans & (x < x0 + (y - y0) * (x1 - x0) / dy)
        inside |= crosses.sum(axis=1) % 2 == 1
    return inside


def tract_widths(stations: npt.ArrayLike, floor: Sequence[Part],
                 roof: Sequence[Part]) -> Floats:
    """The air's mid-sagittal width (n,) mm at each station (n, 2) between the floor's and the
    roof's parts (see the module's docstring); 0 where they touch or overlap: inside a solid
    whose overlap with the other side holds the other side's nearest point."""
    points = np.asarray(stations, dtype=np.float64).reshape(-1, 2)
    fa, fb, f_solids = _segments(floor)
    ra, rb, r_solids = _segments(roof)
    to_floor, floor_at = nearest_on_segments(points, fa, fb)
    to_roof, roof_at = nearest_on_segments(points, ra, rb)
    in_floor, in_roof = _inside(points, fa, fb, f_solids), _inside(points, ra, rb, r_solids)
    # Inside a solid, the other side's nearest point inside it too means the two overlap there.
    overlap = (in_floor & _inside(roof_at, fa, fb, f_solids)) \
        | (in_roof & _inside(floor_at, ra, rb, r_solids)) | (in_floor & in_roof)
    width = np.where(in_floor, to_roof - to_floor,
                     np.where(in_roof, to_floor - to_roof, to_floor + to_roof))
    width = np.where(overlap, 0.0, width)
    return np.asarray(np.maximum(np.where(np.isfinite(width), width, 0.0), 0.0))


def lip_stations(last: npt.ArrayLike, lip_front_x: float,
                 step_mm: float = TRACT_STATION_STEP_MM) -> Floats:
    """Stations (k, 2) forward from the last midline station ``last`` (at the incisors) to the
    lips' front, level with it and at most ``step_mm`` apart; none when the lips do not reach
    past it."""
    x0, y0 = (float(v) for v in np.asarray(last, dtype=np.float64)[:2])
    reach = float(lip_front_x) - x0
    if not reach > 0.0:
        return np.zeros((0, 2))
    count = math.ceil(reach / step_mm)
    xs = x0 + reach * np.arange(1, count + 1) / count
    return np.column_stack([xs, np.full(count, y0)])


def lip_width_mm(lip_rounding: float) -> float:
    """The mouth's width (mm) for a value of the lip_rounding parameter."""
    law = TRACT_AREA_LAWS["lips"]
    return max(law["min_mm"], law["width_mm"] - law["narrowing_mm"] * float(lip_rounding))


def section_region(x: float, y: float, incisor_x: float, uvula_y: float) -> int:
    """The index in ``REGIONS`` of a section whose middle is (x, y)."""
    if x > incisor_x:
        return 2
    return 0 if y < uvula_y else 1


def width_to_area(width_mm: Floats, region: npt.NDArray, lip_width: float) -> Floats:
    """Areas (mm²) of sections of mid-sagittal width ``width_mm`` in ``region`` (indices of
    ``REGIONS``), at least ``TRACT_MIN_AREA_MM2``, which a section narrower than
    ``TRACT_CLOSURE_MM`` (shut) has."""
    d = np.maximum(np.asarray(width_mm, dtype=np.float64), 0.0)
    areas = np.empty_like(d)
    for k, name in enumerate(REGIONS[:2]):
        law = TRACT_AREA_LAWS[name]
        here = region == k
        areas[here] = 100.0 * law["alpha"] * (d[here] / 10.0) ** law["beta"]
    lips = region == 2
    areas[lips] = math.pi / 4.0 * d[lips] * lip_width
    areas[d < TRACT_CLOSURE_MM] = TRACT_MIN_AREA_MM2
    return np.asarray(np.maximum(areas, TRACT_MIN_AREA_MM2))


def area_function(stations: npt.ArrayLike, floor: Sequence[Part], roof: Sequence[Part], *,
                  incisor_x: float, uvula_y: float, lip_front_x: float,
                  lip_rounding: float) -> dict:
    """The tube of a posed tract, glottis first.

    stations : (n, 2) mm, the midline stations from the airway's lower end to the incisors.
    floor, roof : the posed parts' sections (``Part``).
    incisor_x, uvula_y : where the lips' and the pharynx's sections begin (mm).
    lip_front_x : the lips' front (mm); lip_rounding : the face rig's parameter.
    Returns {"length_mm" (m,), "area_mm2" (m,), "position_mm" (m,) the middle of each section
    from the glottis, "width_mm" (m,) the mid-sagittal width of each section (the larynx tube's
    NaN), "region" (m,) indices of ``REGIONS`` (-1 for the larynx tube), "closed" bool: some
    section is shut (narrower than ``TRACT_CLOSURE_MM``)}.
    """
    walk = np.asarray(stations, dtype=np.float64).reshape(-1, 2)
    if len(walk) < 2:
        raise ValueError("an area function needs at least two stations")
    walk = np.vstack([walk, lip_stations(walk[-1], lip_front_x)])
    widths = tract_widths(walk, floor, roof)
    lengths = np.linalg.norm(np.diff(walk, axis=0), axis=1)
    section_width = (widths[:-1] + widths[1:]) / 2.0
    middles = (walk[:-1] + walk[1:]) / 2.0
    regions = np.array([section_region(x, y, incisor_x, uvula_y) for x, y in middles])
    areas = width_to_area(section_width, regions, lip_width_mm(lip_rounding))
    larynx = TRACT_LARYNX_TUBE
    length = np.concatenate([[larynx["length_mm"]], lengths])
    ends = np.cumsum(length)
    return {"length_mm": length,
            "area_mm2": np.concatenate([[larynx["area_mm2"]], areas]),
            "position_mm": ends - length / 2.0,
            "width_mm": np.concatenate([[np.nan], section_width]),
            "region": np.concatenate([[-1], regions]),
            "closed": bool(np.any(section_width < TRACT_CLOSURE_MM))}


def nasal_branch(region: npt.ArrayLike, nose: dict, port_mm2: float) -> dict | None:
    """The nose as a side branch of the tube whose sections have the regions ``region`` (as
    ``area_function`` gives them): {"at": the sections before the junction (those of the larynx
    and the pharynx), "length_mm", "area_mm2": the port (``nose["port_length_mm"]`` long, of
    ``port_mm2``) then the nose's sections}; None while the port is shut (narrower than
    ``TRACT_MIN_AREA_MM2``) or the tube has no mouth."""
    regions = np.asarray(region)
    mouth = np.flatnonzero(regions >= REGIONS.index("oral"))
    if port_mm2 < TRACT_MIN_AREA_MM2 or len(mouth) == 0 or mouth[0] == 0:
        return None
    return {"at": int(mouth[0]),
            "length_mm": [float(nose["port_length_mm"]), *map(float, nose["length_mm"])],
            "area_mm2": [float(port_mm2), *map(float, nose["area_mm2"])]}
