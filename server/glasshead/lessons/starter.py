"""The lessons a new store starts with, so that a first user has something to open at once.

Contrasts that speech therapy teaches first, each as the two phonemes shown side by side and
then minimal pairs of words, on the cutaway in profile with the labels the contrast is about:
/s/ against /ʃ/, /t/ against /k/, /r/ against /l/, the nasals against their oral pairs, and the
vowels from front to back. Migration 0005 inserts them once, into the new ``lessons`` table;
they are ordinary lessons afterwards (edited or deleted like any other, never put back).
Migration 0013 brings a starter lesson nobody has changed (still at version 1) to this content.
"""

from glasshead.lessons.schema import LessonContent
from glasshead.phonemes import lookup

#: Every item opens on the cutaway in profile, close on the mouth: the section shows the tongue,
#: palate and velum that bone and teeth would hide from any other side. Each set names only what
#: differs from the format's defaults (``schema.Views``), as every lesson here leaves out what the
#: defaults give.
_SECTION = {"skin_transparency": 0.8, "cutaway": True, "zoom": 1.5}  # the camera: profile
#: The tongue against the palate: the EPG panel beside the section.
_PALATE = {**_SECTION, "epg": True}
#: The velum and voicing: the 2D diagram and the cues beside the section.
_VELUM = {**_SECTION, "diagram": True}
#: Vowels: no cues (a vowel has no constriction to show air through).
_VOWEL = {**_SECTION, "cues": False}

#: The two or three labels a contrast is about: the articulators and the places they reach.
_LABELS = {
    "s-sh": ["tongue_tip", "alveolar", "postalveolar"],
    "t-k": ["tongue_tip", "tongue_back", "alveolar", "velar"],
    "r-l": ["tongue_tip", "tongue_back", "alveolar_ridge"],
    "nasals": ["velum", "nasal_port", "lips"],
    "vowels": ["tongue_front", "tongue_back", "lips"],
}


def _views(views: dict, labels: str) -> dict:
    return {**views, "labels": _LABELS[labels]}


#: What a try is measured on (schema.Listen), by the phoneme or word it is at: the vowels by
#: their norms, /s/ and /ʃ/ (and words that start with them) on the meter, /r/ by its F3.
_VOWELS = ["i", "ɪ", "ɛ", "æ", "ʌ", "ɑ", "ɔ", "ʊ", "u"]
_VOWEL_WORDS = {"beat": "iy", "bit": "ih", "bet": "eh", "bat": "ae", "but": "ah", "father": "aa",
                "law": "ao", "book": "uh", "boot": "uw"}
#: The norms' codes are ARPAbet in lower case: a held vowel's is its own symbol's.
_VOWEL_CODES = {**{v: lookup(v).arpabet.lower() for v in _VOWELS}, **_VOWEL_WORDS}
_LISTEN: dict[str, dict] = {
    **{key: {"measure": "vowel", "vowel": code} for key, code in _VOWEL_CODES.items()},
    **{key: {"measure": "sibilant", "sound": "s"} for key in ("s", "sip", "sore", "sell")},
    **{key: {"measure": "sibilant", "sound": "sh"} for key in ("ʃ", "ship", "shore", "shell")},
    "r": {"measure": "rhotic"},
}


def _listening(item: dict, key: str) -> dict:
    return {**item, "listen": _LISTEN[key]} if key in _LISTEN else item


def _phoneme(symbol: str, views: dict) -> dict:
    return _listening({"target": {"kind": "phoneme", "text": symbol}, "presentation": "static",
                       "views": views}, symbol)


def _word(text: str, views: dict, speed: float = 0.5) -> dict:
    return _listening({"target": {"kind": "word", "text": text}, "views": views,
                       "speed": speed}, text)


def _contrast(title: str, description: str, phonemes: list[str], words: list[str],
              views: dict) -> dict:
    return {"title": title, "description": description,
            "items": [_phoneme(p, views) for p in phonemes] + [_word(w, views) for w in words]}


STARTER_LESSONS: tuple[dict, ...] = (
    _contrast("/s/ and /ʃ/", "The tongue tip at the ridge, then further back and domed: "
              "watch the groove move on the EPG.", ["s", "ʃ"],
              ["sip", "ship", "sore", "shore", "sell", "shell"], _views(_PALATE, "s-sh")),
    _contrast("/t/ and /k/", "A closure at the front of the palate, then at the back.",
              ["t", "k"], ["tea", "key", "tap", "cap", "tot", "cot"], _views(_PALATE, "t-k")),
    _contrast("/r/ and /l/", "The bunched /r/ keeps off the palate; /l/ touches the ridge "
              "with the sides open.", ["r", "l"],
              ["red", "led", "right", "light", "rock", "lock"], _views(_PALATE, "r-l")),
    _contrast("Nasals and their oral pairs", "The same closures with the velum lowered: air "
              "through the nose for /m n ŋ/, not for /b d ɡ/.", ["m", "b", "n", "d", "ŋ", "ɡ"],
              ["me", "bee", "knee", "dee", "sing", "sig"], _views(_VELUM, "nasals")),
    {"title": "The vowels",
     "description": "From the front of the mouth to the back: how high the tongue is, and "
                    "where, and the lips.",
     "items": [_phoneme(p, _views(_VOWEL, "vowels")) for p in _VOWELS]
     + [_word(w, _views(_VOWEL, "vowels"), speed=0.4) for w in _VOWEL_WORDS]},
)


def starter_lessons() -> list[LessonContent]:
    """The starter lessons, validated."""
    return [LessonContent.model_validate(lesson) for lesson in STARTER_LESSONS]
