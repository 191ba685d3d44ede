"""Fairing across the seam where the face skin meets the head shell.

The shell (``head_shell``) starts on the skin's rim and matches its slope there, but the rim of
the Badin mask is where its finite-element mesh was cut: the last elements fold (a sliver at the
temple turned 60 degrees against its neighbours, a groove two and three vertices in from the rim in
front of the ear), and each notch of the rim runs a short ridge up the shell's meridians. Seen in
the app these read as a crease along the seam, sharpest at the temples.

So the band on both sides of the seam is faired together, as one mesh:

- what moves: the skin vertices within ``SKIN_HOPS`` edges of the rim, each along its own vertex
  normal, and the shell's first ``SHELL_RINGS`` rings, each vertex along its ray from the shell's
  centre (the shell's own parameterisation, so its rings cannot slide over each other). One
  unknown per vertex: a distance moved.
- what it minimises: sum over the band and its neighbours of (n . L x)^2, the normal part of the
  umbrella Laplacian (x minus the mean of its neighbours), which is about the mean curvature
  times the squared edge length: a crease costs much, a smooth bend little, and sliding along the
  surface (the tangential part) costs nothing. Plus ``STAY_WEIGHT`` * t^2, which keeps the band
  near where it was, so the fairing smooths the seam rather than reshaping the head.
- how: linear least squares in the distances, solved three times (``PASSES``), each time along
  the smoothed normals of the previous solution.

Everything else stays where it was: the skin further in (the face as measured), the shell beyond
its first rings. The faired skin vertices keep their face node ids (the jaw skinning reads node
weights at vertex positions, ``face_rig_weights.transfer_weights``), though they now lie up to a
few millimetres off their nodes.
"""

from dataclasses import replace

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.sparse.csgraph import dijkstra

from glasshead.geometry.skin_weights import triangle_edges
from glasshead.pipeline.head_shell import build_head_shell, vertex_normals

#: Skin vertices within this many edges of the rim move (the rim itself is 0).
SKIN_HOPS = 2
#: Shell rings, after the rim, that move.
SHELL_RINGS = 12
#: Weight of t^2 (mm^2) against the squared curvature term: how firmly the band stays put.
STAY_WEIGHT = 0.05
#: Least-squares solves, each with the normals of the previous one.
PASSES = 3
#: Umbrella-averaging steps of the normals the curvature is measured along: with the raw normals
#: of the folded rim the passes did not settle (a fold of 130 degrees after six); with these
#: they do by the third.
NORMAL_SMOOTHING = 5


def close_head(skin, cranium_vertices, neck=None):
    """The head shell (with ``neck``, if given) for a ``FaceSkin`` and the seam between them
    faired: returns (the skin with its border band faired, the ``HeadShell``, its params holding
    ``seam_fairing``)."""
    shell = build_head_shell(skin.vertices, skin.faces, cranium_vertices, neck)
    skin_vertices, shell_vertices, stats = fair_seam(skin.vertices, skin.faces, shell)
    return (replace(skin, vertices=skin_vertices),
            replace(shell, vertices=shell_vertices, params=shell.params | {"seam_fairing": stats}))


def welded(skin_vertices, skin_faces, shell_vertices, shell_faces, rim):
    """Skin and shell as one mesh: (vertices, faces), the skin's vertices first, then the shell's
    after its ring 0 (which is the skin's rim, ``rim`` giving the skin ids)."""
    index = np.arange(len(shell_vertices)) + len(skin_vertices) - len(rim)
    index[: len(rim)] = rim
    vertices = np.vstack([skin_vertices, shell_vertices[len(rim):]])
    return vertices, np.vstack([skin_faces, index[shell_faces]])


def adjacency(faces, count):
    """Symmetric (count, count) sparse matrix with a 1 for each mesh edge."""
    edges = triangle_edges(faces)
    ones = np.ones(2 * len(edges))
    graph = sp.coo_matrix((ones, (np.r_[edges[:, 0], edges[:, 1]],
                                  np.r_[edges[:, 1], edges[:, 0]])), shape=(count, count))
    return graph.tocsr()


def fair_seam(skin_vertices, skin_faces, shell):
    """Fair the band across the skin-shell seam (module docstring).

    skin_vertices (n, 3), skin_faces (m, 3): the face skin; shell: its ``HeadShell``.
    Returns (skin vertices (n, 3), shell vertices, stats dict); the faces are unchanged and the
    shell's ring 0 is again exactly the faired skin's rim.
    """
    skin_vertices = np.asarray(skin_vertices, dtype=np.float64)
    skin_faces = np.asarray(skin_faces, dtype=np.int64)
    rim, n_skin, n_rim = shell.rim, len(skin_vertices), len(shell.rim)
    vertices, faces = welded(skin_vertices, skin_faces, shell.vertices, shell.faces, rim)
    count = len(vertices)
    graph = adjacency(faces, count)
    degree = np.asarray(graph.sum(axis=1)).ravel()
    laplacian = (sp.eye(count) - sp.diags(1.0 / degree) @ graph).tocsr()

    hops = dijkstra(graph[:n_skin][:, :n_skin], directed=False, indices=rim, unweighted=True,
                    min_only=True)
    free = np.zeros(count, dtype=bool)
    free[:n_skin] = hops <= SKIN_HOPS
    free[n_skin:n_skin + SHELL_RINGS * n_rim] = True
    free_ids = np.flatnonzero(free)
    rows = np.flatnonzero(free | (graph @ free.astype(np.float64) > 0))

    centre = np.asarray(shell.params["centre_mm"], dtype=np.float64)
    along = vertices - centre
    along /= np.linalg.norm(along, axis=1)[:, None]
    along[:n_skin] = vertex_normals(skin_vertices, skin_faces)

    rest_curvature = _normal_curvature(vertices, faces, laplacian, rows)
    band = laplacian[rows].tocoo()
    moved = np.zeros(count)
    faired = vertices
    for _ in range(PASSES):
        normals = _smoothed_normals(faired, faces, graph, degree)
        at_row = rows[band.row]
        # n_j . L (x + along t) = n_j . L x + sum_k L_jk (n_j . along_k) t_k
        values = band.data * np.einsum("ij,ij->i", normals[at_row], along[band.col])
        system = sp.csr_matrix((values, (band.row, band.col)), shape=(len(rows), count))
        system = system[:, free_ids]
        offset = np.einsum("ij,ij->i", normals[rows], laplacian[rows] @ vertices)
        lhs = (system.T @ system + STAY_WEIGHT * sp.eye(len(free_ids))).tocsc()
        moved[:] = 0.0
        moved[free_ids] = spla.spsolve(lhs, -(system.T @ offset))
        faired = vertices + along * moved[:, None]

    skin_out = faired[:n_skin]
    shell_out = np.vstack([skin_out[rim], faired[n_skin:]])
    stats = {
        "method": (f"the skin within {SKIN_HOPS} edges of the rim (along its normals) and the "
                   f"shell's first {SHELL_RINGS} rings (along their rays) faired together: least "
                   f"squares of the normal part of the umbrella Laplacian, plus {STAY_WEIGHT} t^2"),
        "skin_vertices_moved": int(np.sum(np.abs(moved[:n_skin]) > 1e-6)),
        "skin_moved_max_mm": round(float(np.abs(moved[:n_skin]).max()), 3),
        "shell_moved_max_mm": round(float(np.abs(moved[n_skin:]).max()), 3),
        "normal_curvature_rms_before_mm": round(rest_curvature, 4),
        "normal_curvature_rms_after_mm": round(
            _normal_curvature(faired, faces, laplacian, rows), 4),
    }
    return skin_out, shell_out, stats


def _normal_curvature(vertices, faces, laplacian, rows):
    """RMS over ``rows`` of n . L x, mm: the quantity the fairing minimises."""
    normals = vertex_normals(vertices, faces)[rows]
    return float(np.sqrt(np.mean(np.einsum("ij,ij->i", normals, laplacian[rows] @ vertices) ** 2)))


def _smoothed_normals(vertices, faces, graph, degree):
    """Vertex normals averaged with their neighbours' NORMAL_SMOOTHING times; (n, 3) unit."""
    normals = vertex_normals(vertices, faces)
    for _ in range(NORMAL_SMOOTHING):
        normals = normals + (graph @ normals) / degree[:, None]
        normals /= np.linalg.norm(normals, axis=1)[:, None]
    return normals
