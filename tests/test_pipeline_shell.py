"""The head shell where it meets the face skin: no fold, no crease, no inward-facing strip."""

import numpy as np
import pytest
from scipy.sparse.csgraph import dijkstra
from scipy.spatial import cKDTree

from glasshead.geometry.meshio import read_face_elems, read_face_nodes
from glasshead.pipeline import sources
from glasshead.pipeline.face_skin import extract_face_skin, head_centre
from glasshead.pipeline.head_shell import build_head_shell
from glasshead.pipeline.seam_fairing import (
    SHELL_RINGS,
    SKIN_HOPS,
    adjacency,
    close_head,
    welded,
)

#: Shell rings next to the rim checked for folds (ring 0 is the rim).
NEAR_RINGS = 3


@pytest.fixture(scope="module")
def raw_head(data_dir):
    """(skin, shell, cranium vertices): the shell as built on the mask's rim, before fairing."""
    cranium = sources.read_badin_mesh(data_dir, "cranium")[0]
    face_dir = data_dir / sources.BADIN
    node_ids, nodes = read_face_nodes(face_dir / "face.node")
    elems = read_face_elems(face_dir / "face.elem", node_ids)
    skin = extract_face_skin(node_ids, nodes, elems, head_centre(cranium))
    return skin, build_head_shell(skin.vertices, skin.faces, cranium), cranium


@pytest.fixture(scope="module")
def head(raw_head):
    """(skin, shell) built from the reference data as `glasshead build` does: seam faired."""
    skin, _, cranium = raw_head
    return close_head(skin, cranium)


def _unit_normals(vertices, faces):
    tri = vertices[faces]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    return normal / np.linalg.norm(normal, axis=1, keepdims=True)


def _edge_dihedrals(vertices, faces):
    """Per interior edge: (the two face ids (e, 2), angle between their normals in degrees (e,))."""
    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    owner = np.tile(np.arange(len(faces)), 3)
    key = np.sort(edges, axis=1)
    order = np.lexsort(key.T[::-1])
    key, owner = key[order], owner[order]
    shared = np.all(key[1:] == key[:-1], axis=1)
    pairs = np.stack([owner[:-1][shared], owner[1:][shared]], axis=1)
    normals = _unit_normals(vertices, faces)
    cosine = np.einsum("ij,ij->i", normals[pairs[:, 0]], normals[pairs[:, 1]])
    return pairs, np.degrees(np.arccos(np.clip(cosine, -1.0, 1.0)))


def _shell_rings(shell):
    """Ring index of each shell face: that of its vertex nearest the rim; (m,) int."""
    return shell.faces.min(axis=1) // len(shell.rim)


def _welded(skin, shell):
    """Skin and shell as one mesh, the shell's ring 0 replaced by the skin's rim vertices."""
    return welded(skin.vertices, skin.faces, shell.vertices, shell.faces, shell.rim)


def test_the_shell_starts_exactly_on_the_skin_rim(head):
    skin, shell = head
    # mm: ring 0 is the rim, taken through angles and radii and back (rounding only).
    np.testing.assert_allclose(shell.vertices[: len(shell.rim)], skin.vertices[shell.rim], rtol=0,
                               atol=1e-9)


def test_no_shell_face_next_to_the_rim_faces_inward(head):
    _, shell = head
    centre = np.asarray(shell.params["centre_mm"])
    near = _shell_rings(shell) <= NEAR_RINGS
    faces = shell.faces[near]
    outward = shell.vertices[faces].mean(axis=1) - centre
    facing = np.einsum("ij,ij->i", _unit_normals(shell.vertices, faces), outward)
    assert near.sum() >= 4 * len(shell.rim)
    assert (facing > 0).all(), f"{(facing <= 0).sum()} of {len(faces)} faces look inward"


def test_the_skin_turns_smoothly_into_the_shell_across_the_seam(head):
    skin, shell = head
    vertices, faces = _welded(skin, shell)
    pairs, angle = _edge_dihedrals(vertices, faces)
    on_skin = pairs < len(skin.faces)
    seam = on_skin[:, 0] != on_skin[:, 1]
    # Every rim edge is shared by one skin and one shell face: the head is closed there.
    assert seam.sum() == len(shell.rim)
    assert angle[seam].max() < 60.0


def test_the_first_shell_rings_do_not_fold(head):
    _skin, shell = head
    pairs, angle = _edge_dihedrals(shell.vertices, shell.faces)
    rings = _shell_rings(shell)[pairs]
    near = rings.max(axis=1) <= NEAR_RINGS
    # Creases where the skin's own rim is notched stay below a right angle; a fold is near 180.
    assert angle[near].max() < 90.0
    assert np.median(angle[near]) < 10.0


def test_the_pole_is_chosen_so_the_meridians_cross_the_rim(head):
    _, shell = head
    assert shell.params["rim_azimuth_turnbacks"] == 0
    assert shell.params["rim_meridian_crossing_min_deg"] > 10.0
    pole = np.asarray(shell.params["pole_direction"])
    assert pole[0] < 0.0 and abs(pole[2]) < 1e-9  # behind the centre, in the mid-sagittal plane


def _near_rim_dihedrals(raw, faired, within_mm=10.0):
    """Angles (deg) between neighbouring faces of the welded head, before and after fairing, for
    the face pairs whose centres both lay within ``within_mm`` of the rim before: the seam and the
    band on both sides of it. raw, faired: (skin, shell) each."""
    vertices, faces = _welded(*raw)
    pairs, before = _edge_dihedrals(vertices, faces)
    rim_points = raw[0].vertices[raw[1].rim]
    distance = cKDTree(rim_points).query(vertices[faces].mean(axis=1))[0]
    near = distance[pairs].max(axis=1) < within_mm
    _, after = _edge_dihedrals(*_welded(*faired))
    return before[near], after[near]


def test_the_faired_seam_has_no_crease_left_where_the_mask_was_cut(raw_head, head):
    """Before fairing, the band within 10 mm of the rim had creases up to 80 degrees (the folded
    sliver at the temple and the ridges its notch ran up the shell); faired, the band bends about
    as much as the face itself does (whose edges have a 90th percentile near 20 degrees)."""
    raw_skin, raw_shell, _ = raw_head
    skin, shell = head
    before, after = _near_rim_dihedrals((raw_skin, raw_shell), (skin, shell))
    assert len(after) > 1000
    assert before.max() > 75.0 and np.percentile(before, 90) > 20.0
    assert after.max() < 60.0
    assert np.percentile(after, 90) < 14.0 and np.percentile(after, 99) < 35.0
    assert np.median(after) < 0.7 * np.median(before)
    report = shell.params["seam_fairing"]
    assert report["normal_curvature_rms_after_mm"] < 0.8 * report["normal_curvature_rms_before_mm"]


def test_fairing_moves_only_the_band_by_a_few_millimetres_and_keeps_the_seam_closed(raw_head,
                                                                                    head):
    raw_skin, raw_shell, _ = raw_head
    skin, shell = head
    np.testing.assert_array_equal(skin.faces, raw_skin.faces)
    np.testing.assert_array_equal(shell.faces, raw_shell.faces)
    np.testing.assert_array_equal(shell.rim, raw_shell.rim)
    # The shell's ring 0 is still the skin's rim, exactly.
    np.testing.assert_array_equal(shell.vertices[: len(shell.rim)], skin.vertices[shell.rim])
    moved = np.linalg.norm(skin.vertices - raw_skin.vertices, axis=1)
    graph = adjacency(skin.faces, len(skin.vertices))
    hops = dijkstra(graph, directed=False, indices=shell.rim, unweighted=True, min_only=True)
    assert moved[hops > SKIN_HOPS].max() == 0.0  # the face as measured
    assert 0.5 < moved.max() < 6.0
    beyond = (SHELL_RINGS + 1) * len(shell.rim)
    np.testing.assert_array_equal(shell.vertices[beyond:], raw_shell.vertices[beyond:])
    assert np.linalg.norm(shell.vertices - raw_shell.vertices, axis=1).max() < 6.0
