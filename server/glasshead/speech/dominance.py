"""The constants of Cohen and Massaro's (1993) coarticulation model: which dominance class each
phone belongs to, which parameter group each articulation parameter belongs to, and per class
and group the dominance magnitude alpha, the anticipation and carry-over rates theta, and the
shared exponent c. The velum's magnitude goes by a class of its own (``velum_class``: nasal,
oral obstruent, sonorant, silence), since what the velum must do depends on manner, not place.

    D_sp(tau) = alpha_sp * exp(-theta_s * |tau|^c),   tau = t - centre of s, in seconds,

theta_s being ``theta_anticipation`` for tau < 0 (the segment is still ahead) and
``theta_carryover`` for tau > 0. The magnitudes are per class and parameter group, because a
segment dominates the articulators it needs and yields the rest to its neighbours: an alveolar
holds its tongue tip and lets the lips round for a following /u/; a bilabial holds the lips and
lets the tongue take the next vowel; /h/ holds nothing. docs/coarticulation.md gives every value
with its reason.

``DEFAULTS`` are the hand-set values; ``speech/constants.json`` holds the values fitted to
VocalTractLab's gestural trajectories (``training.coarticulation``), which ``load_constants``
returns when the file exists. The constants are plain JSON-able dicts so that they can be trained,
stored and passed to ``coarticulate`` alike.
"""

import copy
import json
from functools import lru_cache
from pathlib import Path

from glasshead import phonemes

#: Format of a constants document (``DEFAULTS`` and ``constants.json``).
CONSTANTS_FORMAT_VERSION = 1
CONSTANTS_FILE = Path(__file__).with_name("constants.json")

#: The symbol of silence (pauses and the utterance's edges).
SILENCE = "sil"

#: Parameter groups, each moved by one articulator and so sharing one dominance per class.
GROUPS = ("tongue_tip", "tongue_body", "jaw", "lip_rounding", "lip_closure", "velum")

#: Dominance classes, by place and manner (``phone_class``).
CLASSES = ("silence", "vowel", "rounded_vowel", "bilabial", "labiodental", "coronal", "velar",
           "palatal", "labial_velar", "rhotic", "glottal")

#: The groups whose magnitude goes by the phone's class (the velum's by ``VELUM_CLASSES``).
CLASS_GROUPS = GROUPS[:-1]
#: Velum classes (``velum_class``): nasals must lower the velum, oral obstruents must close it to
#: build up pressure, vowels and approximants may be nasalised by a neighbour.
VELUM_CLASSES = ("silence", "nasal", "obstruent", "sonorant")

#: The tongue tip group: the sagittal tip and blade and the front coronal section; every other
#: tongue parameter is the body's (dorsum, back dorsum, root, body, middle and back sections).
_TIP_PREFIXES = ("tip_", "blade_", "front_")
_LIP_ROUNDING = ("lip_rounding", "lip_protrusion")


def _class(theta_anticipation, theta_carryover, tip, body, jaw, rounding, closure):
    return {"theta_anticipation": theta_anticipation, "theta_carryover": theta_carryover,
            "alpha": {"tongue_tip": tip, "tongue_body": body, "jaw": jaw,
                      "lip_rounding": rounding, "lip_closure": closure}}


#: Hand-set constants (the reasons are in docs/coarticulation.md). theta in 1/s^c.
DEFAULTS = {
    "format_version": CONSTANTS_FORMAT_VERSION,
    "header": "hand-set defaults of glasshead.speech.dominance (docs/coarticulation.md)",
    "c": 1.0,
    "classes": {
        #                 theta: ant. carry  tip  body  jaw  round close
        "silence": _class(15.0, 15.0, 0.05, 0.05, 0.05, 0.05, 0.05),
        "vowel": _class(12.0, 15.0, 0.3, 1.0, 0.8, 0.6, 0.5),
        "rounded_vowel": _class(8.0, 15.0, 0.3, 1.0, 0.8, 1.0, 0.6),
        "bilabial": _class(20.0, 25.0, 0.1, 0.1, 0.5, 0.1, 20.0),
        "labiodental": _class(20.0, 25.0, 0.1, 0.1, 0.6, 0.2, 10.0),
        "coronal": _class(20.0, 25.0, 10.0, 0.3, 0.6, 0.1, 0.2),
        "velar": _class(20.0, 25.0, 0.2, 20.0, 0.5, 0.1, 0.2),
        "palatal": _class(20.0, 25.0, 0.5, 1.0, 0.5, 0.2, 0.2),
        "labial_velar": _class(15.0, 20.0, 0.2, 0.6, 0.5, 1.0, 0.8),
        "rhotic": _class(15.0, 20.0, 0.8, 0.8, 0.5, 0.5, 0.2),
        "glottal": _class(20.0, 25.0, 0.02, 0.02, 0.02, 0.02, 0.02),
    },
    #: The velum's magnitude by ``velum_class`` (its time constants are the phone's class's).
    "velum_alpha": {"silence": 0.05, "nasal": 1.0, "obstruent": 2.0, "sonorant": 0.4},
}


def parameter_group(name: str, velum: tuple = ("velum_opening",)) -> str:
    """The group of an articulation parameter (``GROUPS``)."""
    if name in velum:
        return "velum"
    if name == "jaw_opening":
        return "jaw"
    if name in _LIP_ROUNDING:
        return "lip_rounding"
    if name.startswith("lip_") or name in ("upper_lip_raise", "lower_lip_tuck"):
        return "lip_closure"
    if name.startswith(_TIP_PREFIXES):
        return "tongue_tip"
    return "tongue_body"


_PLACE_CLASS = {"bilabial": "bilabial", "labiodental": "labiodental", "dental": "coronal",
                "alveolar": "coronal", "postalveolar": "coronal", "velar": "velar",
                "palatal": "palatal", "labial-velar": "labial_velar", "glottal": "glottal"}


def phone_class(symbol: str) -> str:
    """The dominance class of an ARPAbet symbol or ``SILENCE``; KeyError for an unknown one."""
    if symbol == SILENCE:
        return "silence"
    p = phonemes.lookup(symbol)
    if p.kind != "consonant":
        return "rounded_vowel" if p.rounded else "vowel"
    if p.arpabet == "R":
        return "rhotic"
    return _PLACE_CLASS[p.place]


def velum_class(symbol: str) -> str:
    """The velum class (``VELUM_CLASSES``) of an ARPAbet symbol or ``SILENCE``."""
    if symbol == SILENCE:
        return "silence"
    p = phonemes.lookup(symbol)
    if p.nasal:
        return "nasal"
    if p.kind == "consonant" and p.manner in ("stop", "fricative", "affricate"):
        return "obstruent"
    return "sonorant"


def validate_constants(constants: dict) -> dict:
    """The constants checked: the known format version, every class with both rates > 0 and
    every group's alpha > 0, every velum class's alpha > 0, and c > 0. ValueError naming what is
    missing or wrong."""
    version = constants.get("format_version", CONSTANTS_FORMAT_VERSION)
    if version != CONSTANTS_FORMAT_VERSION:
        raise ValueError(f"coarticulation constants: format version {version!r} is not the "
                         f"known {CONSTANTS_FORMAT_VERSION}")
    c = constants.get("c")
    if not isinstance(c, int | float) or not c > 0:
        raise ValueError(f"coarticulation constants: c must be a number > 0, not {c!r}")
    classes = constants.get("classes", {})
    for name in CLASSES:
        if name not in classes:
            raise ValueError(f"coarticulation constants: no class {name!r}")
        entry = classes[name]
        for key in ("theta_anticipation", "theta_carryover"):
            if not entry.get(key, 0) > 0:
                raise ValueError(f"coarticulation constants: {name}.{key} must be > 0")
        for group in CLASS_GROUPS:
            if not entry.get("alpha", {}).get(group, 0) > 0:
                raise ValueError(f"coarticulation constants: {name}.alpha.{group} must be > 0")
    for name in VELUM_CLASSES:
        if not constants.get("velum_alpha", {}).get(name, 0) > 0:
            raise ValueError(f"coarticulation constants: velum_alpha.{name} must be > 0")
    return constants


@lru_cache(maxsize=1)
def _stored() -> dict | None:
    if not CONSTANTS_FILE.is_file():
        return None
    return validate_constants(json.loads(CONSTANTS_FILE.read_text()))


def shipped_constants() -> dict:
    """The trained constants, or ``DEFAULTS``, checked, shared: read them, never change them."""
    return _stored() or DEFAULTS


def load_constants() -> dict:
    """A copy of the trained constants (``constants.json``), or of ``DEFAULTS`` when there are
    none."""
    return copy.deepcopy(_stored() or DEFAULTS)
