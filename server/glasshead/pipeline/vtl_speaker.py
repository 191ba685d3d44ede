"""Observations from VocalTractLab's JD3 speaker: the stored vocal tract shapes, read through the
``vocaltractlab-cython`` bindings (VocalTractLab by Peter Birkholz, GPL-3.0).

Everything here is in VocalTractLab's own frame converted to millimetres: +x anterior, +y
superior, z lateral (VTL builds its half surfaces on z <= 0 and mirrors them). The transform
into the project frame is ``pipeline.vtl_registration``.

The bindings hold one speaker in global state (loaded on import); every function here reads
shapes by name from that speaker, so the results depend only on the speaker file.
"""

import difflib
import re
import xml.etree.ElementTree as ET
from functools import lru_cache
from pathlib import Path

import numpy as np

#: VTL lengths are centimetres.
CM_TO_MM = 10.0

#: Surface indices of VocalTract::SurfaceIndex (VocalTractLab's VocalTract.h).
SURFACE = {"upper_teeth": 0, "palate": 6, "tongue": 16, "upper_teeth_twoside": 19}

#: Tract parameters grouped by articulator, with the unit VTL stores them in. Lengths are
#: converted to mm in the records; angles (deg), VS (0..1) and VO (cm^2) are kept as they are.
SETTINGS = {
    "jaw": {"JX": "cm", "JA": "deg"},
    "lips": {"LP": "cm", "LD": "cm"},
    "velum": {"VS": "", "VO": "cm^2"},
    "hyoid": {"HX": "cm", "HY": "cm"},
    "tongue": {"TCX": "cm", "TCY": "cm", "TTX": "cm", "TTY": "cm", "TBX": "cm", "TBY": "cm",
               "TRX": "cm", "TRY": "cm", "TS1": "cm", "TS2": "cm", "TS3": "cm"},
}

#: Consonant shape names, e.g. "tt-alveolar-closure(a)": articulator, place, manner, vowel context.
CONSONANT = re.compile(r"^(ll|tt|tb)-([a-z]+)-([a-z]+)\(([a-z])\)$")
ARTICULATORS = {"ll": "lower lip", "tt": "tongue tip", "tb": "tongue body"}
#: Vowel names are SAMPA symbols; "-raw" marks VTL's second version of a vowel.
VOWEL = re.compile(r"^([a-zA-Z0-9@:]+?)(_low|_mid)?(-raw)?$")


class VtlError(RuntimeError):
    """VocalTractLab data could not be had: the package, the speaker or a shape is missing."""


class VtlUnavailableError(VtlError):
    """The ``vocaltractlab-cython`` package (or its speaker file) is not installed."""


class UnknownShapeError(VtlError, KeyError):
    """No stored shape has the requested name."""

    def __str__(self):  # KeyError would quote the message
        return str(self.args[0])


def api():
    """The loaded ``vocaltractlab_cython`` module; VtlUnavailableError when it cannot load."""
    try:
        import vocaltractlab_cython
    except ImportError as error:  # also a broken binary (missing shared library)
        raise VtlUnavailableError(
            "the VocalTractLab bindings are not installed: pip install vocaltractlab-cython "
            f"(import failed: {error})") from error
    return vocaltractlab_cython


def speaker_file():
    """Path of the speaker file the bindings loaded (their bundled JD3.speaker)."""
    path = api().active_speaker()
    if not path or not Path(path).is_file():
        raise VtlUnavailableError(f"the VocalTractLab speaker file is missing: {path!r}")
    return Path(path)


@lru_cache(maxsize=1)
def _speaker_shapes():
    root = ET.parse(speaker_file()).getroot()
    shapes = root.findall("./vocal_tract_model/shapes/shape")
    if not shapes:
        raise VtlError(f"{speaker_file()} holds no vocal tract shapes")
    return tuple(s.get("name") for s in shapes)


def shape_names():
    """Names of the speaker's vocal tract shapes, in the file's order (glottis shapes excluded:
    they live under glottis_models, not vocal_tract_model)."""
    return list(_speaker_shapes())


def classify(name):
    """What a shape name says: {"kind": "vowel", "vowel", "raw"} or {"kind": "consonant",
    "articulator", "place", "manner", "context"}; kind "other" when it says neither."""
    match = CONSONANT.match(name)
    if match:
        art, place, manner, context = match.groups()
        return {"kind": "consonant", "articulator": ARTICULATORS[art], "place": place,
                "manner": manner, "context": context}
    match = VOWEL.match(name)
    if match:
        symbol, variant, raw = match.groups()
        return {"kind": "vowel", "vowel": symbol + (variant or ""), "raw": bool(raw)}
    return {"kind": "other"}


def tract_params(name):
    """The stored tract parameters of shape ``name``: (19,) float64 in VTL's units.
    UnknownShapeError, naming close matches, when the speaker has no such shape."""
    names = _speaker_shapes()
    if name not in names:
        close = difflib.get_close_matches(str(name), names, n=3, cutoff=0.5)
        hint = f"; did you mean {', '.join(map(repr, close))}?" if close else ""
        raise UnknownShapeError(
            f"VocalTractLab speaker {speaker_file().name} has no vocal tract shape {name!r} "
            f"({len(names)} shapes, e.g. 'a', 'tt-alveolar-closure(a)'){hint}")
    return np.asarray(api().get_shape(name, "tract"), dtype=np.float64)


def formant_peaks(params, count=3):
    """The first ``count`` peaks above 100 Hz (Hz) of VocalTractLab's own transfer function of
    a tract state (glottis to lips, no sinuses or piriform fossa), on an 8192-point spectrum."""
    spectrum = api().tract_state_to_transfer_function(
        params, n_spectrum_samples=8192, paranasal_sinuses=False, piriform_fossa=False)
    magnitude = np.asarray(spectrum["magnitude_spectrum"])
    frequency = np.arange(len(magnitude)) * api().get_constants()["sr_audio"] / len(magnitude)
    db = 20.0 * np.log10(magnitude + 1e-12)
    peaks = np.flatnonzero((frequency[1:-1] > 100) & (db[1:-1] > db[:-2])
                           & (db[1:-1] >= db[2:])) + 1
    return frequency[peaks][:count]


#: The nose's sections in VocalTractLab's full tube of 93 (trachea 23, glottis 2, pharynx and
#: mouth 40, then the nose from its port to the nostrils, then the sinuses and the fossa).
NOSE_SECTIONS = slice(65, 84)


def nose_tube() -> dict:
    """The speaker's nose: {"port_length_mm": its first section's length, "length_mm",
    "area_mm2": the sections after the port, to the nostrils}. The nose does not move; its
    first section, the port, takes the velum's opening."""
    full = api().tract_state_to_full_tube(tract_params("a"))
    lengths = np.asarray(full["tube_length"], dtype=np.float64)[NOSE_SECTIONS] * 10.0
    areas = np.asarray(full["tube_area"], dtype=np.float64)[NOSE_SECTIONS] * 100.0
    return {"port_length_mm": round(float(lengths[0]), 4),
            "length_mm": np.round(lengths[1:], 4).tolist(),
            "area_mm2": np.round(areas[1:], 4).tolist()}


@lru_cache(maxsize=1)
def param_names():
    """The 19 tract parameter names in VTL's order (HX, HY, JX, JA, LP, LD, VS, VO, TCX, ...)."""
    return tuple(p["name"] for p in api().get_param_info("tract"))


def settings(params):
    """Articulator settings of a parameter vector: {group: {name: value}}, lengths in mm."""
    values = dict(zip(param_names(), np.asarray(params, dtype=np.float64), strict=True))
    return {group: {key: round(float(values[key]) * (CM_TO_MM if unit == "cm" else 1.0), 4)
                    for key, unit in members.items()}
            for group, members in SETTINGS.items()}


def _dedupe(points):
    """Drop consecutive repeated points (VTL pads its outlines with copies of the end point)."""
    keep = np.ones(len(points), dtype=bool)
    keep[1:] = np.linalg.norm(np.diff(points, axis=0), axis=1) > 1e-9
    return points[keep]


def outlines(params):
    """Mid-sagittal outlines, mm: {"tongue", "upper", "lower", "epiglottis"} -> (n, 2).

    "tongue" runs from the root at the hyoid over the dorsum to the tip and down its underside;
    "upper" from the larynx up the back pharynx wall, along the velum and hard palate, over the
    upper incisor to the upper lip; "lower" along the front pharynx, lower incisor and lower lip.
    """
    raw = api().get_outlines(np.asarray(params, dtype=np.float64))
    return {key: _dedupe(np.asarray(value, dtype=np.float64) * CM_TO_MM)
            for key, value in raw.items()}


#: Tube::Articulator of VocalTractLab's Tube.h, the articulator that bounds a cross-section.
TUBE_ARTICULATORS = ("vocal folds", "tongue", "lower incisors", "lower lip", "other")


def constriction(params):
    """The narrowest of VTL's 129 cross-sections along the tract's centre line: its area
    (cm^2; 0 for a closure), position from the glottis (mm) and the articulator bounding it."""
    sections = api().get_cross_sections(np.asarray(params, dtype=np.float64))
    k = int(np.argmin(sections["areas"]))
    art = int(sections["articulators"][k])
    return {"min_area_cm2": round(float(sections["areas"][k]), 4),
            "position_mm": round(float(sections["positions"][k]) * CM_TO_MM, 2),
            "articulator": TUBE_ARTICULATORS[art] if 0 <= art < len(TUBE_ARTICULATORS) else art}


def grid_triangles(ribs, points):
    """Triangles (m, 3) int64 of a ribs x points vertex grid (vertex r * points + p)."""
    r, p = np.meshgrid(np.arange(ribs - 1), np.arange(points - 1), indexing="ij")
    a = (r * points + p).ravel()
    b, c, d = a + points, a + points + 1, a + 1
    return np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)]).astype(np.int64)


def surface(params, index):
    """A VTL surface as a grid: vertices (ribs, points, 3) float64 mm."""
    return np.asarray(api().get_surface_vertices(np.asarray(params, dtype=np.float64), index),
                      dtype=np.float64) * CM_TO_MM


def tongue_surface(params):
    """The 3D tongue surface (VTL's TONGUE surface, both sides): vertices (n, 3) mm and
    triangles (m, 3), counter-clockwise seen from the air above (the dorsum's normals point
    up). It is the tongue's exposed sheet from root to tip, not a closed volume."""
    grid = surface(params, SURFACE["tongue"])
    # Ribs run root to tip and rib points -z to +z, so the grid's own order faces down.
    return grid.reshape(-1, 3), grid_triangles(*grid.shape[:2])[:, ::-1].copy()


def mirror_half(grid):
    """A half surface (z <= 0) with its mirror: vertices (n, 3), triangles (m, 3) with the two
    halves' windings consistent (the mirror's triangles reversed)."""
    ribs, points = grid.shape[:2]
    half = grid_triangles(ribs, points)
    other = grid * np.array([1.0, 1.0, -1.0])
    vertices = np.concatenate([grid.reshape(-1, 3), other.reshape(-1, 3)])
    return vertices, np.concatenate([half, half[:, ::-1] + ribs * points])


@lru_cache(maxsize=1)
def _palate():
    params = tract_params(shape_names()[0])  # the hard palate and teeth do not move
    palate = surface(params, SURFACE["palate"])
    teeth = surface(params, SURFACE["upper_teeth"])
    # Midline: the last point of each rib lies on z = 0, back of the hard palate first.
    vault = _dedupe(palate[:, -1, :2])
    incisor = teeth[-1, :, :2]  # the front rib: lingual base, lingual edge, labial edge, ...
    if np.abs(palate[:, -1, 2]).max() > 1e-6 or np.abs(teeth[-1, :, 2]).max() > 1e-6:
        raise VtlError("VocalTractLab's palate or incisor midline is not on z = 0")
    palate_vertices, palate_triangles = mirror_half(palate)
    teeth_grid = surface(params, SURFACE["upper_teeth_twoside"])
    return {
        "vault_outline": vault,
        "incisor_outline": _dedupe(incisor),
        # For registration: vault, then the incisor's lingual face down to its edge. The block
        # incisor's vertical labial face is left out: real incisors are proclined.
        "registration_outline": _dedupe(np.vstack([vault, incisor[1:3]])),
        "palate_surface": (palate_vertices, palate_triangles),
        "upper_teeth_surface": (teeth_grid.reshape(-1, 3), grid_triangles(*teeth_grid.shape[:2])),
    }


def palate_geometry():
    """The speaker's hard palate and upper teeth (fixed in every shape), mm, VTL frame:
    "vault_outline" (k, 2) midline of the hard palate, back to front; "incisor_outline" (5, 2)
    the upper incisor's midline section; "registration_outline" (j, 2) vault plus incisor lingual
    face and edge; "palate_surface" and "upper_teeth_surface": (vertices, triangles)."""
    return _palate()


def observe(name):
    """The record of one stored shape (mm, VTL frame): name, class, params (VTL units, by name),
    settings (by articulator, lengths in mm), the narrowest constriction, the mid-sagittal
    outlines (tongue, upper, lower) and the 3D tongue surface."""
    params = tract_params(name)
    lines = outlines(params)
    vertices, triangles = tongue_surface(params)
    return {
        "name": name,
        "class": classify(name),
        "params": {key: float(value) for key, value in zip(param_names(), params, strict=True)},
        "settings": settings(params),
        "constriction": constriction(params),
        "tongue_outline": lines["tongue"],
        "upper_outline": lines["upper"],
        "lower_outline": lines["lower"],
        "tongue_surface": (vertices, triangles),
    }


def observations(names=None):
    """Records (see ``observe``) of ``names``, default every stored shape."""
    return [observe(name) for name in (shape_names() if names is None else names)]


def tongue_length(outline):
    """Arc length (mm) of a tongue outline from its root end to the tip, the most anterior point
    (the underside beyond the tip is left out)."""
    outline = np.asarray(outline, dtype=np.float64)
    tip = int(np.argmax(outline[:, 0]))
    return float(np.linalg.norm(np.diff(outline[: tip + 1], axis=0), axis=1).sum())
