"""Build step: the face rig definition ``assets/build/face-rig.json``.

It holds everything the skin and lip deformation (``glasshead.geometry.face_rig`` and its JS twin
``web/src/core/faceRig.js``) needs, as data both sides read:

- the lip parameters (name, unit, range, neutral, group; the tongue rig's table format);
- per-vertex jaw weights of ``face_skin``, ``upper_lip`` and ``lower_lip``, in the vertex order of
  the built GLBs (``pipeline.face_rig_weights``), with a few probe positions that let a reader
  check it has the same meshes;
- the lip field's constants (mouth centre and width, bumps, directions, closure share);
- the labial faces of the upper and lower incisors that the lips may not pass
  (``pipeline.face_rig_teeth``);
- the lips' mid-sagittal crossing edges, for measuring the lip gap.

The jaw pose itself is not here: it is the tongue rig's (``geometry.jaw``), one for the head.
"""

import hashlib
import inspect
import json
from pathlib import Path

import numpy as np

from glasshead.constants import FACE_RIG_FILE, FACE_RIG_FORMAT_VERSION
from glasshead.geometry import face_rig as evaluator
from glasshead.geometry import face_teeth, skin_weights
from glasshead.geometry.face_rig import LIP_MESHES, LIP_PARAMETER_NAMES, MESH_NAMES
from glasshead.pipeline import face_rig_sources, face_rig_teeth, face_rig_weights
from glasshead.pipeline.face_rig_sources import FaceSources, load_face_sources
from glasshead.pipeline.outputs import read_json

OUTPUT_NAME = FACE_RIG_FILE
#: Bump when the build changes in a way that must rebuild the output.
BUILD_REVISION = 1

#: The lip parameters, in the tongue rig's table format.
LIP_PARAMETERS = [
    {"name": "lip_opening", "unit": "ratio", "min": 0.0, "max": 1.0, "neutral": 1.0,
     "group": "lips", "description": "share of the lip gap left by the jaw that is kept; "
                                     "0 closes the lips (p, b, m)"},
    {"name": "lip_rounding", "unit": "mm", "min": -4.0, "max": 10.0, "neutral": 0.0,
     "group": "lips", "description": "mouth corners toward the midline (negative: spread)"},
    {"name": "lip_protrusion", "unit": "mm", "min": 0.0, "max": 8.0, "neutral": 0.0,
     "group": "lips", "description": "lips forward (at rest they lie on the teeth)"},
    {"name": "upper_lip_raise", "unit": "mm", "min": -2.0, "max": 6.0, "neutral": 0.0,
     "group": "lips", "description": "upper lip up"},
    {"name": "lower_lip_tuck", "unit": "mm", "min": 0.0, "max": 5.0, "neutral": 0.0,
     "group": "lips", "description": "lower lip up and back under the upper incisors (f, v)"},
]
assert tuple(p["name"] for p in LIP_PARAMETERS) == LIP_PARAMETER_NAMES

#: Shape of the lip field, relative to the mouth centre M and half-width W (see geometry.face_rig).
#: The mouth bump's height (y radius) ends it below the nostrils, whose covers do not move; its
#: depth reaches past the back of the lips, so that they move nearly as one.
MOUTH_BUMP_RADII_MM = (36.0, 24.0)  # x, y; z is MOUTH_BUMP_Z_WIDTHS * W
MOUTH_BUMP_Z_WIDTHS = 2.2
MOUTH_BUMP_PLATEAU = 0.4
#: The raise spreads over the whole upper lip, up to the nostrils: the lip shortens evenly.
RAISE_BUMP = {"offset": (0.0, 0.0), "radii": (25.0, 25.0), "z_widths": 1.6, "plateau": 0.2}
#: The tuck acts on the top of the lower lip (over the lower incisors' edge), not on the part
#: lying on their labial face, which the teeth would only push back out.
TUCK_BUMP = {"offset": (0.0, -1.0), "radii": (18.0, 10.0), "z_widths": 1.2, "plateau": 0.3}
ROUNDING_FORWARD = 0.35
#: Forward travel of the mouth corners per mm they move medially: the slope of the dental arch
#: at the canines is about 0.9, so corners moving in along it stay clear of the teeth.
ROUNDING_ALONG_ARCH = 0.9
RAISE_DIRECTION = (0.2, 1.0, 0.0)
TUCK_DIRECTION = (-0.5, 0.87, 0.0)
#: Share of a closure taken by the upper lip; the lower lip, carried by the jaw, does the rest.
CLOSURE_UPPER_SHARE = 0.35
CLOSURE_ITERATIONS = 12
#: How far closed lips (lip_opening 0: /p b m/) press past touching, mm. The gap is measured
#: vertically, between the upper lip's lowest midline point and the lower lip's highest, which
#: lie about 3.6 mm apart front to back: level with each other, the lips' mid-sagittal sections
#: are still 0.78 mm apart (/m/). Pressed 1 mm, as lips are in a bilabial closure, they meet
#: (0.03 mm at /m/'s jaw, 0.01 at 5 and 10 degrees); pressed further, they cross.
LIP_PRESS_MM = 1.0
#: Rest vertices per mesh stored as probes (evenly spread through the vertex list).
PROBES = 8


def midline_edges(vertices, faces):
    """Edges crossing the mid-sagittal plane: (k, 2) int64 with z[i] <= 0 < z[j]."""
    pairs = skin_weights.triangle_edges(faces)
    z = np.asarray(vertices)[:, 2]
    za, zb = z[pairs[:, 0]], z[pairs[:, 1]]
    forward = (za <= 0) & (zb > 0)
    backward = (zb <= 0) & (za > 0)
    return np.concatenate([pairs[forward], pairs[backward][:, ::-1]]).astype(np.int64)


def mouth_centre(src: FaceSources):
    """Mid-sagittal point halfway between the lips' facing extremes at rest; (3,) float64."""
    upper = evaluator.midline_points(src.upper_lip[0], midline_edges(*src.upper_lip))
    lower = evaluator.midline_points(src.lower_lip[0], midline_edges(*src.lower_lip))
    u, low = upper[np.argmin(upper[:, 1])], lower[np.argmax(lower[:, 1])]
    return np.array([(u[0] + low[0]) / 2.0, (u[1] + low[1]) / 2.0, 0.0])


def mouth_half_width(src: FaceSources):
    """Half the mouth's width: the lips' largest |z|, mm."""
    return float(max(np.abs(src.upper_lip[0][:, 2]).max(), np.abs(src.lower_lip[0][:, 2]).max()))


def reference_vertex(vertices, upper):
    """The vertex nearest the midline at a lip's facing extreme (lowest for the upper lip)."""
    near = np.argsort(np.abs(vertices[:, 2]), kind="stable")[:8]
    y = vertices[near, 1]
    return int(near[np.argmin(y) if upper else np.argmax(y)])


def lip_field(centre, half_width):
    """The ``field`` section of the rig: mouth centre, bumps, directions, closure constants."""
    def bump(offset, radii, z_widths, plateau):
        return {"centre": [float(centre[0] + offset[0]), float(centre[1] + offset[1]), 0.0],
                "radii": [float(radii[0]), float(radii[1]), float(z_widths * half_width)],
                "plateau": float(plateau)}

    def unit(v):
        v = np.asarray(v, dtype=float)
        return (v / np.linalg.norm(v)).tolist()

    return {
        "mouth_centre": [float(v) for v in centre],
        "mouth_half_width": float(half_width),
        "bumps": {"mouth": bump((0.0, 0.0), MOUTH_BUMP_RADII_MM, MOUTH_BUMP_Z_WIDTHS,
                                MOUTH_BUMP_PLATEAU),
                  "raise": bump(**RAISE_BUMP), "tuck": bump(**TUCK_BUMP)},
        "rounding_forward": ROUNDING_FORWARD,
        "rounding_along_arch": ROUNDING_ALONG_ARCH,
        "raise_direction": unit(RAISE_DIRECTION),
        "tuck_direction": unit(TUCK_DIRECTION),
        "closure_upper_share": CLOSURE_UPPER_SHARE,
        "closure_iterations": CLOSURE_ITERATIONS,
        "lip_press_mm": LIP_PRESS_MM,
    }


def build_face_rig(data_dir, assets_dir=None):
    """The face rig definition (a JSON-ready dict), from the build's meshes in ``assets_dir``
    when it has a manifest, else from the sources (``pipeline.face_rig_sources``)."""
    src = load_face_sources(data_dir, assets_dir)
    centre, half_width = mouth_centre(src), mouth_half_width(src)
    node_weights, weight_stats = face_rig_weights.node_jaw_weights(src, centre, half_width)
    meshes = {name: getattr(src, name) for name in MESH_NAMES}
    weights, shared = face_rig_weights.mesh_jaw_weights(meshes, src.nodes, node_weights,
                                                        half_width, src.skin_nodes)
    shell_vertices, shell_faces = src.head_shell
    weights["head_shell"] = face_rig_weights.shell_jaw_weights(
        shell_vertices, shell_faces, src.face_skin[0], weights["face_skin"])
    weight_stats["lip_corner_points_shared"] = shared
    teeth, teeth_stats = face_rig_teeth.incisor_surfaces(
        src.maxilla, src.mandible, [meshes[name][0] for name in MESH_NAMES if name != "head_shell"])

    entries = {}
    for name in MESH_NAMES:
        vertices, faces = meshes[name]
        probes = np.linspace(0, len(vertices) - 1, PROBES).round().astype(int)
        entry = {"vertex_count": len(vertices), "source": src.origin[name],
                 "jaw_weights": [round(float(v), 6) for v in weights[name]],
                 "probes": {"index": probes.tolist(),
                            "position": np.round(vertices[probes], 4).tolist()}}
        if name in LIP_MESHES:
            entry["midline_edges"] = midline_edges(vertices, faces).tolist()
            entry["reference_vertex"] = reference_vertex(vertices, upper=name == "upper_lip")
        entries[name] = entry

    return {
        "format_version": FACE_RIG_FORMAT_VERSION,
        "kind": "glasshead face rig",
        "frame": {"units": "mm", "axes": {"x": "anterior", "y": "superior", "z": "left"}},
        "jaw_parameter": "jaw_opening",
        "parameters": LIP_PARAMETERS,
        "field": lip_field(centre, half_width),
        "teeth": {"upper": {**teeth["upper"], "frame": "maxilla"},
                  "lower": {**teeth["lower"], "frame": "mandible at rest"}},
        "meshes": entries,
        "stats": {"weights": weight_stats, "teeth": teeth_stats},
        "source": {"licence": "ArtiSynth Models licence: Badin et al. face, lips and jaw"},
    }


#: Modules whose code shapes the output; their text is part of the cache key.
CODE = (evaluator, face_teeth, skin_weights, face_rig_sources, face_rig_teeth, face_rig_weights)
#: Data files read besides the built meshes.
DATA_FILES = ("face.node", "face.elem", "face_jaw_attachments.txt", "cranium.obj", "upperlip.obj",
              "lowerlip.obj", "jaw.obj", "maxilla.obj")


def input_key(data_dir, assets_dir):
    """sha256 over the data files, the code and the digests of the built meshes it reads (from
    the manifest's entries: the manifest's other fields change with every build)."""
    digest = hashlib.sha256(f"{BUILD_REVISION} {FACE_RIG_FORMAT_VERSION}".encode())
    base = Path(data_dir) / face_rig_sources.sources.BADIN
    files = [base / name for name in DATA_FILES] + [Path(__file__)]
    files += [Path(inspect.getfile(module)) for module in CODE]
    for path in files:
        digest.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    manifest = Path(assets_dir) / face_rig_sources.MANIFEST
    if manifest.is_file():
        entries = json.loads(manifest.read_text()).get("meshes", [])
        for entry in entries:
            if entry.get("name") in face_rig_sources.SCENE_MESHES and entry.get("scene", True):
                digest.update(f"{entry['name']} {entry.get('sha256')}".encode())
    return digest.hexdigest()


def build_step(ctx):
    """The `glasshead build` step (ctx: ``data_dir``, ``assets_dir``): write ``face-rig.json``
    unless it records the same inputs. Returns the step's report."""
    data_dir, assets_dir = Path(ctx.data_dir), Path(ctx.assets_dir)
    out = assets_dir / OUTPUT_NAME
    key = input_key(data_dir, assets_dir)
    existing = read_json(out)
    skipped = existing.get("inputs_sha256") == key
    rig = existing if skipped else {**build_face_rig(data_dir, assets_dir), "inputs_sha256": key}
    if not skipped:
        write_face_rig(rig, assets_dir)
    return {"step": "face-rig", "file": str(out), "skipped": skipped,
            "vertices": {name: m["vertex_count"] for name, m in rig["meshes"].items()},
            "stats": rig["stats"]}


def write_face_rig(rig, assets_dir):
    """Write ``face-rig.json`` into assets_dir atomically; returns its path."""
    path = Path(assets_dir) / OUTPUT_NAME
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_name(path.name + ".tmp")
    temporary.write_text(json.dumps(rig, separators=(",", ":")))
    temporary.replace(path)
    return path
