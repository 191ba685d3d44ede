"""Real EPG frames of the emuR engassim recordings grouped into consonant classes
(epg.classes): the patterns the articulation targets are checked against."""

import numpy as np
import pytest

from glasshead.epg.classes import (
    ELECTRODES,
    EpgObservationError,
    agreement,
    back_closure,
    central_groove,
    class_frames,
    front_closure,
    majority_pattern,
    side_contact,
)
from glasshead.epg.formats import parse_emur_json
from glasshead.epg.sequence import make_sequence


@pytest.fixture(scope="module")
def classes(data_dir):
    return class_frames(parse_emur_json((data_dir / "epg/emur-engassim.json").read_bytes()))


def test_every_segment_gives_one_frame_of_each_of_its_consonants(classes):
    assert {name: len(c.frames) for name, c in classes.items()} == {
        "alveolar_stop": 17, "alveolar_fricative": 15, "velar_stop": 32}


def test_the_real_alveolar_stop_closes_the_front_with_contact_along_both_sides(classes):
    pattern = classes["alveolar_stop"].majority
    assert front_closure(pattern) and side_contact(pattern) and not back_closure(pattern)


def test_the_real_alveolar_fricative_leaves_a_central_groove(classes):
    pattern = classes["alveolar_fricative"].majority
    assert central_groove(pattern) and not front_closure(pattern)


def test_the_real_velar_stops_fill_the_back_row_but_often_close_behind_it(classes):
    # The Reading palate's last row lies near the end of the hard palate; a velar closure is
    # often farther back, out of its reach: 8 of the 32 frames close R8 completely.
    frames = classes["velar_stop"].frames
    assert sum(back_closure(f) for f in frames) == 8
    pattern = classes["velar_stop"].majority
    assert pattern[7].sum() >= 6 and not front_closure(pattern)


def test_agreement_counts_the_62_electrodes():
    full = ELECTRODES.astype(np.uint8)
    assert agreement(full, full) == 1.0
    assert agreement(np.zeros((8, 8), np.uint8), full) == 0.0
    one_off = full.copy()
    one_off[3, 3] = 0
    np.testing.assert_allclose(agreement(one_off, full), 61 / 62, rtol=0, atol=1e-15)
    assert majority_pattern(np.array([full, full, np.zeros_like(full)])).sum() == 62


def test_a_segment_without_a_consonant_pair_label_is_refused_naming_it():
    sequence = make_sequence(np.zeros((6, 8, 8), np.uint8), np.arange(6) / 100.0, "odd",
                             meta={"label": "a->b"})
    with pytest.raises(EpgObservationError, match="segment 'odd': label 'a->b'"):
        class_frames([sequence])
