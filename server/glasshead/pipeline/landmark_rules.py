"""The rules that find the teaching landmarks on the built meshes (project frame, mm).

Every landmark is read off the anatomy: most from the mid-sagittal section (z = 0) of one
mesh, the palate from the maxilla's midline as the EPG layout finds it (``epg.layout.midline``),
the tongue from the rig's named control points at rest. No coordinate is written by hand. Each
result names its mesh, the feature and the rule, so the build report says how it was found.

Parts (what the label layer names): lips, teeth, alveolar ridge, hard palate, velum, uvula,
tongue tip, blade, front, back and root, pharynx, larynx, nasal port. Places of articulation
along the roof of the mouth, front to back: bilabial, labiodental, dental, alveolar,
postalveolar, palatal, velar, uvular, glottal. References (incisor edges, lip midpoints, the
hard/soft palate junction, the glottis) are the points the others are placed from.

The data hold no epiglottis mesh: the larynx is labelled at the thyroid cartilage's laryngeal
prominence instead.
"""

import numpy as np

from glasshead.epg.layout import midline
from glasshead.epg.palate_section import Section
from glasshead.geometry.landmarks import (
    arc_lengths,
    closest_pair,
    extreme_point,
    farthest_point,
    nearest_point,
    point_at_arc,
    signed_curvature,
)

#: The alveolar ridge is looked for this far (arc length, mm) behind the lingual gingival margin
#: of the upper incisors: the ridge lies within the first half of the hard palate.
RIDGE_SEARCH_MM = 25.0
#: Resampling step and Gaussian smoothing of the palate's midline for its curvature, mm: the
#: maxilla's facets are 1-2 mm long; 2 mm of smoothing keeps the ridge and drops the facets.
CURVE_STEP_MM, CURVE_SIGMA_MM = 0.5, 2.0
#: The velar place sits this fraction of the way from the hard/soft junction to the uvula's tip,
#: on the velum's oral surface: the front of the soft palate, which the dorsum meets for /k g/.
VELAR_FRACTION = 0.4
#: Points of a mesh within this distance of the mid-sagittal plane count as on it, mm (for
#: meshes read as point sets: the larynx cartilages).
MIDLINE_BAND_MM = 5.0
#: The vocal folds' front end is looked for on the thyroid within this height of the vocal
#: processes, mm.
FOLD_HEIGHT_MM = 3.0

DOWN_BACK = np.array([-1.0, -1.0, 0.0]) / np.sqrt(2.0)


def mid_sagittal(vertices, faces) -> np.ndarray:
    """(k, 3) points where the mesh crosses z = 0 (unordered)."""
    points = Section(vertices, faces, origin=(0.0, 0.0, 0.0), normal=(0.0, 0.0, 1.0)).node_points
    if not len(points):
        raise ValueError("the mesh does not cross the mid-sagittal plane")
    return points


def found(position, mesh, feature, rule, **extra) -> dict:
    return {"position": [round(float(c), 3) for c in position], "mesh": mesh, "feature": feature,
            "rule": rule, **extra}


def palate_landmarks(maxilla):
    """Incisor edge, dental, alveolar ridge, hard palate and junction on the maxilla's midline.

    maxilla: (vertices (n, 3), faces (m, 3)). Returns (landmarks dict, measures dict).
    """
    line = midline(*maxilla)
    points, arc = line["polyline"].points, line["arc"]
    start_s, end_s = line["start_s"], line["end_s"]
    front = points[: int(np.searchsorted(arc, start_s)) + 1]
    edge = front[extreme_point(front, (0.0, -1.0, 0.0))]
    edge_s = float(arc[nearest_point(points, edge)])
    curvature, resampled, s = signed_curvature(points[:, :2], CURVE_STEP_MM, CURVE_SIGMA_MM)
    window = np.flatnonzero((s >= start_s) & (s <= start_s + RIDGE_SEARCH_MM))
    # The palate (bone) lies on the right of the front-to-back direction: its bulge into the
    # mouth, the ridge's crest, is the most negative curvature.
    ridge_k = int(window[np.argmin(curvature[window])])
    ridge_s = float(s[ridge_k])
    ridge = point_at_arc(points, arc, ridge_s)
    hard_s = 0.5 * (ridge_s + end_s)
    post_s = 0.5 * (ridge_s + hard_s)
    dental_s = 0.5 * (edge_s + start_s)
    marks = {
        "upper_incisor_edge": found(edge, "maxilla", "incisal edge of the upper central incisors",
                                    "lowest point of the maxilla's midline in front of the "
                                    "incisors' lingual gingival margin"),
        "dental_face": found(point_at_arc(points, arc, dental_s), "maxilla",
                             "lingual face of the upper incisors",
                             "midline point halfway (arc length) from the incisal edge to the "
                             "lingual gingival margin"),
        "alveolar_ridge": found(ridge, "maxilla", "crest of the alveolar ridge",
                                f"greatest convex curvature of the maxilla's midline within "
                                f"{RIDGE_SEARCH_MM:g} mm behind the incisors' lingual gingival "
                                f"margin (smoothed over {CURVE_SIGMA_MM:g} mm)",
                                curvature_per_mm=round(float(-curvature[ridge_k]), 4)),
        "postalveolar": found(point_at_arc(points, arc, post_s), "maxilla",
                              "front slope of the palatal vault",
                              "midline point halfway (arc length) from the alveolar ridge to "
                              "the middle of the hard palate"),
        "hard_palate": found(point_at_arc(points, arc, hard_s), "maxilla",
                             "middle of the palatal vault",
                             "midline point halfway (arc length) from the alveolar ridge to the "
                             "hard/soft palate junction"),
        "hard_soft_junction": found(point_at_arc(points, arc, end_s), "maxilla",
                                    "posterior edge of the hard palate",
                                    "most posterior point of the maxilla's midline"),
    }
    measures = {
        "alveolar_ridge_behind_upper_incisor_edge_mm": round(float(edge[0] - ridge[0]), 2),
        "alveolar_ridge_above_upper_incisor_edge_mm": round(float(ridge[1] - edge[1]), 2),
        "alveolar_ridge_from_upper_incisor_edge_mm": round(float(np.linalg.norm(ridge - edge)), 2),
        "alveolar_ridge_behind_gingival_margin_arc_mm": round(ridge_s - start_s, 2),
        "hard_palate_midline_arc_mm": round(end_s - start_s, 2),
    }
    return marks, measures, {"edge": edge, "junction": point_at_arc(points, arc, end_s)}


def mouth_landmarks(upper_lip, lower_lip, mandible, upper_edge):
    """Lips, lower incisor edge, bilabial and labiodental. Meshes as (vertices, faces);
    ``upper_edge`` (3,) the upper incisal edge."""
    upper = mid_sagittal(*upper_lip)
    lower = mid_sagittal(*lower_lip)
    jaw = mid_sagittal(*mandible)
    upper_low = upper[extreme_point(upper, (0.0, -1.0, 0.0))]
    lower_high = lower[extreme_point(lower, (0.0, 1.0, 0.0))]
    upper_front = upper[extreme_point(upper, (1.0, 0.0, 0.0))]
    lower_front = lower[extreme_point(lower, (1.0, 0.0, 0.0))]
    lower_edge = jaw[extreme_point(jaw, (0.0, 1.0, 0.0))]
    lip_under_edge = lower[nearest_point(lower, upper_edge)]
    marks = {
        "upper_lip": found(upper_front, "upper_lip", "vermilion of the upper lip",
                           "most anterior point of the upper lip's midline"),
        "lower_lip": found(lower_front, "lower_lip", "vermilion of the lower lip",
                           "most anterior point of the lower lip's midline"),
        "lips": found(0.5 * (upper_front + lower_front), "upper_lip, lower_lip", "the lips",
                      "midpoint of the upper and lower lips' most anterior midline points"),
        "lower_incisor_edge": found(lower_edge, "mandible",
                                    "incisal edge of the lower central incisors",
                                    "highest point of the mandible's midline"),
        "bilabial": found(0.5 * (upper_low + lower_high), "upper_lip, lower_lip",
                          "where the lips meet", "midpoint of the upper lip's lowest and the "
                          "lower lip's highest midline points"),
        "labiodental": found(0.5 * (upper_edge + lip_under_edge), "maxilla, lower_lip",
                             "upper incisors' edge against the lower lip",
                             "midpoint of the upper incisal edge and the nearest point of the "
                             "lower lip's midline"),
    }
    return marks, {"lip_gap_mm": round(float(upper_low[1] - lower_high[1]), 2),
                   "upper_incisor_edge_to_lower_lip_mm": round(
                       float(np.linalg.norm(lip_under_edge - upper_edge)), 2)}


def velum_surfaces(velum, junction, tongue_dorsum):
    """The velum's mid-sagittal loop split at its front end (nearest the hard/soft junction) and
    its tip (farthest from it): (oral (k, 3), nasal (m, 3), tip (3,)), each surface ordered from
    the front end to the tip. The oral surface is the one nearer ``tongue_dorsum`` (3,)."""
    vertices, faces = velum
    section = Section(vertices, faces, origin=(0.0, 0.0, 0.0), normal=(0.0, 0.0, 1.0))
    if section.empty:
        raise ValueError("the velum does not cross the mid-sagittal plane")
    loop = section.polyline_through(section.nearest_segment(junction)).points
    front = nearest_point(loop, junction)
    loop = np.roll(loop, -front, axis=0)
    tip = farthest_point(loop, junction)
    one = loop[: tip + 1]
    other = np.concatenate([loop[tip:], loop[:1]])[::-1]
    def gap(curve):
        return float(np.min(np.linalg.norm(curve - tongue_dorsum, axis=1)))
    oral, nasal = (one, other) if gap(one) <= gap(other) else (other, one)
    return oral, nasal, loop[tip]


def velum_landmarks(velum_rest, velum_raised, pharynx, junction, tongue_dorsum):
    """Velum, velar, uvula and nasal port, and the pharyngeal wall's midline (returned for the
    pharynx rule). ``junction`` (3,): the hard/soft palate junction; ``tongue_dorsum`` (3,): a
    point below the velum, which tells its oral surface from its nasal one."""
    rest = mid_sagittal(*velum_rest)
    wall = mid_sagittal(*pharynx)
    oral, nasal, tip = velum_surfaces(velum_rest, junction, tongue_dorsum)
    velar = point_at_arc(oral, arc_lengths(oral), VELAR_FRACTION * arc_lengths(oral)[-1])
    i, j, gap = closest_pair(nasal[:, :2], wall[:, :2])
    port = 0.5 * (nasal[i] + wall[j])
    _, raised_nasal, _ = velum_surfaces(velum_raised, junction, tongue_dorsum)
    _, _, raised_gap = closest_pair(raised_nasal[:, :2], wall[:, :2])
    marks = {
        "velum": found(rest.mean(axis=0), "velum_rest", "the soft palate (rest pose)",
                       "centroid of the rest velum's mid-sagittal section"),
        "velar": found(velar, "velum_rest", "oral surface of the soft palate",
                       f"point {VELAR_FRACTION:g} of the way (arc length) along the rest "
                       "velum's oral surface from its front end to the uvula's tip"),
        "uvula": found(tip, "velum_rest", "tip of the uvula (rest pose)",
                       "point of the rest velum's midline farthest from the hard/soft junction"),
        "nasal_port": found(port, "velum_rest, pharynx",
                            "velopharyngeal port (rest pose)",
                            "midpoint of the narrowest mid-sagittal gap between the rest velum's "
                            "nasal surface and the posterior pharyngeal wall",
                            width_mm=round(gap, 2)),
    }
    measures = {"velum_oral_length_mm": round(float(arc_lengths(oral)[-1]), 2),
                "uvula_from_junction_mm": round(float(np.linalg.norm(tip - junction)), 2),
                "nasal_port_rest_gap_mm": round(gap, 2),
                "nasal_port_raised_gap_mm": round(raised_gap, 2),
                "pharyngeal_wall_midline_top_y_mm": round(float(wall[:, 1].max()), 2)}
    return marks, measures, wall


def tongue_landmarks(tongue, control_points):
    """Tip, blade, front, back and root: the points of the rest tongue's midline nearest the
    rig's named control points at rest. ``control_points``: {name: (x, y)} of the rig."""
    section = mid_sagittal(*tongue)

    def on_tongue(names):
        target = np.mean([[*control_points[n], 0.0] for n in names], axis=0)
        return section[nearest_point(section, target)]

    parts = {"tongue_tip": (("B",), "tip"), "tongue_blade": (("C", "D"), "blade"),
             "tongue_front": (("E", "F"), "front (under the hard palate)"),
             "tongue_back": (("H", "I"), "back (under the soft palate)"),
             "tongue_root": (("K",), "root (facing the pharynx)")}
    return {name: found(on_tongue(names), "tongue_rest", f"tongue {feature}",
                        "point of the rest tongue's midline nearest the mean of the rig's "
                        f"control point{'s' if len(names) > 1 else ''} {' and '.join(names)} "
                        "at rest", controls=list(names))
            for name, (names, feature) in parts.items()}


def throat_landmarks(wall, tongue_root, thyroid, arytenoids):
    """Pharynx, larynx and glottis. ``wall``: the pharyngeal wall's midline points (k, 3);
    ``thyroid``, ``arytenoids``: (n, 3) vertices (the arytenoids of both sides together)."""
    at_root = wall[nearest_point(wall[:, 1:2], tongue_root[1:2])]
    near = np.abs(thyroid[:, 2]) < MIDLINE_BAND_MM
    prominence = thyroid[near][extreme_point(thyroid[near], (1.0, 0.0, 0.0))]
    left, right = arytenoids
    processes = 0.5 * (left[extreme_point(left, (1.0, 0.0, 0.0))]
                       + right[extreme_point(right, (1.0, 0.0, 0.0))])
    inner = thyroid[near & (np.abs(thyroid[:, 1] - processes[1]) < FOLD_HEIGHT_MM)
                    & (thyroid[:, 0] > processes[0])]
    if not len(inner):
        raise ValueError("no thyroid cartilage in front of the arytenoids at their height")
    commissure = inner[extreme_point(inner, (-1.0, 0.0, 0.0))]
    glottis = 0.5 * (processes + commissure)
    glottis[2] = 0.0
    marks = {
        "pharynx": found(0.5 * (tongue_root + at_root), "pharynx", "oropharynx",
                         "midpoint between the tongue root and the posterior pharyngeal wall at "
                         "its height"),
        "larynx": found(prominence, "thyroid", "laryngeal prominence of the thyroid cartilage",
                        f"most anterior thyroid point within {MIDLINE_BAND_MM:g} mm of the "
                        "midline (no epiglottis mesh exists in the data)"),
        "glottis": found(glottis, "arytenoid_left, arytenoid_right, thyroid",
                         "middle of the vocal folds",
                         "midpoint of the arytenoids' vocal processes (their most anterior "
                         "points) and the thyroid's inner surface at their height, on z = 0"),
    }
    return marks, {"pharynx_depth_at_tongue_root_mm": round(float(tongue_root[0] - at_root[0]), 2),
                   "vocal_fold_length_mm": round(float(np.linalg.norm(commissure - processes)),
                                                 2)}
