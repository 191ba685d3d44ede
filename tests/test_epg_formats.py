"""EPG recording formats: emuR JSON, the documented CSV and SSFF, on the real emuR set."""

import json

import numpy as np
import pytest

from glasshead.epg import formats
from glasshead.epg.sequence import (
    EpgFormatError,
    frames_to_raw,
    make_sequence,
    raw_to_frames,
)
from glasshead.vectors.sources import emur_path


@pytest.fixture(scope="module")
def emur_bytes():
    return emur_path().read_bytes()


@pytest.fixture(scope="module")
def sequences(emur_bytes):
    return formats.parse(emur_bytes, "emur-json")


def one_frame_csv(values="0", t="0.0", extra=""):
    header = ",".join(["t_s", *formats.CSV_ELECTRODES])
    row = ",".join([t] + [values] * 62)
    return f"{formats.CSV_MAGIC}\n{extra}{header}\n{row}\n"


def test_the_emur_set_reads_as_32_recordings_of_1421_frames_at_200_hz(sequences):
    assert len(sequences) == 32
    assert sum(s.n_frames for s in sequences) == 1421
    # Rates are derived from frame times and rounded to 1e-6 Hz.
    assert all(s.frame_rate_hz == pytest.approx(200.0, abs=1e-6) for s in sequences)
    first = sequences[0]
    assert first.name == "sp1bescan s->k"
    assert first.meta == {"label": "s->k", "word": "bescan", "utterance": "sp1bescan",
                          "start_s": 155.962, "end_s": 156.225}
    np.testing.assert_allclose(first.t_s[:3], [155.965, 155.970, 155.975], rtol=0,
                               atol=1e-9)  # s, from the file's ms: within 1 ns


def test_raw_bytes_decode_to_the_same_contacts_as_the_row_strings(emur_bytes, sequences):
    # the file's raw bytes are emuR's own compressed layout; our packing must give them back
    segments = json.loads(emur_bytes)["segments"]
    raw = np.array([f["raw"] for s in segments for f in s["frames"]], dtype=np.uint8)
    frames = np.concatenate([s.frames for s in sequences])
    np.testing.assert_array_equal(frames_to_raw(frames), raw)
    np.testing.assert_array_equal(raw_to_frames(raw), frames)


@pytest.mark.parametrize("fmt", ["csv", "ssff"])
def test_every_real_segment_survives_a_round_trip(sequences, fmt):
    for seq in sequences:
        again = formats.parse(formats.serialise([seq], fmt), fmt)[0]
        np.testing.assert_array_equal(again.frames, seq.frames)
        np.testing.assert_allclose(again.t_s, seq.t_s, rtol=0, atol=1e-9)
        assert (again.name, again.meta) == (seq.name, seq.meta)
        assert again.frame_rate_hz == pytest.approx(seq.frame_rate_hz, abs=1e-6)


def test_the_emur_json_export_reproduces_the_reference_segments(emur_bytes, sequences):
    original = json.loads(emur_bytes)["segments"]
    exported = json.loads(formats.serialise(sequences, "emur-json"))["segments"]
    for a, b in zip(original, exported, strict=True):
        assert b["frames"] == a["frames"]
        assert (b["utt"], b["label"], b["word"], b["start_ms"], b["end_ms"]) == \
               (a["utt"], a["label"], a["word"], a["start_ms"], a["end_ms"])


def test_ssff_output_follows_the_emu_header_layout_with_8_bytes_per_frame(sequences):
    seq = sequences[0]
    content = formats.serialise([seq], "ssff")
    header, _, data = content.partition(b"-----------------\n")
    lines = header.decode().splitlines()
    assert lines[:5] == ["SSFF -- (c) SHLRC", "Machine IBM-PC", "Record_Freq 200.0",
                         "Start_Time 155.965", "Column epg BYTE 8"]
    assert len(data) == 8 * seq.n_frames
    assert data[:8] == bytes([195, 131, 131, 1, 1, 129, 1, 0])  # frame 0's raw in the JSON


def test_an_ssff_file_with_other_columns_yields_its_epg_column():
    frames = np.zeros((2, 8, 8), dtype=np.uint8)
    frames[1, 7, :] = 1
    header = (b"SSFF -- (c) SHLRC\nMachine IBM-PC\nRecord_Freq 100.0\nStart_Time 0.5\n"
              b"Column rms SHORT 1\nColumn epg BYTE 8\nOriginal_Freq DOUBLE 20000.0\n"
              b"-----------------\n")
    raw = frames_to_raw(frames)
    body = b"".join(b"\x01\x02" + raw[i].tobytes() for i in range(2))
    seq = formats.parse(header + body, "ssff")[0]
    np.testing.assert_array_equal(seq.frames, frames)
    np.testing.assert_allclose(seq.t_s, [0.5, 0.51], rtol=0, atol=1e-9)  # start + k / rate
    assert seq.frame_rate_hz == pytest.approx(100.0, abs=1e-6)


def test_the_csv_declared_frame_rate_and_name_are_kept():
    text = one_frame_csv(extra="# name: tip up\n# frame_rate_hz: 100\n")
    seq = formats.parse(text.encode(), "csv")[0]
    assert (seq.name, seq.frame_rate_hz, seq.n_frames) == ("tip up", 100.0, 1)


@pytest.mark.parametrize("content, fmt, frame, field", [
    # wrong number of electrodes
    (one_frame_csv().replace(",0\n", "\n", 1).encode(), "csv", 0, "electrodes"),
    (json.dumps({"frames": [{"t_ms": 0, "rows": ["0" * 8] * 7}]}).encode(), "emur-json", 0,
     "rows"),
    (json.dumps({"frames": [{"t_ms": 0, "rows": ["0" * 8] * 7 + ["0" * 9]}]}).encode(),
     "emur-json", 0, "rows[7]"),
    (json.dumps({"frames": [{"t_ms": 0, "raw": [0] * 7}]}).encode(), "emur-json", 0, "raw"),
    # values that are not 0 or 1
    (one_frame_csv("1").replace(",1\n", ",2\n").encode(), "csv", 0, "R8C8"),
    (json.dumps({"frames": [{"t_ms": 0, "rows": ["00000000"] * 7 + ["0000x000"]}]}).encode(),
     "emur-json", 0, "rows[7]"),
    (json.dumps({"frames": [{"t_ms": 0, "raw": [0, 0, 0, 256, 0, 0, 0, 0]}]}).encode(),
     "emur-json", 0, "raw[3]"),
    # a contact where R1 has no electrode
    (json.dumps({"frames": [{"t_ms": 0, "rows": ["10000000"] + ["0" * 8] * 7}]}).encode(),
     "emur-json", 0, "rows[0]"),
    # times that do not increase
    (json.dumps({"frames": [{"t_ms": 5, "rows": ["0" * 8] * 8},
                            {"t_ms": 10, "rows": ["0" * 8] * 8},
                            {"t_ms": 10, "rows": ["0" * 8] * 8}]}).encode(), "emur-json", 2,
     "t_s"),
    ((one_frame_csv(t="0.01") + one_frame_csv(t="0.005").split("\n")[2] + "\n").encode(), "csv",
     1, "t_s"),
])
def test_bad_input_names_the_frame_and_the_field(content, fmt, frame, field):
    with pytest.raises(EpgFormatError) as caught:
        formats.parse(content, fmt)
    assert (caught.value.frame, caught.value.field) == (frame, field)
    assert f"frame {frame}" in str(caught.value) and f"field {field}" in str(caught.value)


def test_a_bad_frame_in_a_later_segment_names_the_segment_too(emur_bytes):
    document = json.loads(emur_bytes)
    document["segments"][5]["frames"][3]["rows"][2] = "0120000"
    with pytest.raises(EpgFormatError, match=r"segment 5, frame 3, field rows\[2\]"):
        formats.parse(json.dumps(document).encode(), "emur-json")


def test_rows_and_raw_that_disagree_are_refused():
    frame = {"t_ms": 0, "rows": ["0" * 8] * 7 + ["11000011"], "raw": [0] * 8}
    with pytest.raises(EpgFormatError, match="frame 0, field raw: rows and raw describe"):
        formats.parse(json.dumps({"frames": [frame]}).encode(), "emur-json")


def test_a_csv_header_with_a_missing_electrode_is_refused_naming_the_line():
    text = one_frame_csv().replace("R5C5,", "", 1)
    with pytest.raises(EpgFormatError, match="field header: line 2: expected 63 columns"):
        formats.parse(text.encode(), "csv")


def test_an_ssff_file_cut_short_names_the_incomplete_frame():
    seq = make_sequence(np.zeros((3, 8, 8), dtype=np.uint8), [0.0, 0.01, 0.02], "x")
    content = formats.serialise([seq], "ssff")[:-3]
    with pytest.raises(EpgFormatError, match="frame 2, field data"):
        formats.parse(content, "ssff")


def test_an_ssff_file_whose_epg_column_is_not_8_bytes_is_refused():
    content = (b"SSFF -- (c) SHLRC\nMachine IBM-PC\nRecord_Freq 100.0\nStart_Time 0.0\n"
               b"Column epg BYTE 7\n-----------------\n" + bytes(14))
    with pytest.raises(EpgFormatError, match="field Column: expected one column 'epg BYTE 8'"):
        formats.parse(content, "ssff")


def test_unevenly_spaced_frames_cannot_be_written_as_ssff():
    seq = make_sequence(np.zeros((4, 8, 8), dtype=np.uint8), [0.0, 0.005, 0.010, 0.017], "x")
    assert seq.frame_rate_hz == pytest.approx(200.0, abs=1e-6)  # the median interval, to 1e-6 Hz
    with pytest.raises(EpgFormatError, match="frame 3, field t_s: frames are not evenly spaced"):
        formats.serialise([seq], "ssff")


def test_the_format_is_told_from_the_name_or_the_first_bytes(sequences):
    assert formats.detect_format(b"{}", "take.json") == "emur-json"
    assert formats.detect_format(formats.serialise(sequences[:1], "ssff")) == "ssff"
    assert formats.detect_format(one_frame_csv().encode()) == "csv"
    with pytest.raises(EpgFormatError, match="field format"):
        formats.detect_format(b"\x00\x01garbage")
