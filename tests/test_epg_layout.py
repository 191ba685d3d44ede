"""Electrode layouts placed on the real Badin maxilla: the placement rule, the file and its build
step.

Everything is measured against the mesh itself (closest points, exact sections, the tooth rule),
never against numbers copied from the layout code.
"""

import hashlib
import itertools
import json

import numpy as np
import pytest
import trimesh

from collision_support import badin_mesh
from glasshead.constants import EPG_LAYOUT_FORMAT_VERSION
from glasshead.epg.dental import LAYOUT_TIP_BAND_MM, tooth_weights
from glasshead.epg.layout import GRIDS, LayoutError, build_layout, layout_document, midline
from glasshead.epg.palate_section import Section
from glasshead.pipeline import epg_layout
from glasshead.pipeline.epg_layout import (
    LAYOUT_FILE,
    LayoutFileError,
    build_epg_layout,
    build_step,
    read_layout,
)


@pytest.fixture(scope="module")
def maxilla():
    return badin_mesh("maxilla")


@pytest.fixture(scope="module")
def document(maxilla):
    return layout_document(*maxilla, source={"mesh": "Badin maxilla"})


def _electrodes(document, grid):
    return {e["id"]: e for e in document["grids"][grid]["electrodes"]}


def _positions(document, grid):
    return np.array([e["position"] for e in document["grids"][grid]["electrodes"]])


def test_the_reading_palate_has_62_electrodes_in_8_rows_with_6_in_the_front_row(document):
    grid = document["grids"]["reading62"]
    assert grid["rows"] == 8 and grid["columns"] == 8 and len(grid["electrodes"]) == 62
    rows = [e["row"] for e in grid["electrodes"]]
    assert [rows.count(r) for r in range(1, 9)] == [6, 8, 8, 8, 8, 8, 8, 8]
    front = sorted(e["column"] for e in grid["electrodes"] if e["row"] == 1)
    assert front == [2, 3, 4, 5, 6, 7]
    assert sorted(grid["missing_cells"]) == [0, 7]
    for e in grid["electrodes"]:
        assert e["id"] == f"R{e['row']}C{e['column']}"
        assert e["cell"] == (e["row"] - 1) * 8 + e["column"] - 1


def test_the_dense_grid_has_96_electrodes_in_12_rows_of_8(document):
    grid = document["grids"]["dense96"]
    assert (grid["rows"], grid["columns"], len(grid["electrodes"])) == (12, 8, 96)
    assert len({e["id"] for e in grid["electrodes"]}) == 96


@pytest.mark.parametrize("grid", list(GRIDS))
def test_every_electrode_lies_on_the_palate_surface(document, maxilla, grid):
    mesh = trimesh.Trimesh(*maxilla, process=False)
    _, distance, _ = trimesh.proximity.closest_point(mesh, _positions(document, grid))
    np.testing.assert_allclose(distance, 0.0, atol=1e-6)


@pytest.mark.parametrize("grid", list(GRIDS))
def test_normals_are_unit_and_face_the_open_mouth(document, maxilla, grid):
    mesh = trimesh.Trimesh(*maxilla, process=False)
    electrodes = document["grids"][grid]["electrodes"]
    normals = np.array([e["normal"] for e in electrodes])
    np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-12)
    # In front of every electrode, along its normal, there is open mouth: the first 3 mm of the
    # ray meet no part of the maxilla (the tongue comes from there).
    origins = _positions(document, grid) + 0.05 * normals
    hits, rays, _ = mesh.ray.intersects_location(origins, normals, multiple_hits=False)
    near = np.linalg.norm(hits - origins[rays], axis=1) < 3.0
    assert not near.any(), [electrodes[r]["id"] for r in rays[near]]
    # The palate faces down: no electrode normal points up.
    assert (normals[:, 1] < 0.2).all()


def test_rows_run_front_to_back_at_equal_steps_along_the_midline(document):
    rows = document["grids"]["reading62"]["rows_detail"]
    s = np.array([r["midline_s_mm"] for r in rows])
    np.testing.assert_allclose(np.diff(s), document["midline"]["length_mm"] / 8, rtol=1e-9)
    np.testing.assert_allclose(s[0], document["midline"]["length_mm"] / 16, rtol=1e-9)
    x = [r["midline_point"][0] for r in rows]
    assert all(a > b for a, b in itertools.pairwise(x)), x
    assert all(abs(r["midline_point"][2]) <= 1e-9 for r in rows)  # on the plane z = 0, in mm


def test_the_midline_runs_from_behind_the_incisors_to_the_back_edge_of_the_hard_palate(
        document, maxilla):
    v, f = maxilla
    start = np.array(document["midline"]["start"])
    end = np.array(document["midline"]["end"])
    incisal_edge = v[np.argmin(v[:, 1])]
    # The start is the incisors' lingual gingival margin: behind and above the incisal edge by
    # about a crown's height, on the tooth rule's half-weight line.
    assert start[0] < incisal_edge[0] - 3.0
    assert 7.0 < start[1] - incisal_edge[1] < 14.0
    # The end is the most posterior point of the mid-sagittal profile.
    section = Section(v, f, origin=(0, 0, 0), normal=(0, 0, 1))
    oral = section.node_points[section.node_points[:, 1] < start[1] + 15]
    assert end[0] == pytest.approx(oral[:, 0].min(), abs=1e-9)
    assert 40.0 < document["midline"]["length_mm"] < 70.0


def test_the_front_row_sits_just_behind_the_upper_incisors(document, maxilla):
    v, _ = maxilla
    teeth = tooth_weights(v, tip_band=LAYOUT_TIP_BAND_MM) > 0.5
    r1 = _positions(document, "reading62")[:6]
    # Within 6 mm of tooth surface, but not on it.
    tree_distance = np.min(np.linalg.norm(r1[:, None] - v[teeth][None], axis=2), axis=1)
    assert (tree_distance < 6.0).all() and (tree_distance > 0.5).all(), tree_distance


def test_columns_mirror_each_other_on_the_symmetric_badin_palate(document):
    for grid in GRIDS:
        electrodes = _electrodes(document, grid)
        for e in electrodes.values():
            twin = electrodes[f"R{e['row']}C{9 - e['column']}"]
            np.testing.assert_allclose(e["position"], np.array(twin["position"]) * [1, 1, -1],
                                       atol=1e-9, err_msg=e["id"])
        # Column 1 is the subject's left (+z).
        assert all(e["position"][2] > 0 for e in electrodes.values() if e["column"] <= 4)


def test_columns_split_each_row_arc_into_equal_steps(document):
    grid = document["grids"]["reading62"]
    for row in grid["rows_detail"][1:]:
        positions = np.array([e["position"] for e in grid["electrodes"]
                              if e["row"] == row["row"]])
        steps = np.linalg.norm(np.diff(positions, axis=0), axis=1)
        # Chords of equal arcs: each no longer than arc / 8, and none much shorter.
        assert (steps <= row["arc_mm"] / 8 + 1e-9).all()
        assert (steps > 0.6 * row["arc_mm"] / 8).all(), (row["row"], steps)


def test_the_outer_columns_reach_the_teeth_where_the_section_has_teeth(document, maxilla):
    v, _ = maxilla
    teeth = v[tooth_weights(v, tip_band=LAYOUT_TIP_BAND_MM) > 0.5]
    electrodes = _electrodes(document, "reading62")
    for row in document["grids"]["reading62"]["rows_detail"]:
        r = row["row"]
        # Column 1 sits half a step inside the left margin (R1's column 2, a step and a half).
        outer, steps = ((f"R{r}C2", f"R{r}C7"), 1.5) if r == 1 else ((f"R{r}C1", f"R{r}C8"), 0.5)
        spacing = row["arc_mm"] / 8
        for name, kind in zip(outer, row["margins"], strict=True):
            gap = np.min(np.linalg.norm(teeth - electrodes[name]["position"], axis=1))
            if kind == "teeth":
                assert gap < (steps + 0.5) * spacing, (name, gap, spacing)


def test_a_reduced_maxilla_of_600_triangles_still_gets_every_electrode():
    import fast_simplification

    v, f = badin_mesh("maxilla")
    rv, rf = fast_simplification.simplify(v.astype(np.float32), f.astype(np.int32),
                                          target_count=600)
    layout = build_layout(rv.astype(np.float64), rf.astype(np.int64), "reading62")
    assert len(layout["electrodes"]) == 62
    mesh = trimesh.Trimesh(rv, rf, process=False)
    _, distance, _ = trimesh.proximity.closest_point(
        mesh, np.array([e["position"] for e in layout["electrodes"]]))
    assert distance.max() < 1e-4


def test_a_maxilla_off_the_midline_or_a_bad_mesh_is_refused(maxilla):
    v, f = maxilla
    with pytest.raises(LayoutError, match="mid-sagittal"):
        midline(v + [0.0, 0.0, 200.0], f)
    with pytest.raises(ValueError, match="faces refer to vertices"):
        build_layout(v, f + len(v))
    with pytest.raises(ValueError, match="unknown electrode grid 'reading64'"):
        build_layout(v, f, "reading62".replace("62", "64"))


def test_the_layout_file_round_trips_and_refuses_another_version(maxilla, tmp_path):
    written = build_epg_layout(*maxilla, tmp_path)
    read = read_layout(tmp_path / LAYOUT_FILE)
    assert read == json.loads(json.dumps(written))
    assert read["format_version"] == EPG_LAYOUT_FORMAT_VERSION
    stale = dict(read, format_version=EPG_LAYOUT_FORMAT_VERSION + 1)
    (tmp_path / LAYOUT_FILE).write_text(json.dumps(stale))
    with pytest.raises(LayoutFileError, match="format_version 2 is not 1"):
        read_layout(tmp_path / LAYOUT_FILE)
    with pytest.raises(LayoutFileError, match="missing"):
        read_layout(tmp_path / "nothing.json")


def test_the_build_step_places_the_scene_maxilla_and_skips_when_up_to_date(maxilla, tmp_path):
    v, f = maxilla
    trimesh.Trimesh(v, f, process=False).export(tmp_path / "maxilla.glb")
    (tmp_path / "manifest.json").write_text(json.dumps(
        {"meshes": [{"name": "maxilla", "file": "maxilla.glb", "scene": True}]}))
    first = build_step(tmp_path)
    assert first["skipped"] is False
    assert first["electrodes"] == {"reading62": 62, "dense96": 96}
    modified = (tmp_path / LAYOUT_FILE).stat().st_mtime_ns
    second = build_step(tmp_path)
    assert second["skipped"] is True and (tmp_path / LAYOUT_FILE).stat().st_mtime_ns == modified
    assert epg_layout.read_layout(tmp_path / LAYOUT_FILE)["source"]["faces"] == len(f)


def test_the_built_layout_is_the_placement_rule_on_the_scene_maxilla():
    from collision_support import built, scene_maxilla

    v, f = scene_maxilla()
    document = read_layout(built(LAYOUT_FILE))
    digest = hashlib.sha256(np.ascontiguousarray(v).tobytes()
                            + np.ascontiguousarray(f).tobytes()).hexdigest()
    assert document["source"]["sha256"] == digest, "the layout is stale: run `glasshead build`"
    fresh = layout_document(v, f)
    mesh = trimesh.Trimesh(v, f, process=False)
    for name in GRIDS:
        built_electrodes = document["grids"][name]["electrodes"]
        placed = fresh["grids"][name]["electrodes"]
        # Ids and cells exactly; positions (mm) and unit normals within the last digits that
        # another CPU, or another numpy, may round differently (as in tests/vectors).
        assert [(e["id"], e["cell"]) for e in built_electrodes] == \
            [(e["id"], e["cell"]) for e in placed]
        for key, atol in (("position", 1e-6), ("normal", 1e-9)):
            np.testing.assert_allclose([e[key] for e in built_electrodes],
                                       [e[key] for e in placed], rtol=0, atol=atol,
                                       err_msg=f"{name}: {key}s")
        _, distance, _ = trimesh.proximity.closest_point(mesh, _positions(document, name))
        assert distance.max() < 1e-6


def test_a_maxilla_stitched_from_two_halves_with_a_seam_keeps_whole_row_arcs(
        maxilla, document, monkeypatch):
    from glasshead.epg import palate_section

    v, f = maxilla
    # The left half on vertices of its own, moved 0.2 mm further left: the halves share no
    # vertex and their sections no longer meet at the midline.
    left = v[f].mean(axis=1)[:, 2] > 0
    copies = np.unique(f[left])
    remap = np.arange(len(v))
    remap[copies] = len(v) + np.arange(len(copies))
    moved = np.concatenate([v, v[copies] + [0.0, 0.0, 0.2]])
    stitched = np.where(left[:, None], remap[f], f)
    whole = np.array([r["arc_mm"] for r in document["grids"]["reading62"]["rows_detail"]])
    layout = build_layout(moved, stitched, "reading62")
    assert len(layout["electrodes"]) == 62
    arcs = np.array([r["arc_mm"] for r in layout["rows_detail"]])
    np.testing.assert_allclose(arcs, whole, rtol=0.1)
    # Without the bridge across the seam each row would stop at the midline.
    monkeypatch.setattr(palate_section, "BRIDGE_MM", 0.0)
    broken = np.array([r["arc_mm"] for r in build_layout(moved, stitched, "reading62")
                       ["rows_detail"]])
    assert (broken < 0.75 * whole).any()
