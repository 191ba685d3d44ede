"""ARPAbet to espeak-ng's phoneme mnemonics (American English voice) and back.

espeak-ng speaks ``[[...]]`` input in its own mnemonics (docs/phonemes.md of espeak-ng): a
stress mark ``'`` (primary) or ``,`` (secondary) before a vowel, ``_:`` a pause. Going forward,
each of our 39 phonemes has one mnemonic (ʌ and ɝ have an unstressed form: ə and ɚ). Coming back,
espeak-ng's own output (a word CMUdict lacks, or an allophone it chose while speaking) uses more
mnemonics than ours; each maps to one or two ARPAbet phones.
"""

from glasshead.phonemes import INVENTORY

#: Our symbol for silence (a pause, or the silence at either end of the audio).
PAUSE = "sil"
VOWELS = frozenset(p.arpabet for p in INVENTORY if p.kind != "consonant")

_FORWARD = {
    "AA": "A:", "AE": "a", "AH": "V", "AO": "O:", "AW": "aU", "AY": "aI", "EH": "E", "ER": "3:",
    "EY": "eI", "IH": "I", "IY": "i:", "OW": "oU", "OY": "OI", "UH": "U", "UW": "u:",
    "B": "b", "CH": "tS", "D": "d", "DH": "D", "F": "f", "G": "g", "HH": "h", "JH": "dZ",
    "K": "k", "L": "l", "M": "m", "N": "n", "NG": "N", "P": "p", "R": "r", "S": "s", "SH": "S",
    "T": "t", "TH": "T", "V": "v", "W": "w", "Y": "j", "Z": "z", "ZH": "Z",
}
#: Unstressed forms: /ʌ/ unstressed is schwa, /ɝ/ unstressed is /ɚ/.
_UNSTRESSED = {"AH": "@", "ER": "3"}

#: espeak-ng's mnemonics (en-us) as ARPAbet; several are allophones or r-coloured vowels.
_BACKWARD: dict[str, tuple[str, ...]] = {m: (a,) for a, m in _FORWARD.items()}
_BACKWARD.update({
    "@": ("AH",), "3": ("ER",), "a#": ("AH",), "0": ("AA",), "A@": ("AA", "R"), "aa": ("AE",),
    "aI3": ("AY", "ER"), "aI@": ("AY", "ER"), "aU@": ("AW", "ER"), "@L": ("AH", "L"),
    "@2": ("AH",), "@5": ("AH",), "VR": ("ER",), "e": ("EH",), "e@": ("EH", "R"), "E2": ("EH",),
    "E3": ("EH",), "i": ("IY",), "i@": ("IY", "R"), "i@3": ("IY", "ER"), "I2": ("IH",),
    "I#": ("IH",), "o@": ("AO", "R"), "O@": ("AO", "R"), "O": ("AO",), "U@": ("UH", "R"),
    "u@": ("UW", "R"), "oU#": ("OW",), "t#": ("T",), "t2": ("T",), "d#": ("D",), "?": ("T",),
    "*": ("T",), "n-": ("N",), "m-": ("M",), "l-": ("L",), "r-": ("R",), "x": ("K",),
    "hw": ("W",), "_": (PAUSE,), "_:": (PAUSE,), "_!": (PAUSE,), "_;_": (PAUSE,),
})
_STRESS_MARKS = {"'": 1, ",": 2, "%": 0, "=": 0}
#: Marks espeak-ng writes between phones that are not phones (";" palatalises the one before).
_MARKS = frozenset({";", "-", "#"})


def arpabet_to_espeak(word: list[tuple[str, int | None]]) -> str:
    """One word's phones, (ARPAbet without stress digit, stress 0/1/2 or None), in espeak-ng's
    ``[[...]]`` notation, e.g. [("S", None), ("T", None), ("UW", 1)] -> "st'u:"; a pause
    [("sil", None)] -> "_:"."""
    out = []
    for symbol, stress in word:
        if symbol == PAUSE:
            out.append("_:")
        elif symbol in VOWELS:
            mnemonic = _UNSTRESSED.get(symbol, _FORWARD[symbol]) if not stress else _FORWARD[
                symbol]
            out.append({1: "'", 2: ","}.get(stress or 0, "") + mnemonic)
        elif symbol in _FORWARD:
            out.append(_FORWARD[symbol])
        else:
            raise ValueError(f"no espeak-ng phoneme for {symbol!r}")
    return "".join(out)


def espeak_to_arpabet(mnemonic: str) -> list[tuple[str, int | None]]:
    """One espeak-ng phone (a stress mark allowed in front) as ARPAbet phones with stress
    (vowels 0/1/2, consonants and pauses None); [] when the mnemonic is not one we know."""
    stress = 0
    while mnemonic and mnemonic[0] in _STRESS_MARKS:
        stress = max(stress, _STRESS_MARKS[mnemonic[0]])
        mnemonic = mnemonic[1:]
    symbols = _BACKWARD.get(mnemonic, ())
    return [(s, (stress if k == 0 else 0) if s in VOWELS else None)
            for k, s in enumerate(symbols)]


def parse_espeak_phonemes(text: str) -> list[tuple[str, int | None]]:
    """espeak-ng's ``TextToPhonemes`` output (phones separated by "|", words by spaces) as
    ARPAbet; ValueError naming the first mnemonic we cannot map."""
    phones = []
    for token in text.replace(" ", "|").split("|"):
        if not token or token in _MARKS:
            continue
        mapped = espeak_to_arpabet(token)
        if not mapped:
            raise ValueError(f"espeak-ng phoneme {token!r} has no ARPAbet equivalent")
        phones.extend(p for p in mapped if p[0] != "sil")
    return phones
