"""The anatomy step of `glasshead build`: every mesh of the head and vocal tract, in the project
frame, as GLB.

Writes into a staging directory (see ``build.py``): one GLB per mesh (smooth vertex normals,
outward winding), ``face_skin_nodes.json`` (the face.node id of each skin vertex, for the jaw
skinning), and returns the manifest entries and the report items.
"""

import hashlib
import json
import time
from pathlib import Path
from typing import Any

import numpy as np
import trimesh

from glasshead.constants import SKIN_NODES_FILE
from glasshead.geometry.meshio import read_face_elems, read_face_nodes
from glasshead.geometry.register_cbct import register_cbct
from glasshead.pipeline import sources
from glasshead.pipeline.face_skin import extract_face_skin, head_centre, uncover_lips
from glasshead.pipeline.head_shell import build_head_shell
from glasshead.pipeline.maxilla_lods import (
    build_lods,
    choose_scene_maxilla,
    mouth_point,
    mouth_residual,
)
from glasshead.pipeline.neck import Neck, fit_neck
from glasshead.pipeline.quantized_glb import STEP_MM, lattice_step, quantized_glb
from glasshead.pipeline.seam_fairing import close_head
from glasshead.pipeline.tract import build_tract, read_tract_sources


def write_glb(path, vertices, faces, min_step_mm=STEP_MM):
    """Write a smooth-shaded mesh (vertex normals from its outward faces) as a quantised GLB
    (``quantized_glb``: positions on a 2^-8 mm lattice shared by every mesh, or the coarser
    ``min_step_mm``); (sha256, largest position error in mm)."""
    mesh = trimesh.Trimesh(np.asarray(vertices, dtype=np.float64), np.asarray(faces), process=False)
    # Normals come from the faces' (outward) winding and are written with the positions.
    data, error = quantized_glb(mesh.vertices, mesh.faces, mesh.vertex_normals, min_step_mm)
    Path(path).write_bytes(data)
    return hashlib.sha256(data).hexdigest(), error


class Timer:
    """Collects the time of each named stage and prints progress as it goes."""

    def __init__(self, log):
        self.log, self.times = log, {}

    def run(self, name, fn, *args):
        started = time.perf_counter()
        result = fn(*args)
        self.times[name] = round(time.perf_counter() - started, 3)
        self.log(f"    {name}: {self.times[name]:.1f} s")
        return result


#: The meshes the neck's skin covers: the hyoid, the larynx's cartilages and the cervical spine.
NECK_COVERS = ("hyoid", "thyroid", "cricoid", "arytenoid_left", "arytenoid_right", "vertebrae")
#: The neck rises this far above the hyoid's top, mm; above, the head's own outline takes over.
NECK_ABOVE_HYOID_MM = 10.0


def neck_of(tract_meshes) -> Neck:
    """The neck round the built larynx, hyoid and spine (``pipeline.neck``)."""
    meshes = {m["name"]: m["vertices"] for m in tract_meshes}
    missing = [name for name in NECK_COVERS if name not in meshes]
    if missing:
        raise ValueError(f"the neck needs the meshes {', '.join(missing)}")
    covered = np.vstack([meshes[name] for name in NECK_COVERS])
    return fit_neck(covered, meshes["cricoid"],
                    top_y=float(meshes["hyoid"][:, 1].max()) + NECK_ABOVE_HYOID_MM)


def neck_from_sources(data_dir, badin) -> Neck:
    """The neck as the build makes it, straight from the sources (for a face rig made without a
    build): the CBCT maxilla registered and the larynx and spine carried over. badin: name ->
    (vertices, faces) of the Badin meshes in the project frame (maxilla, tongue_rest, cranium)."""
    tract_sources = read_tract_sources(data_dir)
    cbct_vertices, cbct_faces = sources.read_cbct_maxilla(data_dir)
    placed, _, registration = register_cbct(cbct_vertices, cbct_faces, *badin["maxilla"])
    meshes, _ = build_tract(tract_sources, cbct_vertices, placed, registration, badin,
                            log=lambda message: None)
    return neck_of(meshes)


def build_anatomy(data_dir, stage_dir, log=print):
    """Build every anatomy mesh into ``stage_dir``; returns (manifest entries, report dict)."""
    timer = Timer(log)
    entries: list[dict] = []
    report: dict[str, Any] = {}

    # The skin shares its rim with the head shell and its lip corners with the lips: all four are
    # written on the lattice of the widest of them.
    shared_step: dict[str, float] = {}

    def emit(name, vertices, faces, role, source, lod="full", scene=True, **extra):
        file = f"{name}.glb"
        digest, error = write_glb(Path(stage_dir) / file, vertices, faces,
                                  shared_step.get(name, STEP_MM))
        report["quantisation_max_error_mm"] = max(report.get("quantisation_max_error_mm", 0.0),
                                                  round(error, 6))
        entries.append({"name": name, "file": file, "sha256": digest, "triangles": len(faces),
                        "vertices": len(vertices), "lod": str(lod), "frame": "project-mm",
                        "scene": scene, "role": role, "source": source} | extra)

    badin = {}
    for stem, (name, _role) in sources.BADIN_MESHES.items():
        badin[name] = timer.run(f"read {stem}.obj", sources.read_badin_mesh, data_dir, stem)
    cranium_vertices = badin["cranium"][0]
    # Read (and check) the vocal tract and neck now, so a bad file stops the build at once.
    tract_sources = timer.run("read vocal tract and neck", read_tract_sources, data_dir)

    face_dir = Path(data_dir) / sources.BADIN
    node_ids, nodes = read_face_nodes(face_dir / "face.node")
    elems = read_face_elems(face_dir / "face.elem", node_ids)
    skin = timer.run("face skin", extract_face_skin, node_ids, nodes, elems,
                     head_centre(cranium_vertices))
    skin = timer.run("skin off the lips", uncover_lips, skin,
                     [badin["upper_lip"], badin["lower_lip"]])
    cbct_vertices, cbct_faces = sources.read_cbct_maxilla(data_dir)
    placed, placed_faces, registration = timer.run(
        "register CBCT maxilla", register_cbct, cbct_vertices, cbct_faces, *badin["maxilla"])
    point = mouth_point(badin["maxilla"][0])
    arch = (badin["maxilla"][0].min(axis=0), badin["maxilla"][0].max(axis=0))
    levels = timer.run("CBCT levels of detail", build_lods, placed, placed_faces, point, arch)
    badin_vertices, badin_faces = badin["maxilla"]
    registration["mouth_facing"] = mouth_residual(badin_vertices, badin_faces, placed,
                                                  placed_faces, point, arch)
    choice = choose_scene_maxilla(registration, levels)
    log(f"    scene maxilla: {choice['mesh']} ({choice['level']})")

    # The vocal tract and neck first: the head shell takes the neck round the larynx and spine.
    tract_meshes, report["tract"] = timer.run(
        "vocal tract and neck", build_tract, tract_sources, cbct_vertices, placed, registration,
        badin, log)
    neck = neck_of(tract_meshes)
    skin, shell = timer.run("head shell and seam", close_head, skin, cranium_vertices, neck)
    skin_meshes = {"face_skin": skin.vertices, "head_shell": shell.vertices,
                   "upper_lip": badin["upper_lip"][0], "lower_lip": badin["lower_lip"][0]}
    step = max(lattice_step(v) for v in skin_meshes.values())
    shared_step.update(dict.fromkeys(skin_meshes, step))
    emit("face_skin", skin.vertices, skin.faces, "skin", "artisynth-badin/face.node+face.elem")
    (Path(stage_dir) / SKIN_NODES_FILE).write_text(
        json.dumps({"mesh": "face_skin", "node_ids": skin.node_ids.tolist()}))
    emit("head_shell", shell.vertices, shell.faces, "shell", "built: closes the face skin")
    report["face_skin"] = {k: v for k, v in skin.stats.items()}
    report["head_shell"] = {"method": build_head_shell.__module__ + " (see its docstring)",
                            "triangles": len(shell.faces)} | shell.params

    for stem, (name, role) in sources.BADIN_MESHES.items():
        # When a CBCT level is chosen, the Badin maxilla stays available under another name.
        replaced = name == "maxilla" and choice["mesh"] != "badin"
        vertices, faces = badin[name]
        emit("maxilla_badin" if replaced else name, vertices, faces, role,
             f"artisynth-badin/{stem}.obj", scene=not replaced)
    emit("maxilla_cbct_full", placed, placed_faces, "bone", "artisynth-dynjaw/maxilla.obj",
         lod="full", scene=False)
    for lod in levels:
        chosen = choice["mesh"] == "cbct" and choice["level"] == lod["level"]
        emit("maxilla" if chosen else f"maxilla_cbct_lod{lod['level']}", lod["vertices"],
             lod["faces"], "bone", "artisynth-dynjaw/maxilla.obj", lod=lod["level"], scene=chosen)

    # The vocal tract and neck; the head shows those in tract.SCENE_MESHES.
    for mesh in tract_meshes:
        emit(mesh["name"], mesh["vertices"], mesh["faces"], mesh["role"], mesh["source"],
             scene=mesh["scene"], **mesh["extra"])

    report["cbct_registration"] = registration
    report["cbct_lods"] = [{k: v for k, v in lod.items() if k not in ("vertices", "faces")}
                           | {"vertices": lod["vertices_count"]} for lod in levels]
    for item in report["cbct_lods"]:
        item.pop("vertices_count", None)
    report["cbct_full_triangles"] = len(cbct_faces)
    report["mouth_point_mm"] = point.round(3).tolist()
    report["mouth_facing"] = (
        "faces seen first from the mouth point, facing it, no higher than the palate vault above "
        "it + 1 mm, within the Badin maxilla's x and |z| extent (see pipeline/maxilla_lods.py)")
    report["scene_maxilla"] = choice
    report["timings_s"] = timer.times
    return entries, report
