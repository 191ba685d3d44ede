"""The anatomy build: the frame conversion checked on anatomy, counts, the skin and the shell."""

import json

import numpy as np
import pytest
import trimesh

from glasshead.geometry.frame import badin_to_project
from glasshead.geometry.meshio import read_obj
from glasshead.pipeline.quantized_glb import lattice_step
from glasshead.pipeline.sources import BADIN


@pytest.fixture(scope="session")
def meshes(built_assets, manifest):
    """name -> trimesh.Trimesh of every built mesh, loaded from its GLB as the browser does."""
    loaded = {}
    for entry in manifest["meshes"]:
        loaded[entry["name"]] = trimesh.load(built_assets / entry["file"], force="mesh",
                                             process=False)
    return loaded


def test_the_incisors_lie_anterior_to_the_molars(meshes):
    maxilla = meshes["maxilla"].vertices
    lowest = maxilla[maxilla[:, 1] < maxilla[:, 1].min() + 4.0]  # cusps and incisal edges
    front = lowest[np.abs(lowest[:, 2]) < 5.0]  # central incisors, near the midline
    sides = lowest[np.abs(lowest[:, 2]) > 20.0]  # molars, far from it
    assert front[:, 0].mean() > sides[:, 0].mean() + 20.0


def test_the_palate_lies_above_the_tongue(meshes):
    maxilla, tongue = meshes["maxilla"].vertices, meshes["tongue_rest"].vertices
    midline = maxilla[np.abs(maxilla[:, 2]) < 2.0]
    assert np.median(midline[:, 1]) > np.median(tongue[:, 1])
    assert maxilla[:, 1].max() > tongue[:, 1].max()


def test_the_lips_lie_anterior_to_the_teeth(meshes):
    for lip in ("upper_lip", "lower_lip"):
        assert meshes[lip].vertices[:, 0].max() > meshes["maxilla"].vertices[:, 0].max()
        assert meshes[lip].vertices[:, 0].max() > meshes["mandible"].vertices[:, 0].max()


def test_the_subjects_right_maps_to_negative_z(data_dir):
    # The Badin frame is right-handed with x posterior and z up, so its +y is the subject's
    # right; the project's +z is the subject's left.
    converted = badin_to_project(np.array([[0.08, 0.03, 0.10], [0.08, -0.03, 0.10]]))
    assert converted[0, 2] < 0 < converted[1, 2]
    # On anatomy: the jaw is symmetric, so its mirrored halves coincide and the mid-sagittal
    # plane of the converted mesh is z = 0.
    jaw = read_obj(data_dir / BADIN / "jaw.obj")[0]
    z = badin_to_project(jaw)[:, 2]
    assert abs(z.max() + z.min()) < 1.0


def test_every_mesh_is_in_millimetres_around_the_mouth(meshes):
    for name, mesh in meshes.items():
        assert 10.0 < np.ptp(mesh.vertices, axis=0).max() < 400.0, name
        assert np.abs(mesh.vertices).max() < 250.0, name


def test_triangle_counts_match_the_sources(data_dir, manifest):
    counts = {m["name"]: m["triangles"] for m in manifest["meshes"]}
    for stem, name in [("maxilla", "maxilla"), ("jaw", "mandible"), ("tongue", "tongue_rest"),
                       ("upperlip", "upper_lip"), ("lowerlip", "lower_lip"),
                       ("cranium", "cranium")]:
        assert counts[name] == len(read_obj(data_dir / BADIN / f"{stem}.obj")[1]), name
    assert counts["maxilla"] == 5808
    assert counts["maxilla_cbct_full"] == 17992
    assert counts["face_skin"] > 3000


def test_the_skin_ends_where_the_lips_begin(meshes, build_report, built_assets):
    # The skin's triangles under the lips are dropped (with them left, about 470 triangle
    # centres lay on or up to 1.4 mm inside a lip); a few at the lips' borders reach just in.
    assert build_report["anatomy"]["face_skin"]["lip_faces_dropped"] > 300
    skin = meshes["face_skin"]
    for name in ("upper_lip", "lower_lip"):
        lip = meshes[name]
        depth = trimesh.proximity.signed_distance(lip, skin.triangles_center)
        assert depth.max() < 0.25, f"a skin triangle's centre lies inside the {name}"
        assert np.sum(depth > -0.05) < 5, f"skin triangles lie on the {name}"
    # The border vertices laid onto the lips lie on no face node, and on a lip.
    report = build_report["anatomy"]["face_skin"]
    node_ids = np.array(json.loads((built_assets / "face_skin_nodes.json").read_text())["node_ids"])
    assert np.sum(node_ids < 0) == report["lip_border_moved"] > 0
    assert 0.0 < report["lip_border_moved_max_mm"] <= 3.0
    lips = trimesh.util.concatenate([meshes["upper_lip"], meshes["lower_lip"]])
    _, gap, _ = trimesh.proximity.closest_point(lips, skin.vertices[node_ids < 0])
    # On a lip, up to half a diagonal of the GLB lattice the skin, shell and lips share.
    step = max(lattice_step(meshes[n].vertices) for n in ("face_skin", "head_shell", "upper_lip",
                                                          "lower_lip"))
    assert gap.max() < np.sqrt(3.0) * step / 2.0 + 1e-6


def test_closed_meshes_have_outward_normals(meshes):
    for name in ("tongue_rest", "mandible", "upper_lip", "lower_lip"):
        mesh = meshes[name]
        assert mesh.is_watertight, name
        assert mesh.volume > 0, f"{name} is wound inward"


def test_skin_normals_point_outward(meshes):
    head = trimesh.util.concatenate([meshes["face_skin"], meshes["head_shell"]])
    head.merge_vertices()
    centre = meshes["cranium"].vertices.mean(axis=0)
    skin = meshes["face_skin"]
    outward = np.einsum("ij,ij->i", skin.face_normals, skin.triangles_center - centre)
    assert (outward > 0).mean() > 0.95
    # The skin and the shell together enclose a positive volume (outward winding overall).
    assert head.volume > 1.0e6  # mm^3: a head is a few litres


def test_the_skin_is_the_outer_surface_only(meshes):
    # Rays from inside the mouth outward first meet the lips or the skin, never a skin face
    # that looks inward (an inner surface lying on the bones would).
    skin = meshes["face_skin"]
    centre = meshes["cranium"].vertices.mean(axis=0)
    to_centre = centre - skin.triangles_center
    facing_in = np.einsum("ij,ij->i", skin.face_normals, to_centre) > 0
    assert facing_in.mean() < 0.05


def test_the_shell_closes_the_head_from_every_side(meshes):
    # The skin ends where the lips begin, so the lips are part of the closed head.
    head = trimesh.util.concatenate([meshes[name] for name in
                                     ("face_skin", "head_shell", "upper_lip", "lower_lip")])
    centre = meshes["cranium"].vertices.mean(axis=0) - np.array([0.0, 20.0, 0.0])
    rng = np.random.default_rng(7)
    directions = rng.normal(size=(2000, 3))
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    hits = head.ray.intersects_any(np.tile(centre, (len(directions), 1)), directions)
    # Every direction except straight down the neck meets the head.
    downward = directions[:, 1] < -0.8
    assert hits[~downward].mean() > 0.99


def test_the_manifest_names_one_scene_mesh_of_each_part(manifest):
    scene = [m["name"] for m in manifest["meshes"] if m["scene"]]
    for name in ("face_skin", "head_shell", "maxilla", "mandible", "tongue_rest", "upper_lip",
                 "lower_lip", "cranium"):
        assert scene.count(name) == 1, name
    assert manifest["frame"]["units"] == "mm"
