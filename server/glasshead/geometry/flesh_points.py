"""Flesh points: where articulography glues its sensors, tracked on the posed rig.

An EMA sensor is glued to the flesh, so it is a material point: it moves with the tissue, not
with a feature of the shape (the highest point of the tongue, say, slides along it). Named after
``docs/ema.md``'s sensors:

- ``tongue_tip``, ``tongue_blade``, ``tongue_dorsum``, ``tongue_back``: points of the tongue's
  upper mid-sagittal outline (the page-angle-0 points of the stations,
  ``TongueRig.page_radii``), fixed at rest by their arc length from the apex
  (``TONGUE_SENSOR_ARC_MM``) as a fractional station index: the segment from station ``i`` to
  the next station along the upper surface and a weight ``t`` on it. In every pose the point is
  the same interpolation of the posed outline, in z = 0. The points are taken from the rig's
  surface before the collision correction (what the tongue's parameters put there; a tip pressed
  into the ridge is not moved back onto it).
- ``lower_incisor``: the rest ``lower_incisor_edge`` landmark moved by the jaw pose.
- ``upper_incisor``: the rest ``upper_incisor_edge`` landmark; the maxilla does not move, so it
  is the fixed reference that EMA heads are corrected to.
- ``upper_lip``, ``lower_lip``: the lip meshes' reference vertices (their vermilion midpoints)
  posed by the face rig (``face_rig.pose_face`` on the two lip meshes only) with the frame's lip
  parameters and jaw pose.

The sensor placements are the conventional ones. Tiede et al.'s Haskins Production Rate
Comparison database (``../shared/data/ema/hprc``) puts the tongue tip sensor about 1 cm behind
the apex, then blade and rear (dorsum) sensors behind it; Wrench's MOCHA-TIMIT corpus places
tip, blade and dorsum alike, each a few centimetres behind the one before. The arcs here
(``TONGUE_SENSOR_ARC_MM``: 10, 25, 40 and 55 mm) are round values of that spacing, with a
fourth, ``tongue_back``, under the soft palate.
"""

from collections.abc import Mapping

import numpy as np
import numpy.typing as npt

from glasshead.geometry import face_rig as face
from glasshead.geometry.face_teeth import teeth_tables
from glasshead.geometry.jaw import apply_jaw_pose, jaw_pose
from glasshead.geometry.tongue_surface import TongueRig

Floats = npt.NDArray[np.float64]

#: Arc length along the tongue's upper mid-sagittal outline from the apex (its most anterior
#: point at rest) to each tongue sensor, mm: the tip 1 cm behind the apex (HPRC), then 15 mm
#: apart (see the module's docstring).
TONGUE_SENSOR_ARC_MM = {"tongue_tip": 10.0, "tongue_blade": 25.0, "tongue_dorsum": 40.0,
                        "tongue_back": 55.0}
#: Every flesh point, in the order of the answer.
FLESH_POINT_NAMES = ("tongue_tip", "tongue_blade", "tongue_dorsum", "tongue_back",
                     "lower_incisor", "upper_lip", "lower_lip", "upper_incisor")
#: The rest landmarks (``landmarks.json``) of the incisor points.
INCISOR_LANDMARKS = {"lower_incisor": "lower_incisor_edge", "upper_incisor": "upper_incisor_edge"}


def midline_page(rig: TongueRig) -> int:
    """The page sample at angle 0 (the mid-sagittal one)."""
    return int(np.argmax(rig.page_cos))


def midline_outline(rig: TongueRig, values: npt.ArrayLike) -> Floats:
    """(stations, 2) float64: the page-angle-0 point of every station, x y in mm, round the
    hub in station order (what ``TongueRig.vertices`` puts at that page in z = 0)."""
    hub, _stations, direction, radii, _stretch = rig.page_radii(values)
    return hub + radii[:, midline_page(rig), None] * direction


def tongue_anchors(rig: TongueRig, arcs_mm: npt.ArrayLike | None = None
                   ) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64], Floats]:
    """Where the tongue sensors sit on the rest outline: (first (k,) int64, second (k,) int64,
    weight (k,) float64), the point being (1 - weight) * outline[first] + weight *
    outline[second].

    The rest outline is ``midline_outline`` at the neutral parameters; the walk starts at its
    most anterior station and goes round toward the upper surface (the neighbour that is
    higher), measuring the arc length of the straight segments between stations.
    arcs_mm : (k,) float, default ``TONGUE_SENSOR_ARC_MM``'s values. ValueError for an arc that
    is negative or longer than half the outline.
    """
    outline = midline_outline(rig, rig.neutral)
    n = len(outline)
    apex = int(np.argmax(outline[:, 0]))
    step = 1 if outline[(apex + 1) % n, 1] > outline[(apex - 1) % n, 1] else -1
    order = (apex + step * np.arange(n // 2 + 1)) % n
    walked = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(outline[order], axis=0),
                                                             axis=1))])
    arcs = np.asarray(list(TONGUE_SENSOR_ARC_MM.values()) if arcs_mm is None else arcs_mm,
                      dtype=np.float64)
    if np.any(arcs < 0) or np.any(arcs >= walked[-1]):
        raise ValueError(f"sensor arcs must lie in [0, {walked[-1]:.1f}) mm, got {arcs}")
    segment = np.searchsorted(walked, arcs, side="right") - 1
    weight = (arcs - walked[segment]) / (walked[segment + 1] - walked[segment])
    return order[segment].astype(np.int64), order[segment + 1].astype(np.int64), weight


def tongue_points(outline: Floats, anchors) -> Floats:
    """(k, 3) float64 tongue sensor positions on a posed outline (stations, 2) (z = 0)."""
    first, second, weight = anchors
    points = np.zeros((len(first), 3))
    points[:, :2] = (1.0 - weight)[:, None] * outline[first] + weight[:, None] * outline[second]
    return points


class FleshPointRig:
    """What the flesh points need, prepared once: the tongue rig and its sensor anchors, the
    rest incisor edges, and the face rig with the two lip meshes.

    tongue : TongueRig.  face_definition : the face rig (``face-rig.json``).
    lip_rest : {"upper_lip": (n, 3), "lower_lip": (m, 3)} rest vertices, project frame, in the
    order the face rig was built for.  landmarks : the ``landmarks.json`` document.
    """

    def __init__(self, tongue: TongueRig, face_definition: dict,
                 lip_rest: Mapping[str, npt.ArrayLike], landmarks: dict):
        self.tongue = tongue
        self._lip_ranges = {p["name"]: (p["min"], p["max"]) for p in face_definition["parameters"]}
        self.anchors = tongue_anchors(tongue)
        self.face = dict(face_definition, teeth=teeth_tables(face_definition["teeth"]))
        self.lips = face.prepare_meshes(face_definition, lip_rest, names=face.LIP_MESHES)
        positions = {mark["name"]: mark["position"] for mark in landmarks["landmarks"]}
        missing = [m for m in INCISOR_LANDMARKS.values() if m not in positions]
        if missing:
            raise ValueError(f"the landmarks lack {', '.join(missing)}")
        self.incisors = {name: np.asarray(positions[mark], dtype=np.float64)
                         for name, mark in INCISOR_LANDMARKS.items()}

    def frame(self, params: Mapping[str, float]) -> dict[str, Floats]:
        """{name: (3,) float64 mm} for one frame's parameters (tongue, jaw and lip values by
        name; missing ones neutral, others ignored; each clipped to its range)."""
        lips = {k: float(v) for k, v in params.items() if k in self._lip_ranges}
        return self.posed(self.tongue.values_clipped(params), lips)

    def posed(self, values: npt.ArrayLike, lips: Mapping[str, float],
              names: tuple[str, ...] = FLESH_POINT_NAMES) -> dict[str, Floats]:
        """{name: (3,) float64 mm} of ``names`` for the tongue rig's ``values`` (P,) and the
        lip parameters ``lips`` by name (missing ones neutral; each clipped to its range). The
        lips are posed only when a lip point is asked for (what makes a frame cost 1.6 ms)."""
        rig = self.tongue
        values = np.asarray(values, dtype=np.float64)
        pose = jaw_pose(values[rig.jaw_parameter], rig.jaw)
        points = dict(zip(TONGUE_SENSOR_ARC_MM,
                          tongue_points(midline_outline(rig, values), self.anchors),
                          strict=True))
        points["lower_incisor"] = apply_jaw_pose(self.incisors["lower_incisor"][None],
                                                 pose)[0]
        if any(name in face.LIP_MESHES for name in names):
            clipped = {k: min(max(float(v), self._lip_ranges[k][0]), self._lip_ranges[k][1])
                       for k, v in lips.items()}
            posed, _ = face.pose_face(self.face, self.lips, clipped, pose)
            for name in face.LIP_MESHES:
                points[name] = posed[name][self.lips[name]["reference_vertex"]]
        points["upper_incisor"] = self.incisors["upper_incisor"].copy()
        return {name: points[name] for name in names}

    @property
    def lip_ranges(self) -> dict[str, tuple[float, float]]:
        """{lip parameter: (min, max)} of the face rig."""
        return dict(self._lip_ranges)

    def tracks(self, tracks: Mapping[str, npt.ArrayLike]) -> dict[str, Floats]:
        """{name: (n_frames, 3) float64 mm} for parameter tracks {name: (n_frames,) values}
        (every track the same length; names the rigs do not know are ignored)."""
        arrays = {k: np.asarray(v, dtype=np.float64) for k, v in tracks.items()}
        lengths = {len(a) for a in arrays.values()}
        if len(lengths) != 1:
            raise ValueError(f"tracks must all have the same length, got {sorted(lengths)}")
        n = lengths.pop()
        out = {name: np.empty((n, 3)) for name in FLESH_POINT_NAMES}
        for i in range(n):
            for name, point in self.frame({k: float(a[i]) for k, a in arrays.items()}).items():
                out[name][i] = point
        return out
