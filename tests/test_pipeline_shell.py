"""The head shell where it meets the face skin: no fold, no crease, no inward-facing strip."""

import numpy as np
import pytest

from glasshead.geometry.meshio import read_face_elems, read_face_nodes
from glasshead.pipeline import sources
from glasshead.pipeline.face_skin import extract_face_skin, head_centre
from glasshead.pipeline.head_shell import build_head_shell

#: Shell rings next to the rim checked for folds (ring 0 is the rim).
NEAR_RINGS = 3


@pytest.fixture(scope="module")
def head(data_dir):
    """(skin, shell) built from the reference data as `glasshead build` does."""
    cranium = sources.read_badin_mesh(data_dir, "cranium")[0]
    face_dir = data_dir / sources.BADIN
    node_ids, nodes = read_face_nodes(face_dir / "face.node")
    elems = read_face_elems(face_dir / "face.elem", node_ids)
    skin = extract_face_skin(node_ids, nodes, elems, head_centre(cranium))
    return skin, build_head_shell(skin.vertices, skin.faces, cranium)


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
    offset = len(skin.vertices)
    index = np.arange(len(shell.vertices)) + offset
    index[: len(shell.rim)] = shell.rim
    vertices = np.vstack([skin.vertices, shell.vertices])
    return vertices, np.vstack([skin.faces, index[shell.faces]])


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
