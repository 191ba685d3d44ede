"""Shared test vectors for synthetic EPG contact, checked by pytest and tests/js/epgContacts.test.js.

Run ``python -m glasshead.epg.contact_vectors`` to rewrite:

- ``tests/vectors/epg-contacts-tables.bin``: collision tables of the Badin maxilla reduced to
  about 600 triangles (3 degree liner, 16 voxels: small, and the kernels do not care);
- ``tests/vectors/epg-contacts.json``: the electrode layout placed on that same reduced maxilla,
  the tongue rig, and two kinds of cases:
  - ``kernel_cases``: a tongue (or a few triangles) given as vertices, float32 values, with the
    contacts both twins must return bit for bit;
  - ``cases``: seeded articulation parameter sets (the jaw included) that each side takes through
    its own tongue evaluator, collision correction and contact test. The two sides' tongues
    differ by float32 rounding (about 1e-6 mm), so a pose is kept only when its contacts stay
    the same with the probe's reach moved by ``MARGIN_MM`` either way: no decision of it lies
    near a boundary.
"""

import base64
import hashlib
import json
import sys
import tempfile
from pathlib import Path

import numpy as np

from glasshead.constants import (
    COLLISION_TOL,
    EPG_CONTACT_BEHIND_MM,
    EPG_CONTACT_TOLERANCE_MM,
    EPG_LAYOUT_FORMAT_VERSION,
)
from glasshead.epg.contacts import contact_grid, electrode_contacts, probes_from_layout
from glasshead.epg.layout import GRIDS, layout_document
from glasshead.epg.sequence import rows_to_strings
from glasshead.epg.synthetic import corrected_tongue
from glasshead.geometry.collision_format import decode_collision_tables
from glasshead.settings import REPO_ROOT

VECTORS_DIR = REPO_ROOT / "tests" / "vectors"
CASES_NAME = "epg-contacts.json"
TABLES_NAME = "epg-contacts-tables.bin"
VECTORS_FORMAT_VERSION = 1
SEED = 20250611
#: Reduction of the maxilla, liner step and voxels of the vector tables.
REDUCED_TRIANGLES = 600
STEP_DEG = 3.0
VOXELS = 16
#: Seeded poses: drawn over every range, and with the tongue raised toward the palate.
UNIFORM_POSES = 40
RAISED_POSES = 100
#: mm. A kept pose's contacts do not change when the probe's reach moves this much.
MARGIN_MM = 1e-4


def reduced_maxilla():
    """(vertices (n, 3) float64, faces (m, 3) int64): the Badin maxilla, project frame, reduced."""
    import fast_simplification

    from glasshead.geometry.collision_vectors import badin_mesh

    v, f = badin_mesh("maxilla")
    rv, rf = fast_simplification.simplify(v.astype(np.float32), f.astype(np.int32),
                                          target_count=REDUCED_TRIANGLES)
    return rv.astype(np.float64), rf.astype(np.int64)


def build_tables(vertices, faces) -> bytes:
    from glasshead.pipeline.collision_tables import TABLES_FILE, build_collision_tables

    with tempfile.TemporaryDirectory() as tmp:
        build_collision_tables(vertices, faces, tmp, step_deg=STEP_DEG, voxels=VOXELS)
        return (Path(tmp) / TABLES_FILE).read_bytes()


def current_rig_definition():
    from glasshead.asset_store import AssetStore
    from glasshead.settings import get_settings

    return AssetStore(get_settings().assets_dir).get("tongue_rig").definition


def encode_f32(values) -> str:
    """Little-endian float32 bytes of ``values``, base64."""
    return base64.b64encode(np.asarray(values, dtype="<f4").tobytes()).decode("ascii")


def decode_f32(text) -> np.ndarray:
    return np.frombuffer(base64.b64decode(text), dtype="<f4").astype(np.float64)


def frame_of(vertices, triangles, probes_by_grid):
    """{grid: {"rows", "contacts"}} for a tongue."""
    out = {}
    for name, probes in probes_by_grid.items():
        contacts = electrode_contacts(vertices, triangles, probes)
        out[name] = {"rows": rows_to_strings(contact_grid(contacts, probes)),
                     "contacted": int(contacts.sum())}
    return out


def _robust(vertices, triangles, probes_by_grid, expected):
    for name, probes in probes_by_grid.items():
        for step in (-MARGIN_MM, MARGIN_MM):
            moved = _with_reach(probes, probes.tolerance + step,
                                            probes.behind + step)
            contacts = electrode_contacts(vertices, triangles, moved)
            if rows_to_strings(contact_grid(contacts, moved)) != expected[name]["rows"]:
                return False
    return True


def _with_reach(probes, tolerance, behind):
    from dataclasses import replace

    return replace(probes, tolerance=tolerance, behind=behind)


def _draw_pose(rig, rng, raised):
    values = rng.uniform(rig.minimum, rig.maximum)
    if raised:
        for k, name in enumerate(rig.parameter_names):
            lo, hi = rig.minimum[k], rig.maximum[k]
            if name == rig.definition["jaw"]["parameter"]:
                values[k] = rng.uniform(lo, lo + 0.2 * (hi - lo))
            elif "height" in name or "advancement" in name:
                values[k] = rng.uniform(rig.neutral[k], hi)
    # Four decimals keep the file small; both sides read the same rounded numbers.
    return np.clip(np.round(values, 4), rig.minimum, rig.maximum)


def _hand_cases(layout, probes):
    """Small meshes placed about one electrode's probe, each with a known answer."""
    grid = layout["grids"]["reading62"]
    electrode = next(e for e in grid["electrodes"] if e["id"] == "R4C4")
    e = np.array(electrode["position"])
    n = np.array(electrode["normal"])
    side = np.cross(n, [0.0, 0.0, 1.0])
    side /= np.linalg.norm(side)
    other = np.cross(n, side)

    def triangle(depth, offset=0.0, size=0.6):
        centre = e + depth * n + offset * side
        return [centre + size * (np.cos(a) * side + np.sin(a) * other)
                for a in (0.3, 0.3 + 2 * np.pi / 3, 0.3 + 4 * np.pi / 3)]

    cases = []

    def add(description, vertices, triangles):
        v = np.asarray(vertices, dtype=np.float32).astype(np.float64)
        t = np.asarray(triangles, dtype=np.int64)
        contacts = electrode_contacts(v, t, probes["reading62"])
        cases.append({"description": description,
                      "input": {"vertices": encode_f32(v.ravel()), "triangles": t.ravel().tolist(),
                                "grid": "reading62"},
                      "expected": {"rows": rows_to_strings(contact_grid(contacts,
                                                                        probes["reading62"])),
                                   "contacted": [i for i, c in zip(probes["reading62"].ids,
                                                                   contacts) if c]}})

    one = [[0, 1, 2]]
    add("a triangle 0.5 mm in front of R4C4 contacts it and nothing else", triangle(0.5), one)
    add("a triangle 1.2 mm in front of R4C4 (beyond the tolerance) contacts nothing",
        triangle(1.2), one)
    add("a triangle 0.3 mm behind R4C4 (into the palate) contacts it", triangle(-0.3), one)
    add("a triangle 0.7 mm behind R4C4 (beyond the probe) contacts nothing", triangle(-0.7), one)
    add("a triangle 1 mm beside the probe of R4C4 contacts nothing", triangle(0.5, offset=1.0),
        one)
    # Two triangles whose shared edge passes exactly through the probe's axis.
    a, b = e + 0.5 * n + 0.8 * other, e + 0.5 * n - 0.8 * other
    add("a probe through the edge shared by two triangles contacts R4C4",
        [a, b, e + 0.5 * n + 0.8 * side, e + 0.5 * n - 0.8 * side], [[0, 1, 2], [1, 0, 3]])
    return cases


def build_documents():
    """(tables bytes, the JSON document)."""
    from glasshead.geometry.tongue_surface import TongueRig

    maxilla_v, maxilla_f = reduced_maxilla()
    tables_bytes = build_tables(maxilla_v, maxilla_f)
    tables = decode_collision_tables(tables_bytes)
    layout = layout_document(maxilla_v, maxilla_f,
                             source={"mesh": f"Badin maxilla reduced to {REDUCED_TRIANGLES} "
                                             "triangles"})
    layout["midline"]["points"] = layout["midline"]["points"][::4]
    definition = current_rig_definition()
    rig = TongueRig(definition)
    probes = {name: probes_from_layout(layout["grids"][name]) for name in GRIDS}

    rng = np.random.default_rng(SEED)
    cases, kernel_cases, drawn, dropped = [], [], 0, 0
    wanted = [("uniform", UNIFORM_POSES), ("raised", RAISED_POSES)]
    for kind, count in wanted:
        kept = 0
        while kept < count:
            values = _draw_pose(rig, rng, raised=kind == "raised")
            drawn += 1
            vertices, counts = corrected_tongue(rig, values, tables)
            expected = frame_of(vertices, rig.triangles, probes)
            if not _robust(vertices, rig.triangles, probes, expected):
                dropped += 1
                continue
            kept += 1
            params = dict(zip(rig.parameter_names, values.tolist()))
            cases.append({"description": f"{kind} pose {kept} (seed {SEED}, draw {drawn})",
                          "input": {"params": params},
                          "expected": {**expected, "collision": counts}})
    # Two real corrected tongues as exact kernel inputs: the fullest contact and the neutral.
    fullest = max(cases, key=lambda c: c["expected"]["reading62"]["contacted"])
    for label, params in (("the neutral tongue", {}),
                          (f"the tongue of {fullest['description']}", fullest["input"]["params"])):
        vertices, _ = corrected_tongue(rig, rig.values_from(params), tables)
        expected = frame_of(vertices, rig.triangles, probes)
        kernel_cases.append({"description": f"{label}, corrected, as float32 vertices",
                             "input": {"vertices": encode_f32(vertices.ravel()),
                                       "triangles": "rig", "grid": "both"},
                             "expected": expected})
    kernel_cases += _hand_cases(layout, probes)

    document = {
        "description": "Synthetic EPG contacts: seeded tongue poses (jaw included) taken through "
                       "the tongue rig, collision correction and the electrode probes; and "
                       "tongues given as float32 vertices. Python writes; JS must agree exactly.",
        "generator": "python -m glasshead.epg.contact_vectors",
        "format_version": VECTORS_FORMAT_VERSION,
        "seed": SEED,
        "constants": {"tolerance_mm": EPG_CONTACT_TOLERANCE_MM,
                      "behind_mm": EPG_CONTACT_BEHIND_MM,
                      "barycentric": COLLISION_TOL.barycentric,
                      "layout_format_version": EPG_LAYOUT_FORMAT_VERSION},
        "margin_mm": MARGIN_MM,
        "draws": {"drawn": drawn, "dropped_near_a_boundary": dropped},
        "tables": {"file": TABLES_NAME, "sha256": hashlib.sha256(tables_bytes).hexdigest(),
                   "maxilla_triangles": len(maxilla_f)},
        "maxilla": {"description": "the reduced maxilla the tables and the layout were built on",
                    "vertices": maxilla_v.tolist(), "faces": maxilla_f.tolist()},
        "rig": definition,
        "layout": layout,
        "kernel_cases": kernel_cases,
        "cases": cases,
    }
    return tables_bytes, document


def main() -> int:
    tables_bytes, document = build_documents()
    (VECTORS_DIR / TABLES_NAME).write_bytes(tables_bytes)
    (VECTORS_DIR / CASES_NAME).write_text(json.dumps(document, separators=(",", ":")) + "\n")
    contacted = sum(c["expected"]["reading62"]["contacted"] for c in document["cases"])
    print(f"wrote {VECTORS_DIR / TABLES_NAME} and {VECTORS_DIR / CASES_NAME}: "
          f"{len(document['cases'])} poses ({document['draws']['dropped_near_a_boundary']} "
          f"dropped near a boundary), {contacted} Reading contacts in all")
    return 0


if __name__ == "__main__":
    sys.exit(main())
