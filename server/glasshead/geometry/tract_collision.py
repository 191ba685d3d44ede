"""Tongue collision with the velum and the pharyngeal wall: the twin of
``web/src/core/tractCollision.js`` (docs/collision.md, "The velum and the pharyngeal wall").

"Inside" is defined as for the palate, from a fixed origin T in the mouth (``tract_origin``): a
tongue vertex P is inside when the segment T -> P crosses a tract triangle (either side) before
reaching P, and it is then moved back along that segment onto the first crossing. The JS twin
finds the triangles a segment can meet through a bounding-volume hierarchy whose boxes are
blended between the velum's measured poses; this twin asks every triangle whose box the
segment's box meets. Both take the same first crossing, computed with the same operations
(``collision.moller_trumbore``), on the same float32 positions: the velum blended as
``velum.js`` blends it and rounded to float32 as its Float32Array stores it.

Steps:

1. Screen: a vertex in front of every tract mesh (x at or beyond ``screen_x``, T being in front
   of them too), or shallower than every tract hull in its direction from T (the depth tables of
   ``tract_screen``): outside (FLAG_SCREENED).
2. Test: the first crossing t of T -> P with the tract meshes; t < 1 moves the vertex to
   T + t (P - T) (FLAG_CORRECTED), otherwise it stays, bit for bit (FLAG_TESTED).
"""

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from glasshead.constants import (
    FLAG_CORRECTED,
    FLAG_SCREENED,
    FLAG_TESTED,
    TRACT_COLLISION_MESHES,
    TRACT_ORIGIN_AHEAD_MM,
    TRACT_ORIGIN_CLEARANCE_MM,
)
from glasshead.geometry.collision import moller_trumbore
from glasshead.geometry.collision_exact import closest_points_on_triangles
from glasshead.geometry.tract_screen import (
    DepthScreen,
    create_depth_screen,
    screen_table,
    screened,
)
from glasshead.geometry.velum import VelumRig, check_opening

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]

#: Tested vertices per block of the brute-force search (bounds its memory).
CHUNK = 128


class TractCollisionError(ValueError):
    """Tract meshes or an origin that cannot be used for collision."""


@dataclass(frozen=True)
class TractMesh:
    """One tract mesh: poses (p, n, 3) float64 holding float32 values (one pose for a still
    mesh) and faces (m, 3) int64."""

    name: str
    poses: Floats
    faces: Ints


@dataclass(frozen=True)
class TractCollider:
    """origin T (3,), screen_x (no tract mesh reaches in front of it), meshes in
    ``TRACT_COLLISION_MESHES`` order, the velum's rest share r (its poses are raised, rest,
    lowered at openings 0, r and 1) and the depth screen."""

    origin: Floats
    screen_x: float
    meshes: tuple[TractMesh, ...]
    rest_share: float
    screen: DepthScreen


def _float32(values: npt.ArrayLike) -> Floats:
    return np.asarray(values, dtype=np.float32).astype(np.float64)


def tract_origin(velum_poses: npt.ArrayLike) -> Floats:
    """T (3,) float64: in the mid-sagittal plane, ``TRACT_ORIGIN_AHEAD_MM`` in front of the
    velum's most anterior point and at the height of its lowest point, over every pose.

    velum_poses : (p, n, 3) float, mm. From T the velum's oral surface and the pharyngeal wall are
    seen from the front, and no tract mesh lies in front of T.
    """
    poses = np.asarray(velum_poses, dtype=np.float64)
    return np.array([poses[..., 0].max() + TRACT_ORIGIN_AHEAD_MM, poses[..., 1].min(), 0.0])


def _check_faces(name: str, faces: npt.ArrayLike, vertex_count: int) -> Ints:
    f = np.asarray(faces)
    if f.ndim != 2 or f.shape[1] != 3 or not len(f) or not np.issubdtype(f.dtype, np.integer):
        raise TractCollisionError(f"{name} faces must be (m, 3) integers, got {f.shape}")
    if f.min() < 0 or f.max() >= vertex_count:
        raise TractCollisionError(f"{name} faces refer to vertices that do not exist")
    return f.astype(np.int64)


def prepare_tract(velum: VelumRig, velum_faces: npt.ArrayLike, pharynx_vertices: npt.ArrayLike,
                  pharynx_faces: npt.ArrayLike) -> TractCollider:
    """The collider for the velum rig (its three poses, with the velum mesh's faces) and the
    pharyngeal wall. Raises TractCollisionError when the meshes do not fit together or T would
    lie within ``TRACT_ORIGIN_CLEARANCE_MM`` of a triangle or behind a mesh."""
    velum_poses = _float32(velum.poses)
    pharynx = _float32(pharynx_vertices)
    if pharynx.ndim != 2 or pharynx.shape[1] != 3 or not np.all(np.isfinite(pharynx)):
        raise TractCollisionError(f"pharynx vertices must be finite (n, 3), got {pharynx.shape}")
    faces = {"velum": _check_faces("velum", velum_faces, velum_poses.shape[1]),
             "pharynx": _check_faces("pharynx", pharynx_faces, len(pharynx))}
    poses = {"velum": velum_poses, "pharynx": pharynx[None]}
    origin = tract_origin(velum_poses)
    meshes = tuple(TractMesh(name, poses[name], faces[name]) for name in TRACT_COLLISION_MESHES)
    screen_x = float(max(m.poses[..., 0].max() for m in meshes))
    if not origin[0] >= screen_x:
        raise TractCollisionError(f"the tract origin x = {origin[0]:.2f} mm lies behind a tract "
                                  f"mesh (front {screen_x:.2f} mm)")
    for mesh in meshes:
        for pose in mesh.poses:
            tri = pose[mesh.faces]
            gap = np.linalg.norm(closest_points_on_triangles(origin, tri[:, 0], tri[:, 1],
                                                             tri[:, 2]) - origin, axis=1).min()
            if gap < TRACT_ORIGIN_CLEARANCE_MM:
                raise TractCollisionError(
                    f"the tract origin {origin.round(2).tolist()} is {gap:.2f} mm from the "
                    f"{mesh.name}; it must keep {TRACT_ORIGIN_CLEARANCE_MM} mm")
    screen = create_depth_screen(origin, [(m.poses, m.faces) for m in meshes])
    return TractCollider(origin, screen_x, meshes, float(velum.rest_share), screen)


def tract_pose(collider: TractCollider, velum_opening: float,
               ) -> list[tuple[Floats, int, float]]:
    """Per mesh: (positions (n, 3) float64 of float32 values, first pose, share u) at this
    opening. The velum blends poses first and first + 1 as velum.js does, stored as float32."""
    opening = check_opening_value(velum_opening)
    r = collider.rest_share
    first, u = (0, opening / r) if opening <= r else (1, (opening - r) / (1.0 - r))
    out = []
    for mesh in collider.meshes:
        if len(mesh.poses) == 1:
            out.append((mesh.poses[0], 0, 0.0))
            continue
        a, b = mesh.poses[first], mesh.poses[first + 1]
        out.append((_float32(a * (1.0 - u) + b * u), first, u))
    return out


def check_opening_value(opening: float) -> float:
    """The opening as a float; ValueError naming velum_opening and its range otherwise (the
    check of ``velum.check_opening``, which needs no rig)."""
    return check_opening(None, opening)


def _first_crossings(rel: Floats, positions: Floats, faces: Ints, origin: Floats) -> Floats:
    """Smallest t in (0, inf) of the segments T + t rel over the triangles whose box meets the
    segment's box (the others cannot be crossed for t <= 1); +inf when none."""
    tri = positions[faces] - origin
    lo, hi = tri.min(axis=1), tri.max(axis=1)
    flat = np.concatenate([tri[:, 0], tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]], axis=1)
    t = np.full(len(rel), np.inf)
    for start in range(0, len(rel), CHUNK):
        block = rel[start:start + CHUNK]
        seg_lo, seg_hi = np.minimum(block, 0.0), np.maximum(block, 0.0)
        meets = np.all((seg_lo[:, None] <= hi[None]) & (seg_hi[:, None] >= lo[None]), axis=2)
        row, k = np.nonzero(meets)
        if not len(row):
            continue
        hits = moller_trumbore(block[row, 0], block[row, 1], block[row, 2], flat[k])
        np.minimum.at(t, start + row, hits)
    return t


def correct_tract(vertices: npt.ArrayLike, collider: TractCollider, velum_opening: float,
                  ) -> tuple[Floats, npt.NDArray[np.uint8], dict[str, int]]:
    """Correct tongue vertices (n, 3) mm (already corrected against the palate) against the
    velum at ``velum_opening`` and the pharyngeal wall.

    Returns (corrected (n, 3) float64, flags (n,) uint8, counts {screened, tested, corrected}).
    Vertices that were outside are returned unchanged, bit for bit. ValueError for bad input.
    """
    points = np.asarray(vertices, dtype=np.float64)
    if points.ndim != 2 or points.shape[1] != 3:
        raise ValueError(f"vertices must have shape (n, 3), got {points.shape}")
    if not np.all(np.isfinite(points)):
        raise ValueError("vertices must be finite numbers")
    posed = tract_pose(collider, velum_opening)
    origin = collider.origin
    moving = collider.screen.moving
    first, share = (posed[moving][1], posed[moving][2]) if moving >= 0 else (0, 0.0)
    table = screen_table(collider.screen, first, share)
    px = points[:, 0] - origin[0]
    py = points[:, 1] - origin[1]
    pz = points[:, 2] - origin[2]
    behind = np.flatnonzero(points[:, 0] < collider.screen_x)
    todo = behind[~screened(collider.screen, origin, points[behind], table)]
    rel = np.stack([px[todo], py[todo], pz[todo]], axis=1)
    t = np.full(len(todo), np.inf)
    for mesh, (positions, _, _) in zip(collider.meshes, posed, strict=True):
        t = np.minimum(t, _first_crossings(rel, positions, mesh.faces, origin))

    out = points.copy()
    flags = np.full(len(points), FLAG_SCREENED, dtype=np.uint8)
    flags[todo] = FLAG_TESTED
    hit = t < 1.0
    rows, th = todo[hit], t[hit]
    out[rows, 0] = origin[0] + rel[hit, 0] * th
    out[rows, 1] = origin[1] + rel[hit, 1] * th
    out[rows, 2] = origin[2] + rel[hit, 2] * th
    flags[rows] = FLAG_CORRECTED
    return out, flags, {"screened": len(points), "tested": len(todo), "corrected": len(rows)}

