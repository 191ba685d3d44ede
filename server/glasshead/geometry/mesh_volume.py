"""Volume, vertex normals and closedness of triangle meshes (twins in web/src/core/tongue.js).

Volume by the divergence theorem: for a closed mesh whose triangles wind counter-clockwise seen
from outside, V = sum over triangles of a . (b x c) / 6 (the signed volumes of the tetrahedra
from the origin; the parts outside the body cancel). Positive for outward winding.
"""

import numpy as np


def _check(vertices, triangles):
    vertices = np.asarray(vertices, dtype=np.float64)
    triangles = np.asarray(triangles)
    if vertices.ndim != 2 or vertices.shape[1] != 3:
        raise ValueError(f"vertices must be (n, 3), got {vertices.shape}")
    if triangles.ndim != 2 or triangles.shape[1] != 3 or not np.issubdtype(triangles.dtype,
                                                                            np.integer):
        raise ValueError(f"triangles must be (m, 3) integers, got {triangles.shape}")
    if triangles.size and (triangles.min() < 0 or triangles.max() >= len(vertices)):
        raise ValueError("triangle indices out of range")
    return vertices, triangles


def mesh_volume(vertices, triangles):
    """Signed volume, mm^3, of a closed mesh: vertices (n, 3) float, triangles (m, 3) int."""
    vertices, triangles = _check(vertices, triangles)
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def vertex_normals(vertices, triangles):
    """Unit normals (n, 3) float64: the area-weighted mean of the adjacent triangles' normals.

    Each triangle adds its unnormalised normal (b - a) x (c - a), whose length is twice its
    area, to its three vertices. A vertex with no area around it gets (0, 0, 0).
    """
    vertices, triangles = _check(vertices, triangles)
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    face = np.cross(b - a, c - a)
    corners = triangles.reshape(-1)
    normals = np.stack([np.bincount(corners, np.repeat(face[:, axis], 3), len(vertices))
                        for axis in range(3)], axis=1)
    length = np.linalg.norm(normals, axis=1)
    nonzero = length > 0
    normals[nonzero] /= length[nonzero, None]
    return normals


def is_closed_manifold(triangles):
    """True when every directed edge appears once and its reverse once (closed, consistently wound)."""
    triangles = np.asarray(triangles)
    edges = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
    directed, counts = np.unique(edges, axis=0, return_counts=True)
    if np.any(counts != 1):
        return False
    forward = {tuple(e) for e in directed.tolist()}
    return all((b, a) in forward for a, b in forward)
