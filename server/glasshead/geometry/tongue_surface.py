"""The reference tongue evaluator (numpy, float64): rig definition + parameters -> surface.

Twin of ``web/src/core/tongue.js``; ``geometry.tongue_rig`` describes the definition. Every
table that does not depend on the parameters (basis functions at the stations and page angles,
the blended rest ratios, the triangles) is built once in ``TongueRig.__init__``; an evaluation is
then a few small matrix products:

1. control points: rest + sum over parameters of (value - neutral) * move; then each point
   moves along its own ray from the hub by the sum of (value - neutral) * its radial move, in
   mm, its distance from the hub kept at least ``TONGUE_CONTROL_FLOOR_MM`` (a radial move
   leaves the point's direction from the hub as it is, whatever the straight moves did, so it
   cannot turn one point past another); then each point turns about the hub by the sum of
   (value - neutral) * its turn, in degrees (a turn keeps the point's distance from the hub,
   so a tongue turned back into the pharynx keeps its pages in order where the same move made
   of straight steps would fold them);
2. the jaw pose moves the sagittal control points and the hub, each by its jaw weight; then the
   hub follows its parameters (their summed move, posed with the jaw) as far as every turn
   between neighbouring stations keeps ``hub.keep`` of its cross product about the unmoved hub;
3. stations: S = B_sagittal @ points; page direction e = (S - H) / |S - H|;
4. radial control values per station, with R = |S - H|, R0 its rest value and w the pole
   half-width: w + (R0 - w) * blended ratio + (R - R0) * follow + blended offsets times the
   coronal weight, at least ``TONGUE_CONTROL_FLOOR_MM`` (the pole controls are w itself);
5. radii at the page samples: lambda = values @ B_coronal^T; vertex = H + lambda * (cos(phi) e
   + sin(phi) (1 + k (1 - sin(phi)^4)) z), k the blended sideways stretch of the sections.

Cohen, Beskow and Massaro (1998), section 3: sagittal and coronal B-splines whose control points
move singly and in pairs under articulation parameters.
"""

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from glasshead.constants import TONGUE_CONTROL_FLOOR_MM
from glasshead.geometry.bspline import basis_matrix
from glasshead.geometry.jaw import apply_jaw_pose, jaw_pose
from glasshead.geometry.mesh_volume import mesh_volume, vertex_normals
from glasshead.geometry.tongue_rig import validate_definition

Floats = npt.NDArray[np.float64]
#: ``TongueRig.control_points``: posed sagittal control points, hub, coronal offsets, stretches.
Controls = tuple[Floats, Floats, Floats, Floats]


class ParameterError(ValueError):
    """A parameter set the rig refuses: an unknown name, or a value outside its range."""

    def __init__(self, name, message):
        self.parameter = name
        super().__init__(message)


@dataclass
class TongueSurface:
    """vertices (n, 3) float64 mm; normals (n, 3) float64 unit; triangles (m, 3) int64;
    volume float mm^3."""

    vertices: np.ndarray
    normals: np.ndarray
    triangles: np.ndarray
    volume: float


def surface_triangles(stations: int, page_samples: int) -> npt.NDArray[np.int64]:
    """Triangles (2 * stations * page_samples, 3) int64 of the surface layout (see tongue_rig).

    Vertex 0 is the right pole, 1 the left pole, ring vertex (i, j) is 2 + i * page_samples + j.
    Winding: (station i, sample j) -> (i + 1, j) -> (i, j + 1) is counter-clockwise from outside.
    """
    if stations < 3 or page_samples < 2:
        raise ValueError("need at least 3 stations and 2 page samples")
    i = np.arange(stations)
    j = np.arange(page_samples - 1)
    here = 2 + i[:, None] * page_samples
    there = 2 + ((i + 1) % stations)[:, None] * page_samples
    a, b, c, d = here + j, there + j, there + j + 1, here + j + 1
    quads = np.stack([np.stack([a, b, c], -1), np.stack([a, c, d], -1)], axis=2).reshape(-1, 3)
    right = np.stack([np.zeros(stations, np.int64), there[:, 0], here[:, 0]], -1)
    last = page_samples - 1
    left = np.stack([here[:, 0] + last, there[:, 0] + last, np.ones(stations, np.int64)], -1)
    return np.concatenate([right, quads, left]).astype(np.int64)


class TongueRig:
    """A loaded rig definition with its parameter-independent tables."""

    def __init__(self, definition: dict[str, Any]):
        validate_definition(definition)
        self.definition = definition
        table = definition["parameters"]
        self.parameter_names = [p["name"] for p in table]
        self.parameters = {p["name"]: p for p in table}
        self._index = {name: k for k, name in enumerate(self.parameter_names)}
        self.neutral = np.array([p["neutral"] for p in table], dtype=np.float64)
        self.minimum = np.array([p["min"] for p in table], dtype=np.float64)
        self.maximum = np.array([p["max"] for p in table], dtype=np.float64)

        sagittal, coronal, surface = (definition[k] for k in ("sagittal", "coronal", "surface"))
        points = sagittal["control_points"]
        point_index = {p["name"]: k for k, p in enumerate(points)}
        self.rest_points = np.array([p["position"] for p in points], dtype=np.float64)
        self.point_jaw_weights = np.array([p["jaw_weight"] for p in points], dtype=np.float64)
        section_weights = np.array([p["section_weights"] for p in points], dtype=np.float64)
        self.station_params = np.array(surface["station_params"], dtype=np.float64)
        self.station_basis = basis_matrix(sagittal["knots"], sagittal["degree"],
                                          self.station_params, count=len(points))
        self.station_blend = self.station_basis @ section_weights
        coronal_weights = np.array([p["coronal_weight"] for p in points], dtype=np.float64)
        self.station_offset_blend = self.station_blend \
            * (self.station_basis @ coronal_weights)[:, None]

        sections = coronal["sections"]
        controls = coronal["controls"]
        control_index = {c: k for k, c in enumerate(controls)}
        self.pole_controls = np.array(coronal["pole_controls"], dtype=np.int64)
        self.pole_half_width = float(coronal["pole_half_width"])
        ratios = np.array([coronal["ratios"][s] for s in sections], dtype=np.float64)
        ratios[:, self.pole_controls] = 0.0
        self.station_ratios = self.station_blend @ ratios
        angles_deg = np.array(surface["page_angles_deg"], dtype=np.float64)
        self.page_basis = basis_matrix(coronal["knots"], coronal["degree"], angles_deg)
        self.page_cos = np.cos(np.radians(angles_deg))
        self.page_sin = np.sin(np.radians(angles_deg))

        count = len(table)
        self.sagittal_moves = np.zeros((count, len(points), 2))
        self.coronal_moves = np.zeros((count, len(sections), len(controls)))
        self.stretch_moves = np.zeros((count, len(sections)))
        self.point_turns = np.zeros((count, len(points)))
        self.point_radials = np.zeros((count, len(points)))
        section_index = {s: k for k, s in enumerate(sections)}
        for k, p in enumerate(table):
            for move in p["moves"]:
                if "turn" in move:
                    self.point_turns[k, point_index[move["point"]]] += move["turn"]
                elif "radial" in move:
                    self.point_radials[k, point_index[move["point"]]] += move["radial"]
                elif "point" in move:
                    self.sagittal_moves[k, point_index[move["point"]]] += move["by"]
                elif "stretch" in move:
                    self.stretch_moves[k, section_index[move["section"]]] += move["stretch"]
                else:
                    self.coronal_moves[k, section_index[move["section"]],
                                       control_index[move["control"]]] += move["by"]

        # the moves as (parameters, everything they move): one product per evaluation
        self._sagittal_moves_flat = self.sagittal_moves.reshape(count, -1)
        self._coronal_moves_flat = self.coronal_moves.reshape(count, -1)

        self.jaw = definition["jaw"]
        self.jaw_parameter = self._index[self.jaw["parameter"]]
        self.hub = np.array(definition["hub"]["position"], dtype=np.float64)
        self.hub_jaw_weight = float(definition["hub"]["jaw_weight"])
        self.hub_follows = np.zeros((count, 2))
        for follow in definition["hub"]["follows"]:
            self.hub_follows[self._index[follow["parameter"]]] += follow["by"]
        self.hub_keep = float(definition["hub"]["keep"])
        self.follow = np.array(coronal["follow"], dtype=np.float64)
        self.rest_radius = np.linalg.norm(self.station_basis @ self.rest_points - self.hub, axis=1)
        self.stations = len(self.station_params)
        self.page_samples = len(angles_deg)
        self.triangles = surface_triangles(self.stations, self.page_samples)
        self.vertex_count = 2 + self.stations * self.page_samples

    # --- parameters ---------------------------------------------------------------------------

    def values_clipped(self, params: Mapping[str, float]) -> Floats:
        """(P,) float64 values of a frame of parameter tracks: names the rig does not know
        ignored, missing ones neutral, each clipped to its range (a coarticulated track, a
        weighted mean of targets in range, can pass a bound by a rounding)."""
        values = self.neutral.copy()
        for name, value in params.items():
            if name in self._index:
                values[self._index[name]] = value
        return np.clip(values, self.minimum, self.maximum)

    def values_from(self, params: Mapping[str, float] | None = None) -> Floats:
        """(P,) float64 parameter values from a name -> value mapping; missing names are neutral.

        Raises ParameterError for an unknown name or a value that is not finite or out of range.
        """
        values = self.neutral.copy()
        for name, value in (params or {}).items():
            if name not in self._index:
                raise ParameterError(name, f"unknown parameter {name!r}; known: "
                                           + ", ".join(self.parameter_names))
            p = self.parameters[name]
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not math.isfinite(value):
                raise ParameterError(name, f"{name} = {value!r} is not a finite number")
            if not p["min"] <= value <= p["max"]:
                raise ParameterError(name, f"{name} = {value:g} is outside its range "
                                           f"[{p['min']:g}, {p['max']:g}] {p['unit']}")
            values[self._index[name]] = float(value)
        return values

    def _checked(self, values: npt.ArrayLike) -> Floats:
        values = np.asarray(values, dtype=np.float64)
        if values.shape != self.neutral.shape:
            raise ValueError(f"values must have shape {self.neutral.shape}, got {values.shape}")
        if not np.all(np.isfinite(values)):
            raise ValueError("parameter values must be finite")
        return values

    # --- evaluation -----------------------------------------------------------------------------

    def control_points(self, values: npt.ArrayLike) -> Controls:
        """Posed sagittal control points (n, 2), hub (2,), coronal offsets (sections, controls)
        and section stretches (sections,)."""
        values = self._checked(values)
        delta = values - self.neutral
        points = self.rest_points + (delta @ self._sagittal_moves_flat).reshape(-1, 2)
        radial = delta @ self.point_radials
        moved = radial != 0
        if np.any(moved):
            away = points[moved] - self.hub
            distance = np.linalg.norm(away, axis=1)
            reach = np.maximum(distance + radial[moved], TONGUE_CONTROL_FLOOR_MM)
            points[moved] = self.hub + away * (reach / distance)[:, None]
        turn = np.radians(delta @ self.point_turns)
        if np.any(turn):
            cos, sin = np.cos(turn), np.sin(turn)
            x, y = (points - self.hub).T
            points = self.hub + np.column_stack((cos * x - sin * y, sin * x + cos * y))
        offsets = (delta @ self._coronal_moves_flat).reshape(self.coronal_moves.shape[1:])
        stretch = delta @ self.stretch_moves
        pose = jaw_pose(values[self.jaw_parameter], self.jaw)
        points = apply_jaw_pose(points, pose, self.point_jaw_weights)
        hub = apply_jaw_pose(self.hub[None, :], pose, [self.hub_jaw_weight])[0]
        fx, fy = (float(f) for f in delta @ self.hub_follows)
        if fx or fy:
            # posed with the jaw: the hub's pose is affine, so only its linear part acts
            w, m = self.hub_jaw_weight, pose
            move = np.array([fx + w * (m[0, 0] * fx + m[0, 1] * fy - fx),
                             fy + w * (m[1, 0] * fx + m[1, 1] * fy - fy)])
            hub = hub + self.hub_share(points, hub, move) * move
        return points, hub, offsets, stretch

    def hub_share(self, points: Floats, hub: Floats, move: Floats) -> float:
        """The share of ``move`` that the hub may take from ``hub`` with the posed ``points``:
        at most 1, and so much that the cross product of every two neighbouring stations seen
        from the hub keeps ``hub_keep`` of its value about ``hub``. With a = S_i - hub and
        b = S_i+1 - hub, the cross product from hub + t * move is a x b - t (a - b) x move:
        linear in t, so its bound is exact."""
        seen = self.station_basis @ points - hub
        following = np.concatenate((seen[1:], seen[:1]))
        cross = seen[:, 0] * following[:, 1] - seen[:, 1] * following[:, 0]
        step = seen - following
        loss = step[:, 0] * move[1] - step[:, 1] * move[0]
        bound = np.divide(cross, loss, out=np.full(self.stations, np.inf),
                          where=(loss > 0) & (cross > 0))
        return min(1.0, (1.0 - self.hub_keep) * float(bound.min()))

    def page_radii(self, values: npt.ArrayLike, posed: Controls | None = None
                   ) -> tuple[Floats, Floats, Floats, Floats, Floats]:
        """Hub (2,), stations (s, 2), page directions (s, 2), radii (s, page_samples) and
        sideways stretch (s,) of the surface. ``posed``: ``control_points(values)`` when the
        caller has them already (rigs that differ only in their sampling pose them alike)."""
        points, hub, offsets, stretch = self.control_points(values) if posed is None else posed
        stations = self.station_basis @ points
        towards = stations - hub
        radius = np.linalg.norm(towards, axis=1)
        direction = towards / radius[:, None]
        pole = self.pole_half_width
        controls = pole + (self.rest_radius[:, None] - pole) * self.station_ratios \
            + (radius - self.rest_radius)[:, None] * self.follow \
            + self.station_offset_blend @ offsets
        # No control comes nearer the hub than the floor: a deep groove where the curve has come
        # close to the hub would otherwise take the radius through it. The B-spline basis is
        # positive and sums to 1, so every radius keeps at least the floor.
        np.maximum(controls, TONGUE_CONTROL_FLOOR_MM, out=controls)
        controls[:, self.pole_controls] = self.pole_half_width
        return hub, stations, direction, controls @ self.page_basis.T, self.station_blend @ stretch

    def vertices(self, values: npt.ArrayLike, posed: Controls | None = None) -> Floats:
        """(vertex_count, 3) float64 surface vertices for parameter values (P,) (``posed``: as
        for ``page_radii``)."""
        hub, _stations, direction, radii, stretch = self.page_radii(values, posed)
        ring = np.empty((self.stations, self.page_samples, 3))
        planar = radii * self.page_cos
        ring[..., 0] = hub[0] + planar * direction[:, 0, None]
        ring[..., 1] = hub[1] + planar * direction[:, 1, None]
        ring[..., 2] = radii * self.page_sin * (1.0 + stretch[:, None] * (1.0 - self.page_sin**4))
        poles = np.array([[hub[0], hub[1], -self.pole_half_width],
                          [hub[0], hub[1], self.pole_half_width]])
        return np.concatenate([poles, ring.reshape(-1, 3)])

    def evaluate(self, values: npt.ArrayLike) -> TongueSurface:
        """The surface (vertices, normals, triangles, volume) for parameter values (P,), as a
        TongueSurface; ``values_from`` turns a name -> value mapping into values."""
        vertices = self.vertices(values)
        return TongueSurface(vertices, vertex_normals(vertices, self.triangles), self.triangles,
                             mesh_volume(vertices, self.triangles))

    def volume(self, values: npt.ArrayLike, posed: Controls | None = None) -> float:
        """Enclosed volume, mm^3, for parameter values (P,) (``posed``: as for
        ``page_radii``)."""
        return mesh_volume(self.vertices(values, posed), self.triangles)

    def pages_in_order(self, values: npt.ArrayLike) -> bool:
        """True when the pages turn once round the hub in order, every radius is positive and
        every stretch keeps the rays of its page in order (-1 < k < 1/4, see
        ``tongue_parameters.STRETCH``): then the surface is closed and free of self-intersection."""
        _hub, _stations, direction, radii, stretch = self.page_radii(values)
        following = np.roll(direction, -1, axis=0)
        turn = np.arctan2(direction[:, 0] * following[:, 1] - direction[:, 1] * following[:, 0],
                          np.einsum("ij,ij->i", direction, following))
        return bool(np.all(turn > 0) and abs(turn.sum() - 2 * np.pi) < 1e-6
                    and np.all(radii > 0) and np.all((stretch > -1) & (stretch < 0.25)))
