"""The inputs of the face rig, read once and put in the project frame.

The meshes the rig deforms (``face_skin``, ``upper_lip``, ``lower_lip``, ``head_shell``) and the
bones it reads
(``mandible``, ``maxilla``) are taken from the anatomy build's GLBs when ``assets_dir`` holds a
manifest naming them, so that the rig's per-vertex data follow the vertex order the web app
loads; without a build they are made from the Badin sources exactly as the anatomy step makes
them. The face's hexahedral mesh, its jaw attachments and the cranium always come from the
sources.
"""

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from glasshead.constants import MANIFEST_FILE, SKIN_NODES_FILE
from glasshead.geometry.frame import badin_to_project
from glasshead.geometry.meshio import MeshFormatError, read_face_elems, read_face_nodes
from glasshead.pipeline import sources
from glasshead.pipeline.anatomy import neck_from_sources
from glasshead.pipeline.face_skin import extract_face_skin, head_centre, uncover_lips
from glasshead.pipeline.outputs import load_built_meshes
from glasshead.pipeline.seam_fairing import close_head

ATTACHMENTS_FILE = "face_jaw_attachments.txt"
MANIFEST = MANIFEST_FILE

#: Meshes taken from the build when it has them: the rig's own meshes and the two bones.
SCENE_MESHES = ("face_skin", "upper_lip", "lower_lip", "head_shell", "mandible", "maxilla")

#: A skin vertex lies on its face node when closer than this, mm (GLB positions lie on a 2^-8 mm
#: lattice, within 0.0034 mm of the node; nodes are millimetres apart).
ON_NODE_MM = 1e-2
#: Smallest share of the skin vertices with a node that must lie on it: all but the outer border
#: band faired into the head shell (``seam_fairing``, about 16 %). A skin made from other nodes
#: has almost none on its nodes.
ON_NODE_SHARE = 0.75


@dataclass
class FaceSources:
    """Project-frame (mm) inputs. Meshes are (vertices (n, 3) float64, faces (m, 3) int64).

    nodes : (p, 3) face.node points in file order.  elems : (k, 8) zero-based node indices.
    jaw_attachments : (a,) zero-based node indices riding on the jaw.
    skin_nodes : (n,) node index of each face_skin vertex (-1: laid onto a lip, on no node);
        the vertices of the faired outer border keep theirs, a few mm off it.
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


def skin_node_indices(skin_vertices, skin_node_ids, index_of, nodes):
    """Zero-based face node index of each skin vertex from its face.node id (-1 stays -1: laid
    onto a lip), ``index_of`` mapping face.node ids to indices; (n,) int64. ValueError if the ids
    are not in face.node or fewer than ON_NODE_SHARE of the vertices lie on their nodes (the skin
    was not made from these nodes)."""
    skin_node_ids = np.asarray(skin_node_ids, dtype=np.int64)
    if skin_node_ids.shape != (len(skin_vertices),):
        raise ValueError(f"{len(skin_node_ids)} skin node ids for {len(skin_vertices)} vertices")
    missing = [int(n) for n in skin_node_ids if n >= 0 and int(n) not in index_of]
    if missing:
        raise ValueError(f"skin node id {missing[0]} is not in face.node")
    index = np.array([index_of[int(n)] if n >= 0 else -1 for n in skin_node_ids], dtype=np.int64)
    has = index >= 0
    distance = np.linalg.norm(np.asarray(skin_vertices)[has] - nodes[index[has]], axis=1)
    if np.mean(distance <= ON_NODE_MM) < ON_NODE_SHARE:
        raise ValueError(f"only {np.sum(distance <= ON_NODE_MM)} of {has.sum()} face_skin vertices "
                         "lie on their face nodes: the skin was not made from this face mesh")
    return index


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
        skin_node_ids = json.loads((Path(assets_dir) / SKIN_NODES_FILE).read_text())["node_ids"]
    else:
        lips = {"upper_lip": sources.read_badin_mesh(data_dir, "upperlip"),
                "lower_lip": sources.read_badin_mesh(data_dir, "lowerlip")}
        skin = extract_face_skin(node_ids, nodes_m, elem_ids, head_centre(cranium[0]))
        skin = uncover_lips(skin, list(lips.values()))
        badin = {name: sources.read_badin_mesh(data_dir, stem)
                 for stem, (name, _) in sources.BADIN_MESHES.items()}
        skin, shell = close_head(skin, cranium[0], neck_from_sources(data_dir, badin))
        skin_node_ids = skin.node_ids
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
        skin_nodes=skin_node_indices(meshes["face_skin"][0], skin_node_ids, index_of, nodes),
        origin=origin,
        **meshes,
    )
