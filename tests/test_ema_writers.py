"""Writers of the EMA file layouts that docs/ema.md documents, written from the documentation and
not from the readers (so that a reader's mistake is not mirrored), and the real HPRC utterances
they are fed with. The other EMA tests import these; the tests here check the writers' bytes
against the published examples the layouts were taken from."""

import struct
from pathlib import Path

import numpy as np
import pytest

from glasshead.settings import get_settings

UTTERANCES = ("F01_B01_S01_R01_N", "M01_B01_S01_R01_N", "M04_B02_S44_R01_N",
              "F01_B01_S01_R01_F")


def hprc_dir() -> Path:
    """../shared/data/ema/hprc; a missing directory fails the test with the path expected."""
    path = get_settings().data_dir / "ema" / "hprc"
    if not (path / f"{UTTERANCES[0]}_ema.csv").is_file():
        pytest.fail(f"reference data missing: expected HPRC EMA in {path} "
                    "(set GLASSHEAD_DATA_DIR)")
    return path


def hprc_csv(utt: str) -> Path:
    return hprc_dir() / f"{utt}_ema.csv"


def hprc_columns(utt: str) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Times and sensor code -> (n, 3) x, y, z straight from the CSV, by the standard library's
    own reading of it."""
    lines = hprc_csv(utt).read_text().splitlines()
    header = lines[0].split(",")
    table = np.array([[float(c) for c in line.split(",")] for line in lines[1:] if line])
    codes = [h[:-2] for h in header[1:] if h.endswith("_x")]
    return table[:, 0], {c: table[:, [header.index(f"{c}_{a}") for a in "xyz"]] for c in codes}


def est_bytes(t_s, channels, values, *, byte_order="01", data_type="binary", breaks=None,
              num_frames=None, header_extra=()) -> bytes:
    """An EST_File Track as Edinburgh Speech Tools' save_est_binary_ts writes it (ASCII: the
    same header and one frame per line). ``breaks``: per-frame flags (1 = value, 0 = break),
    all 1 by default; ``num_frames`` overrides the true count (a lying header)."""
    n = len(t_s)
    flags = np.ones(n) if breaks is None else np.asarray(breaks, dtype=float)
    lines = ["EST_File Track", f"DataType {data_type}"]
    if data_type == "binary":
        lines.append(f"ByteOrder {byte_order}")
    lines += [f"NumFrames {n if num_frames is None else num_frames}",
              f"NumChannels {len(channels)}", "EqualSpace 1", "BreaksPresent true",
              "CommentChar ;", "", *header_extra]
    lines += [f"Channel_{i} {name}" for i, name in enumerate(channels)]
    head = ("\n".join(lines) + "\nEST_Header_End\n").encode()
    if data_type == "ascii":
        rows = [f"{t:f}\t{int(b)} \t" + " ".join(f"{v:.9g}" for v in row) + " \n"
                for t, b, row in zip(t_s, flags, values, strict=True)]
        return head + "".join(rows).encode()
    endian = "<" if byte_order == "01" else ">"
    body = b"".join(struct.pack(f"{endian}{2 + len(channels)}f", t, b, *row)
                    for t, b, row in zip(t_s, flags, values, strict=True))
    return head + body


def mocha_channels(positions: dict[str, np.ndarray]) -> tuple[list[str], np.ndarray]:
    """HPRC positions (mm; x anterior, z up) as MOCHA channels: 1/100 mm, x growing toward the
    back, y up. HPRC's origin is the upper incisor, so MOCHA's ui coil sits at 0."""
    coils = {"ui": np.zeros_like(positions["TT"]), "li": positions["JAW"],
             "ul": positions["UL"], "ll": positions["LL"], "tt": positions["TT"],
             "tb": positions["TB"], "td": positions["TR"]}
    names, columns = [], []
    for coil, xyz in coils.items():
        names += [f"{coil}_x", f"{coil}_y"]
        columns += [-xyz[:, 0] * 100.0, xyz[:, 2] * 100.0]
    return names, np.stack(columns, axis=1)


def xlabel_bytes(labels) -> bytes:
    """An ESPS xlabel file: a header ending in '#', then '<end> <colour> <label>' lines."""
    head = "signal utterance\ntype 0\ncolor 121\ncomment written for a test\nfont -misc-*\n" \
           "separator ;\nnfields 1\n#\n"
    return (head + "".join(f"    {end:.6f}  121 {label}\n" for _, end, label in labels)).encode()


def tsv_bytes(labels) -> bytes:
    return ("start_s\tend_s\tlabel\n"
            + "".join(f"{s:.4f}\t{e:.4f}\t{label}\n" for s, e, label in labels)).encode()


def pos_samples(positions: list[np.ndarray], n_channels: int) -> np.ndarray:
    """(n, n_channels, 7) float32 samples: x, y, z, phi, theta, rms, extra, with the given
    positions in the first channels and a fixed, recognisable fill elsewhere."""
    n = len(positions[0])
    samples = np.full((n, n_channels, 7), 7.5, dtype=np.float32)
    samples[:, :, 3:5] = (12.0, -34.0)  # angles (degrees)
    samples[:, :, 5] = 3.0  # rms
    for channel, xyz in enumerate(positions):
        samples[:, channel, :3] = xyz
    return samples


def ag501_header(n_channels: int, rate_hz: int, *, length: int | None = None) -> bytes:
    """AG501's header: magic, the header's length (8 decimal digits), key=value lines, then
    NUL and SUB up to the stated length."""
    lines = f"NumberOfChannels={n_channels}\nSamplingFrequencyHz={rate_hz}\n"
    size = len("AG50xDATA_V002\n00000000\n") + len(lines) + 2
    stated = size if length is None else length
    return f"AG50xDATA_V002\n{stated:08d}\n{lines}".encode() + b"\x00\x1a"


def ag501_bytes(samples: np.ndarray, rate_hz: int) -> bytes:
    return ag501_header(samples.shape[1], rate_hz) + samples.astype("<f4").tobytes()


def ag500_bytes(samples: np.ndarray) -> bytes:
    assert samples.shape[1] == 12
    return samples.astype("<f4").tobytes()


def test_the_ag501_header_is_the_published_example_byte_for_byte():
    # m2ci-msp/artk, AG501PosFileHeaderTest: a 16-channel, 250 Hz header.
    assert ag501_header(16, 250) == (b"AG50xDATA_V002\n00000070\nNumberOfChannels=16\n"
                                     b"SamplingFrequencyHz=250\n\x00\x1a")


def test_the_est_header_has_the_lines_speech_tools_writes():
    head = est_bytes([0.0], ["ui_x"], [[1.0]], byte_order="10").split(b"EST_Header_End\n")[0]
    assert head.decode().splitlines() == [
        "EST_File Track", "DataType binary", "ByteOrder 10", "NumFrames 1", "NumChannels 1",
        "EqualSpace 1", "BreaksPresent true", "CommentChar ;", "", "Channel_0 ui_x"]


def test_a_binary_est_frame_is_time_break_and_channels_as_float32():
    data = est_bytes([0.5], ["a", "b"], [[1.0, 2.0]], byte_order="10")
    assert data.split(b"EST_Header_End\n")[1] == struct.pack(">4f", 0.5, 1.0, 1.0, 2.0)


def test_the_hprc_columns_are_read_for_every_utterance():
    for utt in UTTERANCES:
        t_s, columns = hprc_columns(utt)
        assert len(t_s) > 200 and {"TT", "TB", "TR", "UL", "LL", "JAW"} <= set(columns)
