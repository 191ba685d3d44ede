"""The four real HPRC utterances of ../shared/data/ema/hprc, read by glasshead.ema."""

import json

import numpy as np
import pytest

from glasshead.ema import HPRC_SENSORS, PAUSE, EmaFormatError, read_ema, read_hprc
from test_ema_writers import UTTERANCES, hprc_columns, hprc_csv, hprc_dir


@pytest.fixture(scope="module")
def recordings():
    return {utt: read_ema(hprc_csv(utt)) for utt in UTTERANCES}


def meta(utt):
    return json.loads((hprc_dir() / f"{utt}_meta.json").read_text())


def tsv_rows(utt, kind):
    lines = (hprc_dir() / f"{utt}_{kind}.tsv").read_text().splitlines()[1:]
    return [(float(s), float(e), label) for s, e, label in (line.split("\t") for line in lines)]


@pytest.mark.parametrize("utt", UTTERANCES)
def test_every_utterance_has_the_frames_rate_and_sensors_its_meta_file_lists(recordings, utt):
    recording, info = recordings[utt], meta(utt)
    assert recording.source_format == "hprc"
    assert recording.name == utt
    assert recording.n_frames == info["ema_frames"]
    assert recording.sample_rate_hz == info["ema_sr"] == 100.0
    assert sorted(recording.sensors) == sorted(HPRC_SENSORS[s] for s in info["sensors"])
    assert recording.dropouts == ()


def test_m04_has_neither_mouth_corner_nor_left_jaw_sensor(recordings):
    sensors = recordings["M04_B02_S44_R01_N"].sensors
    assert "mouth_left" not in sensors and "jaw_left" not in sensors
    assert {"tongue_tip", "tongue_blade", "tongue_dorsum", "upper_lip", "lower_lip",
            "lower_incisor"} == set(sensors)


@pytest.mark.parametrize("utt", UTTERANCES)
def test_positions_are_the_csv_values_in_mm(recordings, utt):
    t_s, columns = hprc_columns(utt)
    recording = recordings[utt]
    np.testing.assert_array_equal(recording.t_s, t_s)
    for code, xyz in columns.items():
        np.testing.assert_array_equal(recording.sensors[HPRC_SENSORS[code]], xyz)
        assert recording.sensors[HPRC_SENSORS[code]].dtype == np.float64


@pytest.mark.parametrize("utt", UTTERANCES)
def test_the_phones_cover_the_signal_without_gaps(recordings, utt):
    recording = recordings[utt]
    phones = recording.phones
    assert len(phones) == meta(utt)["n_phones"]
    assert phones[0].start_s == 0.0 == recording.t_s[0]
    assert recording.t_s[-1] - 0.01 <= phones[-1].end_s <= recording.t_s[-1] + 0.01
    for before, after in zip(phones, phones[1:], strict=False):
        assert after.start_s == before.end_s


@pytest.mark.parametrize("utt", UTTERANCES)
def test_phone_times_and_symbols_match_the_tsv_with_stress_apart(recordings, utt):
    rows = tsv_rows(utt, "phones")
    phones = recordings[utt].phones
    assert [(p.start_s, p.end_s) for p in phones] == [(s, e) for s, e, _ in rows]
    for phone, (_, _, label) in zip(phones, rows, strict=True):
        if label == "sp":
            assert (phone.symbol, phone.stress) == (PAUSE, None)
        elif label[-1].isdigit():
            assert (phone.symbol, phone.stress) == (label[:-1], int(label[-1]))
        else:
            assert (phone.symbol, phone.stress) == (label, None)


def test_the_first_phones_of_m04_are_a_pause_then_open(recordings):
    first = recordings["M04_B02_S44_R01_N"].phones[:4]
    assert [tuple(p) for p in first] == [(0.0, 0.2, "sil", None), (0.2, 0.3297, "OW", 1),
                                         (0.3297, 0.3995, "P", None), (0.3995, 0.4295, "AH", 0)]


@pytest.mark.parametrize("utt", UTTERANCES)
def test_words_are_read_with_pauses_normalised(recordings, utt):
    rows = tsv_rows(utt, "words")
    words = recordings[utt].words
    assert [(w.start_s, w.end_s) for w in words] == [(s, e) for s, e, _ in rows]
    assert [w.label for w in words] == [PAUSE if label == "sp" else label
                                        for _, _, label in rows]


@pytest.mark.parametrize("utt", UTTERANCES)
def test_the_anatomy_is_plausible(recordings, utt):
    mean = {name: xyz.mean(axis=0) for name, xyz in recordings[utt].sensors.items()}
    x, z = 0, 2
    assert mean["upper_lip"][z] > mean["lower_lip"][z] + 10.0
    assert mean["tongue_tip"][x] > mean["tongue_blade"][x] > mean["tongue_dorsum"][x]
    assert mean["upper_lip"][x] > 0.0 > mean["tongue_tip"][x]  # the origin is the upper incisor
    assert mean["lower_incisor"][z] < -5.0
    assert mean["lower_lip"][z] < mean["upper_lip"][z]


def test_the_mouth_corner_is_on_the_speakers_left(recordings):
    for utt in ("F01_B01_S01_R01_N", "M01_B01_S01_R01_N"):
        assert recordings[utt].sensors["mouth_left"][:, 1].mean() > 20.0


def test_arrays_are_read_only(recordings):
    recording = recordings[UTTERANCES[0]]
    with pytest.raises(ValueError):
        recording.t_s[0] = 1.0
    with pytest.raises(ValueError):
        recording.sensors["tongue_tip"][0, 0] = 1.0


def test_read_hprc_is_what_read_ema_dispatches_to(recordings):
    direct = read_hprc(hprc_csv(UTTERANCES[2]))
    np.testing.assert_array_equal(direct.sensors["tongue_tip"],
                                  recordings[UTTERANCES[2]].sensors["tongue_tip"])
    assert direct.phones == recordings[UTTERANCES[2]].phones


def test_a_sensor_asked_for_but_absent_is_named():
    with pytest.raises(EmaFormatError, match=r"M04_B02_S44_R01_N_ema\.csv: sensor\(s\) "
                                             r"mouth_left asked for but not in the file"):
        read_ema(hprc_csv("M04_B02_S44_R01_N"), sensors=["tongue_tip", "mouth_left"])


def test_the_fast_f01_file_names_its_mouth_corner_jaw_and_its_jaw_jawl(recordings):
    # A fault of the shared copy (docs/ema.md): by position and by angles, the columns the fast
    # F01 file calls JAW and JAWL are the normal-rate file's ML and JAW. The reader reports what
    # the file says; this test notices when the data are corrected.
    normal, fast = recordings["F01_B01_S01_R01_N"].sensors, recordings["F01_B01_S01_R01_F"].sensors
    mean = {name: xyz.mean(axis=0) for name, xyz in fast.items()}
    assert np.linalg.norm(mean["lower_incisor"] - normal["mouth_left"].mean(axis=0)) < 2.0
    assert np.linalg.norm(mean["jaw_left"] - normal["lower_incisor"].mean(axis=0)) < 2.0
