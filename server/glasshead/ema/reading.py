"""One entry point for every EMA format: ``read_ema`` (files) and ``parse_ema`` (an upload's bytes)
tell the format from the file's name, else from its first bytes, and hand it to that format's
reader."""

from collections.abc import Mapping
from pathlib import Path

from glasshead.ema.carstens import AG501_MAGIC, parse_carstens, read_carstens
from glasshead.ema.est import EST_MAGIC
from glasshead.ema.hprc import parse_hprc, read_hprc
from glasshead.ema.mocha import parse_mocha, read_mocha
from glasshead.ema.recording import MAX_GAP_S, EmaFormatError, EmaRecording

FORMATS = ("hprc", "mocha", "ag500", "ag501")
#: The Carstens formats, whose files do not name their channels.
CARSTENS = ("ag500", "ag501")
#: Extension -> format (``.pos`` is AG501 when it has the AG501 header, else AG500).
EXTENSIONS = {".csv": "hprc", ".ema": "mocha", ".pos": "carstens"}


def detect_format(path: str | Path, head: bytes) -> str:
    """The format of a file from its name's extension, else from its first bytes (``head``)."""
    kind = EXTENSIONS.get(Path(path).suffix.lower())
    if kind == "carstens" or (kind is None and head.startswith(AG501_MAGIC)):
        return "ag501" if head.startswith(AG501_MAGIC) else "ag500"
    if kind is not None:
        return kind
    if head.startswith(EST_MAGIC):
        return "mocha"
    if head.lstrip(b"\xef\xbb\xbf").startswith(b"time_s"):
        return "hprc"
    raise EmaFormatError(f"cannot tell the format; give format= one of {', '.join(FORMATS)}",
                         source=str(path))


def read_ema(path: str | Path, *, labels: str | Path | None = None, format: str | None = None,
             channels: Mapping[str, int] | None = None, sensors: list[str] | None = None,
             max_gap_s: float = MAX_GAP_S) -> EmaRecording:
    """Read an EMA recording in any of ``FORMATS``.

    ``labels``: a phone label file (HPRC: instead of ``<utt>_phones.tsv``; MOCHA: instead of the
    ``.lab`` beside the file; Carstens: the only source of phones). ``format``: skip detection.
    ``channels``: Carstens only, sensor name -> channel number from 1. ``sensors``: names that
    must be present. ``max_gap_s``: longest run of missing samples to interpolate.
    """
    path = Path(path)
    if format is None:
        with path.open("rb") as file:
            format = detect_format(path, file.read(64))
    check_options(format, channels, str(path))
    if format in CARSTENS:
        recording = read_carstens(path, channels=dict(channels or {}), labels=labels,
                                  sensors=sensors, max_gap_s=max_gap_s)
        return _as_given(recording, format, str(path))
    if format == "hprc":
        return read_hprc(path, phones_path=labels, sensors=sensors, max_gap_s=max_gap_s)
    return read_mocha(path, labels, sensors=sensors, max_gap_s=max_gap_s)


def parse_ema(content: bytes, source: str, *, labels: bytes | None,
              labels_source: str = "labels", format: str | None = None,
              channels: Mapping[str, int] | None = None) -> EmaRecording:
    """``read_ema`` on the bytes of an upload: the sensor file's ``content`` and name
    (``source``, which also tells the format when ``format`` is None), and the phone labels'
    bytes and name. The recording is named after the file, without ``_ema.csv`` or its
    extension."""
    if format is None:
        format = detect_format(source, content[:64])
    check_options(format, channels, source)
    name = Path(source).name.removesuffix("_ema.csv").rsplit(".", 1)[0] or "upload"
    if format in CARSTENS:
        recording = parse_carstens(content, labels, channels=dict(channels or {}), name=name,
                                   source=source, labels_source=labels_source)
        return _as_given(recording, format, source)
    if format == "hprc":
        return parse_hprc(content, phones=labels, name=name, source=source,
                          phones_source=labels_source)
    return parse_mocha(content, labels, name=name, source=source, labels_source=labels_source)


def check_options(format: str, channels: Mapping[str, int] | None, source: str) -> None:
    """EmaFormatError for an unknown format, a Carstens file without ``channels`` or channels
    for a file that names its sensors."""
    if format not in FORMATS:
        raise EmaFormatError(f"unknown format {format!r}; use one of {', '.join(FORMATS)}",
                             source=source)
    if format in CARSTENS and channels is None:
        raise EmaFormatError("Carstens files do not name their channels: give channels, "
                             "e.g. {'TT': 3, 'UL': 5} (numbers from 1)", source=source)
    if format not in CARSTENS and channels is not None:
        raise EmaFormatError(f"channels is for Carstens files; {format} files name their sensors",
                             source=source)


def _as_given(recording: EmaRecording, format: str, source: str) -> EmaRecording:
    if recording.source_format != format:
        raise EmaFormatError(f"format {format} was given, but the file is "
                             f"{recording.source_format}", source=source)
    return recording
