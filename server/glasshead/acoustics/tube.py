"""A vocal tract as a lossy tube: the volume-velocity transfer function from the glottis to the
lips, and its formants.

The tract is a chain of cylindrical sections, glottis first (lengths in mm, areas in mm²), each a
two-port of a lossy transmission line (Sondhi and Schroeter 1987, "A hybrid time-frequency domain
articulatory speech synthesizer", IEEE Trans. ASSP 35: 955-967; the losses as in Flanagan 1972,
"Speech analysis, synthesis and perception", ch. 3):

- in series, per unit length, the air's inertance jωρ/A and the viscous loss of its boundary
  layer, (S/A²)·sqrt(ωρμ/2) as a resistance and as much again as a reactance;
- in shunt, the air's compliance jωA/(ρc²), the heat conducted into the walls,
  S(η-1)/(ρc²)·sqrt(λω/(2 c_p ρ)), and the yielding walls, S/(R_w + jωM_w + K_w/(jω)) per unit
  length (the mass, resistance and stiffness of soft tissue per unit area, as Ishizaka, French
  and Flanagan 1975 measured the relaxed cheek; they keep a closed tract's first resonance near
  200 Hz);

S is the perimeter of a circle of area A. The glottis end is driven by a volume velocity (its
own impedance taken as infinite); the lips radiate into a piston-in-a-baffle load, a resistance
128ρc/(9π²A) in parallel with an inertance 8ρ/(3π·sqrt(πA)). Then, with the chain matrix K of
all sections from the glottis to the lips, U_lips/U_glottis = 1/(K₂₁·Z_rad + K₂₂).

With a nasal branch, the nose is a second chain N that leaves the tract at a junction J after
its first ``at`` sections (the velopharyngeal port is N's first section) and radiates from the
nostrils as a piston of its last section's area. With K₁ the chain up to J and K₂ the chain
from J to the lips, write a = K₂₁₁·Z_lips + K₂₁₂, b = K₂₂₁·Z_lips + K₂₂₂ (J's pressure and the
flow into the mouth per unit of lip flow) and c, d likewise for N and its nostrils. With the
lips' flow c and the nostrils' flow a, J's pressure is a·c on both sides, and the flow that
reaches J from the glottis is b·c + a·d, so

    (U_lips + U_nose) / U_glottis = (a + c) / (K₁₂₁·a·c + K₁₂₂·(b·c + a·d)).

Without the branch (``nasal`` None) it is the oral tube's 1/(K₂₁·Z_rad + K₂₂).

Formants are the peaks of |H| in a band: found on a grid, then each refined by a parabola through
the dB values of its three grid points; the bandwidth is the width of the peak 3 dB down. Pure
numpy; the browser's twin is ``web/src/core/tubeAcoustics.js``, held to the same numbers by the
shared vectors.
"""

import numpy as np

from glasshead.constants import TUBE_AIR, TUBE_FORMANT_BAND_HZ, TUBE_GRID_STEP_HZ, TUBE_WALL

RHO, C = TUBE_AIR["density"], TUBE_AIR["sound_speed"]
MU, LAMBDA = TUBE_AIR["viscosity"], TUBE_AIR["heat_conductivity"]
CP, ETA = TUBE_AIR["specific_heat"], TUBE_AIR["heat_ratio"]
WALL_MASS, WALL_RESISTANCE = TUBE_WALL["mass"], TUBE_WALL["resistance"]
WALL_STIFFNESS = TUBE_WALL["stiffness"]
FORMANT_BAND_HZ, GRID_STEP_HZ = TUBE_FORMANT_BAND_HZ, TUBE_GRID_STEP_HZ
#: Formants reported.
FORMANT_COUNT = 4


def chain(lengths_mm, areas_mm2, frequencies_hz, *, lossy=True):
    """The chain matrix of the tube from the glottis to the lips at each frequency: (n, 2, 2)
    complex, [p, u] at the glottis = K · [p, u] at the lips. Areas must be positive."""
    lengths = np.asarray(lengths_mm, dtype=np.float64) * 1e-3
    areas = np.asarray(areas_mm2, dtype=np.float64) * 1e-6
    if lengths.shape != areas.shape or lengths.ndim != 1 or len(lengths) == 0:
        raise ValueError("a tube needs as many section lengths as areas, at least one")
    if np.any(areas <= 0) or np.any(lengths <= 0):
        raise ValueError("every section of a tube needs a positive length and area")
    omega = 2.0 * np.pi * np.asarray(frequencies_hz, dtype=np.float64)[:, None]
    perimeter = 2.0 * np.sqrt(np.pi * areas)
    series: np.ndarray = 1j * omega * RHO / areas
    shunt: np.ndarray = 1j * omega * areas / (RHO * C * C)
    if lossy:
        viscous = perimeter / areas ** 2 * np.sqrt(omega * RHO * MU / 2.0)
        series = series + viscous * (1.0 + 1j)
        thermal = (perimeter * (ETA - 1.0) / (RHO * C * C)
                   * np.sqrt(LAMBDA * omega / (2.0 * CP * RHO)))
        walls = perimeter / (WALL_RESISTANCE + 1j * omega * WALL_MASS
                             + WALL_STIFFNESS / (1j * omega))
        shunt = shunt + thermal * (1.0 + 1j) + walls
    gamma = np.sqrt(series * shunt)
    impedance = np.sqrt(series / shunt)
    cosh, sinh = np.cosh(gamma * lengths), np.sinh(gamma * lengths)
    total = np.broadcast_to(np.eye(2, dtype=np.complex128), (omega.shape[0], 2, 2)).copy()
    for k in range(len(lengths)):
        section = np.empty((omega.shape[0], 2, 2), dtype=np.complex128)
        section[:, 0, 0] = cosh[:, k]
        section[:, 0, 1] = impedance[:, k] * sinh[:, k]
        section[:, 1, 0] = sinh[:, k] / impedance[:, k]
        section[:, 1, 1] = cosh[:, k]
        total = total @ section
    return total


def radiation_impedance(area_mm2, frequencies_hz):
    """The load of the lip opening: a piston in a baffle, 128ρc/(9π²A) in parallel with
    jω·8ρ/(3π·sqrt(πA)) (Flanagan 1972)."""
    area = float(area_mm2) * 1e-6
    omega = 2.0 * np.pi * np.asarray(frequencies_hz, dtype=np.float64)
    resistance = 128.0 * RHO * C / (9.0 * np.pi ** 2 * area)
    inertance = 8.0 * RHO / (3.0 * np.pi * np.sqrt(np.pi * area))
    return resistance * 1j * omega * inertance / (resistance + 1j * omega * inertance)


def transfer_function(lengths_mm, areas_mm2, frequencies_hz, *, lossy=True, nasal=None):
    """U_lips / U_glottis at each frequency (complex), or (U_lips + U_nose) / U_glottis with a
    nasal branch ``nasal`` = {"at": sections before the junction (1 or more), "length_mm",
    "area_mm2": the nose's sections from the port to the nostrils}. ``lossy=False``: no losses
    and ideal open ends (the textbook tube)."""
    frequencies = np.asarray(frequencies_hz, dtype=np.float64)
    areas = np.asarray(areas_mm2, dtype=np.float64)

    def load(area):
        return radiation_impedance(area, frequencies) if lossy else 0.0

    if nasal is None:
        k = chain(lengths_mm, areas, frequencies, lossy=lossy)
        return 1.0 / (k[:, 1, 0] * load(areas[-1]) + k[:, 1, 1])
    at = int(nasal["at"])
    if not 1 <= at < len(areas):
        raise ValueError(f"a nasal branch must leave the tract between two of its sections, "
                         f"not after section {at} of {len(areas)}")
    lengths = np.asarray(lengths_mm, dtype=np.float64)
    before = chain(lengths[:at], areas[:at], frequencies, lossy=lossy)
    after = chain(lengths[at:], areas[at:], frequencies, lossy=lossy)
    nose = chain(nasal["length_mm"], nasal["area_mm2"], frequencies, lossy=lossy)
    lips, nostrils = load(areas[-1]), load(float(nasal["area_mm2"][-1]))
    a = after[:, 0, 0] * lips + after[:, 0, 1]
    b = after[:, 1, 0] * lips + after[:, 1, 1]
    c = nose[:, 0, 0] * nostrils + nose[:, 0, 1]
    d = nose[:, 1, 0] * nostrils + nose[:, 1, 1]
    return (a + c) / (before[:, 1, 0] * a * c + before[:, 1, 1] * (b * c + a * d))


def formants(lengths_mm, areas_mm2, *, lossy=True, nasal=None, count=FORMANT_COUNT,
             band_hz=FORMANT_BAND_HZ, step_hz=GRID_STEP_HZ):
    """The first ``count`` formants of the tube (with its nasal branch, if any): (frequencies
    Hz, bandwidths Hz), each (count,) float64, NaN where the band holds fewer peaks."""
    grid = np.arange(band_hz[0], band_hz[1] + step_hz / 2, step_hz)
    transfer = transfer_function(lengths_mm, areas_mm2, grid, lossy=lossy, nasal=nasal)
    db = 20.0 * np.log10(np.abs(transfer) + 1e-300)
    peaks = np.flatnonzero((db[1:-1] > db[:-2]) & (db[1:-1] >= db[2:])) + 1
    frequencies = np.full(count, np.nan)
    bandwidths = np.full(count, np.nan)
    for slot, peak in enumerate(peaks[:count]):
        left, centre, right = db[peak - 1:peak + 2]
        curvature = left - 2.0 * centre + right
        offset = 0.5 * (left - right) / curvature if curvature < 0 else 0.0
        frequencies[slot] = grid[peak] + offset * step_hz
        top = centre - 0.25 * (left - right) * offset
        bandwidths[slot] = _width_3db(grid, db, peak, top)
    return frequencies, bandwidths


def _width_3db(grid, db, peak, top):
    """Width of the peak at ``peak`` 3 dB below ``top``, from the grid points on each side
    (linear between the two around each crossing); NaN where a side does not fall that far
    before the next peak."""
    level = top - 3.0
    edges = []
    for direction in (-1, 1):
        k = peak
        while (0 <= k + direction < len(db) and db[k + direction] <= db[k]
               and db[k + direction] > level):
            k += direction
        nxt = k + direction
        if not 0 <= nxt < len(db) or db[nxt] > level:
            return float("nan")
        fraction = (db[k] - level) / (db[k] - db[nxt])
        edges.append(grid[k] + direction * fraction * (grid[1] - grid[0]))
    return float(edges[1] - edges[0])
