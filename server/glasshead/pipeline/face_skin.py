"""The outer skin of the Badin face: the outward boundary of its hexahedral finite-element mesh.

How the skin is found (Badin et al. face model, ``face.node`` / ``face.elem``):

1. Every hexahedron has six quadrilateral faces (node order 0-3 is one quad, 4-7 the opposite
   one; wedges repeat a node id, so a face with three distinct nodes is a triangle and one with
   two is an edge and is dropped). A face used by exactly one element is on the boundary.
2. The boundary is a closed shell around the tissue: the outer skin, the inner surface lying on
   the bones and teeth, and thin walls at the mask's rim, eyes, nostrils and mouth slit. The mesh
   was built in layers through the tissue: each element's quads 0-3 and 4-7 face across the
   tissue, its other four faces along it. Starting from a boundary quad that is quad 0-3 or 4-7
   of its element and stepping from each element to the neighbour behind the opposite quad, one
   reaches the boundary again on the other side of the tissue: a *thickness column*. Its two end
   quads are one outer-skin quad and one inner-surface quad (a few columns end on a side quad,
   where the last element's layering is turned). Walls never start such a column.
3. Of the two ends, the outer one lies farther out along the ray from a head centre (behind the
   face, at mouth height: the middle of the cranium, see ``head_centre``): the column's direction
   from its inner to its outer end agrees with that ray. This fails only where the tissue runs
   nearly along the ray (eyelids); there the misread quads form small islands apart from the main
   skin, so each column whose "outer" end lies outside the largest connected outer region is
   turned over, and the largest connected region is kept.
4. Quads are split on their shorter diagonal; triangles are wound so that their normals point out
   of the tissue (away from the element's centre), which on the outer skin is out of the head.
5. The lips are meshes of their own whose outer surface lies on the skin (``uncover_lips``): the
   skin's triangles over them are dropped and its new border is laid onto them, so the skin ends
   where each lip begins. Left in, the coarse skin triangles and the finer lip surface between
   the shared points part as the lips stretch, and the skin shows through the lip in patches.

Classifying by distance to the bones was tried and rejected: the forehead and the temples have no
bone mesh beneath them (the cranium is a band above the brows), so there the inner and outer
quads are equally far from any bone.
"""

from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp
import trimesh
from scipy.sparse.csgraph import connected_components

from glasshead.geometry.frame import badin_to_project

# Quads of a hexahedron as local node positions, ANSYS/ArtiSynth order: two opposite "cap"
# quads (0-3 and 4-7) then the four sides. OPPOSITE[i] is the quad across the element from i.
HEX_QUADS = ((0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7))
OPPOSITE = (1, 0, 4, 5, 2, 3)
CAP_QUADS = (0, 1)
#: A skin point with a lip this close beneath it (along the skin's inward normal) lies over the
#: lip, mm. The lips' outer surfaces lie on the skin, up to 3 mm under it at their lower edge.
LIP_BENEATH_MM = 3.0
#: Rays toward the lip start this far out of the skin, mm (a lip point on the skin is a hit).
ON_LIP_MM = 1e-3


@dataclass
class FaceSkin:
    """The outer skin in the project frame.

    vertices : (n, 3) float64, mm.   faces : (m, 3) int64, outward winding.
    node_ids : (n,) int64, the face.node id of each skin vertex (for jaw attachments); -1 for
        the border vertices laid onto a lip (``uncover_lips``).
    stats : dict of counts for the build report.
    """

    vertices: np.ndarray
    faces: np.ndarray
    node_ids: np.ndarray
    stats: dict


def _distinct(nodes):
    out = []
    for n in nodes:
        if n not in out:
            out.append(n)
    return out


def _element_faces(elems):
    """Map each face (sorted distinct node tuple) to the list of (element, local quad) using it."""
    faces: dict[tuple, list[tuple[int, int]]] = {}
    for e, hexa in enumerate(elems):
        for q, quad in enumerate(HEX_QUADS):
            nodes = _distinct([int(hexa[i]) for i in quad])
            if len(nodes) >= 3:
                faces.setdefault(tuple(sorted(nodes)), []).append((e, q))
    return faces


def _face_key(elems, e, q):
    nodes = _distinct([int(elems[e][i]) for i in HEX_QUADS[q]])
    return tuple(sorted(nodes)) if len(nodes) >= 3 else None


def _column_end(elems, faces, e, q, max_steps=64):
    """Walk across the tissue from boundary quad (e, q); return the far boundary key or None."""
    for _ in range(max_steps):
        key = _face_key(elems, e, OPPOSITE[q])
        if key is None:
            return None
        users = [u for u in faces[key] if u[0] != e]
        if not users:
            return key
        e, q = users[0]
    return None


def _oriented_polygon(points, elems, e, q):
    """Distinct node indices of quad q of element e, ordered so the normal leaves the element."""
    nodes = _distinct([int(elems[e][i]) for i in HEX_QUADS[q]])
    p = points[nodes]
    normal = np.cross(p[1] - p[0], p[2] - p[0])
    if len(nodes) == 4:
        normal = normal + np.cross(p[2] - p[0], p[3] - p[0])
    if normal @ (p.mean(axis=0) - points[elems[e]].mean(axis=0)) < 0:
        nodes = nodes[::-1]
    return nodes


def _triangulate(points, polygons):
    """Split quads on the shorter diagonal; returns (m, 3) int64."""
    tris = []
    for poly in polygons:
        if len(poly) == 3:
            tris.append(poly)
            continue
        a, b, c, d = poly
        if np.linalg.norm(points[a] - points[c]) <= np.linalg.norm(points[b] - points[d]):
            tris += [[a, b, c], [a, c, d]]
        else:
            tris += [[a, b, d], [b, c, d]]
    return np.asarray(tris, dtype=np.int64)


def _components(polygons):
    """Edge-connected component label of each polygon; (k,) int."""
    edge_owner: dict[tuple[int, int], int] = {}
    rows, cols = [], []
    for i, poly in enumerate(polygons):
        for a, b in zip(poly, poly[1:] + poly[:1], strict=True):
            key = (min(a, b), max(a, b))
            if key in edge_owner:
                rows.append(edge_owner[key])
                cols.append(i)
            else:
                edge_owner[key] = i
    n = len(polygons)
    graph = sp.coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))
    return connected_components(graph, directed=False)[1]


def head_centre(cranium_vertices):
    """Centre used to tell outward from inward: middle of the cranium in x, at the origin's height.

    cranium_vertices : (n, 3) float, project frame mm. Returns (3,) float64.
    """
    lo, hi = np.min(cranium_vertices, axis=0), np.max(cranium_vertices, axis=0)
    return np.array([(lo[0] + hi[0]) / 2.0, 0.0, 0.0])


def extract_face_skin(node_ids, nodes_m, elems, centre):
    """Outer skin of the Badin hexahedral face mesh, in the project frame.

    node_ids : (n,) int, face.node ids.   nodes_m : (n, 3) float, Badin metres.
    elems : (k, 8) int node ids (face.elem).   centre : (3,) float, project mm (``head_centre``).
    Returns a ``FaceSkin``.
    """
    node_ids = np.asarray(node_ids, dtype=np.int64)
    points = badin_to_project(nodes_m)
    index_of = {int(n): i for i, n in enumerate(node_ids)}
    elems = np.vectorize(index_of.__getitem__, otypes=[np.int64])(np.asarray(elems))
    faces = _element_faces(elems)
    boundary = {key: users[0] for key, users in faces.items() if len(users) == 1}

    # Thickness columns: pairs of boundary cap quads joined through the tissue.
    found = set()
    for key, (e, q) in boundary.items():
        if q not in CAP_QUADS:
            continue
        end = _column_end(elems, faces, e, q)
        if end is not None:
            found.add((min(key, end), max(key, end)))
    pairs = sorted(found)
    if not pairs:
        raise ValueError("the face mesh has no thickness columns; is face.elem a layered hex mesh?")

    centroid = {key: points[list(key)].mean(axis=0) for pair in pairs for key in pair}
    a = np.array([centroid[p[0]] for p in pairs])
    b = np.array([centroid[p[1]] for p in pairs])
    a_is_outer = np.einsum("ij,ij->i", a - b, (a + b) / 2.0 - centre) > 0

    polygons_of = {}
    for key in centroid:
        e, q = boundary[key]
        polygons_of[key] = _oriented_polygon(points, elems, e, q)

    def outer_keys(flags):
        return [p[0] if f else p[1] for p, f in zip(pairs, flags, strict=True)]

    # Turn over columns whose outer end is off the main skin, then keep the main skin.
    labels = _components([polygons_of[k] for k in outer_keys(a_is_outer)])
    main = np.argmax(np.bincount(labels))
    turned = labels != main
    a_is_outer = a_is_outer ^ turned
    keys = outer_keys(a_is_outer)
    labels = _components([polygons_of[k] for k in keys])
    keep = labels == np.argmax(np.bincount(labels))
    polygons = [polygons_of[k] for k, kept in zip(keys, keep, strict=True) if kept]

    tris = _triangulate(points, polygons)
    used, inverse = np.unique(tris, return_inverse=True)
    stats = {
        "boundary_faces": len(boundary),
        "thickness_columns": len(pairs),
        "columns_turned_over": int(turned.sum()),
        "wall_faces_dropped": len(boundary) - 2 * len(pairs),
        "outer_faces": len(polygons),
        "islands_dropped": int((~keep).sum()),
    }
    return FaceSkin(points[used], inverse.reshape(-1, 3).astype(np.int64), node_ids[used], stats)


def _lip_beneath(lip, points, normals):
    """How each point lies over a lip: (over (n,) bool, depth (n,) float mm, landing (n, 3)).

    A point is over the lip when it lies inside the lip or on it (depth 0, landing on itself), or
    when the lip is within LIP_BENEATH_MM beneath it along -normal (the skin's inward normal):
    depth is then the distance down to the lip and landing the point reached there.
    """
    hit, ray, _ = lip.ray.intersects_location(points + ON_LIP_MM * normals, -normals,
                                              multiple_hits=False)
    depth = np.full(len(points), np.inf)
    depth[ray] = np.linalg.norm(hit - points[ray], axis=1)
    landing = np.array(points, dtype=np.float64)
    landing[ray] = hit
    # Signed distance (positive inside) rather than Trimesh.contains, whose answer for points on
    # the surface changes from run to run.
    inside = trimesh.proximity.signed_distance(lip, points) >= -ON_LIP_MM
    depth[inside] = 0.0
    landing[inside] = points[inside]
    return inside | (depth <= LIP_BENEATH_MM), depth, landing


def uncover_lips(skin, lips):
    """The skin without the triangles lying over a lip, its new border laid onto the lips.

    skin : ``FaceSkin``.  lips : list of closed (vertices (n, 3), faces) of the lips, project mm,
    whose outer surfaces lie on the skin. A skin triangle is over a lip when its corners and its
    centre each lie inside that lip or have it within LIP_BENEATH_MM beneath them: there the lip,
    whose surface is finer than the skin's, is what shows. Where the lip runs on under the skin,
    the skin's new border would stand clear of it, a slot through which the teeth show; so border
    vertices over a lip are moved down onto it (their ``node_ids`` become -1: they no longer lie
    on a face node). Vertices no triangle uses any more are dropped with their node ids.
    Returns a new ``FaceSkin`` whose stats count the triangles dropped (``lip_faces_dropped``)
    and the border vertices moved (``lip_border_moved``, and the largest move in mm).
    """
    mesh = trimesh.Trimesh(skin.vertices, skin.faces, process=False)
    centres = mesh.triangles_center
    covered = np.zeros(len(skin.faces), dtype=bool)
    depth = np.full(len(skin.vertices), np.inf)
    landing = np.array(skin.vertices, dtype=np.float64)
    for vertices, faces in lips:
        lip = trimesh.Trimesh(np.asarray(vertices, dtype=np.float64), faces, process=False)
        if not lip.is_watertight:
            raise ValueError("a lip mesh must be closed to tell which skin lies over it")
        corners, corner_depth, corner_landing = _lip_beneath(lip, skin.vertices,
                                                             mesh.vertex_normals)
        centre_over = _lip_beneath(lip, centres, mesh.face_normals)[0]
        covered |= corners[skin.faces].all(axis=1) & centre_over
        nearer = corner_depth < depth
        depth[nearer], landing[nearer] = corner_depth[nearer], corner_landing[nearer]
    if covered.all():
        raise ValueError("every skin triangle lies over a lip: the lips are not this face's")
    border = np.zeros(len(skin.vertices), dtype=bool)
    border[skin.faces[covered].ravel()] = True
    border &= np.isin(np.arange(len(skin.vertices)), skin.faces[~covered])
    moved = border & (depth > ON_LIP_MM) & (depth <= LIP_BENEATH_MM)
    vertices = np.where(moved[:, None], landing, skin.vertices)
    node_ids = np.where(moved, -1, skin.node_ids)
    used, inverse = np.unique(skin.faces[~covered], return_inverse=True)
    stats = skin.stats | {"lip_faces_dropped": int(covered.sum()),
                          "lip_border_moved": int(moved.sum()),
                          "lip_border_moved_max_mm": round(float(depth[moved].max(initial=0.0)), 3)}
    return replace(skin, vertices=vertices[used], faces=inverse.reshape(-1, 3).astype(np.int64),
                   node_ids=node_ids[used], stats=stats)
