"""tube-acoustics.json: tubes of known shape through the lossy tube model, with their transfer
function at a few frequencies and their formants and bandwidths.

pytest (tests/test_tube_acoustics.py) checks that the file is what this module makes, and
``tests/js/tubeAcoustics.test.js`` that the JavaScript twin gives the same numbers. The tubes are
the textbook ones (Fant 1960, "Acoustic theory of speech production"): a uniform 17.5 cm tube, the
two-tube /ɑ/ (a narrow back, a wide front) and /i/ (a wide back, a narrow front), and a three-tube
/u/ (a narrow middle and lips), each with and without losses; then the uniform tube and the /ɑ/
with a nose, a side branch of 19 sections 6 mm long (its port first, then a cavity that widens
to 4 cm² and narrows to the nostrils), leaving the tract 7 cm above the glottis.
"""

import numpy as np

from glasshead.acoustics import tube
from glasshead.constants import TUBE_AIR, TUBE_FORMANT_BAND_HZ, TUBE_GRID_STEP_HZ, TUBE_WALL
from glasshead.vectors.common import case, document, tolerance

NAME = "tube-acoustics.json"
FORMAT_VERSION = 1
#: Frequencies the transfer function is given at, Hz.
FREQUENCIES_HZ = (150.0, 480.0, 1234.5, 2600.0, 4100.0)  # off the lossless tube's poles
TOLERANCES = {
    "transfer": tolerance(1e-9, "relative", "complex products of up to 40 sections round "
                                            "differently in the last bits between the twins"),
    "frequency": tolerance(1e-6, "Hz", "a peak's parabola through three dB values of the grid"),
}

#: (description, [(length mm, area mm²)] glottis first).
TUBES = (
    ("a uniform 17.5 cm tube of 3 cm²", [(175.0, 300.0)]),
    ("the two-tube /ɑ/: 8.75 cm of 1 cm² then 8.75 cm of 7 cm²", [(87.5, 100.0), (87.5, 700.0)]),
    ("the two-tube /i/: 9 cm of 8 cm² then 6 cm of 1 cm²", [(90.0, 800.0), (60.0, 100.0)]),
    ("a three-tube /u/: 7 cm of 5 cm², 3 cm of 0.5 cm², 5 cm of 6 cm², 1 cm of 0.3 cm² lips",
     [(70.0, 500.0), (30.0, 50.0), (50.0, 600.0), (10.0, 30.0)]),
)
#: Each tube is cut into sections of about this length, mm, as an area function is.
SECTION_MM = 5.0
#: The nose of the nasal cases: its sections' areas from the port (given per case), mm², each
#: 6 mm long, and how far above the glottis it leaves the tract, mm.
NOSE_MM2 = (30.0, 100.0, 240.0, 400.0, 330.0, 300.0, 300.0, 270.0, 250.0, 240.0, 240.0, 185.0,
            80.0, 140.0, 175.0, 130.0, 175.0, 80.0)
NOSE_SECTION_MM = 6.0
JUNCTION_MM = 70.0
#: (description, the tube's parts as TUBES, the port's area mm²).
NASAL_TUBES = (
    ("the uniform tube with a nose, its port 0.5 cm² open", TUBES[0][1], 50.0),
    ("the two-tube /ɑ/ with a nose, its port 0.2 cm² open", TUBES[1][1], 20.0),
)


def sections(tube_parts):
    """The lengths and areas of a tube of cylinders cut into sections of about SECTION_MM."""
    lengths, areas = [], []
    for length, area in tube_parts:
        count = max(1, round(length / SECTION_MM))
        lengths += [length / count] * count
        areas += [area] * count
    return lengths, areas


def nose(port_mm2):
    """The nasal branch of the nasal cases for a port of ``port_mm2``, leaving after the
    sections that reach ``JUNCTION_MM``."""
    areas = [port_mm2, *NOSE_MM2]
    return {"length_mm": [NOSE_SECTION_MM] * len(areas), "area_mm2": areas}


def _case(description, parts, lossy, port_mm2=None):
    lengths, areas = sections(parts)
    nasal = None
    if port_mm2 is not None:
        nasal = {"at": int(np.searchsorted(np.cumsum(lengths), JUNCTION_MM - 1e-9) + 1),
                 **nose(port_mm2)}
    transfer = tube.transfer_function(lengths, areas, FREQUENCIES_HZ, lossy=lossy, nasal=nasal)
    frequencies, bandwidths = tube.formants(lengths, areas, lossy=lossy, nasal=nasal)
    plain = [None if np.isnan(v) else float(v) for v in frequencies]
    # A lossless tube's peaks are poles: their width on a grid says nothing, so none is given.
    widths = [None if np.isnan(v) or not lossy else float(v) for v in bandwidths]
    return case(f"{description}, {'lossy' if lossy else 'lossless with an ideal open end'}",
                {"lengths_mm": lengths, "areas_mm2": areas, "lossy": lossy,
                 "frequencies_hz": list(FREQUENCIES_HZ), "nasal": nasal},
                {"transfer": [[float(z.real), float(z.imag)] for z in transfer],
                 "formants_hz": plain, "bandwidths_hz": widths})


def build_document():
    cases = [_case(description, parts, lossy) for description, parts in TUBES
             for lossy in (False, True)]
    cases += [_case(description, parts, lossy, port) for description, parts, port in NASAL_TUBES
              for lossy in (False, True)]
    return document(
        NAME, "Tubes of known shape, glottis first, through the lossy tube model: U_lips/U_glottis "
              "(re, im) at frequencies_hz, and the first four formants and their 3 dB bandwidths "
              "(null where the band holds fewer peaks, and for a lossless tube). With a nasal "
              "branch (nasal: the nose's sections from its port, leaving the tract after its "
              "first `at` sections), (U_lips + U_nose)/U_glottis",
        FORMAT_VERSION, cases,
        constants={"air": TUBE_AIR, "wall": TUBE_WALL, "band_hz": list(TUBE_FORMANT_BAND_HZ),
                   "grid_step_hz": TUBE_GRID_STEP_HZ},
        tolerances=TOLERANCES)


def files():
    return {NAME: build_document()}
