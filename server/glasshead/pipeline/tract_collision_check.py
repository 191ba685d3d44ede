"""The `glasshead build` step that checks the tongue's collision with the velum and the pharyngeal
wall can be set up on the built meshes (geometry.tract_collision): the origin T lies in front of
every tract mesh and keeps its clearance from each in every velum pose. It writes nothing; its
report gives T, the screen plane and the clearances, and a failure stops the build naming why.
"""

import numpy as np

from glasshead.constants import PHARYNX_GLB, VELUM_REST_GLB, VELUM_RIG_FILE
from glasshead.geometry.collision_exact import closest_points_on_triangles
from glasshead.geometry.tract_collision import TractCollisionError, prepare_tract
from glasshead.geometry.velum import VelumRigError, prepare_velum
from glasshead.pipeline.outputs import load_built_meshes, read_json


class TractCollisionBuildError(RuntimeError):
    """The built tract meshes cannot be collided with; the message names the file and why."""


def build_step(ctx):
    assets_dir = ctx.assets_dir
    try:
        rig = prepare_velum(read_json(assets_dir / VELUM_RIG_FILE))
        meshes = load_built_meshes(assets_dir, ["velum_rest", "pharynx"])
        collider = prepare_tract(rig, meshes["velum_rest"][1], meshes["pharynx"][0],
                                 meshes["pharynx"][1])
    except (TractCollisionError, VelumRigError, KeyError, OSError, ValueError) as exc:
        raise TractCollisionBuildError(
            f"tract collision cannot be set up from {VELUM_RIG_FILE}, {VELUM_REST_GLB} and "
            f"{PHARYNX_GLB} in {assets_dir}: {exc}") from exc
    clearance = {}
    for mesh in collider.meshes:
        gaps = []
        for pose in mesh.poses:
            tri = pose[mesh.faces]
            near = closest_points_on_triangles(collider.origin, tri[:, 0], tri[:, 1], tri[:, 2])
            gaps.append(float(np.linalg.norm(near - collider.origin, axis=1).min()))
        clearance[mesh.name] = round(min(gaps), 3)
    return {"step": "tract-collision", "origin_mm": np.round(collider.origin, 3).tolist(),
            "screen_x_mm": round(collider.screen_x, 3), "clearance_mm": clearance,
            "triangles": {m.name: len(m.faces) for m in collider.meshes}}
