"""Levels of detail of the high-resolution CBCT maxilla, and the choice of the scene maxilla.

The CBCT maxilla (17,992 triangles) is reduced by quadric error metrics (Garland and Heckbert
1997, through ``fast-simplification``), as the paper reduced its palate from about 16,000 to
1,600 polygons. Each level is measured against the full mesh by the symmetric Hausdorff distance
(``surface_distance.hausdorff``), over the whole mesh and over the mouth-facing surface.

Mouth-facing surface: the faces the tongue can touch, i.e. the faces seen from a point inside the
oral cavity (``MOUTH_POINT`` below). A face is mouth-facing when a ray from that point to its
centroid hits it first; this is the same view of the palate that the collision liner has from
its origin O, so it covers the palate vault, the alveolar ridge and the lingual and occlusal faces
of the teeth, and leaves out the outer (buccal, labial, nasal, zygomatic) bone.
"""

import time

import fast_simplification
import numpy as np
import trimesh

from glasshead.pipeline.surface_distance import SampledSurface, hausdorff

#: Target triangle counts, from near-full to the paper's 1,600.
LOD_TARGETS = (12000, 8000, 5000, 3200, 1600)
#: The mouth-facing Hausdorff bound a scene maxilla must meet, mm.
MOUTH_FACING_BOUND_MM = 0.3
#: Above this mean registration residual the CBCT is too unlike the Badin speaker to replace
#: its maxilla: the Badin tongue, jaw and face would not fit it.
MAX_REGISTRATION_MEAN_MM = 1.0


def mouth_point(maxilla_vertices):
    """A point inside the oral cavity, below the palate vault: mid-sagittal, at the middle of the
    maxilla's antero-posterior extent, 3 mm above its lowest point (the incisal edges)."""
    v = np.asarray(maxilla_vertices, dtype=np.float64)
    return np.array([0.5 * (v[:, 0].min() + v[:, 0].max()), v[:, 1].min() + 3.0, 0.0])


def mouth_facing(vertices, faces, point):
    """(m,) bool: faces whose centroid is seen from ``point`` (first hit of the ray)."""
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    centroids = mesh.triangles_center
    directions = centroids - point
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    origins = np.broadcast_to(point, directions.shape)
    first = mesh.ray.intersects_first(ray_origins=origins, ray_directions=directions)
    return first == np.arange(len(faces))


def build_lods(vertices, faces, point):
    """Reduce the mesh to each of ``LOD_TARGETS`` and measure it.

    vertices (n, 3) float mm, faces (m, 3) int; point (3,) the mouth point.
    Returns a list of dicts: level, triangles, vertices, faces, hausdorff_mm, mouth_hausdorff_mm,
    seconds (reduction plus measurement).
    """
    full = SampledSurface(vertices, faces)
    full_mask = mouth_facing(vertices, faces, point)
    levels = []
    for level, target in enumerate(LOD_TARGETS):
        started = time.perf_counter()
        reduction = 1.0 - target / len(faces)
        v, f = fast_simplification.simplify(
            np.asarray(vertices, dtype=np.float32), np.asarray(faces, dtype=np.int32),
            target_reduction=reduction)
        v, f = v.astype(np.float64), f.astype(np.int64)
        reduced = SampledSurface(v, f)
        whole, mouth = hausdorff(full, reduced, full_mask, mouth_facing(v, f, point))
        levels.append({
            "level": level, "target": target, "triangles": len(f), "vertices_count": len(v),
            "hausdorff_mm": round(whole, 3), "mouth_hausdorff_mm": round(mouth, 3),
            "seconds": round(time.perf_counter() - started, 3), "vertices": v, "faces": f,
        })
    return levels


def choose_scene_maxilla(registration, levels):
    """Which maxilla the scene shows, and why: {"mesh": "badin"|"cbct", "level", "reason"}."""
    residual = registration["badin_to_cbct"]["mean_mm"]
    within = [lod for lod in levels if lod["mouth_hausdorff_mm"] <= MOUTH_FACING_BOUND_MM]
    if residual > MAX_REGISTRATION_MEAN_MM:
        return {"mesh": "badin", "level": "full", "reason": (
            f"the CBCT maxilla is another subject's: registered onto the Badin maxilla it is "
            f"{residual} mm off on average (95th percentile "
            f"{registration['badin_to_cbct']['p95_mm']} mm), so the Badin tongue, jaw, lips and "
            f"face would not fit it; the Badin maxilla (same speaker, full resolution, 0 mm from "
            f"itself) is shown. CBCT levels within {MOUTH_FACING_BOUND_MM} mm on the mouth-facing "
            f"surface: {[lod['triangles'] for lod in within] or 'none'}.")}
    if not within:
        return {"mesh": "badin", "level": "full",
                "reason": f"no CBCT level stays within {MOUTH_FACING_BOUND_MM} mm mouth-facing"}
    best = min(within, key=lambda lod: lod["triangles"])
    return {"mesh": "cbct", "level": best["level"], "reason": (
        f"the coarsest CBCT level within {MOUTH_FACING_BOUND_MM} mm on the mouth-facing surface "
        f"({best['triangles']} triangles, {best['mouth_hausdorff_mm']} mm)")}
