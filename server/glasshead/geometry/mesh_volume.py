"""Volume, vertex normals and closedness of triangle meshes (twins in web/src/core/tongue.js).

Volume by the divergence theorem: for a closed mesh whose triangles wind counter-clockwise seen
from outside, V = sum over triangles of a . (b x c) / 6 (the signed volumes of the tetrahedra
from the origin; the parts outside the body cancel). Positive for outward winding.
"""

import numpy as np
import numpy.typing as npt


def _check(vertices: npt.ArrayLike,
           triangles: npt.ArrayLike) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.integer]]:
    v = np.asarray(vertices, dtype=np.float64)
    t = np.asarray(triangles)
    if v.ndim != 2 or v.shape[1] != 3:
        raise ValueError(f"vertices must be (n, 3), got {v.shape}")
    if t.ndim != 2 or t.shape[1] != 3 or not np.issubdtype(t.dtype, np.integer):
        raise ValueError(f"triangles must be (m, 3) integers, got {t.shape}")
    if t.size and (t.min() < 0 or t.max() >= len(v)):
        raise ValueError("triangle indices out of range")
    return v, t


def mesh_volume(vertices: npt.ArrayLike, triangles: npt.ArrayLike) -> float:
    """Signed volume, mm^3, of a closed mesh: vertices (n, 3) float, triangles (m, 3) int."""
    v, t = _check(vertices, triangles)
    a, b, c = (v[t[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def vertex_normals(vertices: npt.ArrayLike, triangles: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Unit normals (n, 3) float64: the area-weighted mean of the adjacent triangles' normals.

    Each triangle adds its unnormalised normal (b - a) x (c - a), whose length is twice its
    area, to its three vertices. A vertex with no area around it gets (0, 0, 0).
    """
    v, t = _check(vertices, triangles)
    a, b, c = (v[t[:, k]] for k in range(3))
    face = np.cross(b - a, c - a)
    corners = t.reshape(-1)
    # bincount with weights sums in float64 (numpy's stubs declare its integer form only)
    normals = np.stack([np.bincount(corners, np.repeat(face[:, axis], 3), len(v))
                        for axis in range(3)], axis=1).astype(np.float64, copy=False)
    length = np.linalg.norm(normals, axis=1)
    nonzero = length > 0
    normals[nonzero] /= length[nonzero, None]
    return normals


def is_closed_manifold(triangles: npt.ArrayLike) -> bool:
    """True when every directed edge appears once and its reverse once (closed, consistently
    wound)."""
    t = np.asarray(triangles)
    edges = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    directed, counts = np.unique(edges, axis=0, return_counts=True)
    if np.any(counts != 1):
        return False
    forward = {tuple(e) for e in directed.tolist()}
    return all((b, a) in forward for a, b in forward)
