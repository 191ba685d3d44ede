"""flesh-points.json: the flesh points' shared vectors (``geometry.flesh_points``).

Inputs are the other vector files' fixtures, so that both sides read the same numbers: the tongue
rig of tongue-surface.json, and the face rig, jaw and rest meshes of face-rig.json; this file's
fixtures add the rest incisor edges (from the built landmarks, rounded to 0.1 micrometre).
Expected: the tongue sensors' anchors on the rest outline (station pairs and weights), and per
case the eight points. Cases: every face-rig.json case's lip parameters and jaw opening (those
keep the lips' and teeth's decisions clear of their thresholds), the first with the tongue at
rest, the others with a seeded random tongue drawn uniformly within every range.

The anchors' station pairs are integers decided by floats (which segment holds an arc); the
generator checks that every arc lies more than ``MARGIN_MM`` inside its segment, so float32
JavaScript cannot pick another.
"""

import numpy as np

from glasshead.constants import (
    FACE_VERTEX_TOLERANCE_MM,
    LANDMARKS_FILE,
    TONGUE_VERTEX_TOLERANCE_MM,
)
from glasshead.geometry.flesh_points import (
    FLESH_POINT_NAMES,
    INCISOR_LANDMARKS,
    TONGUE_SENSOR_ARC_MM,
    FleshPointRig,
    midline_outline,
)
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.vectors import sources
from glasshead.vectors.common import case, document, read, rounded, tolerance

FORMAT_VERSION = 1
SEED = 20261128
PARAM_DECIMALS = 4
RESULT_DECIMALS = 5
REST_DECIMALS = 4
#: mm. Every sensor arc lies at least this far from both ends of its segment.
MARGIN_MM = 0.05

TOLERANCES = {
    "point_mm": tolerance(max(TONGUE_VERTEX_TOLERANCE_MM, FACE_VERTEX_TOLERANCE_MM), "mm",
                          "JavaScript interpolates float32 tongue positions and poses float32 "
                          "lips (a few 1e-6 mm off); a wrong point is off by far more"),
    "weight": tolerance(1e-5, "1", "anchor weights from float32 rest positions in JavaScript"),
    "stored_mm": tolerance(1e-5, "mm", "stored values are rounded to 5 decimals (at most 5e-6 "
                                       "off); the float64 reference reproduces them within that"),
}


def inputs():
    """(tongue definition, face fixtures {rig, jaw, rest}, incisors {name: (3,)}, face cases)."""
    tongue = read("tongue-surface.json")["fixtures"]["rig"]
    face = read("face-rig.json")
    marks = {m["name"]: m["position"] for m in sources.built_json(LANDMARKS_FILE)["landmarks"]}
    incisors = {name: np.round(marks[mark], REST_DECIMALS).tolist()
                for name, mark in INCISOR_LANDMARKS.items()}
    return tongue, face["fixtures"], incisors, face["cases"]


def make_rig(tongue, face_fixtures, incisors):
    """The FleshPointRig of the fixtures (float64 of the stored numbers)."""
    lips = {name: np.asarray(face_fixtures["rest"][name], dtype=np.float64).reshape(-1, 3)
            for name in ("upper_lip", "lower_lip")}
    landmarks = {"landmarks": [{"name": INCISOR_LANDMARKS[name], "position": position}
                               for name, position in incisors.items()]}
    return FleshPointRig(TongueRig(tongue), face_fixtures["rig"], lips, landmarks)


def check_margins(rig):
    """RuntimeError unless every arc lies ``MARGIN_MM`` inside its segment."""
    outline = midline_outline(rig.tongue, rig.tongue.neutral)
    first, second, weight = rig.anchors
    length = np.linalg.norm(outline[second] - outline[first], axis=1)
    near = np.minimum(weight, 1 - weight) * length
    if np.any(near < MARGIN_MM):
        raise RuntimeError(f"flesh-points.json: a sensor arc lies within {MARGIN_MM} mm of a "
                           f"station ({near.min():.3g} mm)")


def tongue_draws(tongue: TongueRig, seed=SEED):
    """Endless seeded tongue parameter sets, the jaw left out (the face case gives it)."""
    rng = np.random.default_rng(seed)
    keep = [k for k, name in enumerate(tongue.parameter_names)
            if k != tongue.jaw_parameter]
    low, high = tongue.minimum[keep], tongue.maximum[keep]
    names = [tongue.parameter_names[k] for k in keep]
    while True:
        values = np.clip(np.round(rng.uniform(low, high), PARAM_DECIMALS), low, high)
        yield dict(zip(names, values.tolist(), strict=True))


def flesh_document():
    tongue, face_fixtures, incisors, face_cases = inputs()
    rig = make_rig(tongue, face_fixtures, incisors)
    check_margins(rig)
    first, second, weight = rig.anchors
    draws = tongue_draws(rig.tongue)
    cases = []
    for number, face_case in enumerate(face_cases):
        params = dict(face_case["input"]["params"])
        if number:
            params.update(next(draws))
        points = rig.frame(params)
        tongue_note = "tongue at rest" if not number else f"random tongue (seed {SEED})"
        cases.append(case(f"{face_case['description']}; {tongue_note}", {"params": params}, {
            "points": {name: rounded(points[name], RESULT_DECIMALS)
                       for name in FLESH_POINT_NAMES}}))
    return document(
        "flesh-points.json",
        "Flesh points (EMA sensor points) of the tongue rig of tongue-surface.json's fixtures "
        "and the face rig, jaw and rest meshes of face-rig.json's, with the incisor edges in "
        "fixtures: for every face-rig.json case's lip and jaw parameters, with the tongue at rest "
        f"in the first and drawn uniformly within every range with numpy seed {SEED} in the "
        "others",
        FORMAT_VERSION, cases,
        constants={"seed": SEED, "arcs_mm": TONGUE_SENSOR_ARC_MM, "margin_mm": MARGIN_MM,
                   "names": list(FLESH_POINT_NAMES)},
        tolerances=TOLERANCES,
        fixtures={"tongue_rig": "tongue-surface.json", "face_rig": "face-rig.json",
                  "incisors": incisors,
                  "anchors": {"first": first.tolist(), "second": second.tolist(),
                              "weight": rounded(weight, RESULT_DECIMALS + 3)}})


def files():
    return {"flesh-points.json": flesh_document()}
