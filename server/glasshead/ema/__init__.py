"""Electromagnetic articulography (EMA): real sensor tracks with their phone labels.

``recording`` holds the checked recording in memory (one frame: mm, x anterior, y the speaker's
left, z up) and ``EmaFormatError``; ``labels`` reads phone and word label files and checks
ARPAbet; ``hprc``, ``mocha`` (with ``est``, the Edinburgh Speech Tools track file) and
``carstens`` read the formats; ``reading.read_ema`` picks the reader. docs/ema.md describes the
formats, the frame and the assumptions.
"""

from glasshead.ema.carstens import parse_carstens, read_carstens
from glasshead.ema.est import EstTrack, parse_est_track
from glasshead.ema.hprc import HPRC_SENSORS, parse_hprc, read_hprc
from glasshead.ema.labels import PAUSE, parse_label_file
from glasshead.ema.mocha import MOCHA_SENSORS, parse_mocha, read_mocha
from glasshead.ema.reading import FORMATS, detect_format, parse_ema, read_ema
from glasshead.ema.recording import (
    MAX_GAP_S,
    SENSOR_NAMES,
    Dropout,
    EmaFormatError,
    EmaRecording,
    Phone,
    Word,
    project_axes,
)

__all__ = [
    "FORMATS", "HPRC_SENSORS", "MAX_GAP_S", "MOCHA_SENSORS", "PAUSE", "SENSOR_NAMES", "Dropout",
    "EmaFormatError", "EmaRecording", "EstTrack", "Phone", "Word", "detect_format",
    "parse_carstens", "parse_ema", "parse_est_track", "parse_hprc", "parse_label_file",
    "parse_mocha", "project_axes", "read_carstens", "read_ema", "read_hprc", "read_mocha",
]
