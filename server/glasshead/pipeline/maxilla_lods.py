"""Levels of detail of the high-resolution CBCT maxilla, and the choice of the scene maxilla.

The CBCT maxilla (17,992 triangles) is reduced by quadric error metrics (Garland and Heckbert
1997, through ``fast-simplification``), as the paper reduced its palate from about 16,000 to
1,600 polygons. Each level is measured against the full mesh by the symmetric Hausdorff distance
(``surface_distance.hausdorff``), over the whole mesh and over the mouth-facing surface.

Mouth-facing surface: the faces the tongue can touch. A face is mouth-facing when, seen from a
point inside the oral cavity (``mouth_point``), (1) a ray from that point to its centroid hits it
first, (2) its normal points toward the point, (3) its centroid is no higher than the palate vault
above the point (+``VAULT_MARGIN_MM``), and (4) its centroid lies within the antero-posterior and
lateral extent of the Badin maxilla (the dental arch). (1)-(2) are the view of the palate the
collision liner has from its origin O: the vault, the alveolar ridge, the lingual and occlusal
faces of the teeth; (3)-(4) drop bone seen past the last molars (pterygoid plates, the inner face
of the zygomatic arches), which the tongue cannot reach.

Open borders. The CBCT mesh is open (2,270 border edges: cut bone, holes in the thin palate).
Quadric simplification without border constraints shrinks open borders, and that alone made a
12,000-triangle level 2.5 mm off on the palate. As Garland and Heckbert (1997, section 5) do with
constraint planes, each border edge gets a perpendicular "fence": a wall quad along the vertex
normals, ``FENCE_MM`` high, whose quadrics make moving the border costly. The fence is removed
after simplification (every face with a vertex off the original surface by more than half the
fence height), and the requested count is corrected until the surface alone has the target count.
"""

import time

import fast_simplification
import numpy as np
import trimesh

from glasshead.geometry.surface_distance import SampledSurface, hausdorff, summarise

#: Target triangle counts, from near-full to the paper's 1,600.
LOD_TARGETS = (12000, 8000, 5000, 3200, 1600)
#: The mouth-facing Hausdorff bound a scene maxilla must meet, mm.
MOUTH_FACING_BOUND_MM = 0.3
#: Height of the border fences, mm.
FENCE_MM = 2.0
#: A face may lie this far above the palate vault and still be mouth-facing, mm.
VAULT_MARGIN_MM = 1.0
#: Relative tolerance on a level's triangle count.
COUNT_TOLERANCE = 0.01
#: Above this mean registration residual the CBCT is too unlike the Badin speaker to replace
#: its maxilla: the Badin tongue, jaw and face would not fit it.
MAX_REGISTRATION_MEAN_MM = 1.0


def mouth_point(maxilla_vertices):
    """A point inside the oral cavity, below the palate vault: mid-sagittal, at the middle of the
    maxilla's antero-posterior extent, 3 mm above its lowest point (the incisal edges)."""
    v = np.asarray(maxilla_vertices, dtype=np.float64)
    return np.array([0.5 * (v[:, 0].min() + v[:, 0].max()), v[:, 1].min() + 3.0, 0.0])


def mouth_facing(vertices, faces, point, arch=None):
    """(m,) bool: the mouth-facing faces (see the module docstring).

    point (3,) float mm; arch: optional ((3,), (3,)) lower and upper corners of the dental arch's
    box (only x and |z| are used); without it condition (4) is not applied.
    """
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    centroids = mesh.triangles_center
    directions = centroids - point
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    origins = np.broadcast_to(point, directions.shape)
    first = mesh.ray.intersects_first(ray_origins=origins, ray_directions=directions)
    seen = first == np.arange(len(faces))
    facing = np.einsum("ij,ij->i", mesh.face_normals, point - centroids) > 0
    up = mesh.ray.intersects_location([point], [[0.0, 1.0, 0.0]], multiple_hits=False)[0]
    vault = up[:, 1].max() if len(up) else np.inf
    below = centroids[:, 1] <= vault + VAULT_MARGIN_MM
    if arch is not None:
        lo, hi = np.asarray(arch[0]), np.asarray(arch[1])
        below &= (centroids[:, 0] >= lo[0]) & (centroids[:, 0] <= hi[0])
        below &= np.abs(centroids[:, 2]) <= max(abs(lo[2]), abs(hi[2]))
    return seen & facing & below


def _simplify_once(vertices, faces, request, fence, surface):
    v, f = fast_simplification.simplify(
        np.asarray(vertices, dtype=np.float32), np.asarray(faces, dtype=np.int32),
        target_count=int(request))
    v, f = v.astype(np.float64), f.astype(np.int64)
    off = surface.distance(v) > fence / 2.0
    f = f[~off[f].any(axis=1)]
    used, inverse = np.unique(f, return_inverse=True)
    return v[used], inverse.reshape(-1, 3).astype(np.int64)


def simplify_keeping_borders(vertices, faces, target, fence=FENCE_MM):
    """Quadric simplification of an open mesh to about ``target`` triangles with fenced borders.

    vertices (n, 3) float mm, faces (m, 3) int. Returns (v (k, 3) float64, f (t, 3) int64).
    """
    vertices = np.asarray(vertices, dtype=np.float64)
    faces = np.asarray(faces, dtype=np.int64)
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    border = mesh.edges[trimesh.grouping.group_rows(mesh.edges_sorted, require_count=1)]
    ends = np.unique(border)
    wall_id = np.full(len(vertices), -1)
    wall_id[ends] = len(vertices) + np.arange(len(ends))
    a, b = border[:, 0], border[:, 1]
    walls = np.concatenate([np.stack([b, a, wall_id[a]], axis=1),
                            np.stack([b, wall_id[a], wall_id[b]], axis=1)])
    fenced_v = np.vstack([vertices, vertices[ends] + fence * mesh.vertex_normals[ends]])
    fenced_f = np.vstack([faces, walls])
    from glasshead.geometry.surface_distance import SurfaceDistance

    surface = SurfaceDistance(vertices, faces)
    request = target + len(walls)
    for _ in range(8):
        v, f = _simplify_once(fenced_v, fenced_f, min(request, len(fenced_f) - 1), fence, surface)
        if abs(len(f) - target) <= COUNT_TOLERANCE * target:
            break
        request -= len(f) - target
    return v, f


def build_lods(vertices, faces, point, arch=None):
    """Reduce the mesh to each of ``LOD_TARGETS`` and measure it.

    vertices (n, 3) float mm, faces (m, 3) int; point (3,) the mouth point; arch: the dental
    arch's box for ``mouth_facing``.
    Returns a list of dicts: level, triangles, vertices, faces, hausdorff_mm, mouth_hausdorff_mm,
    mouth_faces, seconds (reduction), seconds_with_measurement.
    """
    full = SampledSurface(vertices, faces)
    full_mask = mouth_facing(vertices, faces, point, arch)
    levels = []
    for level, target in enumerate(LOD_TARGETS):
        started = time.perf_counter()
        v, f = simplify_keeping_borders(vertices, faces, target)
        simplified = time.perf_counter() - started
        reduced = SampledSurface(v, f)
        whole, mouth = hausdorff(full, reduced, full_mask, mouth_facing(v, f, point, arch))
        levels.append({
            "level": level, "target": target, "triangles": len(f), "vertices_count": len(v),
            "hausdorff_mm": round(whole, 3), "mouth_hausdorff_mm": round(mouth, 3),
            "mouth_faces": int(mouth_facing(v, f, point, arch).sum()),
            "seconds": round(simplified, 3),
            "seconds_with_measurement": round(time.perf_counter() - started, 3),
            "vertices": v, "faces": f,
        })
    return levels


def mouth_residual(badin_vertices, badin_faces, cbct_vertices, cbct_faces, point, arch):
    """Registration residual on the mouth-facing surfaces, both directions (summaries in mm):
    the error a CBCT maxilla would bring to the palate the tongue touches."""
    badin = SampledSurface(badin_vertices, badin_faces)
    cbct = SampledSurface(cbct_vertices, cbct_faces)
    b_mask = mouth_facing(badin_vertices, badin_faces, point, arch)[badin.face_of]
    c_mask = mouth_facing(cbct_vertices, cbct_faces, point, arch)[cbct.face_of]
    return {
        "badin_to_cbct": summarise(cbct.query.distance(badin.points[b_mask])),
        "cbct_to_badin": summarise(badin.query.distance(cbct.points[c_mask])),
    }


def choose_scene_maxilla(registration, levels):
    """Which maxilla the scene shows, and why: {"mesh": "badin"|"cbct", "level", "reason"}."""
    residual = registration["badin_to_cbct"]["mean_mm"]
    mouth = registration.get("mouth_facing", {}).get("badin_to_cbct")
    mouth_text = (f" On the mouth-facing surface alone the residual is {mouth['mean_mm']} mm mean, "
                  f"{mouth['p95_mm']} mm 95th percentile, already over the "
                  f"{MOUTH_FACING_BOUND_MM} mm budget before any simplification." if mouth else "")
    within = [lod for lod in levels if lod["mouth_hausdorff_mm"] <= MOUTH_FACING_BOUND_MM]
    if residual > MAX_REGISTRATION_MEAN_MM:
        return {"mesh": "badin", "level": "full", "reason": (
            f"the CBCT maxilla is another subject's: registered onto the Badin maxilla it is "
            f"{residual} mm off on average (95th percentile "
            f"{registration['badin_to_cbct']['p95_mm']} mm), so the Badin tongue, jaw, lips and "
            f"face would not fit it; the Badin maxilla (same speaker, full resolution, 0 mm from "
            f"itself) is shown. CBCT levels within {MOUTH_FACING_BOUND_MM} mm on the mouth-facing "
            f"surface (against the full CBCT): {[lod['triangles'] for lod in within] or 'none'}."
            + mouth_text)}
    if not within:
        return {"mesh": "badin", "level": "full",
                "reason": f"no CBCT level stays within {MOUTH_FACING_BOUND_MM} mm mouth-facing"}
    best = min(within, key=lambda lod: lod["triangles"])
    return {"mesh": "cbct", "level": best["level"], "reason": (
        f"the coarsest CBCT level within {MOUTH_FACING_BOUND_MM} mm on the mouth-facing surface "
        f"({best['triangles']} triangles, {best['mouth_hausdorff_mm']} mm)")}
