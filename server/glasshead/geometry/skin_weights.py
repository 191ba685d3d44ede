"""Jaw skinning weights: a harmonic field over the face's hexahedral mesh, carried onto surfaces.

A weight of 1 means a point rides fully on the mandible, 0 that it stays with the maxilla and
cranium. The known values (nodes attached to either bone, the lips' midline parts) are fixed and
the rest is the discrete harmonic interpolant: each free node holds the edge-length-weighted mean
of its neighbours. Harmonic weights are smooth, bounded by the fixed values (maximum principle, so
always within [0, 1]) and follow the tissue's connectivity rather than straight-line distance, so
the upper and lower lips, which touch but share no element, get different weights (Baran and
Popovic 2007, "Automatic rigging and animation of 3D characters", section 4, use the same
principle for bone weights on a surface; here it runs through the tissue volume).
"""

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components
from scipy.sparse.linalg import spsolve
from scipy.spatial import cKDTree

#: The 12 edges of a hexahedron as local node pairs (ANSYS/ArtiSynth node order).
HEX_EDGES = ((0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
             (0, 4), (1, 5), (2, 6), (3, 7))

#: Two points closer than this (mm) are the same point (surface vertex on a face node): built
#: meshes lie on a 2^-8 mm lattice (pipeline/quantized_glb.py), within 0.0034 mm of a node.
COINCIDENT_MM = 1e-2

#: Shortest edge length (mm) used in 1 / length weights, so a degenerate edge cannot dominate.
MIN_EDGE_MM = 1e-3


def hex_edges(elems):
    """Unique undirected edges of a hexahedral mesh.

    elems : (k, 8) int, zero-based node indices; wedges may repeat an index.
    Returns (e, 2) int64 with edge[:, 0] < edge[:, 1].
    """
    elems = np.asarray(elems)
    if elems.ndim != 2 or elems.shape[1] != 8:
        raise ValueError(f"elems must have shape (k, 8), got {elems.shape}")
    pairs = np.concatenate([elems[:, list(p)] for p in HEX_EDGES]).astype(np.int64)
    pairs = np.sort(pairs, axis=1)
    pairs = pairs[pairs[:, 0] != pairs[:, 1]]
    return np.unique(pairs, axis=0)


def triangle_edges(faces):
    """Unique undirected edges of a triangle mesh; faces (m, 3) int. Returns (e, 2) int64."""
    faces = np.asarray(faces)
    if faces.ndim != 2 or faces.shape[1] != 3:
        raise ValueError(f"faces must have shape (m, 3), got {faces.shape}")
    pairs = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]).astype(np.int64)
    pairs = np.sort(pairs, axis=1)
    return np.unique(pairs[pairs[:, 0] != pairs[:, 1]], axis=0)


def harmonic_weights(points, edges, fixed_index, fixed_value):
    """Harmonic interpolation over a graph with fixed (Dirichlet) values.

    points : (n, 3) float, node positions (for 1 / length edge weights).
    edges : (e, 2) int node pairs.   fixed_index : (f,) int.   fixed_value : (f,) float.
    Every connected component must hold at least one fixed node.
    Returns (n,) float64; fixed nodes keep their values exactly.
    """
    points = np.asarray(points, dtype=np.float64)
    edges = np.asarray(edges, dtype=np.int64)
    fixed_index = np.asarray(fixed_index, dtype=np.int64)
    fixed_value = np.asarray(fixed_value, dtype=np.float64)
    n = len(points)
    if fixed_index.shape != fixed_value.shape or fixed_index.ndim != 1:
        raise ValueError("fixed_index and fixed_value must be 1-D arrays of the same length")
    if len(fixed_index) and (fixed_index.min() < 0 or fixed_index.max() >= n):
        raise ValueError("fixed_index holds an index outside the points")
    if len(np.unique(fixed_index)) != len(fixed_index):
        raise ValueError("fixed_index repeats a node")
    lengths = np.linalg.norm(points[edges[:, 0]] - points[edges[:, 1]], axis=1)
    k = 1.0 / np.maximum(lengths, MIN_EDGE_MM)
    pairs = (np.r_[edges[:, 0], edges[:, 1]], np.r_[edges[:, 1], edges[:, 0]])
    adjacency = sp.coo_matrix((np.r_[k, k], pairs), shape=(n, n)).tocsr()
    is_fixed = np.zeros(n, dtype=bool)
    is_fixed[fixed_index] = True
    _, label = connected_components(adjacency, directed=False)
    unanchored = np.setdiff1d(label, label[is_fixed])
    if len(unanchored):
        raise ValueError(f"{len(unanchored)} connected part(s) of the graph have no fixed node")
    laplacian = sp.diags(np.asarray(adjacency.sum(axis=1)).ravel()) - adjacency
    free = np.flatnonzero(~is_fixed)
    values = np.zeros(n)
    values[fixed_index] = fixed_value
    if len(free):
        lff = laplacian[free][:, free].tocsc()
        rhs = -laplacian[free][:, fixed_index] @ fixed_value
        values[free] = spsolve(lff, rhs)
    return values


def transfer_weights(vertices, faces, node_points, node_weights, extra_fixed=None):
    """Carry node weights onto a triangle surface that shares some of its points with the nodes.

    Vertices lying on a node (within COINCIDENT_MM) take its weight exactly, so a surface and the
    skin stay joined wherever they share points; ``extra_fixed`` pins more vertices (points shared
    with another surface but with no node). The others get the harmonic interpolant over the
    surface's own edges. A connected part of the surface touching no node takes, at every vertex,
    the weight of the nearest node.

    vertices : (n, 3) float.  faces : (m, 3) int.  node_points : (p, 3) float.
    node_weights : (p,) float.  extra_fixed : optional (indices (k,) int, values (k,) float).
    Returns (n,) float64.
    """
    vertices = np.asarray(vertices, dtype=np.float64)
    node_weights = np.asarray(node_weights, dtype=np.float64)
    if len(node_weights) != len(node_points):
        raise ValueError("node_weights must have one value per node point")
    distance, nearest = cKDTree(np.asarray(node_points, dtype=np.float64)).query(vertices)
    edges = triangle_edges(faces)
    n = len(vertices)
    graph = sp.coo_matrix((np.ones(len(edges)), (edges[:, 0], edges[:, 1])), shape=(n, n))
    _, label = connected_components(graph, directed=False)
    fixed = distance <= COINCIDENT_MM
    values = node_weights[nearest]
    if extra_fixed is not None:
        index, value = (np.asarray(a) for a in extra_fixed)
        if index.shape != value.shape or index.ndim != 1:
            raise ValueError("extra_fixed must be two 1-D arrays of the same length")
        fixed[index] = True
        values[index] = value
    for part in np.unique(label):
        members = label == part
        if not fixed[members].any():
            fixed |= members
    index = np.flatnonzero(fixed)
    return harmonic_weights(vertices, edges, index, values[index])
