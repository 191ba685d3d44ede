"""An uploaded EMA recording beside the head: read from its files' bytes, the head driven by its
phones (``ema_comparison.drive``), scored (``ema_comparison.compare_one``) and laid out for the
clinician view to play.

The scores are those of ``glasshead compare-ema`` for a speaker with one recording: the sensors
are registered onto the head's points by an affine map fitted on one half of the speech and
scored on the other (two folds in time). For drawing, the sensors of every frame are mapped by
one affine map fitted on all of the speech (``display_registration`` in the answer says so), then
put in the project frame (+x anterior, +y up, +z left, mm) on the head's upper incisor, as the
head's own flesh points are. The tracks sent for playing are thinned to at most
``PLAY_RATE_HZ`` frames a second; the scores use every sample.
"""

import math
from collections.abc import Mapping

import numpy as np

from glasshead.ema import EmaRecording, parse_carstens, parse_hprc, parse_mocha, project_axes
from glasshead.ema.labels import PAUSE
from glasshead.ema.reading import FORMATS, detect_format
from glasshead.ema.recording import EmaFormatError
from glasshead.geometry.flesh_points import FleshPointRig
from glasshead.phonemes import lookup
from glasshead.speech import ema_comparison as cmp

#: Frames a second of the tracks sent for playing (a screen shows no more).
PLAY_RATE_HZ = 100.0
#: Longest recording the head says (its tracks are made at the recording's rate).
MAX_SECONDS = 60.0
MAX_FRAMES = 30_000


def read_upload(content: bytes, filename: str, labels: bytes | None, *,
                labels_name: str = "labels", format: str | None = None,
                channels: Mapping[str, int] | None = None) -> EmaRecording:
    """The recording in an upload: the sensor file's bytes and name, the phone labels' bytes
    (HPRC's ``_phones.tsv``, MOCHA's ``.lab``, or a label file for a Carstens file) and their
    file's name, the format
    (default: told from the name, else the first bytes) and, for Carstens, the channels.
    Raises ``EmaFormatError`` naming the file and line."""
    if format is None:
        format = detect_format(filename, content[:64])
    if format not in FORMATS:
        raise EmaFormatError(f"unknown format {format!r}; use one of {', '.join(FORMATS)}",
                             source=filename)
    if labels is None:
        raise EmaFormatError("the recording has no phone labels: send them as labels (HPRC's "
                             "_phones.tsv, MOCHA's .lab)", source=filename)
    stem = filename.rsplit("/", 1)[-1].removesuffix("_ema.csv").rsplit(".", 1)[0] or "upload"
    if format == "hprc":
        return parse_hprc(content, phones=labels, name=stem, source=filename,
                          phones_source=labels_name)
    if format == "mocha":
        if channels is not None:
            raise EmaFormatError("channels is for Carstens files; MOCHA files name their "
                                 "sensors", source=filename)
        return parse_mocha(content, labels, name=stem, source=filename, labels_source=labels_name)
    if channels is None:
        raise EmaFormatError("Carstens files do not name their channels: give channels, e.g. "
                             "{\"TT\": 3, \"UL\": 5} (numbers from 1)", source=filename)
    return parse_carstens(content, labels, channels=channels, name=stem, source=filename,
                          labels_source=labels_name)


def check_length(recording: EmaRecording) -> None:
    """EmaFormatError when the head would have to say more than it says at once."""
    span = float(recording.t_s[-1] - recording.t_s[0]) if recording.n_frames else 0.0
    if span > MAX_SECONDS or recording.n_frames > MAX_FRAMES:
        raise EmaFormatError(f"the recording has {recording.n_frames} frames over {span:.1f} s; "
                             f"the head plays at most {MAX_SECONDS:g} s and {MAX_FRAMES} frames",
                             source=recording.name)


def _rounded(values: np.ndarray, digits: int = 3) -> list:
    """Lists of floats rounded for JSON, NaN as None."""
    rounded = np.round(np.asarray(values, dtype=np.float64), digits).tolist()

    def clean(value):
        if isinstance(value, list):
            return [clean(v) for v in value]
        return None if value is None or not math.isfinite(value) else value

    return clean(rounded)


def _finite(value):
    return value if isinstance(value, (int, float)) and math.isfinite(value) else None


def _clean_report(report):
    """The comparison's report with NaN as None (JSON has no NaN)."""
    if isinstance(report, dict):
        return {k: _clean_report(v) for k, v in report.items()}
    if isinstance(report, list):
        return [_clean_report(v) for v in report]
    if isinstance(report, float):
        return _finite(report)
    return report


def playback(recording: EmaRecording, targets: dict, rig: FleshPointRig,
             constants: dict | None = None) -> dict:
    """The document the clinician view plays (see the module docstring): the recording's
    source and phones, the frame times, the measured sensors and the head's flesh points in the
    project frame, the head's parameter tracks, and the comparison's scores. Raises
    ``ema_comparison.ComparisonError`` for a recording that cannot be compared."""
    check_length(recording)
    driven = cmp.drive(recording, targets, rig, constants)
    report = cmp.compare_one([driven], 0)
    speech = driven.speech
    display = cmp.fit_registration([({n: v[speech] for n, v in driven.measured.items()},
                                     {n: v[speech] for n, v in driven.head.items()})])
    incisor = rig.incisors["upper_incisor"]
    step = max(1, int(round(recording.sample_rate_hz / PLAY_RATE_HZ)))
    shown = np.arange(0, recording.n_frames, step)
    measured = {name: project_axes(display.apply(name, driven.measured[name][shown])) + incisor
                for name in cmp.COMPARED}
    head = {name: project_axes(driven.head[name][shown]) + incisor for name in cmp.COMPARED}
    residual = np.concatenate([np.linalg.norm(measured[n][speech[shown]] - head[n][speech[shown]],
                                              axis=1) for n in cmp.COMPARED])
    phones = []
    for phone in recording.phones:
        ipa = None if phone.symbol == PAUSE else lookup(phone.symbol).ipa
        phones.append({"symbol": phone.symbol, "ipa": ipa, "start_s": round(phone.start_s, 4),
                       "end_s": round(phone.end_s, 4)})
    return {
        "name": recording.name,
        "source": {"format": recording.source_format, "speaker": driven.speaker,
                   "sample_rate_hz": recording.sample_rate_hz, "frames": recording.n_frames,
                   "sensors": sorted(recording.sensors),
                   "dropouts": [{"sensor": d.sensor, "start_s": d.start_s, "end_s": d.end_s}
                                for d in recording.dropouts]},
        "phones": phones,
        "t_s": _rounded(recording.t_s[shown] - recording.t_s[0], 4),
        "speech": speech[shown].tolist(),
        "sensors": list(cmp.COMPARED),
        "measured": {name: _rounded(values) for name, values in measured.items()},
        "head": {name: _rounded(values) for name, values in head.items()},
        "params": {name: _rounded(track[shown], 4) for name, track in driven.tracks.items()},
        "display_registration": {
            "fitted_on": "all of the speech", "rms_mm": round(float(np.sqrt(np.mean(
                residual**2))), 3) if residual.size else None},
        "scores": _clean_report({"registration": report["registration"],
                                 "frames": report["frames"], "sensors": report["sensors"],
                                 "signals": report["signals"]}),
    }
