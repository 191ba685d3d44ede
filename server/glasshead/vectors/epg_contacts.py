"""epg-contacts-tables.bin and epg-contacts.json: the synthetic EPG contact's shared vectors.

- ``epg-contacts-tables.bin``: collision tables of the Badin maxilla reduced to about 600
  triangles (3 degree liner, 16 voxels: small, and the kernels do not care);
- ``epg-contacts.json``: fixtures hold the reduced maxilla, its tables (file and hash), the
  electrode layout placed on it and the tongue rig. Cases are of two kinds:
  - seeded articulation parameter sets (``input.params``, the jaw included) that each side takes
    through its own tongue evaluator, collision correction and contact test;
  - tongues, or a few triangles, given as float32 vertices (``input.vertices``, base64), with the
    contacts both twins must return bit for bit.

Contacts and collision counts are integers decided by floats, and the two sides' tongues differ
by float32 rounding (about 1e-5 mm; two CPUs differ far less). So a pose is kept only when no
decision of it lies near a boundary: its contacts stay the same with every probe's reach moved by
``MARGIN_MM`` either way and with every probe moved ``MARGIN_MM`` sideways, and every vertex of
its tongue is away from the collision tables' boundaries (``collision.robust_mask``). The
kernel inputs pass the same contact check.
"""

import hashlib
import tempfile
from dataclasses import replace
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
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.vectors import sources
from glasshead.vectors.collision import robust_mask
from glasshead.vectors.common import case, document, encode_f32, tolerance
from glasshead.vectors.epg_hand_cases import hand_cases

CASES_NAME = "epg-contacts.json"
TABLES_NAME = "epg-contacts-tables.bin"
FORMAT_VERSION = 2
SEED = 20250611
#: Reduction of the maxilla, liner step and voxels of the vector tables.
REDUCED_TRIANGLES = 600
STEP_DEG = 3.0
VOXELS = 16
#: Seeded poses: drawn over every range, and with the tongue raised toward the palate.
UNIFORM_POSES = 40
RAISED_POSES = 100
#: mm. A kept pose's contacts do not change when a probe's reach, or the probe itself sideways,
#: moves this much.
MARGIN_MM = 1e-4

TOLERANCES = {
    "electrode_mm": tolerance(1e-6, "mm", "the layout placed again on the maxilla in float64: "
                                          "other CPUs differ in the last digits (about 1e-13 mm)"),
    "normal": tolerance(1e-9, "1", "unit electrode normals placed again in float64: other CPUs "
                                   "differ in the 16th digit"),
}


def reduced_maxilla():
    """(vertices (n, 3) float64, faces (m, 3) int64): the Badin maxilla, project frame, reduced."""
    import fast_simplification

    v, f = sources.badin_mesh("maxilla")
    rv, rf = fast_simplification.simplify(v.astype(np.float32), f.astype(np.int32),
                                          target_count=REDUCED_TRIANGLES)
    return rv.astype(np.float64), rf.astype(np.int64)


def build_tables(vertices, faces) -> bytes:
    from glasshead.pipeline.collision_tables import TABLES_FILE, build_collision_tables

    with tempfile.TemporaryDirectory() as tmp:
        build_collision_tables(vertices, faces, tmp, step_deg=STEP_DEG, voxels=VOXELS)
        return (Path(tmp) / TABLES_FILE).read_bytes()


def frame_of(vertices, triangles, probes_by_grid):
    """{grid: {"rows", "contacted"}} for a tongue."""
    out = {}
    for name, probes in probes_by_grid.items():
        contacts = electrode_contacts(vertices, triangles, probes)
        out[name] = {"rows": rows_to_strings(contact_grid(contacts, probes)),
                     "contacted": int(contacts.sum())}
    return out


def _sideways(directions):
    """Two unit vectors perpendicular to each direction (k, 3): (k, 3), (k, 3)."""
    helper = np.where(np.abs(directions[:, 2:3]) < 0.9, [[0.0, 0.0, 1.0]], [[1.0, 0.0, 0.0]])
    first = np.cross(directions, helper)
    first /= np.linalg.norm(first, axis=1, keepdims=True)
    return first, np.cross(directions, first)


def nudged_probes(probes, margin=MARGIN_MM):
    """The probes with their reach moved by ``margin`` either way, and moved ``margin`` sideways
    in four directions: every nearby probe whose answer a float32 tongue could give."""
    first, second = _sideways(probes.directions)
    out = [replace(probes, tolerance=probes.tolerance + step, behind=probes.behind + step)
           for step in (-margin, margin)]
    out += [replace(probes, origins=probes.origins + sign * margin * side)
            for side in (first, second) for sign in (-1.0, 1.0)]
    return out


def contacts_hold(vertices, triangles, probes_by_grid, margin=MARGIN_MM):
    """True when every nudged probe of every grid gives the same contacts as the probe itself."""
    for probes in probes_by_grid.values():
        rows = rows_to_strings(contact_grid(electrode_contacts(vertices, triangles, probes),
                                            probes))
        for nudged in nudged_probes(probes, margin):
            contacts = electrode_contacts(vertices, triangles, nudged)
            if rows_to_strings(contact_grid(contacts, nudged)) != rows:
                return False
    return True


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


def pose_cases(rig, tables, probes):
    """(cases, draws): the kept seeded poses and how many were drawn and dropped."""
    rng = np.random.default_rng(SEED)
    cases, drawn, dropped = [], 0, 0
    for kind, count in (("uniform", UNIFORM_POSES), ("raised", RAISED_POSES)):
        kept = 0
        while kept < count:
            values = _draw_pose(rig, rng, raised=kind == "raised")
            drawn += 1
            vertices, counts = corrected_tongue(rig, values, tables)
            if not (robust_mask(rig.vertices(values), tables).all()
                    and contacts_hold(vertices, rig.triangles, probes)):
                dropped += 1
                continue
            kept += 1
            params = dict(zip(rig.parameter_names, values.tolist(), strict=True))
            cases.append(case(f"{kind} pose {kept} (seed {SEED}, draw {drawn})",
                              {"params": params},
                              {**frame_of(vertices, rig.triangles, probes), "collision": counts}))
    return cases, {"drawn": drawn, "dropped_near_a_boundary": dropped}


def kernel_tongue_cases(rig, tables, probes, poses):
    """Two real corrected tongues as exact float32 inputs: the neutral and the fullest contact."""
    fullest = max(poses, key=lambda c: c["expected"]["reading62"]["contacted"])
    cases = []
    for label, params in (("the neutral tongue", {}),
                          (f"the tongue of {fullest['description']}", fullest["input"]["params"])):
        vertices, _ = corrected_tongue(rig, rig.values_from(params), tables)
        vertices = vertices.astype(np.float32).astype(np.float64)
        if not contacts_hold(vertices, rig.triangles, probes):
            raise RuntimeError(f"{CASES_NAME}: {label} as float32 is near a contact boundary")
        cases.append(case(f"{label}, corrected, as float32 vertices",
                          {"vertices": encode_f32(vertices.ravel()), "triangles": "rig",
                           "grid": "both"},
                          frame_of(vertices, rig.triangles, probes)))
    return cases


def build_files():
    """{file name: bytes or document} of both files."""
    maxilla_v, maxilla_f = reduced_maxilla()
    tables_bytes = build_tables(maxilla_v, maxilla_f)
    tables = decode_collision_tables(tables_bytes)
    layout = layout_document(maxilla_v, maxilla_f,
                             source={"mesh": f"Badin maxilla reduced to {REDUCED_TRIANGLES} "
                                             "triangles"})
    layout["midline"]["points"] = layout["midline"]["points"][::4]
    definition = sources.tongue_rig_definition()
    rig = TongueRig(definition)
    probes = {name: probes_from_layout(layout["grids"][name]) for name in GRIDS}

    poses, draws = pose_cases(rig, tables, probes)
    kernel = kernel_tongue_cases(rig, tables, probes, poses)
    kernel += hand_cases(layout, probes, contacts_hold)
    doc = document(
        CASES_NAME,
        "Synthetic EPG contacts: seeded tongue poses (jaw included) taken through the tongue "
        "rig, collision correction and the electrode probes of the layout in fixtures; and "
        "tongues given as float32 vertices. Python writes; JS must agree exactly.",
        FORMAT_VERSION, poses + kernel,
        constants={"seed": SEED, "margin_mm": MARGIN_MM,
                   "tolerance_mm": EPG_CONTACT_TOLERANCE_MM, "behind_mm": EPG_CONTACT_BEHIND_MM,
                   "barycentric": COLLISION_TOL.barycentric,
                   "layout_format_version": EPG_LAYOUT_FORMAT_VERSION,
                   "uniform_poses": UNIFORM_POSES, "raised_poses": RAISED_POSES,
                   "draws": draws},
        tolerances=TOLERANCES,
        fixtures={
            "tables": {"file": TABLES_NAME, "sha256": hashlib.sha256(tables_bytes).hexdigest(),
                       "maxilla_triangles": len(maxilla_f)},
            "maxilla": {"description": "the reduced maxilla the tables and the layout were "
                                       "built on",
                        "vertices": maxilla_v.tolist(), "faces": maxilla_f.tolist()},
            "rig": definition,
            "layout": layout,
        })
    contacted = sum(c["expected"]["reading62"]["contacted"] for c in poses)
    print(f"    {CASES_NAME}: {len(poses)} poses ({draws['dropped_near_a_boundary']} of "
          f"{draws['drawn']} dropped near a boundary), {contacted} Reading contacts in all")
    return {TABLES_NAME: tables_bytes, CASES_NAME: doc}


def files():
    return build_files()
