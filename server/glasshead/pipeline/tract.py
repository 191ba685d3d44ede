"""The vocal tract and neck in the build: airway, palate, velum, pharynx, hyoid, larynx, spine.

Two sources (see the data README):

- the Badin speaker's tract (``artisynth-badin-tract``), in the head's own frame: converted like
  the head's meshes (``sources.read_tract_mesh``; the velum files are in millimetres);
- the CBCT subject's larynx cartilages, hyoid and cervical spine (``artisynth-dynjaw``), carried
  over by the maxilla's registration (``pipeline.larynx``).

The scene's hyoid is the Badin speaker's own (``hyoid``): it belongs to the same person as the
tongue, airway and pharynx, and needs no registration. The CBCT subject's (``hyoid_cbct``) is
kept to show how well that subject's neck is carried over (``tract_checks.hyoid_agreement``).

The velum is one mesh in three poses with the same vertices and faces; each pose is its own GLB
(``velum_raised``, ``velum_rest``, ``velum_lowered``), in the same vertex order, so a later step
blends positions vertex by vertex. Plain GLBs rather than one GLB with morph targets: the web
app's glTF geometry keeps only positions, normals and the index, and trimesh neither writes nor
reads morph targets, so the Python twin can read the poses as it reads every other mesh.

There is no nasal cavity mesh in the data, and none is made here.
"""

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from glasshead.geometry.meshio import MeshFormatError
from glasshead.pipeline import sources, tract_checks
from glasshead.pipeline.larynx import carry, cbct_affine, place_vertebrae

#: Order of the meshes in the manifest: the tract from the lips down, then the neck.
ORDER = ["airway", "palate", "velum_raised", "velum_rest", "velum_lowered", "pharynx", "hyoid",
         "hyoid_cbct", "thyroid", "cricoid", "arytenoid_left", "arytenoid_right", "vertebrae"]

#: The meshes the head shows (manifest ``scene: true``). Left out: ``hyoid_cbct`` (another person's,
#: see ``SCENE_HYOID``), the raised and lowered velum (the web app poses ``velum_rest``'s vertices
#: from the velum rig, which holds all three poses) and the tract ``palate`` (the maxilla is the
#: scene's hard palate, 0.2 mm median from this surface, and carries the EPG electrodes; the soft
#: palate is the velum). The airway is drawn as the air of the cutaway, not as a surface.
SCENE_MESHES = frozenset({"airway", "velum_rest", "pharynx", "hyoid", "thyroid", "cricoid",
                          "arytenoid_left", "arytenoid_right", "vertebrae"})

SCENE_HYOID = {
    "mesh": "hyoid",
    "reason": "the Badin speaker's own hyoid: the same person as the tongue, airway and pharynx, "
              "in their frame with no registration; the CBCT subject's (hyoid_cbct) is another "
              "person's, carried by a registration fitted on the maxilla some 70 mm above it",
}


@dataclass
class TractSources:
    """What the tract step reads, checked, before the slow steps of the anatomy build run.

    tract: name -> (vertices (n, 3) float64 project mm, faces (m, 3) int64), Badin tract.
    neck: name -> (vertices (n, 3) float64 CBCT mm, faces (m, 3) int64), CBCT's own axes.
    vertebrae_transform: (4, 4) float64, the Amira matrix of vertebrae.obj, read from
    transform_path.
    """

    tract: dict
    neck: dict
    vertebrae_transform: np.ndarray
    transform_path: Path


def read_tract_sources(data_dir):
    """Read and check every tract and neck file (``MeshFormatError`` names a bad one)."""
    data_dir = Path(data_dir)
    tract = {name: sources.read_tract_mesh(data_dir, stem)
             for stem, (name, _role, _unit) in sources.TRACT_MESHES.items()}
    check_velum_topology(data_dir, tract)
    neck = {name: sources.read_cbct_mesh(data_dir, stem)
            for stem, (name, _role) in sources.CBCT_NECK_MESHES.items()}
    transform_path = data_dir / sources.VERTEBRAE_TRANSFORM
    return TractSources(tract, neck, sources.read_amira_transform(transform_path), transform_path)


def check_velum_topology(data_dir, tract):
    """Raise ``MeshFormatError`` naming the pose whose vertex count or faces differ from the
    rest pose's: the three poses must be one mesh, to be blended vertex by vertex."""
    rest_vertices, rest_faces = tract["velum_rest"]
    for name in sources.VELUM_POSES:
        vertices, faces = tract[name]
        if len(vertices) != len(rest_vertices) or not np.array_equal(faces, rest_faces):
            raise MeshFormatError(
                Path(data_dir) / sources.TRACT / f"{name}.obj",
                f"{len(vertices)} vertices and {len(faces)} faces do not match velum_rest.obj's "
                f"{len(rest_vertices)} and {len(rest_faces)} (the poses must share one topology)")


def edge_stats(faces):
    """Open edges (used by one face) and misoriented ones (two faces run them the same way)."""
    directed = np.asarray(faces)[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    _, per_direction = np.unique(directed, axis=0, return_counts=True)
    _, per_edge = np.unique(np.sort(directed, axis=1), axis=0, return_counts=True)
    return {"open_edges": int(np.sum(per_edge == 1)),
            "misoriented_edges": int(np.sum(per_direction > 1))}


def build_tract(src, cbct_vertices, placed_vertices, registration, head, log=print):
    """Place every tract and neck mesh in the project frame and measure how they fit.

    src: ``TractSources``. cbct_vertices (n, 3), placed_vertices (n, 3): the CBCT maxilla before
    and after ``register_cbct``; registration: its report. head: name -> (vertices, faces) of
    the head's meshes in the project frame (needs maxilla, tongue_rest, cranium).
    Returns (meshes: list of dicts with name, vertices, faces, role, source, scene (whether the
    head shows it) and extra manifest fields, in ``ORDER``; report dict).
    """
    to_project = cbct_affine(cbct_vertices, placed_vertices)
    placed = dict(src.tract)
    for name, (vertices, faces) in src.neck.items():
        if name != "vertebrae":
            placed[name] = carry(to_project, vertices, faces)
    stored, vertebra_faces = src.neck["vertebrae"]
    others = {"pharynx": placed["pharynx"][0], "cricoid": placed["cricoid"][0],
              "cranium": head["cranium"][0]}
    vertebrae, placement = place_vertebrae(stored, src.vertebrae_transform, to_project, others,
                                           src.transform_path)
    placed["vertebrae"] = carry(to_project, vertebrae, vertebra_faces)
    log(f"    vertebrae: {placement['placement']}")

    origin = {name: (f"artisynth-badin-tract/{stem}.obj", role)
              for stem, (name, role, _unit) in sources.TRACT_MESHES.items()}
    origin |= {name: (f"artisynth-dynjaw/{stem}.obj", role)
               for stem, (name, role) in sources.CBCT_NECK_MESHES.items()}
    meshes = []
    for name in ORDER:
        vertices, faces = placed[name]
        extra = {}
        if name in sources.VELUM_POSES:
            extra = {"pose_set": "velum", "pose": name.removeprefix("velum_"),
                     "poses": list(sources.VELUM_POSES)}
        meshes.append({"name": name, "vertices": vertices, "faces": faces,
                       "role": origin[name][1], "source": origin[name][0],
                       "scene": name in SCENE_MESHES, "extra": extra})

    trimeshes = {name: tract_checks.as_mesh(*placed[name]) for name in placed}
    trimeshes |= {name: tract_checks.as_mesh(*head[name])
                  for name in ("maxilla", "tongue_rest", "cranium")}
    report = {
        "meshes": {m["name"]: {"source": m["source"], "role": m["role"],
                               "triangles": len(m["faces"])} | edge_stats(m["faces"])
                   for m in meshes},
        "scene_hyoid": SCENE_HYOID,
        "scene_meshes": sorted(SCENE_MESHES),
        "nasal_cavity": "no mesh in the data; none is built",
        "velum": velum_report(placed),
        "cbct_to_project": np.round(to_project, 6).tolist(),
        "vertebrae_transform": placement,
        "airway_fit": tract_checks.airway_fit(trimeshes),
        "velum_continuation": tract_checks.velum_continuation(trimeshes["velum_rest"],
                                                              trimeshes["maxilla"]),
        "relations": tract_checks.relations(trimeshes),
        "hyoid_agreement": tract_checks.hyoid_agreement(trimeshes["hyoid"],
                                                        trimeshes["hyoid_cbct"]),
    }
    residual = registration_residual(registration, placed_vertices, report["hyoid_agreement"])
    for name, _role in sources.CBCT_NECK_MESHES.values():
        centroid = placed[name][0].mean(axis=0)
        lever = float(np.linalg.norm(centroid - np.mean(placed_vertices, axis=0)))
        report["meshes"][name]["registration"] = residual | {
            "distance_from_registered_maxilla_mm": round(lever, 1)}
    return meshes, report


def registration_residual(registration, placed_vertices, hyoid):
    """The residual a CBCT neck mesh inherits: the maxilla's, and the hyoid check at the neck."""
    mouth = registration.get("mouth_facing", {}).get("badin_to_cbct", {})
    return {"registered_on": "the CBCT maxilla (anatomy.cbct_registration)",
            "maxilla_icp_trimmed_rms_mm": registration.get("icp_trimmed_rms_mm"),
            "maxilla_mouth_facing_rms_mm": mouth.get("rms_mm"),
            "hyoid_centroid_offset_mm": hyoid["centroid_distance_mm"]}


def velum_report(placed):
    """The three velum poses: shared topology, and how far each moves from rest (mm)."""
    rest, faces = placed["velum_rest"]
    moves = {name: np.linalg.norm(placed[name][0] - rest, axis=1)
             for name in sources.VELUM_POSES}
    return {"poses": list(sources.VELUM_POSES), "vertices": len(rest), "triangles": len(faces),
            "same_faces": all(np.array_equal(placed[name][1], faces)
                              for name in sources.VELUM_POSES),
            "storage": "one GLB per pose, same vertex order and faces; blend positions vertex "
                       "by vertex (raised -> rest -> lowered)",
            "largest_move_from_rest_mm": {name: round(float(move.max()), 2)
                                          for name, move in moves.items()},
            "mean_move_from_rest_mm": {name: round(float(move.mean()), 2)
                                       for name, move in moves.items()}}
