"""Bad HPRC files and bad label files, made from copies of the real ones: each refused with a
message naming the file, the line or time, and the problem. And the choice of reader."""

import json
import re
import shutil

import numpy as np
import pytest

from glasshead.ema import EmaFormatError, detect_format, parse_label_file, read_ema
from glasshead.ema.labels import split_phone
from test_ema_writers import ag501_bytes, est_bytes, hprc_dir, pos_samples

UTT = "M04_B02_S44_R01_N"


@pytest.fixture
def utt_copy(tmp_path):
    """A writable copy of one HPRC utterance's files; returns the path of its CSV."""
    for suffix in ("_ema.csv", "_phones.tsv", "_words.tsv", "_meta.json"):
        shutil.copy(hprc_dir() / f"{UTT}{suffix}", tmp_path / f"{UTT}{suffix}")
    return tmp_path / f"{UTT}_ema.csv"


def edit_lines(path, edit):
    lines = path.read_text().splitlines()
    edit(lines)
    path.write_text("\n".join(lines) + "\n")


def edit_meta(csv, **changes):
    path = csv.with_name(f"{UTT}_meta.json")
    meta = json.loads(path.read_text())
    meta.update(changes)
    path.write_text(json.dumps(meta))


def blank_sensor(csv, sensor, rows):
    """Empty the position cells of one sensor on the given data rows (0-based)."""
    def edit(lines):
        header = lines[0].split(",")
        columns = [header.index(f"{sensor}_{a}") for a in "xyz"]
        for row in rows:
            cells = lines[row + 1].split(",")
            for c in columns:
                cells[c] = "nan" if row % 2 else ""
            lines[row + 1] = ",".join(cells)
    edit_lines(csv, edit)


def refused(csv, match, **options):
    with pytest.raises(EmaFormatError, match=match):
        read_ema(csv, **options)


# --- HPRC files --------------------------------------------------------------------------------

def test_a_meta_file_that_lies_about_the_frame_count_is_refused(utt_copy):
    edit_meta(utt_copy, ema_frames=256)
    refused(utt_copy, r"M04_B02_S44_R01_N_meta\.json: ema_frames says 256 frames, the CSV has 255")


def test_a_sample_rate_of_zero_or_below_is_refused(utt_copy):
    edit_meta(utt_copy, ema_sr=0)
    refused(utt_copy, r"_meta\.json: sample rate ema_sr 0 is not a positive number")
    edit_meta(utt_copy, ema_sr=-100.0)
    refused(utt_copy, r"_meta\.json: sample rate ema_sr -100\.0 is not a positive number")


def test_a_sample_rate_that_does_not_match_the_times_is_refused(utt_copy):
    edit_meta(utt_copy, ema_sr=200.0)
    refused(utt_copy, r"_ema\.csv, line 3: frame 1: the step from 0\.000000 s to 0\.010000 s "
                      r"does not match the sample rate of 200 Hz")


def test_a_sensor_the_meta_file_lists_but_the_csv_lacks_is_named(utt_copy):
    edit_meta(utt_copy, sensors=["TR", "TB", "TT", "UL", "LL", "JAW", "ML"])
    refused(utt_copy, r"_meta\.json: sensors lists ML, which the CSV has no columns for")


def test_times_that_do_not_increase_name_the_line(utt_copy):
    def edit(lines):
        cells = lines[11].split(",")
        cells[0] = "0.0900"
        lines[11] = ",".join(cells)
    edit_lines(utt_copy, edit)
    refused(utt_copy, r"_ema\.csv, line 12: frame 10: times do not increase \(0\.090000 s, then "
                      r"0\.090000 s\)")


def test_a_cell_that_is_not_a_number_names_line_and_column(utt_copy):
    edit_lines(utt_copy, lambda lines: lines.__setitem__(5, lines[5].replace(",", ",x", 1)))
    refused(utt_copy, r"_ema\.csv, line 6: TR_x: 'x-4[\d.]+' is not a number")


def test_a_short_row_names_its_line(utt_copy):
    edit_lines(utt_copy, lambda lines: lines.__setitem__(20, lines[20].rsplit(",", 1)[0]))
    refused(utt_copy, r"_ema\.csv, line 21: expected 37 columns, got 36")


def test_a_sensor_without_its_z_column_is_refused(utt_copy):
    edit_lines(utt_copy, lambda lines: lines.__setitem__(0, lines[0].replace("TT_z", "TT_q")))
    refused(utt_copy, r"_ema\.csv, line 1: column 'TT_q' is not <sensor>_x/_y/_z/_ang1-3")


def test_missing_samples_of_40_ms_are_interpolated_and_reported(utt_copy):
    before = read_ema(utt_copy)
    blank_sensor(utt_copy, "TT", range(100, 104))
    after = read_ema(utt_copy)
    assert after.dropouts == (("tongue_tip", 1.0, 1.04, 4),)
    tip = before.sensors["tongue_tip"]
    w = np.arange(1, 5)[:, None] / 5.0
    np.testing.assert_allclose(after.sensors["tongue_tip"][100:104],
                               (1 - w) * tip[99] + w * tip[104], atol=1e-12)
    np.testing.assert_array_equal(np.delete(after.sensors["tongue_tip"], range(100, 104), 0),
                                  np.delete(tip, range(100, 104), 0))
    np.testing.assert_array_equal(after.sensors["upper_lip"], before.sensors["upper_lip"])


def test_missing_samples_at_the_start_hold_the_first_sample(utt_copy):
    before = read_ema(utt_copy)
    blank_sensor(utt_copy, "UL", range(0, 3))
    after = read_ema(utt_copy)
    assert after.dropouts == (("upper_lip", 0.0, 0.03, 3),)
    np.testing.assert_array_equal(after.sensors["upper_lip"][:3],
                                  np.repeat(before.sensors["upper_lip"][3:4], 3, axis=0))


def test_missing_samples_of_80_ms_are_refused_naming_sensor_and_span(utt_copy):
    blank_sensor(utt_copy, "TT", range(100, 108))
    refused(utt_copy, r"M04_B02_S44_R01_N_ema\.csv: sensor tongue_tip: 8 samples missing from "
                      r"1\.000 s to 1\.080 s \(80 ms\), longer than the 50 ms that may be "
                      r"interpolated")


def test_the_longest_gap_filled_can_be_changed(utt_copy):
    blank_sensor(utt_copy, "TT", range(100, 108))
    assert read_ema(utt_copy, max_gap_s=0.1).dropouts == (("tongue_tip", 1.0, 1.08, 8),)


def test_a_missing_phone_file_is_named(utt_copy):
    utt_copy.with_name(f"{UTT}_phones.tsv").unlink()
    refused(utt_copy, r"_ema\.csv: no phone labels: expected M04_B02_S44_R01_N_phones\.tsv "
                      r"beside it")


def test_phones_past_the_end_of_the_signal_name_file_and_line(utt_copy):
    phones = utt_copy.with_name(f"{UTT}_phones.tsv")
    edit_lines(phones, lambda lines: lines.__setitem__(29, "2.3351\t2.5600\tsp"))
    refused(utt_copy, r"_phones\.tsv, line 30: label 'sp' ends at 2\.5600 s, past the end of the "
                      r"signal \(2\.5400 s, last sample\)")


def test_words_past_the_end_of_the_signal_name_file_and_line(utt_copy):
    words = utt_copy.with_name(f"{UTT}_words.tsv")
    edit_lines(words, lambda lines: lines.__setitem__(11, "2.3351\t2.9000\tsp"))
    refused(utt_copy, r"_words\.tsv, line 12: label 'sp' ends at 2\.9000 s, past the end")


def test_an_unknown_phone_names_symbol_and_line(utt_copy):
    phones = utt_copy.with_name(f"{UTT}_phones.tsv")
    edit_lines(phones, lambda lines: lines.__setitem__(6, lines[6].replace("DH", "DX")))
    refused(utt_copy, r"_phones\.tsv, line 7: unknown phone symbol 'DX': not one of the 39 "
                      r"ARPAbet phones")


def test_phones_out_of_order_or_overlapping_name_the_line(utt_copy):
    phones = utt_copy.with_name(f"{UTT}_phones.tsv")
    original = phones.read_text()

    def swap(lines):
        lines[4], lines[5] = lines[5], lines[4]
    edit_lines(phones, swap)
    refused(utt_copy, r"_phones\.tsv, line 6: labels out of order: 'AH0' starts at 0\.3995 s, "
                      r"before 'N' \(line 5\) ends at 0\.4694 s")
    phones.write_text(original)
    edit_lines(phones, lambda lines: lines.__setitem__(5, "0.4100\t0.4694\tN"))
    refused(utt_copy, r"_phones\.tsv, line 6: labels overlapping: 'N' starts at 0\.41 s, before "
                      r"'AH0' \(line 5\) ends at 0\.4295 s")


def test_a_label_file_given_by_the_caller_replaces_the_phones(utt_copy, tmp_path):
    labels = tmp_path / "mine.tsv"
    labels.write_text("0.0\t1.0\tsil\n1.0\t2.0\tAA1\n")
    recording = read_ema(utt_copy, labels=labels)
    assert [p.symbol for p in recording.phones] == ["sil", "AA"]


# --- label files -------------------------------------------------------------------------------

def labels_refused(text, match):
    with pytest.raises(EmaFormatError, match=match):
        parse_label_file(text.encode(), "utt.lab")


def test_an_xlabel_file_is_read_with_each_label_ending_at_its_time():
    text = "signal utt\nnfields 1\n#\n    0.25 121 sil\n    0.40 121 dh\n    0.55 121 ah0\n"
    labels = parse_label_file(text.encode(), "utt.lab")
    assert [(s, e, t) for s, e, t, _ in labels] == [(0.0, 0.25, "sil"), (0.25, 0.4, "dh"),
                                                     (0.4, 0.55, "ah0")]
    assert [label.line for label in labels] == [4, 5, 6]


def test_a_plain_start_end_label_file_is_read():
    labels = parse_label_file(b"0.0 0.3 sil\n0.3 0.5 p\n", "utt.lab")
    assert [(s, e, t) for s, e, t, _ in labels] == [(0.0, 0.3, "sil"), (0.3, 0.5, "p")]


def test_xlabel_times_that_go_back_are_refused_with_their_line():
    labels_refused("#\n 0.5 121 sil\n 0.3 121 p\n",
                   r"utt\.lab, line 3: label 'p' ends \(0\.3 s\) before it starts \(0\.5 s\)")


def test_an_xlabel_line_without_a_label_is_refused():
    labels_refused("#\n 0.5 121\n", r"utt\.lab, line 2: expected '<end time> <colour> <label>'")


def test_a_time_that_is_not_a_number_is_refused():
    labels_refused("0.0\tabc\tsil\n", r"utt\.lab, line 1: end time 'abc' is not a number")
    labels_refused("0.0\tinf\tsil\n", r"utt\.lab, line 1: end time 'inf' is not a finite number")


def test_a_negative_start_is_refused():
    labels_refused("-0.5 0.2 sil\n", r"utt\.lab, line 1: label 'sil' starts before 0")


@pytest.mark.parametrize(("label", "want"), [("AA1", ("AA", 1)), ("aa0", ("AA", 0)),
                                             ("ER2", ("ER", 2)), ("NG", ("NG", None)),
                                             ("sp", ("sil", None)), ("pau", ("sil", None)),
                                             ("h#", ("sil", None)), ("SIL", ("sil", None)),
                                             ("breath", ("sil", None))])
def test_phones_split_into_symbol_and_stress(label, want):
    assert split_phone(label, "x") == want


@pytest.mark.parametrize(("label", "problem"), [
    ("K1", "phone 'K1': a stress digit on a consonant"),
    ("AA3", "phone 'AA3': stress 3 is not 0, 1 or 2"),
    ("AX", "unknown phone symbol 'AX'"),
    ("bcl", "unknown phone symbol 'bcl'"),
])
def test_bad_phones_are_named(label, problem):
    with pytest.raises(EmaFormatError, match=re.escape(f"x, line 3: {problem}")):
        split_phone(label, "x", 3)


# --- choosing the reader -----------------------------------------------------------------------

def test_the_format_comes_from_the_extension_else_the_first_bytes():
    assert detect_format("a_ema.csv", b"") == "hprc"
    assert detect_format("a.ema", b"") == "mocha"
    assert detect_format("a.pos", b"AG50xDATA_V002\n") == "ag501"
    assert detect_format("a.pos", b"\x00\x00\x80?") == "ag500"
    assert detect_format("a.bin", b"EST_File Track\n") == "mocha"
    assert detect_format("a.bin", b"AG50xDATA_V002\n") == "ag501"
    assert detect_format("a.txt", b"time_s,TT_x") == "hprc"
    with pytest.raises(EmaFormatError, match=r"a\.bin: cannot tell the format; give format= one "
                                             r"of hprc, mocha, ag500, ag501"):
        detect_format("a.bin", b"\x00\x00\x80?")


def test_a_file_named_otherwise_is_read_by_its_content_or_by_format(tmp_path):
    content = est_bytes([0.0, 0.002], ["tt_x", "tt_y"], np.ones((2, 2)))
    path = tmp_path / "utt.track"
    path.write_bytes(content)
    assert read_ema(path).source_format == "mocha"
    assert read_ema(path, format="mocha").sensors["tongue_tip"].shape == (2, 3)
    with pytest.raises(EmaFormatError, match=r"unknown format 'est'; use one of"):
        read_ema(path, format="est")
    with pytest.raises(EmaFormatError, match=r"utt\.track: channels is for Carstens files"):
        read_ema(path, channels={"TT": 1})


def test_a_format_that_contradicts_the_file_is_refused(tmp_path):
    path = tmp_path / "utt.pos"
    path.write_bytes(ag501_bytes(pos_samples([np.zeros((10, 3))], 4), 250))
    with pytest.raises(EmaFormatError, match=r"utt\.pos: format ag500 was given, but the file is "
                                             r"ag501"):
        read_ema(path, format="ag500", channels={"TT": 1})
