"""The velum (soft palate) posed by ``velum_opening``, and the nasal port's smallest cross-section.

Twin of ``web/src/core/velum.js``; the definition is ``velum-rig.json`` (``pipeline.velum_rig``,
format in docs/velum.md).

Piecewise-linear blend of three measured poses of one mesh (raised at 0, rest at r, lowered
at 1), vertex by vertex, as a morph target; the nasal port is the smallest cut across the
passage between the posed velum and the posterior pharyngeal wall, the wall being the raised
velum's posterior surface (where it closes the port) sampled at fixed points of that surface
(docs/velum.md).

Shapes: positions (n, 3) float64 mm, project frame; n = the rig's vertex count (3,787).
"""

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from glasshead.constants import VELUM_PARAMETER, VELUM_POSES, VELUM_RIG_FORMAT_VERSION

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]


class VelumRigError(ValueError):
    """A velum rig definition that cannot be read."""


@dataclass(frozen=True)
class VelumRig:
    """A velum rig ready to pose.

    poses : (3, n, 3) float64, raised, rest, lowered (mm). rest_share : r in (0, 1).
    port_vertices : (k, 3) int64 and port_weights : (k, 3) float64, each sample a fixed point of
    a raised-pose triangle (barycentric); port_wall : (k, 3) that point in the raised pose;
    port_normals : (k, 3) unit normals of the wall toward the pharynx; port_rows : (k,) int64, the
    cut each sample lies on; row_count; width_mm : the width a sample stands for.
    """

    definition: Mapping[str, Any]
    poses: Floats
    rest_share: float
    port_vertices: Ints
    port_weights: Floats
    port_wall: Floats
    port_normals: Floats
    port_rows: Ints
    row_count: int
    width_mm: float

    @property
    def vertex_count(self) -> int:
        return int(self.poses.shape[1])

    @property
    def parameter(self) -> Mapping[str, Any]:
        return dict(self.definition["parameters"][0])


def _array(block: Mapping[str, Any], key: str, dtype: type, width: int, what: str) -> Any:
    values: npt.NDArray[Any] = np.asarray(block.get(key, []), dtype=dtype)
    if values.ndim != 1 or len(values) % width:
        raise VelumRigError(f"{what}.{key} must be a flat list of {width}-tuples")
    return values.reshape(-1, width)


def prepare_velum(definition: Mapping[str, Any]) -> VelumRig:
    """Check a velum rig definition (a dict from ``velum-rig.json``) and make it ready to pose.
    Raises VelumRigError naming what is wrong."""
    if not isinstance(definition, Mapping):
        raise VelumRigError("the velum rig must be a JSON object")
    version = definition.get("format_version")
    if version != VELUM_RIG_FORMAT_VERSION:
        raise VelumRigError(f"velum rig format_version {version!r} is not "
                            f"{VELUM_RIG_FORMAT_VERSION}")
    parameters = definition.get("parameters")
    if not isinstance(parameters, list) or len(parameters) != 1 \
            or parameters[0].get("name") != VELUM_PARAMETER:
        raise VelumRigError(f"the velum rig must have the one parameter {VELUM_PARAMETER}")
    spec = parameters[0]
    for key in ("unit", "min", "max", "neutral", "group", "description"):
        if key not in spec:
            raise VelumRigError(f"parameter {VELUM_PARAMETER} lacks {key}")
    if (spec["min"], spec["max"]) != (0, 1):
        raise VelumRigError(f"{VELUM_PARAMETER} must run from 0 to 1")
    poses = definition.get("poses")
    if not isinstance(poses, Mapping):
        raise VelumRigError("the velum rig lacks poses")
    names = tuple(poses.get("names", ()))
    if names != VELUM_POSES:
        raise VelumRigError(f"poses.names must be {list(VELUM_POSES)}, got {list(names)}")
    count = poses.get("vertex_count")
    blended = []
    for name in VELUM_POSES:
        positions = _array(poses.get("positions", {}), name, np.float64, 3, "poses.positions")
        if len(positions) != count or not np.all(np.isfinite(positions)):
            raise VelumRigError(f"pose {name} must have {count} finite vertices")
        blended.append(positions)
    r = poses.get("at", [None, None, None])[1]
    if not isinstance(r, (int, float)) or not 0 < r < 1 or spec["neutral"] != r:
        raise VelumRigError("poses.at[1] (the rest share r) must lie in (0, 1) and be the "
                            "parameter's neutral value")
    port = definition.get("port")
    if not isinstance(port, Mapping):
        raise VelumRigError("the velum rig lacks port")
    vertices = _array(port, "vertices", np.int64, 3, "port")
    weights = _array(port, "weights", np.float64, 3, "port")
    normals = _array(port, "normals", np.float64, 3, "port")
    rows = np.asarray(port.get("rows", []), dtype=np.int64)
    k = len(vertices)
    if not k or len(weights) != k or len(normals) != k or rows.shape != (k,):
        raise VelumRigError("port vertices, weights, normals and rows must have one entry "
                            "per sample")
    if vertices.min() < 0 or vertices.max() >= count:
        raise VelumRigError(f"port vertices must lie in [0, {count})")
    row_count = int(port.get("row_count", 0))
    if row_count < 1 or rows.min() < 0 or rows.max() >= row_count:
        raise VelumRigError("port rows must lie in [0, row_count)")
    width = float(port.get("width_mm", 0.0))
    if not width > 0:
        raise VelumRigError("port width_mm must be positive")
    stack = np.stack(blended)
    wall = _sample_points(stack[0], vertices, weights)
    return VelumRig(definition, stack, float(r), vertices, weights, wall, normals, rows,
                    row_count, width)


def _rig(rig: "VelumRig | Mapping[str, Any]") -> VelumRig:
    return rig if isinstance(rig, VelumRig) else prepare_velum(rig)


def check_opening(rig: VelumRig | None, opening: float) -> float:
    """The opening as a float; ValueError naming the parameter and its range when it is not a
    finite number in [0, 1]."""
    if isinstance(opening, bool) or not isinstance(opening, (int, float, np.floating)) \
            or not math.isfinite(opening):
        raise ValueError(f"{VELUM_PARAMETER} = {opening!r} is not a finite number")
    if not 0.0 <= opening <= 1.0:
        raise ValueError(f"{VELUM_PARAMETER} = {opening:g} is outside its range [0, 1] ratio")
    return float(opening)


def _segment(rig: VelumRig, opening: float) -> tuple[Floats, Floats, float]:
    """The two poses the opening lies between and its share u of the way from the first."""
    r = rig.rest_share
    if opening <= r:
        return rig.poses[0], rig.poses[1], opening / r
    return rig.poses[1], rig.poses[2], (opening - r) / (1.0 - r)


def _sample_points(positions: Floats, vertices: Ints, weights: Floats) -> Floats:
    return (weights[:, 0, None] * positions[vertices[:, 0]]
            + weights[:, 1, None] * positions[vertices[:, 1]]
            + weights[:, 2, None] * positions[vertices[:, 2]])


# A morph-target (blend-shape) blend, piecewise linear through the three measured poses:
# p(o) = a (1 - u) + b u, with (a, b, u) = (raised, rest, o / r) for o <= r and
# (rest, lowered, (o - r) / (1 - r)) above; exact at o = 0, r and 1.
def pose_velum(rig: "VelumRig | Mapping[str, Any]", opening: float,
               out: Floats | None = None) -> Floats:
    """Velum vertex positions (n, 3) float64 mm at ``opening`` in [0, 1]; written into ``out``
    when given (an (n, 3) float64 array). ValueError for an opening out of range."""
    rig = _rig(rig)
    a, b, u = _segment(rig, check_opening(rig, opening))
    if out is None:
        out = np.empty_like(a)
    elif out.shape != a.shape or out.dtype != np.float64:
        raise ValueError(f"out must be a {a.shape} float64 array")
    np.multiply(a, 1.0 - u, out=out)
    out += b * u
    return out


def port_gaps(rig: "VelumRig | Mapping[str, Any]", opening: float) -> Floats:
    """(k,) float64 mm: at each port sample, how far the posed velum lies in front of the wall
    along the wall's normal (0 where it touches or would pass it)."""
    rig = _rig(rig)
    a, b, u = _segment(rig, check_opening(rig, opening))
    vertices, weights = rig.port_vertices, rig.port_weights
    # The same operations in the same order as the wall's (``_sample_points``): at opening 0 the
    # points are the wall's bit for bit, and every gap is exactly 0.
    posed = a[vertices] * (1.0 - u) + b[vertices] * u
    points = (weights[:, 0, None] * posed[:, 0] + weights[:, 1, None] * posed[:, 1]
              + weights[:, 2, None] * posed[:, 2])
    gaps = np.einsum("ij,ij->i", rig.port_wall - points, rig.port_normals)
    return np.maximum(gaps, 0.0)


def port_cut_areas(rig: "VelumRig | Mapping[str, Any]", opening: float) -> Floats:
    """(rows,) float64 mm^2: the area of each cut across the passage (its gaps times the width
    each sample stands for)."""
    rig = _rig(rig)
    gaps = port_gaps(rig, opening)
    areas: Floats = np.bincount(rig.port_rows, weights=gaps * rig.width_mm,
                                minlength=rig.row_count).astype(np.float64)
    return areas


def nasal_port_area(rig: "VelumRig | Mapping[str, Any]", opening: float) -> float:
    """The nasal port's smallest cross-section, mm^2, at ``opening``: the smallest cut area
    (``port_cut_areas``). Exactly 0 at opening 0 (the raised velum is the wall)."""
    return float(port_cut_areas(rig, opening).min())
