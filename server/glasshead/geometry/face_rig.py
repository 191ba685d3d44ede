"""Face deformation: the skin and lips following the jaw, and the lip parameters.

Reference (numpy, float64) twin of ``web/src/core/faceRig.js``; the shared vectors in
``tests/vectors/face-rig.json`` keep the two in agreement. The rig definition (``face-rig.json``,
written by ``glasshead.pipeline.face_rig``) holds every number used here.

A posed vertex is found in four steps, each a function of the vertex's rest position and its jaw
weight w only, so two meshes sharing a point (a lip and the skin) move it identically:

1. Shape offsets (protrusion, rounding, upper-lip raise, lower-lip tuck): smooth compact bumps
   centred on the mouth times a direction, added at rest, i.e. in the frame of whichever bone the
   vertex follows.
2. Jaw skinning: the vertex takes the fraction w of the jaw's rigid motion along its screw axis
   (Chasles' theorem; screw linear interpolation, ScLERP, as in Kavan, Collins, Zara and
   O'Sullivan 2008, "Geometric skinning with approximate dual quaternion blending", section 3).
   Unlike blending matrices, this keeps w = 0.5 points on the arc, with no shrinking.
3. Closure: the lips' mid-sagittal gap is measured and, as far as ``lip_opening`` asks, closed by
   a bump times (w - a) times one vector C, so the upper lip (w = 0) moves by -a C and the lower
   (w = 1) by (1 - a) C; C is solved from the measured gap.
4. Teeth: points of the skin and lips behind the labial faces of the incisors are pushed out onto
   them (the upper faces fixed to the maxilla, the lower ones moving with the jaw;
   ``geometry.face_teeth``).

Points whose weight and field coefficients are all 0 (most of the head shell and the upper face)
do not move at all: the real-time twin skips them.

``lip_opening`` is the share of the lips' natural gap (the gap the jaw and the shape parameters
leave) that is kept: 1 leaves the lips as the jaw takes them, 0 closes them (/p b m/) and presses
them ``field.lip_press_mm`` past level, so that their sections meet (``closure_target``).
"""

import numpy as np

from glasshead.constants import (
    FACE_RIG_COEFF_COUNT,
    FACE_RIG_LIP_MESHES,
    FACE_RIG_LIP_PARAMETERS,
    FACE_RIG_MESHES,
    FACE_RIG_TEETH_MESHES,
)
from glasshead.geometry.face_teeth import clamp_to_teeth

#: Row layout of the per-vertex field coefficients (``field_coefficients``).
COEFF_COUNT = FACE_RIG_COEFF_COUNT
(COEFF_PROTRUSION, COEFF_ROUND_X, COEFF_ROUND_Z, COEFF_RAISE, COEFF_TUCK,
 COEFF_CLOSURE) = range(COEFF_COUNT)

#: Layout of the jaw screw (``jaw_screw``): axis u, angle, slide along u, t_perp, u x t_perp.
SCREW_SIZE = 11

#: Below this rotation (radians) the jaw motion is treated as a pure translation.
SCREW_MIN_ANGLE = 1e-9

#: The meshes the rig deforms, the lips, the meshes kept in front of the incisors and the lip
#: parameters in table order (declared once, in constants.py, for both evaluators).
MESH_NAMES = FACE_RIG_MESHES
LIP_MESHES = FACE_RIG_LIP_MESHES
TEETH_MESHES = FACE_RIG_TEETH_MESHES
LIP_PARAMETER_NAMES = FACE_RIG_LIP_PARAMETERS


def _points(name, array):
    array = np.asarray(array, dtype=np.float64)
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError(f"{name} must have shape (n, 3), got {array.shape}")
    return array


def rigid_parts(jaw_pose):
    """(rotation (3, 3), translation (3,)) float64 of a jaw pose.

    jaw_pose : (3, 4) [R | t] (``geometry.jaw.jaw_pose``) or (4, 4) homogeneous; maps rest
    mandible points to posed ones (project frame, mm). ValueError unless a finite rigid motion.
    """
    m = np.asarray(jaw_pose, dtype=np.float64)
    if m.shape not in ((3, 4), (4, 4)) or not np.all(np.isfinite(m)):
        raise ValueError(f"jaw pose must be a finite (3, 4) or (4, 4) matrix, got {m.shape}")
    r, t = m[:3, :3], m[:3, 3]
    if not np.allclose(r @ r.T, np.eye(3), atol=1e-6) or np.linalg.det(r) < 0:
        raise ValueError("jaw pose must be a rigid motion (a rotation and a translation)")
    return r, t


def jaw_screw(jaw_pose):
    """Screw decomposition of the jaw's rigid motion (Chasles' theorem: a turn about an axis and
    a slide along it).

    jaw_pose : (3, 4) or (4, 4), see ``rigid_parts``.
    Returns (11,) float64: axis u (3), angle (rad, >= 0), slide d along u, the translation's part
    perpendicular to u, t_perp (3), and u x t_perp (3).
    """
    r, t = rigid_parts(jaw_pose)
    skew = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]])
    sin_angle = 0.5 * np.linalg.norm(skew)
    cos_angle = 0.5 * (np.trace(r) - 1.0)
    angle = float(np.arctan2(sin_angle, cos_angle))
    if angle < SCREW_MIN_ANGLE:
        axis = np.array([0.0, 0.0, 1.0])
        angle = 0.0
    else:
        # The skew part vanishes near 180 degrees, far outside any jaw motion.
        axis = skew / np.linalg.norm(skew)
    slide = float(axis @ t)
    t_perp = t - slide * axis
    return np.concatenate([axis, [angle, slide], t_perp, np.cross(axis, t_perp)])


def skin_jaw(rest, weights, screw, out=None):
    """Move each point by the fraction w of the jaw's screw motion.

    The fraction w of a screw (u, angle, d) through a point p turns by w*angle about the axis and
    slides by w*d: x' = R(w*angle) x + A t_perp + B (u x t_perp) + w d u, with A and B below
    (from p = (t_perp + cot(angle/2) u x t_perp) / 2, which avoids p itself: it runs to infinity as
    the angle goes to zero).

    rest : (n, 3) float.  weights : (n,) float in [0, 1].  screw : (11,) from ``jaw_screw``.
    Returns (n, 3) float64 (written into ``out`` when given).
    """
    rest = _points("rest", rest)
    w = np.asarray(weights, dtype=np.float64)
    if w.shape != (len(rest),):
        raise ValueError(f"weights must have shape ({len(rest)},), got {w.shape}")
    u, angle, slide = screw[0:3], screw[3], screw[4]
    t_perp, u_cross_t = screw[5:8], screw[8:11]
    phi = w * angle
    c, s = np.cos(phi), np.sin(phi)
    if angle > SCREW_MIN_ANGLE:
        half_cot = 0.5 / np.tan(0.5 * angle)
        a = 0.5 * (1.0 - c) + half_cot * s
        b = half_cot * (1.0 - c) - 0.5 * s
    else:
        a, b = w, np.zeros_like(w)
    u_dot_x = rest @ u
    rotated = (rest * c[:, None] + np.cross(u, rest) * s[:, None]
               + np.outer(u_dot_x * (1.0 - c), u))
    result = (rotated + a[:, None] * t_perp + b[:, None] * u_cross_t
              + np.outer(w * slide, u))
    if out is not None:
        out[...] = result
        return out
    return result


def smooth_bump(points, bump):
    """A compact bump with a flat top: 1 inside ``plateau``, falling to 0 at the ellipsoid's edge.

    points : (n, 3) float.  bump : dict with ``centre`` (3), ``radii`` (3, > 0), ``plateau`` in
    [0, 1).  With r = |(p - centre) / radii|, the value is S((1 - r) / (1 - plateau)) clamped to
    [0, 1], S the quintic smoothstep 6t^5 - 15t^4 + 10t^3 (C2 at both ends).
    Returns (n,) float64.
    """
    points = _points("points", points)
    centre = np.asarray(bump["centre"], dtype=np.float64)
    radii = np.asarray(bump["radii"], dtype=np.float64)
    plateau = float(bump["plateau"])
    if np.any(radii <= 0) or not 0.0 <= plateau < 1.0:
        raise ValueError("a bump needs positive radii and a plateau in [0, 1)")
    r = np.linalg.norm((points - centre) / radii, axis=1)
    t = np.clip((1.0 - r) / (1.0 - plateau), 0.0, 1.0)
    return t * t * t * (t * (6.0 * t - 15.0) + 10.0)


def field_coefficients(rest, weights, field):
    """Per-vertex coefficients of the lip fields (fixed for a mesh; computed once at load).

    rest : (n, 3) float.  weights : (n,) jaw weights.  field : the rig's ``field`` dict.
    Returns (n, 6) float64, columns COEFF_*:
      protrusion  x offset per mm of ``lip_protrusion``,
      round_x, round_z  x and z offsets per mm of ``lip_rounding`` (corners move medially),
      raise  offset per mm of ``upper_lip_raise`` along ``raise_direction``,
      tuck  offset per mm of ``lower_lip_tuck`` along ``tuck_direction``,
      closure  the factor bump * (w - a) applied to the closure vector.
    """
    rest = _points("rest", rest)
    w = np.asarray(weights, dtype=np.float64)
    if w.shape != (len(rest),):
        raise ValueError(f"weights must have shape ({len(rest)},), got {w.shape}")
    bumps = field["bumps"]
    mouth = smooth_bump(rest, bumps["mouth"])
    zn = rest[:, 2] / float(field["mouth_half_width"])
    coeffs = np.empty((len(rest), COEFF_COUNT))
    coeffs[:, COEFF_PROTRUSION] = mouth
    # Rounding: the corners (|z| = half width) move medially by the full amount, an odd profile
    # m(z) = z exp((1 - z^2) / 2) that is 0 on the midline and 1 at a corner; they also come
    # forward by ``rounding_along_arch`` |m|, riding round the dental arch instead of into it,
    # and the middle of the lips comes forward by ``rounding_forward``.
    medial = zn * np.exp(0.5 * (1.0 - zn * zn))
    coeffs[:, COEFF_ROUND_X] = mouth * (float(field["rounding_forward"]) * np.exp(-zn * zn)
                                        + float(field["rounding_along_arch"]) * np.abs(medial))
    coeffs[:, COEFF_ROUND_Z] = -mouth * medial
    coeffs[:, COEFF_RAISE] = smooth_bump(rest, bumps["raise"]) * (1.0 - w)
    coeffs[:, COEFF_TUCK] = smooth_bump(rest, bumps["tuck"]) * w
    coeffs[:, COEFF_CLOSURE] = mouth * (w - float(field["closure_upper_share"]))
    return coeffs


def shape_offsets(coeffs, params, field, out=None):
    """Offsets (before jaw skinning) of the shape parameters; coeffs (n, 6). Returns (n, 3)."""
    coeffs = np.asarray(coeffs, dtype=np.float64)
    raise_dir = np.asarray(field["raise_direction"], dtype=np.float64)
    tuck_dir = np.asarray(field["tuck_direction"], dtype=np.float64)
    prot, rnd = params["lip_protrusion"], params["lip_rounding"]
    up, tuck = params["upper_lip_raise"], params["lower_lip_tuck"]
    result = (np.outer(coeffs[:, COEFF_RAISE] * up, raise_dir)
              + np.outer(coeffs[:, COEFF_TUCK] * tuck, tuck_dir))
    # Rounding brings the lips forward; spreading (rnd < 0) does not pull them into the teeth.
    result[:, 0] += prot * coeffs[:, COEFF_PROTRUSION] + max(rnd, 0.0) * coeffs[:, COEFF_ROUND_X]
    result[:, 2] += rnd * coeffs[:, COEFF_ROUND_Z]
    if out is not None:
        out[...] = result
        return out
    return result


def midline_points(points, edges):
    """Where the edges cross the mid-sagittal plane z = 0.

    points : (n, 3) float.  edges : (k, 2) int, each with z[i] <= 0 < z[j] at rest (the pose is
    symmetric, so the crossing edges stay the same).  Returns (k, 3) float64.
    """
    points = _points("points", points)
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    a, b = points[edges[:, 0]], points[edges[:, 1]]
    t = a[:, 2] / (a[:, 2] - b[:, 2])
    return a + t[:, None] * (b - a)


def lip_gap(upper_points, upper_edges, lower_points, lower_edges):
    """The lips' mid-sagittal gap: lowest point of the upper lip above the highest of the lower.

    Returns (gap, upper_lowest_y, lower_highest_y); gap = max(0, difference), 0 when in contact.
    """
    upper_y = midline_points(upper_points, upper_edges)[:, 1].min()
    lower_y = midline_points(lower_points, lower_edges)[:, 1].max()
    return max(0.0, float(upper_y - lower_y)), float(upper_y), float(lower_y)


def closure_target(opening, natural_gap, press):
    """The vertical gap the closure aims at, mm: the kept gap g = ``opening`` x ``natural_gap``,
    less a press that reaches ``press`` at ``opening`` 0 (closed lips press past level, so that
    their mid-sagittal sections meet) and fades as g grows to ``press`` or ``opening`` to 1."""
    kept = opening * natural_gap
    return kept - press * (1.0 - opening) * max(0.0, 1.0 - kept / press)


def solve_closure(upper, lower, target_gap, iterations):
    """Vertical closure amount c (mm) making the measured gap equal ``target_gap``.

    upper, lower : tuples (midline y values (k,), closure factors (k,)) of the lips' crossing
    points; a point's height becomes y + factor * c. The gap, min(upper) - max(lower), is
    piecewise linear and decreasing in c; each step is a Newton step on the current extreme pair.
    Returns float c.
    """
    (uy, uf), (ly, lf) = upper, lower
    c = 0.0
    for _ in range(int(iterations)):
        iu = int(np.argmin(uy + uf * c))
        il = int(np.argmax(ly + lf * c))
        gap = (uy[iu] + uf[iu] * c) - (ly[il] + lf[il] * c)
        slope = lf[il] - uf[iu]
        if slope <= 0.0 or abs(gap - target_gap) < 1e-9:
            break
        c += (gap - target_gap) / slope
    return float(c)


def lip_parameters(rig, params):
    """Validated lip parameters with neutral values filled in.

    params : mapping name -> float (a subset of the rig's lip parameters; others, such as the
    jaw's or the tongue's, are ignored). Raises ValueError naming a parameter that is not a finite
    number or lies outside its range.  Returns dict name -> float.
    """
    values = {}
    for spec in rig["parameters"]:
        name = spec["name"]
        value = params.get(name, spec["neutral"])
        try:
            value = float(value)
        except (TypeError, ValueError):
            raise ValueError(f"{name} must be a number, got {value!r}") from None
        if not np.isfinite(value) or not spec["min"] <= value <= spec["max"]:
            raise ValueError(f"{name} = {value} is outside [{spec['min']}, {spec['max']}] "
                             f"{spec['unit']}")
        values[name] = value
    return values


def prepare_meshes(rig, rest_vertices, names=MESH_NAMES):
    """The fixed per-mesh data a pose needs, from the rig and the meshes' rest vertices.

    rest_vertices : dict with every name in ``names`` -> (n, 3) float, project frame, in the
    vertex order the rig was built for.  names : the meshes to prepare (MESH_NAMES, or a subset
    that holds both lips: ``pose_face`` then poses only those).  Returns dict name -> dict of
    ``rest``, ``weights``, ``coeffs`` and, for the lips, ``midline_edges`` and
    ``reference_vertex``.
    """
    unknown = [n for n in names if n not in MESH_NAMES]
    if unknown or not set(LIP_MESHES) <= set(names):
        raise ValueError(f"names must be meshes of the rig ({', '.join(MESH_NAMES)}) including "
                         f"both lips, got {', '.join(names)}")
    prepared = {}
    for name in names:
        if name not in rest_vertices:
            raise ValueError(f"rest_vertices lacks the mesh {name!r}")
        rest = _points(name, rest_vertices[name])
        spec = rig["meshes"][name]
        if len(rest) != spec["vertex_count"]:
            raise ValueError(f"{name} has {len(rest)} vertices; the rig was built for "
                             f"{spec['vertex_count']}")
        weights = np.asarray(spec["jaw_weights"], dtype=np.float64)
        entry = {"rest": rest, "weights": weights,
                 "coeffs": field_coefficients(rest, weights, rig["field"])}
        if name in LIP_MESHES:
            entry["midline_edges"] = np.asarray(spec["midline_edges"], dtype=np.int64)
            entry["reference_vertex"] = int(spec["reference_vertex"])
        prepared[name] = entry
    return prepared


def _midline_factors(points, edges, factors):
    """Closure factors interpolated at the midline crossings, like ``midline_points``."""
    a, b = points[edges[:, 0], 2], points[edges[:, 1], 2]
    t = a / (a - b)
    return (1.0 - t) * factors[edges[:, 0]] + t * factors[edges[:, 1]]


def pose_face(rig, prepared, params, jaw_pose):
    """Pose the skin, the lips and the head shell.

    rig : the face-rig definition (dict).  prepared : from ``prepare_meshes``.
    params : lip parameters (see ``lip_parameters``).  jaw_pose : (3, 4) or (4, 4) rigid jaw
    motion (``geometry.jaw.jaw_pose`` for the jaw opening).
    Returns (posed, info): posed is dict name -> (n, 3) float64; info holds ``natural_gap`` (the
    lips' gap before closure), ``lip_gap`` (after everything), ``closure`` (the vector C, (3,)) and
    ``teeth_clamped`` (points pushed out of the incisors).
    """
    values = lip_parameters(rig, params)
    field = rig["field"]
    rotation, translation = rigid_parts(jaw_pose)
    screw = jaw_screw(jaw_pose)
    posed = {}
    for name, mesh in prepared.items():
        shaped = mesh["rest"] + shape_offsets(mesh["coeffs"], values, field)
        posed[name] = skin_jaw(shaped, mesh["weights"], screw)

    up, low = prepared["upper_lip"], prepared["lower_lip"]
    pu, pl = posed["upper_lip"], posed["lower_lip"]
    natural_gap, _, _ = lip_gap(pu, up["midline_edges"], pl, low["midline_edges"])
    target = closure_target(values["lip_opening"], natural_gap, field["lip_press_mm"])
    closure = np.zeros(3)
    if natural_gap > 0.0 and target < natural_gap:
        share = 1.0 - values["lip_opening"]
        fu = up["coeffs"][:, COEFF_CLOSURE]
        fl = low["coeffs"][:, COEFF_CLOSURE]
        # Forward-backward: give back, by the same share, the change of the lips' relative depth.
        iu, il = up["reference_vertex"], low["reference_vertex"]
        depth_now = pu[iu, 0] - pl[il, 0]
        depth_rest = up["rest"][iu, 0] - low["rest"][il, 0]
        slope = fl[il] - fu[iu]
        if slope > 0.0:
            closure[0] = share * (depth_now - depth_rest) / slope
        # Vertical: close the measured gap down to the target.
        upper = (midline_points(pu, up["midline_edges"])[:, 1],
                 _midline_factors(pu, up["midline_edges"], fu))
        lower = (midline_points(pl, low["midline_edges"])[:, 1],
                 _midline_factors(pl, low["midline_edges"], fl))
        closure[1] = solve_closure(upper, lower, target, field["closure_iterations"])
    clamped = 0
    for name, mesh in prepared.items():
        points = posed[name]
        points += np.outer(mesh["coeffs"][:, COEFF_CLOSURE], closure)
        if name in TEETH_MESHES:
            clamped += clamp_to_teeth(points, rig["teeth"], rotation, translation)
    gap, _, _ = lip_gap(posed["upper_lip"], up["midline_edges"],
                        posed["lower_lip"], low["midline_edges"])
    info = {"natural_gap": natural_gap, "lip_gap": gap, "closure": closure,
            "teeth_clamped": clamped}
    return posed, info
