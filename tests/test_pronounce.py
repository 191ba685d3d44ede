"""Words to ARPAbet with stress: CMUdict first, espeak-ng's rules for the rest, text normalised."""

from glasshead.speech.espeak import get_engine
from glasshead.speech.espeak_phones import arpabet_to_espeak, parse_espeak_phonemes
from glasshead.speech.pronounce import pronounce, tokenize


def _only_word(text):
    result = pronounce(text, get_engine())
    assert len(result.words) == 1, result
    return result.words[0]


def test_stew_and_key_come_from_cmudict_with_stress():
    stew, key = _only_word("stew"), _only_word("Key")
    assert (stew.phones, stew.source) == ([("S", None), ("T", None), ("UW", 1)], "cmudict")
    assert (key.phones, key.source) == ([("K", None), ("IY", 1)], "cmudict")


def test_an_invented_word_goes_through_espeak_ng():
    word = _only_word("blorfing")
    assert word.source == "espeak-ng"
    assert [s for s, _ in word.phones] == ["B", "L", "AO", "R", "F", "IH", "NG"]
    assert ("AO", 1) in word.phones  # the stress espeak-ng placed is kept


def test_a_number_is_read_out_by_espeak_ng():
    word = _only_word("42")
    assert word.source == "espeak-ng"
    symbols = [s for s, _ in word.phones]
    assert symbols[:3] == ["F", "AO", "R"] and symbols[-2:] == ["T", "UW"]  # forty-two
    year = _only_word("1998")  # espeak-ng writes a palatalisation mark (;) in "ninety"
    assert [s for s, _ in year.phones][-2:] == ["EY", "T"]


def test_case_is_ignored_and_punctuation_becomes_pauses():
    assert tokenize("Hello, WORLD! Again.") == ["hello", "sil", "world", "sil", "again"]
    assert tokenize("  ...Well -- yes  ") == ["well", "sil", "yes"]
    assert tokenize("Café don\u2019t") == ["cafe", "don't"]


def test_a_word_neither_can_pronounce_is_named_and_the_rest_still_spoken():
    result = pronounce("say 日本 again", get_engine())
    assert result.unpronounceable == ["日本"]
    assert [w.text for w in result.words] == ["say", "again"]


def test_without_espeak_ng_a_word_cmudict_lacks_is_unpronounceable():
    result = pronounce("stew blorfing", espeak=None)
    assert [w.text for w in result.words] == ["stew"]
    assert result.unpronounceable == ["blorfing"]


def test_arpabet_goes_to_espeak_notation_and_back():
    word = [("S", None), ("T", None), ("UW", 1), ("ER", 0), ("AH", 0), ("AH", 2)]
    assert arpabet_to_espeak(word) == "st'u:3@,V"
    assert parse_espeak_phonemes("s|t|'u: 3|@|,V") == word
    assert parse_espeak_phonemes("b|'V|t#|3") == [("B", None), ("AH", 1), ("T", None),
                                                  ("ER", 0)]
