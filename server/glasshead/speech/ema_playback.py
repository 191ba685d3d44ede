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

from glasshead.ema import EmaFormatError, EmaRecording, parse_ema, project_axes
from glasshead.ema.labels import PAUSE
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
    """The recording in an upload (``ema.parse_ema``), which must have its phone labels: the
    head says them. Raises ``EmaFormatError`` naming the file and line."""
    if labels is None:
        raise EmaFormatError("the recording has no phone labels: send them as labels (HPRC's "
                             "_phones.tsv, MOCHA's .lab)", source=filename)
    return parse_ema(content, filename, labels=labels, labels_source=labels_name, format=format,
                     channels=channels)


def check_length(recording: EmaRecording) -> None:
    """EmaFormatError when the head would have to say more than it says at once."""
    span = float(recording.t_s[-1] - recording.t_s[0]) if recording.n_frames else 0.0
    if span > MAX_SECONDS or recording.n_frames > MAX_FRAMES:
        raise EmaFormatError(f"the recording has {recording.n_frames} frames over {span:.1f} s; "
                             f"the head plays at most {MAX_SECONDS:g} s and {MAX_FRAMES} frames",
                             source=recording.name)


def _json_safe(value):
    """``value`` (dicts, lists, numbers) with every NaN or infinity as None: JSON has none."""
    if isinstance(value, dict):
        return {k: _json_safe(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_json_safe(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _rounded(values, digits: int = 3) -> list:
    """An array as nested lists of floats rounded for JSON, NaN as None."""
    return _json_safe(np.round(np.asarray(values, dtype=np.float64), digits).tolist())


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
        "scores": _json_safe({"registration": report["registration"],
                                 "frames": report["frames"], "sensors": report["sensors"],
                                 "signals": report["signals"]}),
    }
