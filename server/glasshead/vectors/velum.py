"""velum.json: the velum rig's shared vectors.

Fixture: the built velum rig (without its build report and inputs hash). Cases: the three
measured openings (0, r, 1), fixed openings in each segment, ``RANDOM_CASES`` seeded random
openings, and refusals of openings out of range. Expected: the nasal port's smallest cut and
every cut's area (mm^2), and the posed positions of ``PROBES`` vertices spread through the mesh.
The port area has no threshold a float can flip: gaps are clamped at 0 continuously.
"""

import numpy as np

from glasshead.constants import (
    VELUM_PARAMETER,
    VELUM_PORT_TOLERANCE_MM2,
    VELUM_RIG_FILE,
    VELUM_VERTEX_TOLERANCE_MM,
)
from glasshead.geometry import velum
from glasshead.vectors import sources
from glasshead.vectors.common import case, document, rounded, tolerance

FORMAT_VERSION = 1
SEED = 20250611
RANDOM_CASES = 24
PROBES = 16
OPENING_DECIMALS = 6
RESULT_DECIMALS = 6
FIXED_OPENINGS = (0.1, 0.25, 0.5, 0.6, 0.8, 0.9, 0.99)
REFUSED = (1.5, -0.1)

TOLERANCES = {
    "vertex_mm": tolerance(VELUM_VERTEX_TOLERANCE_MM, "mm",
                           "JavaScript blends float32 poses into float32 output (about 4e-6 mm "
                           "of rounding at 60 mm); a wrong segment or share is off by far more"),
    "area_mm2": tolerance(VELUM_PORT_TOLERANCE_MM2, "mm2",
                          "JavaScript reads float32 poses: each gap a few 1e-6 mm off, a cut "
                          "sums about 20 of them over 1 mm widths"),
    "stored": tolerance(1e-5, "1", "stored values are rounded to 6 decimals (at most 5e-7 off); "
                                   "the float64 reference reproduces them on any CPU within "
                                   "that"),
}


def velum_definition():
    """The built velum rig, checked, without its build report and inputs hash."""
    definition = sources.built_json(VELUM_RIG_FILE)
    velum.prepare_velum(definition)
    return {k: v for k, v in definition.items() if k not in ("report", "inputs_sha256")}


def openings(rig):
    """(description, opening) of every computed case."""
    r = rig.rest_share
    out = [("raised (opening 0): the port is closed", 0.0),
           (f"rest (opening r = {r:g})", r), ("lowered (opening 1)", 1.0)]
    for o in FIXED_OPENINGS:
        out.append((f"opening {o:g} ({'raised to rest' if o <= r else 'rest to lowered'})", o))
    rng = np.random.default_rng(SEED)
    for k in range(RANDOM_CASES):
        out.append((f"random opening {k} (seed {SEED})",
                    float(np.round(rng.uniform(0.0, 1.0), OPENING_DECIMALS))))
    return out


def probe_vertices(rig, count=PROBES):
    """``count`` vertex indices spread through the mesh."""
    return np.linspace(0, rig.vertex_count - 1, count).round().astype(int).tolist()


def velum_document():
    definition = velum_definition()
    rig = velum.prepare_velum(definition)
    probes = probe_vertices(rig)
    cases = []
    for description, opening in openings(rig):
        posed = velum.pose_velum(rig, opening)
        cases.append(case(description, {VELUM_PARAMETER: opening}, {
            "port_area_mm2": round(velum.nasal_port_area(rig, opening), RESULT_DECIMALS),
            "cut_areas_mm2": rounded(velum.port_cut_areas(rig, opening), RESULT_DECIMALS),
            "probe_positions": rounded(posed[probes].ravel(), RESULT_DECIMALS)}))
    for opening in REFUSED:
        cases.append(case(f"{VELUM_PARAMETER} {opening:g} is refused", {VELUM_PARAMETER: opening},
                          {"error": "outside its range [0, 1]"}))
    return document(
        "velum.json",
        "The velum posed by velum_opening (a piecewise-linear blend of the raised, rest and "
        "lowered poses) and the nasal port's smallest cross-section, from the built velum rig.",
        FORMAT_VERSION, cases,
        constants={"seed": SEED, "rest_share": rig.rest_share, "probes": PROBES},
        tolerances=TOLERANCES,
        fixtures={"rig": definition, "probe_vertices": probes})


def files():
    return {"velum.json": velum_document()}
