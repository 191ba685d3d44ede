"""Synthetic EPG contact: the probe test, the shared vectors, and real tongues on the real palate.

The physical tests run the whole chain on the Badin maxilla (collision tables built here from the
full mesh) with the tongue rig the build wrote: parameters -> tongue -> correction -> contacts.
"""

import hashlib

import numpy as np
import pytest

from collision_support import badin_mesh, tongue_rig
from glasshead.constants import (
    COLLISION_TOL,
    EPG_CONTACT_BEHIND_MM,
    EPG_CONTACT_TOLERANCE_MM,
    EPG_LAYOUT_FORMAT_VERSION,
)
from glasshead.epg.contacts import (
    contact_grid,
    electrode_contacts,
    probe_hits,
    probes_from_layout,
)
from glasshead.epg.indices import epg_indices
from glasshead.epg.layout import layout_document
from glasshead.epg.sequence import rows_to_strings
from glasshead.epg.synthetic import corrected_tongue, synthetic_frame
from glasshead.geometry.collision_format import decode_collision_tables
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.pipeline.collision_tables import TABLES_FILE, build_collision_tables
from vector_support import decode_f32, read_vectors, tol

VECTORS = read_vectors("epg-contacts.json")
FIXTURES = VECTORS["fixtures"]
TABLES_BYTES = read_vectors(FIXTURES["tables"]["file"])
POSES = [c for c in VECTORS["cases"] if "params" in c["input"]]
KERNEL_CASES = [c for c in VECTORS["cases"] if "vertices" in c["input"]]


@pytest.fixture(scope="module")
def vector_setup():
    rig = TongueRig(FIXTURES["rig"])
    tables = decode_collision_tables(TABLES_BYTES)
    probes = {name: probes_from_layout(FIXTURES["layout"]["grids"][name])
              for name in ("reading62", "dense96")}
    return rig, tables, probes


@pytest.fixture(scope="module")
def badin(tmp_path_factory):
    """The full Badin maxilla: its Reading probes and collision tables, and the built rig."""
    v, f = badin_mesh("maxilla")
    out = tmp_path_factory.mktemp("epg-tables")
    build_collision_tables(v, f, out)
    tables = decode_collision_tables((out / TABLES_FILE).read_bytes())
    layout = layout_document(v, f)
    return tongue_rig(), tables, probes_from_layout(layout["grids"]["reading62"])


def _frame(badin, **params):
    rig, tables, probes = badin
    return synthetic_frame(rig, rig.values_from(params), tables, probes)


# --- the probe test ------------------------------------------------------------------------------

def _triangle_across(origin, direction, depth, offset=(0.0, 0.0, 0.0), size=0.5):
    """A small triangle crossing the line origin + t direction at t = depth (shifted by offset)."""
    d = np.asarray(direction, dtype=float)
    side = np.cross(d, [0.0, 0.0, 1.0])
    side /= np.linalg.norm(side)
    up = np.cross(d, side)
    centre = np.asarray(origin) + depth * d + np.asarray(offset)
    return [centre + size * side, centre - size * (side + up) / 2, centre + size * up]


@pytest.mark.parametrize("depth, hit", [
    (0.0, True), (0.5, True), (EPG_CONTACT_TOLERANCE_MM - 1e-9, True),
    (EPG_CONTACT_TOLERANCE_MM + 1e-6, False), (-EPG_CONTACT_BEHIND_MM + 1e-9, True),
    (-EPG_CONTACT_BEHIND_MM - 1e-6, False), (3.0, False),
])
def test_a_probe_reaches_from_behind_the_electrode_to_the_tolerance_in_front(depth, hit):
    origin, direction = np.array([1.0, 20.0, 3.0]), np.array([0.0, -0.8, -0.6])
    a, b, c = (np.array([p]) for p in _triangle_across(origin, direction, depth))
    result = probe_hits(origin, direction, a, b, c, EPG_CONTACT_TOLERANCE_MM,
                        EPG_CONTACT_BEHIND_MM)
    assert result.tolist() == [hit]


def test_a_probe_through_the_edge_shared_by_two_triangles_hits_them_both():
    origin, direction = np.zeros(3), np.array([0.0, -1.0, 0.0])
    left, right = [-1.0, -0.5, -1.0], [1.0, -0.5, -1.0]
    a = np.array([[0.0, -0.5, 1.0], [0.0, -0.5, 1.0]])
    b = np.array([left, right])
    c = np.array([[0.0, -0.5, -1.0], [0.0, -0.5, -1.0]])
    # The probe passes exactly through the edge from (0, -0.5, 1) to (0, -0.5, -1).
    assert probe_hits(origin, direction, a, b, c, 1.0, 0.5).tolist() == [True, True]
    assert COLLISION_TOL.barycentric > 0


def test_contacts_are_laid_out_in_the_grid_with_the_r1_corners_empty(vector_setup):
    _, _, probes = vector_setup
    reading = probes["reading62"]
    grid = contact_grid(np.ones(reading.count, dtype=np.uint8), reading)
    assert grid.shape == (8, 8) and grid.sum() == 62
    assert grid[0, 0] == 0 and grid[0, 7] == 0
    with pytest.raises(ValueError, match="expected 62 contacts"):
        contact_grid(np.ones(61), reading)


def test_bad_probes_and_meshes_are_refused_with_a_message(vector_setup):
    _, _, probes = vector_setup
    grid = FIXTURES["layout"]["grids"]["reading62"]
    skewed = dict(grid, electrodes=[dict(e, normal=[0, 2, 0]) for e in grid["electrodes"]])
    with pytest.raises(ValueError, match="unit vectors"):
        probes_from_layout(skewed)
    with pytest.raises(ValueError, match="tolerance > 0"):
        probes_from_layout(grid, tolerance=0.0)
    with pytest.raises(ValueError, match="shape \\(n, 3\\)"):
        electrode_contacts(np.zeros((4, 2)), [[0, 1, 2]], probes["reading62"])
    with pytest.raises(ValueError, match="do not exist"):
        electrode_contacts(np.zeros((3, 3)), [[0, 1, 3]], probes["reading62"])


# --- the shared vectors --------------------------------------------------------------------------

@pytest.mark.vectors
def test_the_vectors_hold_100_or_more_poses_with_the_jaw_and_record_their_inputs():
    assert len(POSES) >= 100 and len(POSES) + len(KERNEL_CASES) == len(VECTORS["cases"])
    assert any(c["input"]["params"]["jaw_opening"] > 7 for c in POSES)
    assert sum(c["expected"]["reading62"]["contacted"] for c in POSES) > 1000
    assert hashlib.sha256(TABLES_BYTES).hexdigest() == FIXTURES["tables"]["sha256"]
    constants = VECTORS["constants"]
    assert (constants["tolerance_mm"], constants["behind_mm"], constants["barycentric"],
            constants["layout_format_version"]) == (
        EPG_CONTACT_TOLERANCE_MM, EPG_CONTACT_BEHIND_MM, COLLISION_TOL.barycentric,
        EPG_LAYOUT_FORMAT_VERSION)


@pytest.mark.vectors
def test_the_vector_layout_is_the_placement_rule_on_the_vector_maxilla():
    v = np.array(FIXTURES["maxilla"]["vertices"], dtype=np.float64)
    f = np.array(FIXTURES["maxilla"]["faces"], dtype=np.int64)
    assert len(f) == FIXTURES["tables"]["maxilla_triangles"]
    layout = layout_document(v, f)
    # Placed again in float64: positions and normals may differ in the last digits on another
    # CPU (the file states the tolerances); ids, cells and rows are exact.
    for name, grid in layout["grids"].items():
        stored = FIXTURES["layout"]["grids"][name]["electrodes"]
        def exact(electrodes):
            return [{k: v for k, v in e.items() if k not in ("position", "normal")}
                    for e in electrodes]

        assert exact(grid["electrodes"]) == exact(stored), name
        for key, tolerance in (("position", tol(VECTORS, "electrode_mm")),
                               ("normal", tol(VECTORS, "normal"))):
            np.testing.assert_allclose([e[key] for e in grid["electrodes"]],
                                       [e[key] for e in stored], rtol=0, atol=tolerance,
                                       err_msg=f"{name}: electrode {key}s")


@pytest.mark.vectors
def test_every_vector_pose_gives_the_recorded_contacts_in_python(vector_setup):
    rig, tables, probes = vector_setup
    for case in POSES:
        vertices, counts = corrected_tongue(rig, rig.values_from(case["input"]["params"]), tables)
        assert counts == case["expected"]["collision"], case["description"]
        for name, grid_probes in probes.items():
            contacts = electrode_contacts(vertices, rig.triangles, grid_probes)
            rows = rows_to_strings(contact_grid(contacts, grid_probes))
            assert rows == case["expected"][name]["rows"], (case["description"], name)


@pytest.mark.vectors
def test_every_vector_kernel_case_gives_the_recorded_contacts_in_python(vector_setup):
    rig, _, probes = vector_setup
    for case in KERNEL_CASES:
        vertices = decode_f32(case["input"]["vertices"]).reshape(-1, 3)
        if case["input"]["triangles"] == "rig":
            for name, grid_probes in probes.items():
                contacts = electrode_contacts(vertices, rig.triangles, grid_probes)
                assert rows_to_strings(contact_grid(contacts, grid_probes)) \
                    == case["expected"][name]["rows"], (case["description"], name)
        else:
            triangles = np.array(case["input"]["triangles"]).reshape(-1, 3)
            contacts = electrode_contacts(vertices, triangles, probes["reading62"])
            contacted = [i for i, c in zip(probes["reading62"].ids, contacts, strict=True) if c]
            assert contacted == case["expected"]["contacted"], case["description"]


# --- real tongues on the real palate -------------------------------------------------------------

def test_the_neutral_tongue_touches_no_electrode(badin):
    frame = _frame(badin)
    assert frame.contacts.sum() == 0


def test_a_tongue_tip_raised_to_the_alveolar_ridge_contacts_only_the_front_rows(badin):
    frame = _frame(badin, tip_height=8.0, tip_advancement=4.0, blade_height=4.0)
    rows = frame.grid.sum(axis=1)
    assert rows[:2].sum() >= 8, rows
    assert rows[3:].sum() == 0, rows
    # The front row is closed across: a /t/-like seal.
    assert frame.grid[0, 1:7].all()


def test_a_raised_back_of_the_tongue_closes_the_velar_rows_and_leaves_the_front_open(badin):
    frame = _frame(badin, back_dorsum_height=8.0, dorsum_height=10.0, body_height=4.0)
    rows = frame.grid.sum(axis=1)
    assert (rows[5:] == 8).all(), rows  # a /k/-like closure across R6-R8
    assert rows[:2].sum() == 0, rows
    back = epg_indices(frame.grid[None])
    tip = epg_indices(_frame(badin, tip_height=8.0, tip_advancement=4.0, blade_height=4.0)
                      .grid[None])
    # (R6 + R7 + R8) / 24: 24 / 24 and 0 / 24, up to rounding
    assert back["dorsopalatal"][0] == pytest.approx(1.0, abs=1e-12)
    assert tip["dorsopalatal"][0] == pytest.approx(0.0, abs=1e-12)
    assert back["anteriority"][0] < 0.3 and tip["anteriority"][0] > 0.7
    assert back["cog"][0] < 2.5 and tip["cog"][0] > 6.0


def test_a_tongue_raised_at_the_back_touches_the_sides_first(badin):
    frame = _frame(badin, back_dorsum_height=8.0, body_height=6.0)
    outer = frame.grid[2:, [0, 7]].sum()
    centre = frame.grid[2:, 2:6].sum()
    assert outer >= 10 and centre == 0, rows_to_strings(frame.grid)


def test_more_jaw_opening_never_adds_contacts_to_a_raised_tip(badin):
    previous = None
    for jaw in (0.0, 3.0, 6.0, 10.0):
        count = int(_frame(badin, tip_height=8.0, tip_advancement=6.0, blade_height=6.0,
                           jaw_opening=jaw).contacts.sum())
        assert previous is None or count <= previous, (jaw, count, previous)
        previous = count
    assert previous == 0
