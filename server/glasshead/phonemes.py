"""The phoneme inventory: CMUdict's 39 ARPAbet phonemes of American English, with IPA, phonetic
features, example words and the measured shape each articulation target is fitted to.

Features follow the IPA chart (place, manner, voicing; vowel height, backness, rounding). The
``source`` of each target names the VocalTractLab JD3 shape it is fitted to (docs/observations.md)
with the vowel contexts measured for it, or, where no shape was measured, says why the target is
built from phonetic reasoning instead (docs/targets.md). Nasals lower the velum;
every other phoneme raises it.

Symbols are accepted as ARPAbet (any case, stress digits ignored) or IPA (``lookup``).
"""

from dataclasses import dataclass

#: The vowel contexts the JD3 consonant shapes were measured in.
CONTEXTS = ("a", "i", "u")


@dataclass(frozen=True)
class Phoneme:
    """One phoneme. ``shape``: the JD3 shape name stem it is fitted to (consonants are measured
    in each of ``CONTEXTS``, names ``stem(a)`` etc.; vowels are one shape), or None when no shape
    was measured and ``reasoning`` says how its target is built."""

    arpabet: str
    ipa: str
    kind: str  # "vowel", "diphthong" or "consonant"
    voiced: bool
    nasal: bool
    place: str  # consonants: bilabial ... glottal; vowels: "front", "central" or "back"
    manner: str  # consonants: stop, fricative, affricate, nasal, lateral, approximant;
    # vowels: close, near-close, close-mid, open-mid, open and so on
    rounded: bool
    examples: tuple[str, ...]
    shape: str | None
    reasoning: str = ""

    @property
    def contexts(self) -> tuple[str, ...]:
        """The vowel contexts a measured consonant shape exists in (none for vowels)."""
        return CONTEXTS if self.shape and self.kind == "consonant" else ()

    @property
    def velum_lowered(self) -> bool:
        return self.nasal


def _c(arpabet, ipa, voiced, place, manner, examples, shape, reasoning="", nasal=False,
       rounded=False):
    return Phoneme(arpabet, ipa, "consonant", voiced, nasal, place, manner, rounded,
                   tuple(examples.split()), shape, reasoning)


def _v(arpabet, ipa, place, manner, examples, shape, rounded=False, kind="vowel", reasoning=""):
    return Phoneme(arpabet, ipa, kind, True, False, place, manner, rounded,
                   tuple(examples.split()), shape, reasoning)


INVENTORY: tuple[Phoneme, ...] = (
    # Vowels: JD3's vowel shapes (SAMPA names) nearest in quality.
    _v("AA", "ɑ", "back", "open", "father cot", "a"),
    _v("AE", "æ", "front", "near-open", "cat trap", "E",
       reasoning="JD3 has no /æ/; its /ɛ/ (E) is the nearest front vowel, lowered by the fit's "
                 "jaw where the rig allows"),
    _v("AH", "ʌ", "central", "open-mid", "cut but", "6"),
    _v("AO", "ɔ", "back", "open-mid", "caught law", "O", rounded=True),
    _v("EH", "ɛ", "front", "open-mid", "bed red", "E"),
    _v("ER", "ɝ", "central", "open-mid", "bird hurt", "@",
       reasoning="JD3 has no rhotic vowel; the schwa (@) shape stands for its tongue body"),
    _v("IH", "ɪ", "front", "near-close", "bit sit", "I"),
    _v("IY", "i", "front", "close", "beat see", "i"),
    _v("UH", "ʊ", "back", "near-close", "book put", "U", rounded=True),
    _v("UW", "u", "back", "close", "boot two", "u", rounded=True),
    _v("AW", "aʊ", "back", "open", "cow out", "a", kind="diphthong",
       reasoning="a diphthong: the target is its first element /a/; speech glides to /ʊ/"),
    _v("AY", "aɪ", "front", "open", "bite my", "a", kind="diphthong",
       reasoning="a diphthong: the target is its first element /a/; speech glides to /ɪ/"),
    _v("EY", "eɪ", "front", "close-mid", "bait day", "e", kind="diphthong",
       reasoning="a diphthong: the target is its first element /e/; speech glides to /ɪ/"),
    _v("OW", "oʊ", "back", "close-mid", "boat go", "o", rounded=True, kind="diphthong",
       reasoning="a diphthong: the target is its first element /o/; speech glides to /ʊ/"),
    _v("OY", "ɔɪ", "back", "open-mid", "boy toy", "O", rounded=True, kind="diphthong",
       reasoning="a diphthong: the target is its first element /ɔ/; speech glides to /ɪ/"),
    # Consonants.
    _c("P", "p", False, "bilabial", "stop", "pie cap", "ll-labial-closure"),
    _c("B", "b", True, "bilabial", "stop", "buy cab", "ll-labial-closure"),
    _c("M", "m", True, "bilabial", "nasal", "my some", "ll-labial-closure", nasal=True),
    _c("F", "f", False, "labiodental", "fricative", "fan off", "ll-dental-fricative"),
    _c("V", "v", True, "labiodental", "fricative", "van of", "ll-dental-fricative"),
    _c("TH", "θ", False, "dental", "fricative", "thin bath", "tt-dental-fricative"),
    _c("DH", "ð", True, "dental", "fricative", "this bathe", "tt-dental-fricative"),
    _c("T", "t", False, "alveolar", "stop", "tie cat", "tt-alveolar-closure"),
    _c("D", "d", True, "alveolar", "stop", "die cad", "tt-alveolar-closure"),
    _c("N", "n", True, "alveolar", "nasal", "nigh can", "tt-alveolar-closure", nasal=True),
    _c("S", "s", False, "alveolar", "fricative", "sip bus", "tt-alveolar-fricative"),
    _c("Z", "z", True, "alveolar", "fricative", "zip buzz", "tt-alveolar-fricative"),
    _c("L", "l", True, "alveolar", "lateral", "lie ball", "tt-alveolar-lateral"),
    _c("SH", "ʃ", False, "postalveolar", "fricative", "ship wish", "tt-postalveolar-fricative"),
    _c("ZH", "ʒ", True, "postalveolar", "fricative", "measure vision",
       "tt-postalveolar-fricative"),
    _c("CH", "tʃ", False, "postalveolar", "affricate", "chip much", "tt-postalveolar-closure",
       reasoning="an affricate: the target is its closure; speech releases into /ʃ/"),
    _c("JH", "dʒ", True, "postalveolar", "affricate", "jump edge", "tt-postalveolar-closure",
       reasoning="an affricate: the target is its closure; speech releases into /ʒ/"),
    _c("Y", "j", True, "palatal", "approximant", "yes you", "tb-palatal-fricative",
       reasoning="JD3 has a palatal fricative, not the approximant: the fit to it is opened by "
                 "lowering the tongue body 2 mm from the palate, as an approximant is wider"),
    _c("K", "k", False, "velar", "stop", "kite back", "tb-velar-closure"),
    _c("G", "ɡ", True, "velar", "stop", "go bag", "tb-velar-closure"),
    _c("NG", "ŋ", True, "velar", "nasal", "sing long", "tb-velar-closure", nasal=True),
    _c("W", "w", True, "labial-velar", "approximant", "we away", None, rounded=True,
       reasoning="no JD3 shape: /w/ is a rounded /u/ with a closer lip opening, so its target is "
                 "the /u/ fit with the lips rounded and protruded further"),
    _c("R", "ɹ", True, "postalveolar", "approximant", "red car", None, rounded=True,
       reasoning="no JD3 shape: American /ɹ/ is bunched (tongue body raised toward the "
                 "postalveolar region, tip lowered, root retracted into the pharynx) with some "
                 "lip rounding, built from the postalveolar fricative fit with the tip lowered "
                 "and a gap kept from the palate"),
    _c("HH", "h", False, "glottal", "fricative", "hat ahead", None,
       reasoning="no supralaryngeal shape: /h/ takes the neighbouring vowel's articulation; its "
                 "target is the neutral schwa-like rest pose, which coarticulation overrides"),
)

_BY_ARPABET = {p.arpabet: p for p in INVENTORY}
_BY_IPA = {p.ipa: p for p in INVENTORY}
# Common alternative IPA spellings.
_BY_IPA.update({"g": _BY_ARPABET["G"], "r": _BY_ARPABET["R"], "ɚ": _BY_ARPABET["ER"],
                "ɜ": _BY_ARPABET["ER"], "ʧ": _BY_ARPABET["CH"], "ʤ": _BY_ARPABET["JH"],
                "ə": _BY_ARPABET["AH"], "a": _BY_ARPABET["AA"], "e": _BY_ARPABET["EY"],
                "o": _BY_ARPABET["OW"]})


class UnknownPhonemeError(KeyError):
    """A symbol that is neither an ARPAbet nor an IPA symbol of the inventory."""

    def __str__(self) -> str:
        return str(self.args[0])


def lookup(symbol: str) -> Phoneme:
    """The phoneme for an ARPAbet symbol (any case; a stress digit 0-2 is ignored) or an IPA
    symbol. UnknownPhonemeError naming the symbol and the choices otherwise."""
    if not isinstance(symbol, str) or not symbol.strip():
        raise UnknownPhonemeError("a phoneme symbol must be a non-empty string")
    text = symbol.strip()
    if text in _BY_IPA:
        return _BY_IPA[text]
    key = text.upper().rstrip("012")
    if key in _BY_ARPABET:
        return _BY_ARPABET[key]
    raise UnknownPhonemeError(
        f"unknown phoneme {symbol!r}: use one of the 39 ARPAbet symbols "
        f"({' '.join(p.arpabet for p in INVENTORY)}) or their IPA ({' '.join(_BY_IPA)})")
