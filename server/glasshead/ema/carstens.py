"""Carstens AG500 and AG501 position files (``.pos``).

Both hold float32 little-endian samples: per sample, per channel, 7 values
x, y, z (mm), phi, theta (degrees), rms, extra (``VALUES_PER_CHANNEL``); only x, y, z are read.

AG501 files start with an ASCII header::

    AG50xDATA_V002
    00000070                   the header's length in bytes, decimal: the data start there
    NumberOfChannels=16
    SamplingFrequencyHz=250
    \\0\\x1a                     padding up to the header length

AG500 files have no header: 12 channels at 200 Hz.

Sources (docs/ema.md): m2ci-msp/artk ``AG501PosFileHeader`` and its test (a 68-byte header of
four lines, plus 2 bytes, says ``00000070``), ``AG500PosFile`` (little-endian float32, 7 fields,
12 channels, 200 Hz); rticulate ``read_ag500_pos`` (the same 12 x 7 float32 layout and 200 Hz).

The files name no channels: the caller maps names to channel numbers, counted from 1 as
Carstens' software counts them, e.g. ``{"TT": 3, "UL": 5}``. Codes in ``SENSOR_CODES`` become
their sensor names; other names are kept in lower case. Positions are in the file's axes unless
``axes`` says otherwise (``orient``); sample i is at i / rate seconds.
"""

import math
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from glasshead.ema.labels import finite_number, read_phones
from glasshead.ema.recording import (
    MAX_GAP_S,
    SENSOR_CODES,
    EmaFormatError,
    EmaRecording,
    Phone,
    build_recording,
    orient,
)

AG501_MAGIC = b"AG50xDATA_V"
AG501_VERSION = b"AG50xDATA_V002"
AG500_CHANNELS = 12
AG500_RATE_HZ = 200.0
#: x, y, z, phi, theta, rms, extra.
VALUES_PER_CHANNEL = 7
#: Bytes of one channel's values in one sample.
CHANNEL_BYTES = VALUES_PER_CHANNEL * 4


def read_carstens(path: str | Path, *, channels: Mapping[str, int],
                  labels: str | Path | None = None, axes: str = "+x +y +z",
                  sample_rate_hz: float | None = None, sensors: list[str] | None = None,
                  max_gap_s: float = MAX_GAP_S) -> EmaRecording:
    """Read an AG500 or AG501 ``.pos`` file (told apart by the AG501 header) and, when given, a
    phone label file (``labels``: TSV, xlabel or plain; see ``glasshead.ema.labels``)."""
    path = Path(path)
    lab = Path(labels).read_bytes() if labels is not None else None
    return parse_carstens(path.read_bytes(), lab, channels=channels, name=path.stem,
                          source=str(path),
                          labels_source=str(labels) if labels is not None else None,
                          axes=axes, sample_rate_hz=sample_rate_hz, sensors=sensors,
                          max_gap_s=max_gap_s)


def parse_carstens(content: bytes, labels: bytes | None = None, *, channels: Mapping[str, int],
                   name: str, source: str | None = None, labels_source: str | None = None,
                   axes: str = "+x +y +z", sample_rate_hz: float | None = None,
                   sensors: list[str] | None = None,
                   max_gap_s: float = MAX_GAP_S) -> EmaRecording:
    """A recording from the bytes of a ``.pos`` file (and of a label file).

    ``channels``: name -> channel number from 1. ``sample_rate_hz`` overrides the AG501 header's
    rate or AG500's 200 Hz. ``sensors``: names that must be present.
    """
    source = source or name
    labels_source = labels_source or f"{name} labels"
    if content.startswith(AG501_MAGIC):
        fmt = "ag501"
        n_channels, rate, data_at = parse_ag501_header(content, source)
    else:
        fmt = "ag500"
        n_channels, rate, data_at = AG500_CHANNELS, AG500_RATE_HZ, 0
    if sample_rate_hz is not None:
        rate = sample_rate_hz
    if not (math.isfinite(rate) and rate > 0):
        raise EmaFormatError(f"sample rate {rate} Hz is not a positive number", source=source)
    body = content[data_at:]
    sample_bytes = n_channels * CHANNEL_BYTES
    whole, part = divmod(len(body), sample_bytes)
    if part:
        raise EmaFormatError(
            f"truncated: {len(body)} bytes of data are {whole} samples of {n_channels} channels "
            f"x {VALUES_PER_CHANNEL} float32 ({sample_bytes} bytes) and {part} bytes more",
            source=source)
    if whole == 0:
        raise EmaFormatError("no samples", source=source)
    table = np.frombuffer(body, dtype="<f4").reshape(whole, n_channels, VALUES_PER_CHANNEL)
    positions = {}
    for sensor, number in _channel_map(channels, n_channels, source).items():
        positions[sensor] = orient(table[:, number - 1, :3].astype(np.float64), axes,
                                   source=source)
    phones: tuple[Phone, ...] = ()
    phone_lines = None
    if labels is not None:
        phones, phone_lines = read_phones(labels, labels_source)
    return build_recording(name=name, source=source, source_format=fmt,
                           t_s=np.arange(whole) / rate, sensors=positions, sample_rate_hz=rate,
                           phones=phones, labels_source=labels_source, phone_lines=phone_lines,
                           required=sensors, max_gap_s=max_gap_s)


def parse_ag501_header(content: bytes, source: str) -> tuple[int, float, int]:
    """(channels, sample rate in Hz, offset of the data) of an AG501 file."""
    lines = content[:4096].split(b"\n")
    if lines[0].rstrip(b"\r") != AG501_VERSION:
        raise EmaFormatError(f"unknown Carstens header {lines[0][:20]!r}: this reader knows "
                             f"{AG501_VERSION.decode()}", source=source, line=1)
    if len(lines) < 2 or not lines[1].strip().isdigit():
        raise EmaFormatError("the second line must be the header's length in bytes, e.g. "
                             "00000070", source=source, line=2)
    length = int(lines[1])
    lines_end = len(lines[0]) + len(lines[1]) + 2
    if length < lines_end or length > len(content):
        raise EmaFormatError(f"header length {length} bytes is impossible for a file of "
                             f"{len(content)} bytes", source=source, line=2)
    fields: dict[str, tuple[str, int]] = {}
    for number, raw in enumerate(content[lines_end:length].split(b"\n"), start=3):
        text = raw.strip(b"\x00\x1a \r\t")
        if not text:
            continue
        key, sep, value = text.decode("latin-1").partition("=")
        if not sep:
            raise EmaFormatError(f"header line {text[:40]!r} is not key=value", source=source,
                                 line=number)
        fields[key.strip()] = (value.strip(), number)
    n_channels = _header_number(fields, "NumberOfChannels", source)
    if n_channels != int(n_channels) or n_channels < 1:
        raise EmaFormatError(f"NumberOfChannels {n_channels:g} is not a whole number of at "
                             "least 1", source=source, line=fields["NumberOfChannels"][1])
    rate = _header_number(fields, "SamplingFrequencyHz", source)
    if rate <= 0:
        raise EmaFormatError(f"sample rate SamplingFrequencyHz={rate:g} is not positive",
                             source=source, line=fields["SamplingFrequencyHz"][1])
    return int(n_channels), rate, length


def _header_number(fields: dict[str, tuple[str, int]], key: str, source: str) -> float:
    if key not in fields:
        raise EmaFormatError(f"the header has no {key}", source=source)
    text, line = fields[key]
    return finite_number(text, f"{key}=", source, line)


def _channel_map(channels: Mapping[str, int], n_channels: int, source: str) -> dict[str, int]:
    if not channels:
        raise EmaFormatError("Carstens files do not name their channels: give channels, "
                             "e.g. {'TT': 3, 'UL': 5} (numbers from 1)", source=source)
    named: dict[str, int] = {}
    for key, number in channels.items():
        sensor = SENSOR_CODES.get(key.upper(), key.lower())
        if isinstance(number, bool) or not isinstance(number, int) \
                or not 1 <= number <= n_channels:
            raise EmaFormatError(f"channel {number!r} for {key} is not a channel number from 1 "
                                 f"to {n_channels}", source=source)
        if sensor in named:
            raise EmaFormatError(f"{key} names sensor {sensor} a second time", source=source)
        if number in named.values():
            raise EmaFormatError(f"channel {number} is given to two sensors", source=source)
        named[sensor] = number
    return named
