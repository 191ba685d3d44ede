"""The vocal tract's frame change checked on anatomy: measures for the build report.

Each measure compares meshes that came into the project frame by different routes (the head's
Badin meshes, the tract's Badin meshes with the velum in millimetres, the CBCT neck carried by
the maxilla's registration), so a wrong axis, unit or winding shows as a large number:

- the airway hugs the tissue around it: distances to the airway's wall from the surfaces that
  face it near the mid-sagittal plane (``BAND_MM``): the rest tongue's upper surface, the
  maxilla's palatal vault, the tract's palate and the velum's oral surface (facing down), and
  the pharyngeal wall (facing forward, down to the airway's open lower end), by
  ``trimesh.proximity.closest_point``. Away from the
  midline these surfaces meet the teeth and cheeks, which have no mesh in the airway;
- the velum continues the hard palate backwards;
- the pharyngeal wall lies behind the tongue root; the larynx below the hyoid and in front of
  the vertebrae (``larynx.midline_clearance``);
- the CBCT subject's hyoid, carried over, against the Badin speaker's own.
"""

import numpy as np
import trimesh

from glasshead.pipeline.larynx import midline_clearance

#: Surface points sampled per measure; enough for a stable median and 95th percentile, few
#: enough that each closest-point query takes well under a second.
SAMPLES = 1500
#: Points sampled per mesh for the front/back comparisons (cheap: no closest-point query).
DENSE_SAMPLES = 20000
#: Half-width of the mid-sagittal band where the tissue faces the airway, mm (beyond it the
#: tongue's sides meet the teeth, the palate's sides lie over them).
BAND_MM = 10.0
#: A face "faces" a direction when its unit normal's component along it exceeds this.
FACING = 0.3


def as_mesh(vertices, faces):
    """A ``trimesh.Trimesh`` kept exactly as given (no merging or reordering)."""
    return trimesh.Trimesh(np.asarray(vertices, np.float64), np.asarray(faces), process=False)


def sample(mesh, keep=None, count=SAMPLES, seed=0):
    """(count, 3) points spread by area over the faces of ``mesh`` where ``keep`` (m,) bool."""
    if keep is not None:
        if not np.any(keep):
            raise ValueError("no faces selected to sample")
        mesh = mesh.submesh([np.flatnonzero(keep)], append=True)
    points, _ = trimesh.sample.sample_surface(mesh, count, seed=seed)
    return np.asarray(points)


def distance_summary(points, surface):
    """Median, 95th percentile and largest distance (mm) from (n, 3) points to ``surface``."""
    _, distance, _ = trimesh.proximity.closest_point(surface, points)
    return {"median_mm": round(float(np.median(distance)), 2),
            "p95_mm": round(float(np.percentile(distance, 95)), 2),
            "max_mm": round(float(distance.max()), 2), "points": len(points)}


def facing(mesh, axis, sign):
    """Faces (m,) bool near the midline (|z| < ``BAND_MM``) whose normal points along
    ``sign`` (+1 or -1) times the project ``axis`` (0 = x anterior, 1 = y superior)."""
    return ((sign * mesh.face_normals[:, axis] > FACING)
            & (np.abs(mesh.triangles_center[:, 2]) < BAND_MM))


def palatal_vault(maxilla, tongue):
    """Faces (m,) bool of the maxilla's palatal vault: facing down near the midline, above the
    tongue's top less 5 mm (the incisors' lingual faces below that are left out)."""
    return facing(maxilla, 1, -1) & (maxilla.triangles_center[:, 1]
                                     > tongue.vertices[:, 1].max() - 5.0)


def airway_fit(meshes):
    """Distances from the tissue around the airway to its wall; ``meshes``: name -> Trimesh."""
    airway = meshes["airway"]
    tongue, velum = meshes["tongue_rest"], meshes["velum_rest"]
    palate, pharynx = meshes["palate"], meshes["pharynx"]
    return {
        "tongue_upper_surface": distance_summary(sample(tongue, facing(tongue, 1, 1)), airway),
        "maxilla_palatal_vault": distance_summary(
            sample(meshes["maxilla"], palatal_vault(meshes["maxilla"], tongue), seed=1), airway),
        "palate_oral_surface": distance_summary(sample(palate, facing(palate, 1, -1), seed=2),
                                                airway),
        "velum_rest_oral_surface": distance_summary(sample(velum, facing(velum, 1, -1), seed=3),
                                                    airway),
        "pharynx_front_surface": distance_summary(
            sample(pharynx, facing(pharynx, 0, 1) & (pharynx.triangles_center[:, 1]
                                                     > airway.vertices[:, 1].min()), seed=4),
            airway),
    }


def velum_continuation(velum, maxilla):
    """How the rest velum meets the hard palate: the gap from its front end to the maxilla, and
    how far it reaches behind the maxilla's back edge, near the midline (mm)."""
    points = velum.vertices[np.abs(velum.vertices[:, 2]) < BAND_MM]
    front = points[points[:, 0] > points[:, 0].max() - 2.0]
    _, gap, _ = trimesh.proximity.closest_point(maxilla, front)
    bone = maxilla.vertices[np.abs(maxilla.vertices[:, 2]) < BAND_MM]
    return {"front_gap_to_maxilla_mm": round(float(np.median(gap)), 2),
            "front_x_mm": round(float(points[:, 0].max()), 2),
            "maxilla_back_x_mm": round(float(bone[:, 0].min()), 2),
            "reaches_behind_maxilla_mm": round(float(bone[:, 0].min() - points[:, 0].min()), 2)}


def relations(meshes):
    """Front/back and above/below relations of the tract and neck; ``meshes``: name -> Trimesh."""
    dense = {name: sample(meshes[name], count=DENSE_SAMPLES, seed=5)
             for name in ("tongue_rest", "pharynx", "vertebrae", "thyroid", "cricoid",
                          "arytenoid_left", "arytenoid_right")}
    larynx = np.vstack([dense[name] for name in ("thyroid", "cricoid", "arytenoid_left",
                                                 "arytenoid_right")])
    tongue = dense["tongue_rest"]
    root = tongue[tongue[:, 1] < np.percentile(tongue[:, 1], 50)]  # the tongue's lower half
    hyoid = meshes["hyoid"].vertices
    below_hyoid = {name: round(float(hyoid[:, 1].mean() - meshes[name].vertices[:, 1].mean()), 2)
                   for name in ("thyroid", "cricoid", "arytenoid_left", "arytenoid_right")}
    return {
        "tongue_root_in_front_of_pharynx_mm": midline_clearance(root, dense["pharynx"]),
        "larynx_centroid_below_hyoid_centroid_mm": below_hyoid,
        "larynx_in_front_of_vertebrae_mm": midline_clearance(larynx, dense["vertebrae"]),
        "pharynx_in_front_of_vertebrae_mm": midline_clearance(dense["pharynx"],
                                                              dense["vertebrae"]),
        "vertebrae_below_cranium_mm": round(float(meshes["cranium"].vertices[:, 1].min()
                                                  - meshes["vertebrae"].vertices[:, 1].max()), 2),
    }


def hyoid_agreement(badin_hyoid, cbct_hyoid):
    """The CBCT subject's hyoid, carried over, against the Badin speaker's own: centroid offset
    (x, y, z and length, mm) and surface distances both ways. Two people's bones differ, so this
    bounds (does not measure alone) the registration's error at the neck."""
    offset = cbct_hyoid.vertices.mean(axis=0) - badin_hyoid.vertices.mean(axis=0)
    return {"centroid_offset_mm": np.round(offset, 2).tolist(),
            "centroid_distance_mm": round(float(np.linalg.norm(offset)), 2),
            "cbct_to_badin": distance_summary(sample(cbct_hyoid, seed=6), badin_hyoid),
            "badin_to_cbct": distance_summary(sample(badin_hyoid, seed=7), cbct_hyoid)}
