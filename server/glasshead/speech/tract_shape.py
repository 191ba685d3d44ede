"""A posed head's tract: the mid-sagittal section of every part that bounds the air, its area
function (``acoustics.area_function``) and the formants of that tube (``acoustics.tube``).

The parts, as the browser's diagram cuts them (``scene/DiagramSection.js``):
- the tongue: its mid-sagittal outline (the page-angle-0 points of the rig's stations, where
  the surface meets z = 0), posed with the jaw;
- the velum: the rig's blend for ``velum_opening``, cut at z = 0;
- the lips: the face rig's posed lip meshes, cut at z = 0; the lips' front is the mean of
  their most anterior points;
- the mandible: its rest section moved by the jaw's pose;
- the still parts (palate, pharyngeal wall, the larynx's entrance) and the stations, from
  ``tract-section.json``.

The nasal branch is the nose of ``tract-section.json`` behind the velum's port
(``geometry.velum.nasal_port_area``, ``area_function.nasal_branch``); with the port open, the
formants are those of the tube with its nose.
"""

from collections.abc import Mapping, Sequence

import numpy as np
import numpy.typing as npt

from glasshead.acoustics import tube
from glasshead.acoustics.area_function import (
    Part,
    area_function,
    chain_part,
    nasal_branch,
    plane_segments,
)
from glasshead.geometry import face_rig as face
from glasshead.geometry.flesh_points import FleshPointRig, midline_outline
from glasshead.geometry.jaw import apply_jaw_pose, jaw_pose
from glasshead.geometry.velum import VelumRig, nasal_port_area, pose_velum

Floats = npt.NDArray[np.float64]


def _parts(polylines) -> list[Part]:
    return [chain_part(p["points"], p["closed"]) for p in polylines]


class TractShape:
    """What the area function of a pose needs, prepared once.

    flesh : the flesh points' rig (its tongue rig, face rig and prepared lips).
    velum : the velum rig; velum_faces : the rest velum mesh's faces (m, 3).
    lip_faces : {"upper_lip": faces, "lower_lip": faces}.  section : ``tract-section.json``.
    """

    def __init__(self, flesh: FleshPointRig, velum: VelumRig, velum_faces: npt.ArrayLike,
                 lip_faces: Mapping[str, npt.ArrayLike], section: dict):
        self.flesh = flesh
        self.tongue = flesh.tongue
        self.velum = velum
        self.velum_faces = np.asarray(velum_faces, dtype=np.int64)
        self.lip_faces = {name: np.asarray(lip_faces[name], dtype=np.int64)
                          for name in face.LIP_MESHES}
        self.stations = np.asarray(section["stations"], dtype=np.float64)
        self.incisor_x = float(section["incisor_x"])
        self.uvula_y = float(section["uvula_y"])
        self.still_floor = _parts(section["still"]["floor"])
        self.still_roof = _parts(section["still"]["roof"])
        self.mandible = [(np.asarray(p["points"], dtype=np.float64), p["closed"])
                         for p in section["mandible"]]
        self.lip_ranges = flesh.lip_ranges
        self.nose = section["nose"]

    def parts(self, params: Mapping[str, float]) -> dict:
        """The posed section: {"floor": [Part], "roof": [Part], "lip_front_x", "lip_rounding",
        "velum_opening"} for a frame's parameters by name (missing ones neutral; each clipped
        to its range)."""
        rig = self.tongue
        values = rig.values_clipped(params)
        pose = jaw_pose(values[rig.jaw_parameter], rig.jaw)
        tongue = chain_part(midline_outline(rig, values), True)
        mandible = [chain_part(apply_jaw_pose(np.column_stack([p, np.zeros(len(p))]),
                                              pose)[:, :2], closed)
                    for p, closed in self.mandible]
        opening = min(max(float(params.get("velum_opening", 0.0)), 0.0), 1.0)
        velum = (plane_segments(pose_velum(self.velum, opening), self.velum_faces), True)
        lips = {k: min(max(float(v), lo), hi) for k, v in params.items()
                if k in self.lip_ranges for lo, hi in [self.lip_ranges[k]]}
        posed, _ = face.pose_face(self.flesh.face, self.flesh.lips, lips, pose)
        upper = plane_segments(posed["upper_lip"], self.lip_faces["upper_lip"])
        lower = plane_segments(posed["lower_lip"], self.lip_faces["lower_lip"])
        fronts = [s.reshape(-1, 2)[:, 0].max() for s in (upper, lower) if len(s)]
        return {"floor": [tongue, (lower, True), *mandible, *self.still_floor],
                "roof": [velum, (upper, True), *self.still_roof],
                "lip_front_x": float(np.mean(fronts)) if fronts else self.incisor_x,
                "lip_rounding": float(lips.get("lip_rounding", 0.0)),
                "velum_opening": opening}

    def area_function(self, params: Mapping[str, float]) -> dict:
        """``area_function.area_function`` of the pose, with the nasal port's area
        (``nasal_port_mm2``) and the nasal branch (``nasal``, None while the port is shut)."""
        parts = self.parts(params)
        result = area_function(self.stations, parts["floor"], parts["roof"],
                               incisor_x=self.incisor_x, uvula_y=self.uvula_y,
                               lip_front_x=parts["lip_front_x"],
                               lip_rounding=parts["lip_rounding"])
        result["nasal_port_mm2"] = nasal_port_area(self.velum, parts["velum_opening"])
        result["nasal"] = nasal_branch(result["region"], self.nose, result["nasal_port_mm2"])
        return result

    def frames(self, tracks: Mapping[str, Sequence[float]]) -> list[dict]:
        """The area function of every frame of parameter tracks {name: (n_frames,) values}."""
        arrays = {k: np.asarray(v, dtype=np.float64) for k, v in tracks.items()}
        count = min((len(a) for a in arrays.values()), default=0)
        return [self.area_function({k: float(a[i]) for k, a in arrays.items()})
                for i in range(count)]

    def acoustics(self, params: Mapping[str, float]) -> dict:
        """The area function and the tube's formants: {"area_function": ..., "formants":
        (4,) Hz, "bandwidths": (4,) Hz}."""
        result = self.area_function(params)
        frequencies, bandwidths = tube.formants(result["length_mm"], result["area_mm2"],
                                                nasal=result["nasal"])
        return {"area_function": result, "formants": frequencies, "bandwidths": bandwidths}
