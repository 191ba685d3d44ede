"""Jaw skinning weights of the face skin and the lips (a part of the face rig build).

The weights are a harmonic field through the face's hexahedral mesh (``geometry.skin_weights``)
with fixed values:

- 1 on the face nodes listed in ``face_jaw_attachments.txt``, except those nearer the maxilla or
  cranium than the mandible (listed in error: two forehead nodes), and on the middle of the lower
  lip;
- 0 on nodes lying on the maxilla or cranium (and not on the mandible), on the middle of the
  upper lip, on every node above the mouth whose nearest bone is the maxilla or cranium, and on
  the borders of the eyes and nostrils, whose covers are built once at load.

The skin's outer rim is left free: under the chin and along the jaw line it rides on the jaw
(several rim nodes are attachments), as the mandible swings the chin back by up to 35 mm, more
than the skin between the chin and the rim could take up without folding. The head shell, which
shares the rim, follows: its weights are harmonic over its own surface, equal to the skin's on
the rim and 0 farther than SHELL_BLEND_MM from every moving rim point.

The field is carried onto each mesh by ``transfer_weights``: vertices on a node take its value,
so the skin and the lips, which share the points of the skin's border, move as one. The two lips
share a few points at the corners of the mouth that lie on no node; both lips take the mean of
their separate values there, so the corners stay joined too.
"""

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from glasshead.geometry.skin_weights import (
    COINCIDENT_MM,
    harmonic_weights,
    hex_edges,
    transfer_weights,
    triangle_edges,
)
from glasshead.geometry.surface_distance import SurfaceDistance
from glasshead.pipeline.face_rig_sources import FaceSources

#: A face node lies on a bone (or a lip surface) when closer than this, mm.
ON_SURFACE_MM = 1.5
#: Fraction of the mouth's half-width, either side of the midline, where the lips are fixed to
#: their bone (nodes on a lip, and the lip's own vertices on no node: its inner side); toward the
#: corners their weights are free to blend. With 0.3 the lower lip's inner side took 0.7 to 0.8
#: (harmonic over the lip, from the corners' 0.2), lagged behind the jaw and showed its inside
#: as a U from 5 degrees; fixed over most of the width, the lip rides on the jaw as one piece.
LIP_MIDDLE_FRACTION = {"upper_lip": 0.75, "lower_lip": 0.75}
#: Nodes higher than this above the mouth centre with the maxilla or cranium as nearest bone are
#: fixed to 0 (the cheeks and nose stay put; below it the cheek stretches over the jaw).
UPPER_FACE_ABOVE_MOUTH_MM = 5.0
#: Radius of the region about each corner of the mouth that takes the corner's weight, mm
#: (16 mm, for a jaw opening to 25 degrees, drew the weights of the lower lip's outer half
#: down to 0.2 to 0.5; 8 mm let the upper lip's edges near a corner stretch over 5 times their
#: rest length; 12 mm keeps them within that and the corners from folding).
CORNER_RADIUS_MM = 12.0
#: Shell vertices farther than this from every rim point with a weight above RIM_MOVING keep
#: still; nearer, the shell blends from the rim's weights down to 0 (mm).
SHELL_BLEND_MM = 70.0
RIM_MOVING = 1e-3


def boundary_loops(faces):
    """Vertex sets of a triangle mesh's open borders: list of (k,) int64 arrays."""
    faces = np.asarray(faces, dtype=np.int64)
    edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    unique, count = np.unique(edges, axis=0, return_counts=True)
    border = unique[count == 1]
    if len(border) == 0:
        return []
    n = int(faces.max()) + 1
    graph = sp.coo_matrix((np.ones(len(border)), (border[:, 0], border[:, 1])), shape=(n, n))
    _, label = connected_components(graph, directed=False)
    on_border = np.unique(border)
    return [on_border[label[on_border] == k] for k in np.unique(label[on_border])]


def still_skin_vertices(src: FaceSources):
    """Skin vertices on the borders of the eyes and nostrils, which must not move: every open
    border but the mouth's (the one touching the lips) and the rim (the one shared with the head
    shell). Returns (k,) int64 skin vertex indices."""
    lips = cKDTree(np.concatenate([src.upper_lip[0], src.lower_lip[0]]))
    shell = cKDTree(src.head_shell[0])
    skin = src.face_skin[0]
    still = [loop for loop in boundary_loops(src.face_skin[1])
             if not np.any(lips.query(skin[loop])[0] <= COINCIDENT_MM)
             and not np.any(shell.query(skin[loop])[0] <= COINCIDENT_MM)]
    return np.concatenate(still) if still else np.zeros(0, dtype=np.int64)


def node_jaw_weights(src: FaceSources, mouth_centre, mouth_half_width):
    """Jaw weight of every face node; returns ((p,) float64, stats dict)."""
    nodes = src.nodes
    to_jaw = SurfaceDistance(*src.mandible).distance(nodes)
    to_upper = np.minimum(SurfaceDistance(*src.maxilla).distance(nodes),
                          SurfaceDistance(*src.cranium).distance(nodes))
    to_upper_lip = SurfaceDistance(*src.upper_lip).distance(nodes)
    to_lower_lip = SurfaceDistance(*src.lower_lip).distance(nodes)
    middle_upper = np.abs(nodes[:, 2]) < LIP_MIDDLE_FRACTION["upper_lip"] * mouth_half_width
    middle_lower = np.abs(nodes[:, 2]) < LIP_MIDDLE_FRACTION["lower_lip"] * mouth_half_width
    still = np.zeros(len(nodes), dtype=bool)
    still_nodes = src.skin_nodes[still_skin_vertices(src)]
    still[still_nodes[still_nodes >= 0]] = True

    attached = src.jaw_attachments
    kept = attached[(to_jaw[attached] <= to_upper[attached]) & ~still[attached]]
    one = np.zeros(len(nodes), dtype=bool)
    one[kept] = True
    # Where the lips touch, a node near both belongs to the nearer one.
    one |= middle_lower & (to_lower_lip < ON_SURFACE_MM) & (to_lower_lip <= to_upper_lip)
    zero = (to_upper < ON_SURFACE_MM) & (to_jaw > ON_SURFACE_MM)
    zero |= middle_upper & (to_upper_lip < ON_SURFACE_MM) & (to_upper_lip < to_lower_lip)
    zero |= (to_upper < to_jaw) & (nodes[:, 1] > mouth_centre[1] + UPPER_FACE_ABOVE_MOUTH_MM)
    zero &= ~one
    zero |= still
    one &= ~still
    fixed = np.flatnonzero(one | zero)
    weights = harmonic_weights(nodes, hex_edges(src.elems), fixed, one[fixed].astype(float))
    stats = {"attachments_listed": len(attached), "attachments_used": len(kept),
             "nodes_fixed_to_jaw": int(one.sum()), "nodes_fixed_to_skull": int(zero.sum()),
             "still_border_nodes": int(still.sum())}
    return weights, stats


def lip_middle(name, vertices, nodes, mouth_half_width):
    """Vertices of a lip within its LIP_MIDDLE_FRACTION of the mouth's half-width of the midline
    and on no face node (the lip's inner side, which the node field does not reach); (k,) int64."""
    vertices = np.asarray(vertices, dtype=np.float64)
    off_node = cKDTree(nodes).query(vertices)[0] > COINCIDENT_MM
    middle = np.abs(vertices[:, 2]) < LIP_MIDDLE_FRACTION[name] * mouth_half_width
    return np.flatnonzero(middle & off_node)


def mesh_jaw_weights(meshes, nodes, node_weights, mouth_half_width, skin_nodes):
    """Per-vertex jaw weights of the face skin and both lips.

    meshes : dict with ``face_skin``, ``upper_lip``, ``lower_lip`` -> (vertices, faces).
    nodes : (p, 3) face nodes; node_weights : (p,) from ``node_jaw_weights``.
    skin_nodes : (n,) the node of each face_skin vertex (-1: none): each takes its node's weight,
        also where the seam's fairing moved it off the node.
    mouth_half_width : mm; the middle of each lip (``lip_middle``) is fixed to its bone's weight.
    Returns (dict name -> (n,) float64 in [0, 1], number of lip corner points shared).
    """
    bone = {"upper_lip": 0.0, "lower_lip": 1.0}
    middles = {name: lip_middle(name, meshes[name][0], nodes, mouth_half_width) for name in bone}

    def carry(name, extra=None):
        vertices, faces = meshes[name]
        if extra is None:
            extra = (np.zeros(0, dtype=np.int64), np.zeros(0))
        if name in bone:
            fixed = np.setdiff1d(middles[name], extra[0])
            extra = (np.concatenate([extra[0], fixed]),
                     np.concatenate([extra[1], np.full(len(fixed), bone[name])]))
        return np.clip(transfer_weights(vertices, faces, nodes, node_weights, extra), 0.0, 1.0)

    names = ("face_skin", "upper_lip", "lower_lip")
    on_node = np.flatnonzero(np.asarray(skin_nodes) >= 0)
    weights = {name: carry(name) for name in names[1:]}
    weights["face_skin"] = carry("face_skin", (on_node, node_weights[skin_nodes[on_node]]))
    upper, lower = meshes["upper_lip"][0], meshes["lower_lip"][0]
    distance, partner = cKDTree(upper).query(lower)
    in_lower = np.flatnonzero(distance <= COINCIDENT_MM)
    in_upper = partner[in_lower]
    if len(in_lower) == 0:
        raise ValueError("the lips share no point: no corners of the mouth")
    shared = 0.5 * (weights["upper_lip"][in_upper] + weights["lower_lip"][in_lower])
    weights["upper_lip"] = carry("upper_lip", (in_upper, shared))
    weights["lower_lip"] = carry("lower_lip", (in_lower, shared))
    corners = []
    for side in (-1.0, 1.0):
        mine = np.sign(lower[in_lower, 2]) == side
        corners.append((lower[in_lower[mine]].mean(axis=0), float(shared[mine].mean())))
    for name in names:
        weights[name] = relax_corners(meshes[name][0], weights[name], corners)
    return weights, len(in_lower)


def relax_corners(vertices, weights, corners, radius=CORNER_RADIUS_MM):
    """Flatten the weights about the corners of the mouth.

    At a corner the lower lip's weight (near 1) meets the upper lip's (near 0): whatever the
    field, points close around the corner would turn about it by up to the full jaw motion and
    fold as the mouth opens wide. Within ``radius`` of a corner the weight is drawn to the
    corner's: w' = w_c + (w - w_c) S(r / radius), S the cubic smoothstep, so points near the
    corner move together and the fan of tissue around it stretches instead.
    corners : [(centre (3,), weight)].  Returns (n,) float64.
    """
    result = np.asarray(weights, dtype=np.float64).copy()
    for centre, corner_weight in corners:
        t = np.clip(np.linalg.norm(vertices - centre, axis=1) / radius, 0.0, 1.0)
        result = corner_weight + (result - corner_weight) * t * t * (3.0 - 2.0 * t)
    return result


def shell_jaw_weights(shell_vertices, shell_faces, skin_vertices, skin_weights):
    """Jaw weights of the head shell: the skin's on the shared rim, 0 farther than
    SHELL_BLEND_MM from every moving rim point, harmonic in between. Returns (n,) float64."""
    shell_vertices = np.asarray(shell_vertices, dtype=np.float64)
    distance, nearest = cKDTree(skin_vertices).query(shell_vertices)
    rim = np.flatnonzero(distance <= COINCIDENT_MM)
    if len(rim) == 0:
        raise ValueError("the head shell shares no point with the face skin")
    rim_weights = np.asarray(skin_weights)[nearest[rim]]
    moving = shell_vertices[rim[rim_weights > RIM_MOVING]]
    far = np.ones(len(shell_vertices), dtype=bool)
    if len(moving):
        far = cKDTree(moving).query(shell_vertices)[0] > SHELL_BLEND_MM
    far[rim] = False
    fixed = np.concatenate([rim, np.flatnonzero(far)])
    values = np.concatenate([rim_weights, np.zeros(int(far.sum()))])
    edges = triangle_edges(shell_faces)
    return np.clip(harmonic_weights(shell_vertices, edges, fixed, values), 0.0, 1.0)
