"""Shared helpers for the face rig tests: the built rig and meshes, poses, and the measures of a
posed face (folds, stretch, seams, depth behind the real incisors, lip interpenetration).

Everything here reads what `glasshead build` wrote from the real Badin data; the tests take the
``built_assets`` fixture, which builds what is missing (it never skips).
"""

import json
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import numpy as np
import scipy.sparse as sp
import trimesh
from scipy.spatial import cKDTree

from glasshead.geometry import face_rig
from glasshead.geometry.jaw import jaw_pose
from glasshead.geometry.tongue_parameters import JAW_PARAMETER

#: The jaw's largest opening, degrees (the tongue rig's jaw_opening range).
JAW_MAX_DEG = JAW_PARAMETER[3]

#: Rest vertices closer than this are one point shared by two meshes (GLB float32), mm.
SEAM_MM = 1e-3


@dataclass
class Face:
    """The built rig with its meshes: rig (dict), jaw (the tongue rig's jaw block), meshes
    (name -> (vertices, faces), every mesh of the build), prepared (geometry.face_rig)."""

    rig: dict
    jaw: dict
    meshes: dict
    prepared: dict

    def pose(self, jaw_opening=0.0, **lips):
        """(posed dict, info) for a jaw opening in degrees and lip parameters."""
        return face_rig.pose_face(self.rig, self.prepared, lips, self.jaw_pose(jaw_opening))

    def jaw_pose(self, jaw_opening):
        return jaw_pose(jaw_opening, self.jaw)


@cache
def load_face(assets_dir):
    """The Face of a built assets directory (cached per directory)."""
    assets = Path(assets_dir)
    rig = json.loads((assets / "face-rig.json").read_text())
    jaw = json.loads((assets / "tongue-rig.json").read_text())["jaw"]
    manifest = json.loads((assets / "manifest.json").read_text())
    meshes = {}
    for entry in manifest["meshes"]:
        if entry.get("scene", True):
            mesh = trimesh.load(assets / entry["file"], force="mesh", process=False)
            meshes[entry["name"]] = (np.asarray(mesh.vertices, dtype=np.float64),
                                     np.asarray(mesh.faces, dtype=np.int64))
    rest = {name: meshes[name][0] for name in face_rig.MESH_NAMES}
    return Face(rig, jaw, meshes, face_rig.prepare_meshes(rig, rest))


def triangle_normals(vertices, faces):
    return np.cross(vertices[faces[:, 1]] - vertices[faces[:, 0]],
                    vertices[faces[:, 2]] - vertices[faces[:, 0]])


@cache
def _vertex_sharing(faces_key, n_vertices):
    faces = np.frombuffer(faces_key, dtype=np.int64).reshape(-1, 3)
    m = len(faces)
    incidence = sp.coo_matrix((np.ones(3 * m), (faces.ravel(), np.repeat(np.arange(m), 3))),
                              shape=(n_vertices, m)).tocsr()
    return (incidence.T @ incidence).tocsr()


def neighbourhood_agreement(vertices, faces):
    """Per triangle, the cosine between its normal and the area-weighted normal of every
    triangle sharing a vertex with it (itself included): about 1 on a smooth surface, negative
    for a triangle turned over against the surface around it. (m,) float64."""
    faces = np.ascontiguousarray(faces, dtype=np.int64)
    sharing = _vertex_sharing(faces.tobytes(), len(vertices))
    n = triangle_normals(vertices, faces)
    around = sharing @ n
    unit = n / np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    return np.einsum("ij,ij->i", unit, around / np.maximum(
        np.linalg.norm(around, axis=1, keepdims=True), 1e-300))


@cache
def _edges(faces_key):
    faces = np.frombuffer(faces_key, dtype=np.int64).reshape(-1, 3)
    return np.unique(np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]],
                                             faces[:, [2, 0]]]), axis=1), axis=0)


def edge_stretch(rest, posed, faces):
    """Posed over rest length of every edge; (e,) float64."""
    edges = _edges(np.ascontiguousarray(faces, dtype=np.int64).tobytes())
    length = np.linalg.norm(rest[edges[:, 0]] - rest[edges[:, 1]], axis=1)
    return np.linalg.norm(posed[edges[:, 0]] - posed[edges[:, 1]], axis=1) / length


def seam_pairs(meshes, names):
    """Rest points shared by two of the named meshes: list of (name_a, i, name_b, j)."""
    pairs = []
    for k, a in enumerate(names):
        tree = cKDTree(meshes[a][0])
        for b in names[k + 1:]:
            distance, index = tree.query(meshes[b][0])
            for j in np.flatnonzero(distance <= SEAM_MM):
                pairs.append((a, int(index[j]), b, int(j)))
    return pairs


def depth_behind_incisors(points, bone_vertices, bone_faces, half_width=14.0, reach=12.0):
    """How far points lie behind a bone's labial surface: for each point within ``half_width``
    of the midline, a ray along +x; a hit within ``reach`` means the point is behind (inside or
    past) that surface by the hit distance. Exact raycasts on the real mesh, independent of the
    rig's tables. Returns the largest depth, mm (0 when none)."""
    mesh = trimesh.Trimesh(bone_vertices, bone_faces, process=False)
    near = points[np.abs(points[:, 2]) < half_width]
    hits, ray, _ = mesh.ray.intersects_location(near, np.tile([1.0, 0.0, 0.0], (len(near), 1)),
                                                multiple_hits=False)
    depth = hits[:, 0] - near[ray, 0]
    depth = depth[depth < reach]
    return float(depth.max(initial=0.0))


def interpenetration(upper_vertices, upper_faces, lower_vertices):
    """Deepest lower-lip vertex inside the (closed) upper lip, mm; 0 when none is inside."""
    upper = trimesh.Trimesh(upper_vertices, upper_faces, process=False)
    inside = upper.contains(lower_vertices)
    if not inside.any():
        return 0.0
    return float(trimesh.proximity.closest_point(upper, lower_vertices[inside])[1].max())


def random_lip_sets(rig, count, seed, closed_share=0.3, jaw_range=JAW_PARAMETER[2:4]):
    """``count`` seeded random (jaw opening, lip params) across every range."""
    rng = np.random.default_rng(seed)
    sets = []
    for _ in range(count):
        params = {s["name"]: float(rng.uniform(s["min"], s["max"])) for s in rig["parameters"]}
        if rng.random() < closed_share:
            params["lip_opening"] = 0.0
        sets.append((float(rng.uniform(*jaw_range)), params))
    return sets


def extreme_sets(rig):
    """Every lip parameter alone at each extreme, and some strong combinations, at jaw openings
    0, half the jaw's range and its maximum."""
    lips = [{}]
    for spec in rig["parameters"]:
        lips += [{spec["name"]: spec["min"]}, {spec["name"]: spec["max"]}]
    lips += [{"lip_opening": 0.0, "lip_rounding": 10.0, "lip_protrusion": 8.0},
             {"lip_opening": 0.0, "upper_lip_raise": 6.0, "lower_lip_tuck": 5.0},
             {"upper_lip_raise": 6.0, "lower_lip_tuck": 5.0, "lip_rounding": -4.0}]
    return [(opening, params) for opening in (0.0, 0.5 * JAW_MAX_DEG, JAW_MAX_DEG)
            for params in lips]


def skin_showing_through_lips(posed, faces, step=0.5, within=0.5):
    """Where the skin shows through a lip, seen from the front.

    Rays along -x on a ``step`` mm grid over the posed lips; a ray shows the skin through a lip
    when the first surface it meets is the skin and a lip lies less than ``within`` mm behind it
    (a fold of the skin in front of the lip, or the two surfaces crossing). posed : name ->
    (n, 3) posed vertices; faces : name -> (m, 3). Returns (rays showing it, rays over the lips).
    """
    names = ("face_skin", "upper_lip", "lower_lip")
    offsets = np.cumsum([0] + [len(posed[name]) for name in names])
    mesh = trimesh.Trimesh(np.concatenate([posed[name] for name in names]),
                           np.concatenate([faces[name] + offsets[k]
                                           for k, name in enumerate(names)]),
                           process=False)
    owner = np.concatenate([np.full(len(faces[name]), k) for k, name in enumerate(names)])
    lips = np.concatenate([posed["upper_lip"], posed["lower_lip"]])
    low, high = lips.min(axis=0), lips.max(axis=0)
    yy, zz = np.meshgrid(np.arange(low[1], high[1], step), np.arange(low[2], high[2], step),
                         indexing="ij")
    origins = np.stack([np.full(yy.size, high[0] + 50.0), yy.ravel(), zz.ravel()], axis=1)
    hits, ray, triangle = mesh.ray.intersects_location(
        origins, np.tile([-1.0, 0.0, 0.0], (len(origins), 1)), multiple_hits=True)
    order = np.lexsort((-hits[:, 0], ray))  # per ray, front to back
    hits, ray, who = hits[order], ray[order], owner[triangle[order]]
    first = np.r_[True, ray[1:] != ray[:-1]]
    showing, over_lips = set(), set()
    front_x = dict(zip(ray[first], hits[first, 0], strict=True))
    front_who = dict(zip(ray[first], who[first], strict=True))
    for x, r, k in zip(hits[:, 0], ray, who, strict=True):
        if k == 0:
            continue
        over_lips.add(int(r))
        if front_who[r] == 0 and 0.0 < front_x[r] - x < within:
            showing.add(int(r))
    return len(showing), len(over_lips)
