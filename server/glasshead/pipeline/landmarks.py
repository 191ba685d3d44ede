"""Build step: the teaching landmarks, written to ``landmarks.json`` and the build report.

The label layer of the web app names the parts of the mouth and throat and the places of
articulation along the roof of the mouth at these points. They are found on the built meshes by
the rules in ``pipeline.landmark_rules`` (each entry names its mesh, feature and rule) and the
tongue rig's control points at rest; none is placed by hand.

The file (format version ``LANDMARKS_FORMAT_VERSION``) holds one list, ``landmarks``, each entry
``{name, label, kind, position, mesh, feature, rule, meshes}``: ``kind`` is ``part`` (a thing the
layer names), ``place`` (a place of articulation; ``order`` runs front to back and ``at`` names
the point it is defined by) or ``reference`` (a point the others are placed from). ``meshes``
lists the scene meshes a pointer over which may be named by a part. ``measures`` holds distances
between landmarks (the alveolar ridge behind the incisors, the velum's length, the port's gap).

The step is skipped when the file was built from the same meshes and rig by the same builder.
The API serves the file through the asset store (GET /anatomy/landmarks).
"""

import hashlib
import json
from pathlib import Path

import numpy as np

from glasshead.constants import (
    LANDMARKS_FILE,
    LANDMARKS_FORMAT_VERSION,
    TONGUE_RIG_FILE,
)
from glasshead.geometry.landmarks import validate_landmarks
from glasshead.pipeline import landmark_rules as rules
from glasshead.pipeline.outputs import current_output, load_built_meshes

#: Bumped whenever a rule changes, so that landmarks built from the same meshes rebuild.
BUILDER_VERSION = 1

#: The meshes the rules read, by manifest name.
MESHES = ("maxilla", "mandible", "upper_lip", "lower_lip", "tongue_rest", "velum_rest",
          "velum_raised", "pharynx", "thyroid", "arytenoid_left", "arytenoid_right")

VELUM_MESHES = ["velum_raised", "velum_rest", "velum_lowered", "palate"]
LARYNX_MESHES = ["thyroid", "cricoid", "arytenoid_left", "arytenoid_right"]
TONGUE_MESHES = ["tongue_rest"]

#: The parts, in the order the layer lists them: (name, label, the point it is shown at, the
#: scene meshes it names when pointed at).
PARTS: tuple[tuple[str, str, str, list[str]], ...] = (
    ("lips", "lips", "lips", ["upper_lip", "lower_lip"]),
    ("teeth", "teeth", "teeth", ["maxilla", "mandible"]),
    ("alveolar_ridge", "alveolar ridge", "alveolar_ridge", ["maxilla"]),
    ("hard_palate", "hard palate", "hard_palate", ["maxilla"]),
    ("velum", "velum (soft palate)", "velum", VELUM_MESHES),
    ("uvula", "uvula", "uvula", VELUM_MESHES),
    ("tongue_tip", "tongue tip", "tongue_tip", TONGUE_MESHES),
    ("tongue_blade", "tongue blade", "tongue_blade", TONGUE_MESHES),
    ("tongue_front", "tongue front", "tongue_front", TONGUE_MESHES),
    ("tongue_back", "tongue back", "tongue_back", TONGUE_MESHES),
    ("tongue_root", "tongue root", "tongue_root", TONGUE_MESHES),
    ("pharynx", "pharynx", "pharynx", ["pharynx"]),
    ("larynx", "larynx", "larynx", LARYNX_MESHES),
    ("nasal_port", "nasal port", "nasal_port", []),
)

#: The places of articulation along the roof of the mouth, front to back: (name, the point
#: that defines it).
PLACES = (
    ("bilabial", "bilabial"),
    ("labiodental", "labiodental"),
    ("dental", "dental_face"),
    ("alveolar", "alveolar_ridge"),
    ("postalveolar", "postalveolar"),
    ("palatal", "hard_palate"),
    ("velar", "velar"),
    ("uvular", "uvula"),
    ("glottal", "glottis"),
)

#: Points found by the rules that are neither a part's nor a place's own, kept as references.
REFERENCES = ("upper_incisor_edge", "lower_incisor_edge", "upper_lip", "lower_lip",
              "hard_soft_junction", "glottis")

NOTES = {
    "epiglottis": "the data hold no epiglottis mesh; the larynx is labelled at the thyroid "
                  "cartilage's laryngeal prominence, the glottis between the arytenoids' vocal "
                  "processes and the thyroid",
    "nasal_port": "no nasal cavity mesh exists; the port is the gap between the velum's nasal "
                  "surface and the posterior pharyngeal wall",
}


def load_meshes(assets_dir, names=MESHES):
    """{name: (vertices (n, 3) float64, faces (m, 3) int64)} of built meshes, and
    {name: sha256} from the manifest."""
    built = load_built_meshes(assets_dir, names)
    return ({name: (vertices, faces) for name, (vertices, faces, _) in built.items()},
            {name: sha256 for name, (_, _, sha256) in built.items()})


def find_points(meshes, rig):
    """Every point the rules find: ({name: found dict}, measures)."""
    controls = {c["name"]: c["position"] for c in rig["sagittal"]["control_points"]}
    palate, measures, at = rules.palate_landmarks(meshes["maxilla"])
    mouth, mouth_measures = rules.mouth_landmarks(meshes["upper_lip"], meshes["lower_lip"],
                                                  meshes["mandible"], at["edge"])
    tongue = rules.tongue_landmarks(meshes["tongue_rest"], controls)
    dorsum = np.array(tongue["tongue_back"]["position"])
    velum, velum_measures, wall = rules.velum_landmarks(
        meshes["velum_rest"], meshes["velum_raised"], meshes["pharynx"], at["junction"], dorsum)
    throat, throat_measures = rules.throat_landmarks(
        wall, np.array(tongue["tongue_root"]["position"]), meshes["thyroid"][0],
        (meshes["arytenoid_left"][0], meshes["arytenoid_right"][0]))
    points = {**palate, **mouth, **tongue, **velum, **throat}
    upper, lower = (np.array(points[n]["position"]) for n in ("upper_incisor_edge",
                                                               "lower_incisor_edge"))
    points["teeth"] = rules.found(0.5 * (upper + lower), "maxilla, mandible",
                                  "the central incisors", "midpoint of the upper and lower "
                                  "incisal edges")
    measures.update(mouth_measures, **velum_measures, **throat_measures)
    measures["incisal_gap_mm"] = round(float(upper[1] - lower[1]), 2)
    return points, measures


def landmarks_document(meshes, rig, source=None):
    """The landmarks file's document (see the module docstring)."""
    points, measures = find_points(meshes, rig)
    entries = []
    for name, label, at, hover in PARTS:
        entries.append({"name": name, "label": label, "kind": "part", **points[at],
                        "meshes": hover})
    for order, (name, at) in enumerate(PLACES):
        point = points[at]
        entries.append({"name": name, "label": name, "kind": "place", "order": order, "at": at,
                        **point, "rule": f"at the {at.replace('_', ' ')}: {point['rule']}",
                        "meshes": []})
    for name in REFERENCES:
        entries.append({"name": name, "label": name.replace("_", " "), "kind": "reference",
                        **points[name], "meshes": []})
    return {"format_version": LANDMARKS_FORMAT_VERSION, "builder": BUILDER_VERSION,
            "frame": {"units": "mm", "axes": {"x": "anterior", "y": "superior", "z": "left"}},
            "source": source or {}, "landmarks": entries, "measures": measures, "notes": NOTES}


def _digest(hashes, rig_bytes):
    digest = hashlib.sha256()
    for name in sorted(hashes):
        digest.update(f"{name}:{hashes[name]}\0".encode())
    digest.update(rig_bytes)
    return digest.hexdigest()


def build_step(assets_dir):
    """The `glasshead build` step; returns its report (positions of every landmark, measures)."""
    assets = Path(assets_dir)
    rig_bytes = (assets / TONGUE_RIG_FILE).read_bytes()
    meshes, hashes = load_meshes(assets)
    digest = _digest(hashes, rig_bytes)
    out = assets / LANDMARKS_FILE
    existing = current_output(out, digest, BUILDER_VERSION, LANDMARKS_FORMAT_VERSION)
    if existing is not None:
        return report(out, existing, skipped=True)
    document = landmarks_document(meshes, json.loads(rig_bytes),
                                  source={"sha256": digest, "meshes": sorted(hashes),
                                          "rig": TONGUE_RIG_FILE})
    validate_landmarks(document)
    temporary = out.with_name(out.name + ".tmp")
    temporary.write_text(json.dumps(document, indent=1) + "\n")
    temporary.replace(out)
    return report(out, document, skipped=False)


def report(path, document, skipped):
    """The build report's section: every landmark's position, kind and rule, and the measures."""
    return {"step": "landmarks", "file": str(path), "skipped": skipped,
            "positions_mm": {e["name"]: e["position"] for e in document["landmarks"]},
            "rules": {e["name"]: f"{e['mesh']}: {e['rule']}" for e in document["landmarks"]},
            "measures": document["measures"], "notes": document["notes"]}
