"""The inputs of the face rig, read once and put in the project frame.

The meshes the rig deforms (``face_skin``, ``upper_lip``, ``lower_lip``, ``head_shell``) and the
bones it reads
(``mandible``, ``maxilla``) are taken from the anatomy build's GLBs when ``assets_dir`` holds a
manifest naming them, so that the rig's per-vertex data follow the vertex order the web app
loads; without a build they are made from the Badin sources exactly as the anatomy step makes
them. The face's hexahedral mesh, its jaw attachments and the cranium always come from the
sources.
"""

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

from glasshead.constants import MANIFEST_FILE
from glasshead.geometry.frame import badin_to_project
from glasshead.geometry.meshio import MeshFormatError, read_face_elems, read_face_nodes
from glasshead.pipeline import sources
from glasshead.pipeline.face_skin import extract_face_skin, head_centre, uncover_lips
from glasshead.pipeline.head_shell import build_head_shell
from glasshead.pipeline.outputs import load_built_meshes

ATTACHMENTS_FILE = "face_jaw_attachments.txt"
MANIFEST = MANIFEST_FILE

#: Meshes taken from the build when it has them: the rig's own meshes and the two bones.
SCENE_MESHES = ("face_skin", "upper_lip", "lower_lip", "head_shell", "mandible", "maxilla")

#: A skin vertex lies on a face node when closer than this, mm (GLB positions lie on a 2^-8 mm
#: lattice, within 0.0034 mm of the node; nodes are millimetres apart).
ON_NODE_MM = 1e-2
#: Largest share of skin vertices on no node (those laid onto the lips at the skin's border).
OFF_NODE_SHARE = 0.05


@dataclass
class FaceSources:
    """Project-frame (mm) inputs. Meshes are (vertices (n, 3) float64, faces (m, 3) int64).

    nodes : (p, 3) face.node points in file order.  elems : (k, 8) zero-based node indices.
    jaw_attachments : (a,) zero-based node indices riding on the jaw.
    skin_nodes : (n,) node index of each face_skin vertex (-1: laid onto a lip, on no node).
    head_shell : the shell closing the head, which shares the skin's rim.
    origin : where each mesh came from ("build <sha256>" or "sources").
    """

    nodes: np.ndarray
    elems: np.ndarray
    jaw_attachments: np.ndarray
    mandible: tuple
    maxilla: tuple
    cranium: tuple
    upper_lip: tuple
    lower_lip: tuple
    face_skin: tuple
    head_shell: tuple
    skin_nodes: np.ndarray
    origin: dict = field(default_factory=dict)


def read_attachments(path, node_ids):
    """Zero-based indices of the node ids listed in face_jaw_attachments.txt; (a,) int64."""
    path = Path(path)
    try:
        listed = np.array([int(tok) for tok in path.read_text().split()], dtype=np.int64)
    except FileNotFoundError:
        raise MeshFormatError(path, "file not found") from None
    except ValueError:
        raise MeshFormatError(path, "node ids must be integers") from None
    index_of = {int(n): i for i, n in enumerate(node_ids)}
    missing = [int(n) for n in listed if int(n) not in index_of]
    if missing:
        raise MeshFormatError(path, f"node id {missing[0]} is not in face.node")
    return np.unique([index_of[int(n)] for n in listed]).astype(np.int64)


def read_scene_meshes(assets_dir):
    """The built GLBs of SCENE_MESHES: dict name -> ((vertices, faces), sha256); {} without a
    manifest. Raises ValueError when the manifest lacks one of them or its file is missing."""
    if not (Path(assets_dir) / MANIFEST).is_file():
        return {}
    built = load_built_meshes(assets_dir, SCENE_MESHES, scene_only=True)
    return {name: ((vertices, faces), sha256) for name, (vertices, faces, sha256) in built.items()}


def skin_node_indices(skin_vertices, nodes):
    """The face node under each skin vertex, -1 for the few laid onto the lips at the skin's
    border (``face_skin.uncover_lips``); (n,) int64. ValueError if more than OFF_NODE_SHARE of
    the vertices lie on no node."""
    distance, nearest = cKDTree(nodes).query(skin_vertices)
    off = distance > ON_NODE_MM
    if off.mean() > OFF_NODE_SHARE:
        worst = int(np.argmax(distance))
        raise ValueError(f"{off.sum()} face_skin vertices lie on no face node (vertex {worst} is "
                         f"{distance[worst]:.3g} mm from every node): the skin was not made from "
                         "this face mesh")
    return np.where(off, -1, nearest).astype(np.int64)


def load_face_sources(data_dir, assets_dir=None):
    """Read and convert every input of the face rig (see the module docstring)."""
    base = Path(data_dir) / sources.BADIN
    node_ids, nodes_m = read_face_nodes(base / "face.node")
    elem_ids = read_face_elems(base / "face.elem", node_ids)
    index_of = {int(n): i for i, n in enumerate(node_ids)}
    elems = np.vectorize(index_of.__getitem__, otypes=[np.int64])(elem_ids)
    cranium = sources.read_badin_mesh(data_dir, "cranium")
    nodes = badin_to_project(nodes_m)

    built = read_scene_meshes(assets_dir) if assets_dir is not None else {}
    if built:
        meshes = {name: mesh for name, (mesh, _) in built.items()}
        origin = {name: f"build {digest}" for name, (_, digest) in built.items()}
    else:
        lips = {"upper_lip": sources.read_badin_mesh(data_dir, "upperlip"),
                "lower_lip": sources.read_badin_mesh(data_dir, "lowerlip")}
        skin = extract_face_skin(node_ids, nodes_m, elem_ids, head_centre(cranium[0]))
        skin = uncover_lips(skin, list(lips.values()))
        shell = build_head_shell(skin.vertices, skin.faces, cranium[0])
        meshes = {"face_skin": (skin.vertices, skin.faces),
                  "head_shell": (shell.vertices, shell.faces),
                  **lips,
                  "mandible": sources.read_badin_mesh(data_dir, "jaw"),
                  "maxilla": sources.read_badin_mesh(data_dir, "maxilla")}
        origin = {name: "sources" for name in meshes}
    return FaceSources(
        nodes=nodes,
        elems=elems,
        jaw_attachments=read_attachments(base / ATTACHMENTS_FILE, node_ids),
        cranium=cranium,
        skin_nodes=skin_node_indices(meshes["face_skin"][0], nodes),
        origin=origin,
        **meshes,
    )
