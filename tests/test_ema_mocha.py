"""MOCHA-TIMIT files (EST track + xlabel phones) written from real HPRC data, read back, and
every way an EST file can be wrong."""

import re

import numpy as np
import pytest

from glasshead.ema import EmaFormatError, parse_est_track, read_ema, read_mocha
from test_ema_writers import (
    est_bytes,
    hprc_columns,
    hprc_dir,
    mocha_channels,
    xlabel_bytes,
)

UTT = "M01_B01_S01_R01_N"
#: float32 keeps 24 bits: 1e-7 of a value in 1/100 mm, i.e. well under 1e-4 mm at 100 mm.
MM_TOL = 1e-4
#: float32 times below 10 s are exact to 1e-6 s.
TIME_TOL = 1e-6


def hprc_phones():
    lines = (hprc_dir() / f"{UTT}_phones.tsv").read_text().splitlines()[1:]
    return [(float(s), float(e), label) for s, e, label in (line.split("\t") for line in lines)]


def write_mocha(tmp_path, *, name="fsew0_001", rate_hz=None, labels=True, **options):
    """A MOCHA utterance from the HPRC one (times as written, or regular at ``rate_hz``)."""
    t_s, positions = hprc_columns(UTT)
    if rate_hz is not None:
        t_s = np.arange(len(t_s)) / rate_hz
    channels, values = mocha_channels(positions)
    path = tmp_path / f"{name}.ema"
    path.write_bytes(est_bytes(t_s, channels, values, **options))
    if labels:
        (tmp_path / f"{name}.lab").write_bytes(xlabel_bytes(hprc_phones()))
    return path, t_s, positions, channels, values


@pytest.mark.parametrize(("data_type", "byte_order"),
                         [("binary", "01"), ("binary", "10"), ("ascii", "01")])
def test_a_mocha_file_reads_back_to_the_hprc_positions_in_the_frame(tmp_path, data_type,
                                                                    byte_order):
    path, t_s, positions, _, _ = write_mocha(tmp_path, data_type=data_type,
                                             byte_order=byte_order)
    recording = read_ema(path)
    assert recording.source_format == "mocha"
    assert recording.name == "fsew0_001"
    assert recording.sample_rate_hz == 100.0
    np.testing.assert_allclose(recording.t_s, t_s, atol=TIME_TOL, rtol=0)
    pairs = {"tongue_tip": "TT", "tongue_blade": "TB", "tongue_dorsum": "TR",
             "upper_lip": "UL", "lower_lip": "LL", "lower_incisor": "JAW"}
    for sensor, code in pairs.items():
        got, want = recording.sensors[sensor], positions[code]
        np.testing.assert_allclose(got[:, 0], want[:, 0], atol=MM_TOL, rtol=0)  # anterior
        np.testing.assert_array_equal(got[:, 1], 0.0)  # 2D: no lateral coordinate
        np.testing.assert_allclose(got[:, 2], want[:, 2], atol=MM_TOL, rtol=0)  # up
    np.testing.assert_array_equal(recording.sensors["upper_incisor"], 0.0)
    assert recording.dropouts == ()


def test_the_lab_file_beside_it_gives_the_phones_with_stress_apart(tmp_path):
    path, *_ = write_mocha(tmp_path)
    phones = read_ema(path).phones
    want = hprc_phones()
    assert len(phones) == len(want)
    for phone, (start, end, label) in zip(phones, want, strict=True):
        assert phone.start_s == pytest.approx(start, abs=1e-6)
        assert phone.end_s == pytest.approx(end, abs=1e-6)
        assert phone.symbol == ("sil" if label == "sp" else label.rstrip("012"))
    assert phones[2].stress == 0 and phones[1].stress is None


def test_mocha_at_500_hz_takes_its_rate_from_the_frame_times(tmp_path):
    path, *_ = write_mocha(tmp_path, rate_hz=500.0, labels=False)
    recording = read_mocha(path)
    assert recording.sample_rate_hz == 500.0
    assert recording.phones == ()


def test_units_and_axes_can_be_overridden(tmp_path):
    path, _, positions, _, _ = write_mocha(tmp_path, labels=False)
    recording = read_mocha(path, units_mm=0.1, axes="+x 0 -y")
    np.testing.assert_allclose(recording.sensors["tongue_tip"][:, 0],
                               -positions["TT"][:, 0] * 10.0, atol=1e-3, rtol=0)
    np.testing.assert_allclose(recording.sensors["tongue_tip"][:, 2],
                               -positions["TT"][:, 2] * 10.0, atol=1e-3, rtol=0)


def test_break_frames_of_40_ms_are_interpolated_and_reported(tmp_path):
    t_s, positions = hprc_columns(UTT)
    channels, values = mocha_channels(positions)
    breaks = np.ones(len(t_s))
    breaks[100:104] = 0.0  # 4 frames at 100 Hz
    values = values.copy()
    values[100:104] = 9999.0  # what a break frame holds is not a value
    path = tmp_path / "gap.ema"
    path.write_bytes(est_bytes(t_s, channels, values, breaks=breaks))
    recording = read_ema(path)
    assert {d.sensor for d in recording.dropouts} == set(recording.sensors)
    for dropout in recording.dropouts:
        assert dropout.frames == 4
        assert dropout.start_s == pytest.approx(1.0, abs=TIME_TOL)
        assert dropout.end_s == pytest.approx(1.04, abs=TIME_TOL)
    tip = recording.sensors["tongue_tip"]
    w = np.arange(1, 5) / 5.0
    want = (1 - w)[:, None] * tip[99] + w[:, None] * tip[104]
    np.testing.assert_allclose(tip[100:104], want, atol=1e-9)


def test_break_frames_of_80_ms_are_refused_naming_sensor_and_span(tmp_path):
    t_s, positions = hprc_columns(UTT)
    channels, values = mocha_channels(positions)
    breaks = np.ones(len(t_s))
    breaks[100:108] = 0.0
    path = tmp_path / "gap.ema"
    path.write_bytes(est_bytes(t_s, channels, values, breaks=breaks))
    with pytest.raises(EmaFormatError, match=r"gap\.ema: sensor upper_incisor: 8 samples missing "
                                             r"from 1\.000 s to 1\.080 s \(80 ms\), longer than "
                                             r"the 50 ms"):
        read_ema(path)


def est_error(content, match):
    with pytest.raises(EmaFormatError, match=match):
        parse_est_track(content, "utt.ema")


def small_track(**options):
    return est_bytes([0.0, 0.002, 0.004], ["tt_x", "tt_y"], [[1, 2], [3, 4], [5, 6]], **options)


def test_a_truncated_binary_file_is_refused():
    est_error(small_track()[:-6], r"^utt\.ema: truncated: NumFrames 3 of 16 bytes need 48 bytes "
                                  r"of data, the file holds 42 \(2 whole frames and 10 bytes\)")


def test_a_header_claiming_more_frames_than_there_are_is_refused():
    est_error(small_track(num_frames=5), r"utt\.ema: truncated: NumFrames 5 .* holds 48 \(3 whole")


def test_a_header_claiming_fewer_frames_than_there_are_is_refused():
    est_error(small_track(num_frames=2), r"utt\.ema: the header says NumFrames 2, but the data "
                                         r"hold 48 bytes: 3 frames of 16 bytes")


def test_an_ascii_file_with_a_frame_count_that_lies_is_refused():
    est_error(small_track(data_type="ascii", num_frames=4),
              r"utt\.ema: the header says NumFrames 4, but the data have 3 frame lines")


def test_an_ascii_frame_with_a_missing_value_names_its_line():
    content = small_track(data_type="ascii").replace(b"\t3 4 \n", b"\t3 \n")
    est_error(content, r"utt\.ema, line 13: frame 1: expected 4 numbers \(time, break flag and "
                       r"2 channels\), got 3")


def test_an_ascii_frame_with_a_word_for_a_number_names_its_line():
    content = small_track(data_type="ascii").replace(b"\t5 6 \n", b"\t5 x \n")
    est_error(content, r"utt\.ema, line 14: frame 2: 'x' is not a number")


def test_an_unknown_byte_order_names_its_line():
    est_error(small_track(byte_order="11"), r"utt\.ema, line 3: ByteOrder '11': binary data "
                                            r"needs 01 \(little-endian\) or 10 \(big-endian\)")


def test_a_file_that_is_not_an_est_track_is_refused():
    est_error(b"\x00\x01garbage", r"utt\.ema: not an EST file")
    est_error(small_track().replace(b"EST_File Track", b"EST_File fmatrix"),
              r"utt\.ema, line 1: an EST file of type 'fmatrix', not Track")
    est_error(small_track().replace(b"EST_Header_End", b"EST_Header_Eh!"),
              r"utt\.ema: no EST_Header_End line")


def test_a_channel_named_twice_or_beyond_the_count_is_refused():
    content = small_track(header_extra=["Channel_2 tb_x"])
    est_error(content, r"utt\.ema, line 10: Channel_2 is beyond NumChannels 2")
    content = small_track(header_extra=["Channel_1 tb_x"])
    est_error(content, r"utt\.ema, line 12: Channel_1 is named twice")


def test_times_that_do_not_increase_are_refused(tmp_path):
    path = tmp_path / "back.ema"
    path.write_bytes(est_bytes([0.0, 0.002, 0.002, 0.006], ["tt_x", "tt_y"], np.ones((4, 2))))
    with pytest.raises(EmaFormatError, match=r"back\.ema: frame 2: times do not increase "
                                             r"\(0\.002000 s, then 0\.002000 s\)"):
        read_mocha(path)


def test_times_that_go_back_in_an_ascii_file_name_the_line(tmp_path):
    path = tmp_path / "back.ema"
    path.write_bytes(est_bytes([0.0, 0.004, 0.002], ["tt_x", "tt_y"], np.ones((3, 2)),
                               data_type="ascii"))
    with pytest.raises(EmaFormatError, match=r"back\.ema, line 14: frame 2: times do not "
                                             r"increase"):
        read_mocha(path)


def test_a_sample_rate_of_zero_is_refused(tmp_path):
    path, *_ = write_mocha(tmp_path, labels=False)
    with pytest.raises(EmaFormatError, match=r"fsew0_001\.ema: sample rate 0 Hz is not a "
                                             r"positive number"):
        read_mocha(path, sample_rate_hz=0)
    with pytest.raises(EmaFormatError, match=r"sample rate -500\.0 Hz is not a positive"):
        read_mocha(path, sample_rate_hz=-500.0)


def test_a_coil_without_its_y_channel_is_refused(tmp_path):
    path = tmp_path / "half.ema"
    path.write_bytes(est_bytes([0.0, 0.002], ["tt_x", "tt_y", "td_x"], np.ones((2, 3))))
    with pytest.raises(EmaFormatError, match=r"half\.ema: sensor tongue_dorsum has no y channel"):
        read_mocha(path)


def test_a_missing_sensor_asked_for_is_named(tmp_path):
    path, *_ = write_mocha(tmp_path, labels=False)
    with pytest.raises(EmaFormatError, match=r"sensor\(s\) velum asked for but not in the file"):
        read_ema(path, sensors=["velum", "tongue_tip"])


def test_a_label_past_the_end_of_the_signal_names_the_lab_file_and_line(tmp_path):
    path, t_s, *_ = write_mocha(tmp_path, labels=False)
    phones = hprc_phones()
    phones[-1] = (phones[-1][0], float(t_s[-1]) + 0.5, "sp")
    (tmp_path / "fsew0_001.lab").write_bytes(xlabel_bytes(phones))
    line = 8 + len(phones)
    with pytest.raises(EmaFormatError,
                       match=re.escape(f"fsew0_001.lab, line {line}: label 'sp' ends at "
                                       f"{t_s[-1] + 0.5:.4f} s, past the end of the signal")):
        read_ema(path)


def test_a_label_within_one_frame_past_the_end_is_accepted(tmp_path):
    path, t_s, *_ = write_mocha(tmp_path, labels=False)
    phones = hprc_phones()
    phones[-1] = (phones[-1][0], float(t_s[-1]) + 0.009, "sp")
    (tmp_path / "fsew0_001.lab").write_bytes(xlabel_bytes(phones))
    assert read_ema(path).phones[-1].end_s == pytest.approx(t_s[-1] + 0.009)


def test_an_unknown_phone_in_a_lab_file_names_symbol_and_line(tmp_path):
    path, *_ = write_mocha(tmp_path, labels=False)
    phones = hprc_phones()
    phones[3] = (phones[3][0], phones[3][1], "@@")  # MOCHA's own symbol, not ARPAbet
    (tmp_path / "fsew0_001.lab").write_bytes(xlabel_bytes(phones))
    with pytest.raises(EmaFormatError, match=r"fsew0_001\.lab, line 12: unknown phone symbol "
                                             r"'@@': not one of the 39 ARPAbet phones"):
        read_ema(path)
