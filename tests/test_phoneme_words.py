"""How each phoneme is made, in a teacher's words: one for every phoneme, short, and served."""

import re

from glasshead.phoneme_words import HOW_IT_IS_MADE
from glasshead.phonemes import INVENTORY

API = "/api/v1"
#: Longest description, characters: two short sentences a teacher reads out.
MOST_CHARACTERS = 180


def test_every_phoneme_has_a_short_description_and_nothing_else_does():
    assert set(HOW_IT_IS_MADE) == {p.arpabet for p in INVENTORY}
    for arpabet, words in HOW_IT_IS_MADE.items():
        assert 30 <= len(words) <= MOST_CHARACTERS, f"{arpabet}: {len(words)} characters"
        assert words[0].isupper() and words.rstrip("'").endswith((".", "'")), arpabet


def test_the_voice_is_named_as_the_phoneme_is_voiced():
    for phoneme in INVENTORY:
        words = HOW_IT_IS_MADE[phoneme.arpabet].lower()
        if phoneme.kind == "consonant" and not phoneme.voiced:
            assert "no voice" in words, phoneme.arpabet
        if phoneme.nasal:
            assert "nose" in words, phoneme.arpabet


def test_a_description_names_the_articulator_of_its_place():
    names = {"bilabial": "lips", "labiodental": "lower lip", "dental": "between the teeth",
             "alveolar": "ridge", "velar": "soft palate"}
    for phoneme in INVENTORY:
        if phoneme.kind == "consonant" and phoneme.place in names:
            as_for = HOW_IT_IS_MADE[phoneme.arpabet].startswith("As for")  # said by its pair
            assert as_for or re.search(names[phoneme.place], HOW_IT_IS_MADE[phoneme.arpabet]), \
                phoneme.arpabet


def test_get_phonemes_serves_how_each_is_made(start_app):
    _, client = start_app()
    listed = client.get(f"{API}/phonemes").json()["phonemes"]
    assert {p["arpabet"]: p["how"] for p in listed} == HOW_IT_IS_MADE
    assert client.get(f"{API}/phonemes/s").json()["how"] == HOW_IT_IS_MADE["S"]
