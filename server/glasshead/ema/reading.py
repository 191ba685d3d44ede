"""One entry point for every EMA format: ``read_ema`` tells the format from the file's name, else
from its first bytes, and hands it to that format's reader."""

from collections.abc import Mapping
from pathlib import Path

from glasshead.ema.carstens import AG501_MAGIC, read_carstens
from glasshead.ema.est import EST_MAGIC
from glasshead.ema.hprc import read_hprc
from glasshead.ema.mocha import read_mocha
from glasshead.ema.recording import MAX_GAP_S, EmaFormatError, EmaRecording

FORMATS = ("hprc", "mocha", "ag500", "ag501")
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
    if format not in FORMATS:
        raise EmaFormatError(f"unknown format {format!r}; use one of {', '.join(FORMATS)}",
                             source=str(path))
    if format in ("ag500", "ag501"):
        if channels is None:
            raise EmaFormatError("Carstens files do not name their channels: give channels, "
                                 "e.g. {'TT': 3, 'UL': 5} (numbers from 1)", source=str(path))
        recording = read_carstens(path, channels=channels, labels=labels, sensors=sensors,
                                  max_gap_s=max_gap_s)
        if recording.source_format != format:
            raise EmaFormatError(f"format {format} was given, but the file is "
                                 f"{recording.source_format}", source=str(path))
        return recording
    if channels is not None:
        raise EmaFormatError(f"channels is for Carstens files; {format} files name their sensors",
                             source=str(path))
    if format == "hprc":
        return read_hprc(path, phones_path=labels, sensors=sensors, max_gap_s=max_gap_s)
    return read_mocha(path, labels, sensors=sensors, max_gap_s=max_gap_s)
