"""Carstens AG500 and AG501 .pos files written from real HPRC data, read back, and every way one
can be wrong."""

import numpy as np
import pytest

from glasshead.ema import EmaFormatError, parse_carstens, read_carstens, read_ema
from test_ema_writers import (
    ag500_bytes,
    ag501_bytes,
    ag501_header,
    hprc_columns,
    hprc_dir,
    pos_samples,
    tsv_bytes,
)

UTT = "F01_B01_S01_R01_N"
#: float32 of positions up to about 60 mm: within 4e-6 mm.
MM_TOL = 1e-5
#: Channels (from 1) the HPRC sensors are written to.
CHANNELS = {"TR": 2, "TB": 3, "TT": 4, "UL": 6, "LL": 7, "JAW": 9, "ML": 10, "JAWL": 11}


def samples(n_channels):
    _, positions = hprc_columns(UTT)
    placed = [np.zeros_like(positions["TT"])] * n_channels
    for code, channel in CHANNELS.items():
        placed[channel - 1] = positions[code]
    return pos_samples(placed, n_channels), positions


def phones_tsv():
    return (hprc_dir() / f"{UTT}_phones.tsv").read_bytes()


def check_positions(recording, positions):
    names = {"TR": "tongue_dorsum", "TB": "tongue_blade", "TT": "tongue_tip", "UL": "upper_lip",
             "LL": "lower_lip", "JAW": "lower_incisor", "ML": "mouth_left", "JAWL": "jaw_left"}
    assert set(recording.sensors) == set(names.values())
    for code, name in names.items():
        np.testing.assert_allclose(recording.sensors[name], positions[code], atol=MM_TOL, rtol=0)


def test_an_ag501_file_reads_back_to_the_hprc_positions(tmp_path):
    data, positions = samples(16)
    path = tmp_path / "0001.pos"
    path.write_bytes(ag501_bytes(data, 100))  # HPRC's rate, so that its phones fit
    labels = tmp_path / "0001.tsv"
    labels.write_bytes(phones_tsv())
    recording = read_ema(path, channels=CHANNELS, labels=labels)
    assert recording.source_format == "ag501"
    assert recording.sample_rate_hz == 100.0
    np.testing.assert_allclose(recording.t_s, np.arange(len(data)) / 100.0)
    check_positions(recording, positions)
    assert recording.phones[1].symbol == "DH" and recording.phones[2].stress == 0


def test_an_ag500_file_has_12_channels_at_200_hz(tmp_path):
    data, positions = samples(12)
    path = tmp_path / "0001.pos"
    path.write_bytes(ag500_bytes(data))
    recording = read_carstens(path, channels=CHANNELS)
    assert recording.source_format == "ag500"
    assert recording.sample_rate_hz == 200.0
    assert recording.n_frames == len(data)
    check_positions(recording, positions)
    assert recording.phones == ()


def test_articulatory_names_work_as_channel_keys_and_other_names_are_kept():
    data, positions = samples(16)
    recording = parse_carstens(ag501_bytes(data, 250), channels={"tongue_tip": 4, "REF": 1},
                               name="x")
    np.testing.assert_allclose(recording.sensors["tongue_tip"], positions["TT"], atol=MM_TOL)
    np.testing.assert_array_equal(recording.sensors["ref"], 0.0)


def test_axes_turn_device_coordinates_into_the_frame():
    data, positions = samples(16)
    recording = parse_carstens(ag501_bytes(data, 250), channels={"TT": 4}, name="x",
                               axes="-y +x +z")
    tip = recording.sensors["tongue_tip"]
    np.testing.assert_allclose(tip, np.stack([-positions["TT"][:, 1], positions["TT"][:, 0],
                                              positions["TT"][:, 2]], axis=1), atol=MM_TOL)


def carstens_error(content, match, **options):
    options.setdefault("channels", {"TT": 4})
    with pytest.raises(EmaFormatError, match=match):
        parse_carstens(content, name="0001", source="0001.pos", **options)


def test_a_truncated_ag501_file_is_refused():
    data, _ = samples(16)
    carstens_error(ag501_bytes(data, 250)[:-10],
                   r"^0001\.pos: truncated: \d+ bytes of data are 261 samples of 16 channels x 7 "
                   r"float32 \(448 bytes\) and 438 bytes more")


def test_a_truncated_ag500_file_is_refused():
    data, _ = samples(12)
    carstens_error(ag500_bytes(data)[:-4], r"0001\.pos: truncated: .* 12 channels")


def test_a_sample_rate_of_zero_in_the_header_names_its_line():
    data, _ = samples(16)
    content = ag501_bytes(data, 250).replace(b"SamplingFrequencyHz=250", b"SamplingFrequencyHz=0")
    content = content.replace(b"00000070", b"00000068")
    carstens_error(content, r"0001\.pos, line 4: sample rate SamplingFrequencyHz=0 is not "
                            r"positive")


def test_a_negative_sample_rate_given_by_the_caller_is_refused():
    data, _ = samples(12)
    carstens_error(ag500_bytes(data), r"0001\.pos: sample rate -200\.0 Hz is not a positive",
                   sample_rate_hz=-200.0)


def test_a_header_length_beyond_the_file_is_refused():
    data, _ = samples(16)
    content = ag501_header(16, 250, length=99999999) + data[:1].astype("<f4").tobytes()
    carstens_error(content, r"0001\.pos, line 2: header length 99999999 bytes is impossible")


def test_an_unknown_header_version_is_refused():
    data, _ = samples(16)
    carstens_error(ag501_bytes(data, 250).replace(b"V002", b"V009"),
                   r"0001\.pos, line 1: unknown Carstens header b'AG50xDATA_V009'")


def test_channels_are_required_and_checked():
    data, _ = samples(16)
    content = ag501_bytes(data, 250)
    carstens_error(content, r"0001\.pos: Carstens files do not name their channels", channels={})
    carstens_error(content, r"channel 17 for TT is not a channel number from 1 to 16",
                   channels={"TT": 17})
    carstens_error(content, r"channel 0 for TT is not a channel number from 1 to 16",
                   channels={"TT": 0})
    carstens_error(content, r"channel 4 is given to two sensors", channels={"TT": 4, "TB": 4})
    carstens_error(content, r"JAW names sensor lower_incisor a second time",
                   channels={"LI": 3, "JAW": 4})


def test_read_ema_asks_for_channels_for_a_pos_file(tmp_path):
    data, _ = samples(12)
    path = tmp_path / "0001.pos"
    path.write_bytes(ag500_bytes(data))
    with pytest.raises(EmaFormatError, match=r"0001\.pos: Carstens files do not name"):
        read_ema(path)


def test_a_missing_sensor_asked_for_is_named():
    data, _ = samples(16)
    carstens_error(ag501_bytes(data, 250), r"sensor\(s\) velum asked for but not in the file",
                   sensors=["velum"])


def test_nan_samples_of_40_ms_are_interpolated_and_80_ms_refused():
    data, positions = samples(16)
    gap = data.copy()
    gap[50:60, 3, :3] = np.nan  # 10 samples at 250 Hz = 40 ms on the tongue tip
    recording = parse_carstens(ag501_bytes(gap, 250), channels={"TT": 4, "UL": 6}, name="x")
    assert recording.dropouts == (("tongue_tip", 0.2, 0.24, 10),)
    tip = recording.sensors["tongue_tip"]
    assert np.isfinite(tip).all()
    assert np.all(np.abs(np.diff(tip[48:62], axis=0)) < 5.0)
    gap[50:70, 3, :3] = np.nan  # 80 ms
    carstens_error(ag501_bytes(gap, 250), r"0001\.pos: sensor tongue_tip: 20 samples missing "
                                          r"from 0\.200 s to 0\.280 s \(80 ms\)")


def test_labels_past_the_end_of_a_pos_file_are_refused():
    data, _ = samples(16)
    short = data[:40]  # 0.4 s at 100 Hz; the phones run to 2.6 s
    with pytest.raises(EmaFormatError, match=r"0001\.tsv, line 6: label 'ER1' ends at 0\.4893 s, "
                                             r"past the end of the signal \(0\.3900 s"):
        parse_carstens(ag501_bytes(short, 100), phones_tsv(), channels={"TT": 4}, name="0001",
                       labels_source="0001.tsv")


def test_phone_labels_may_be_given_as_tsv_bytes():
    data, _ = samples(16)
    rows = [(0.0, 0.5, "sil"), (0.5, 1.0, "AA1")]
    recording = parse_carstens(ag501_bytes(data, 250), tsv_bytes(rows), channels={"TT": 4},
                               name="x")
    assert [tuple(p) for p in recording.phones] == [(0.0, 0.5, "sil", None),
                                                    (0.5, 1.0, "AA", 1)]
