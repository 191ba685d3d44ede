"""The jaw opening of each target by the class of its sound, in mm at the lower incisors.

JD3 (VocalTractLab's speaker) speaks with a nearly closed jaw: mapped one to one, its angles
opened the rig's jaw 2.15 degrees for /ɑ/ and 0.04 for /i/. Speakers open far more.

Openings are the vertical distance of the lower incisal edge from the intercuspal position (the
teeth together), as Burnett (1999) measured them: the mean incisor positions of 30 adults for
the 24 English consonants lie 2.5 mm (the sibilants, the most closed speaking position) to
11.7 mm (/h/, which takes the next vowel's opening) from it, and grow next to open vowels
(Int. J. Prosthodontics 12(3):263-271). The rig's closed jaw (jaw_opening 0, which /ʃ/ and /f/
take) is its most closed speaking position, so it stands at Burnett's 2.5 mm and an opening is
2.5 mm plus the incisal edge's drop from there (``INTERCUSPAL_AT_CLOSED_MM``).

The HPRC recordings (``glasshead compare-ema``'s data, docs/ema.md), measured the same way (the
jaw coil's drop from each speaker's most closed position in speech, the 99th percentile of its
height, plus 2.5 mm; the median within each phone, then over 3 speakers), give in running
speech: /æ/ 9.9 mm, /ɑ/ 8.5, /ɝ/ 8.0, /eɪ/ 6.3, /i/ 5.7, /ɪ/ 5.7, /ʌ/ 5.6, /u/ 5.5, /n/ 5.5,
/d/ 5.0, /t/ 3.7, /s/ 3.4. So the targets (citation forms, which running speech undershoots in
the open vowels and overshoots in the close ones) open: the open vowels 9.5 mm, the open-mid 7,
the close-mid 5.5, the near-close 5 and the close 4.5 (open vowels at least 8 mm, close vowels
2 to 5 mm). /æ/ is the /ɛ/ fit opened 2 degrees further (``phoneme_targets.REASONED``). The
alveolar consonants keep JD3's jaw within 2 to 5 mm; the other consonants keep JD3's, which the
contact fits of the velar and palatal closures were tuned on. A contact fit may still close a
target's jaw to reach the palate (``fitting.fit_contact``).
"""

import numpy as np

from glasshead import phonemes
from glasshead.geometry.jaw import apply_jaw_pose, jaw_pose

#: mm from the intercuspal position at the rig's closed jaw (Burnett's sibilant position).
INTERCUSPAL_AT_CLOSED_MM = 2.5
#: mm from the intercuspal position, by a vowel's manner (``phonemes.Phoneme.manner``).
VOWEL_OPENING_MM = {"open": 9.5, "near-open": 9.5, "open-mid": 7.0, "close-mid": 5.5,
                    "near-close": 5.0, "close": 4.5}
#: mm from the intercuspal position: the alveolar consonants' band (JD3's shapes named
#: ``tt-alveolar-...``).
ALVEOLAR_OPENING_MM = (2.0, 5.0)
ALVEOLAR_SHAPE_PREFIX = "tt-alveolar-"


def vowel_shape_manners() -> dict[str, str]:
    """JD3 vowel shape name -> the manner of the first vowel fitted to it as it is (/ɛ/ for E,
    not /æ/, which is made from E's fit), else of a diphthong's first element fitted to it
    (/eɪ/ for e), else of the first vowel that stands in for it (/ɝ/ for @)."""
    vowels = [p for p in phonemes.INVENTORY if p.kind in ("vowel", "diphthong") and p.shape]
    order = ([p for p in vowels if p.kind == "vowel" and not p.reasoning]
             + [p for p in vowels if p.kind == "diphthong"] + [p for p in vowels if p.reasoning])
    manners: dict[str, str] = {}
    for phoneme in order:
        if phoneme.shape and phoneme.manner in VOWEL_OPENING_MM:
            manners.setdefault(phoneme.shape, phoneme.manner)
    return manners


class JawOpenings:
    """Openings in mm (from the intercuspal position) and the rig's jaw_opening in degrees, from
    the rig's jaw block and range and the rest lower incisal edge (``landmarks.json``'s
    ``lower_incisor_edge``)."""

    def __init__(self, jaw: dict, spec: dict, lower_incisor):
        self.jaw, self.spec = jaw, spec
        self.lower_incisor = np.asarray(lower_incisor, dtype=np.float64)
        self.manners = vowel_shape_manners()

    def opening_mm(self, degrees: float) -> float:
        """The incisal opening (mm from the intercuspal position) at ``degrees``."""
        moved = apply_jaw_pose(self.lower_incisor[None, :2], jaw_pose(degrees, self.jaw))[0]
        return INTERCUSPAL_AT_CLOSED_MM + float(self.lower_incisor[1] - moved[1])

    def degrees(self, opening_mm: float) -> float:
        """The jaw_opening (deg, within the rig's range) that gives ``opening_mm``: bisection,
        the opening growing with the angle over the range."""
        low, high = float(self.spec["min"]), float(self.spec["max"])
        if self.opening_mm(high) <= opening_mm:
            return high
        if self.opening_mm(low) >= opening_mm:
            return low
        for _ in range(60):
            middle = 0.5 * (low + high)
            if self.opening_mm(middle) < opening_mm:
                low = middle
            else:
                high = middle
        return round(0.5 * (low + high), 4)

    def for_shape(self, shape_name: str, jd3_degrees: float) -> float:
        """The jaw_opening (deg) a shape's target is fitted with: its class's for a vowel, JD3's
        within the alveolar band for an alveolar, JD3's otherwise."""
        manner = self.manners.get(shape_name)
        if manner in VOWEL_OPENING_MM:
            return self.degrees(VOWEL_OPENING_MM[manner])
        if shape_name.startswith(ALVEOLAR_SHAPE_PREFIX):
            low, high = (self.degrees(mm) for mm in ALVEOLAR_OPENING_MM)
            return float(np.clip(jd3_degrees, low, high))
        return float(jd3_degrees)
