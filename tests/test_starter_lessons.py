"""The starter lessons teach what they say: each contrast's words are minimal pairs that differ
in exactly the two phonemes it contrasts, and each vowel's word carries that vowel (CMUdict's
pronunciation, as the speech player speaks it)."""

import pytest

from glasshead.lessons.starter import STARTER_LESSONS, starter_lessons
from glasshead.phonemes import lookup
from glasshead.speech.pronounce import pronounce

CONTRASTS = [lesson for lesson in STARTER_LESSONS if lesson["title"] != "The vowels"]


def targets(lesson: dict, kind: str) -> list[str]:
    return [item["target"]["text"] for item in lesson["items"] if item["target"]["kind"] == kind]


def phones(word: str) -> list[str]:
    """The word's ARPAbet phones without stress, from CMUdict (no espeak-ng guess)."""
    (spoken,) = pronounce(word).words
    assert spoken.source == "cmudict", f"{word!r} is not in CMUdict"
    return [symbol for symbol, _ in spoken.phones]


def test_every_starter_lesson_is_a_valid_lesson_of_phonemes_and_words():
    lessons = starter_lessons()
    assert [lesson.title for lesson in lessons] == [s["title"] for s in STARTER_LESSONS]
    assert len(lessons) == 5
    for lesson in lessons:
        kinds = {item.target.kind for item in lesson.items}
        assert kinds == {"phoneme", "word"}, lesson.title


@pytest.mark.parametrize("lesson", CONTRASTS, ids=lambda lesson: lesson["title"])
def test_a_contrast_lessons_words_are_minimal_pairs_of_its_phonemes(lesson):
    arpabet = [lookup(symbol).arpabet for symbol in targets(lesson, "phoneme")]
    pairs = {frozenset(arpabet[k:k + 2]) for k in range(0, len(arpabet), 2)}
    words = targets(lesson, "word")
    assert len(words) == 6
    for first, second in zip(words[::2], words[1::2], strict=True):
        a, b = phones(first), phones(second)
        differing = [(x, y) for x, y in zip(a, b, strict=True) if x != y]
        assert len(differing) == 1, (first, second, a, b)
        assert frozenset(differing[0]) in pairs, (first, second, differing)


def test_the_nasal_lesson_pairs_each_nasal_with_its_oral_stop_at_the_same_place():
    (lesson,) = [s for s in STARTER_LESSONS if s["title"].startswith("Nasals")]
    phonemes = [lookup(symbol) for symbol in targets(lesson, "phoneme")]
    for nasal, oral in zip(phonemes[::2], phonemes[1::2], strict=True):
        assert nasal.nasal and not oral.nasal and oral.manner == "stop"
        assert nasal.place == oral.place and nasal.voiced == oral.voiced


def test_each_vowel_of_the_vowel_lesson_is_in_its_word():
    (lesson,) = [s for s in STARTER_LESSONS if s["title"] == "The vowels"]
    vowels = [lookup(symbol) for symbol in targets(lesson, "phoneme")]
    assert all(vowel.kind == "vowel" for vowel in vowels)
    words = targets(lesson, "word")
    assert len(words) == len(vowels) == 9
    for vowel, word in zip(vowels, words, strict=True):
        assert vowel.arpabet in phones(word), (vowel.ipa, word, phones(word))


def test_the_starter_lessons_name_no_value_the_format_gives_by_default():
    """The defaults live in the lesson schema only: a starter lesson that spelled one out would
    keep it when the schema's default changed."""
    from pydantic import BaseModel

    from glasshead.lessons.schema import Item, LessonContent

    def spelled_defaults(model: type[BaseModel], written: dict, where: str) -> list[str]:
        found = []
        for name, value in written.items():
            field = model.model_fields[name]
            nested = field.annotation if isinstance(field.annotation, type) else None
            if isinstance(value, dict) and nested and issubclass(nested, BaseModel):
                found += spelled_defaults(nested, value, f"{where}.{name}")
            elif not field.is_required() and value == field.get_default(call_default_factory=True):
                found.append(f"{where}.{name}")
        return found

    found = []
    for lesson in STARTER_LESSONS:
        found += spelled_defaults(LessonContent, {k: v for k, v in lesson.items() if k != "items"},
                                  lesson["title"])
        for k, item in enumerate(lesson["items"]):
            found += spelled_defaults(Item, item, f"{lesson['title']} item {k}")
    assert found == []


def test_the_label_names_a_lesson_may_list_are_the_parts_and_places_the_build_labels():
    from glasshead.constants import LABEL_NAMES
    from glasshead.pipeline.landmarks import PARTS, PLACES

    assert list(LABEL_NAMES) == [part[0] for part in PARTS] + [place[0] for place in PLACES]
