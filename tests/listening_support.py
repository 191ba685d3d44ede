"""What the listening kernels and Praat measure from real recordings, on one time grid each.

Two trackers give the same ``Track`` per file:

- ours: ``node scripts/measure.mjs FILE... --group G``, one node process for all the files of a
  talker group, one JSON object per 10 ms hop;
- Praat, through parselmouth: To Pitch (autocorrelation, 10 ms, floor and ceiling per group),
  To Formant (burg) (5 formants, ceiling 5000 / 5500 / 6500 Hz for men / women / children, 25 ms
  window, 10 ms, pre-emphasis from 50 Hz), To Intensity (floor = the pitch floor), and the
  spectral centroid (power-weighted mean frequency, 0 Hz to the Nyquist frequency, as ours) of
  To Spectrogram (25 ms, 10 ms, up to the Nyquist frequency rather than Praat's default 5 kHz),
  all read at the formant frames' times.

Both are read at a time by the same ``sample`` (linear between the two frames around it), so
that the comparison with the published measurements is between the trackers, not the readers.

The Hillenbrand et al. (1995) tokens come with the authors' times (timedata.dat, in ms): the
vowel's start and end, and two judges' steady-state times. Their steady-state measurements are
read at judge 1's time: with Praat, it gives the smaller F1 and F2 errors (median 1.7 % and
1.6 %, against 2.1 % and 1.9 % at judge 2's time and 2.0 % and 1.7 % at the mean of the two).

Everything is read from the reference data directory (GLASSHEAD_DATA_DIR, by default
../shared/data) and never copied; a missing file fails the calling test with its path.
"""

import csv
import json
import math
import subprocess
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import parselmouth
import pytest

from glasshead.settings import REPO_ROOT, get_settings

#: The command that prints our measures, relative to the repository.
MEASURE_SCRIPT = Path("scripts") / "measure.mjs"

#: A node process measuring a group's files must finish within this, s.
MEASURE_TIMEOUT_S = 600

#: Hillenbrand's first letter of a file name -> our talker group.
GROUP_OF_KIND = {"m": "man", "w": "woman", "b": "child", "g": "child"}

#: Praat's To Pitch floor and ceiling per group, Hz: the kernels' (web/src/core/listen/params.js).
#: Hillenbrand's steady-state F0 spans 91-189 (men), 166-272 (women) and 183-294 Hz (children).
PITCH_RANGE_HZ = {"man": (60.0, 250.0), "woman": (120.0, 400.0), "child": (150.0, 500.0)}

#: Praat's To Formant (burg) ceiling per group, Hz (the kernels use the same).
FORMANT_CEILING_HZ = {"man": 5000.0, "woman": 5500.0, "child": 6500.0}

#: Analysis window of the formants and of Praat's spectrogram, s.
WINDOW_S = 0.025

#: Hop of every track, s.
HOP_S = 0.01


def speech_dir() -> Path:
    """The speech recordings' folder of the reference data; fails the test when it is missing."""
    return require(Path(get_settings().data_dir) / "speech")


def require(path: Path) -> Path:
    """``path`` when it exists, otherwise the calling test fails with it and what to set."""
    if not path.exists():
        pytest.fail(f"reference data missing: {path} (set GLASSHEAD_DATA_DIR to the shared data "
                    "directory)")
    return path


@dataclass
class Track:
    """A tracker's measures of one recording, one row per hop.

    t : (n,) float, frame centres, s; f0 : (n,) float, Hz, NaN where unvoiced;
    intensity_db : (n,) float; formants : (n, 4) float, F1-F4 in Hz, NaN where not found;
    centroid : (n,) float, spectral centroid, Hz (NaN where not given).
    """

    t: np.ndarray
    f0: np.ndarray
    intensity_db: np.ndarray
    formants: np.ndarray
    centroid: np.ndarray


@dataclass(frozen=True)
class Token:
    """One Hillenbrand recording with the authors' times (s) and measurements.

    ``ref`` maps a tokens.csv column (``f0_ss``, ``F1_ss``, ``F2_50``...) to Hz, NaN where the
    authors found it not measurable.
    """

    file: str
    group: str
    talker: str
    vowel: str
    path: Path
    start_s: float
    end_s: float
    steady_s: float
    ref: dict = field(hash=False, compare=False)

    def at_share(self, share):
        """The time at ``share`` (0..1) of the vowel, s."""
        return self.start_s + share * (self.end_s - self.start_s)


def hillenbrand_tokens() -> list[Token]:
    """The 576 /hVd/ tokens of Hillenbrand et al. (1995), in tokens.csv's order."""
    folder = speech_dir() / "hillenbrand1995-dev"
    tokens = []
    with require(folder / "tokens.csv").open(newline="") as handle:
        for row in csv.DictReader(handle):
            measured = {key: float(value) if value else math.nan for key, value in row.items()
                        if key[:1] in "fF" and key[1:2] in "012345" and key != "file"}
            tokens.append(Token(
                file=row["file"], group=GROUP_OF_KIND[row["file"][0]], talker=row["talker"],
                vowel=row["vowel"], path=require(folder / "audio" / f"{row['file']}.wav"),
                start_s=float(row["vowel_start_ms"]) / 1000,
                end_s=float(row["vowel_end_ms"]) / 1000,
                steady_s=float(row["steady_ms_judge1"]) / 1000, ref=measured))
    return tokens


def sample(t, values, time):
    """``values`` (n,) or (n, k) on frame times ``t`` (n,), read at ``time`` (s): linear between
    the two frames around it; where one of them is NaN, the other; NaN where both are."""
    values = np.asarray(values, dtype=np.float64)
    i = int(np.clip(np.searchsorted(t, time) - 1, 0, len(t) - 2))
    w = float(np.clip((time - t[i]) / (t[i + 1] - t[i]), 0.0, 1.0))
    a, b = values[i], values[i + 1]
    mixed = (1 - w) * a + w * b
    return np.where(np.isnan(a), b, np.where(np.isnan(b), a, mixed))


# ---------------------------------------------------------------------------------------------
# Praat

def praat_track(path: Path, group: str) -> Track:
    """Praat's measures of a recording (see the module's docstring for the settings)."""
    sound = parselmouth.Sound(str(path))
    floor, ceiling = PITCH_RANGE_HZ[group]
    pitch = sound.to_pitch(time_step=HOP_S, pitch_floor=floor, pitch_ceiling=ceiling)
    formant = sound.to_formant_burg(time_step=HOP_S, max_number_of_formants=5,
                                    maximum_formant=FORMANT_CEILING_HZ[group],
                                    window_length=WINDOW_S, pre_emphasis_from=50.0)
    intensity = sound.to_intensity(minimum_pitch=floor, time_step=HOP_S)
    spectrogram = sound.to_spectrogram(window_length=WINDOW_S, time_step=HOP_S,
                                       maximum_frequency=sound.sampling_frequency / 2)
    t = np.asarray(formant.xs())
    f0 = np.array([pitch.get_value_at_time(x) for x in t])
    formants = np.array([[formant.get_value_at_time(k, x) for k in range(1, 5)] for x in t])
    level = np.array([intensity.get_value(x) for x in t])
    freqs = np.asarray(spectrogram.ys())
    power = np.asarray(spectrogram.values)  # (frequencies, frames)
    frames = np.clip(np.round((t - spectrogram.x1) / spectrogram.dx).astype(int), 0,
                     power.shape[1] - 1)
    with np.errstate(invalid="ignore", divide="ignore"):
        centroid = (freqs @ power / power.sum(axis=0))[frames]
    return Track(t=t, f0=f0, intensity_db=level, formants=formants, centroid=centroid)


# ---------------------------------------------------------------------------------------------
# Ours

def measure_script() -> Path | None:
    """scripts/measure.mjs when it exists, else None."""
    script = REPO_ROOT / MEASURE_SCRIPT
    return script if script.is_file() else None


def measure_hops(path, group) -> list[dict]:
    """The listening kernels' hops of one WAV file (``scripts/measure.mjs``), as printed: one
    dict per 10 ms hop."""
    script = measure_script()
    assert script is not None, f"{MEASURE_SCRIPT} is missing: the listening kernels cannot be run"
    out = subprocess.run(["node", str(script), str(path), "--group", group], cwd=REPO_ROOT,
                         capture_output=True, text=True, check=True,
                         timeout=MEASURE_TIMEOUT_S).stdout
    return [json.loads(line) for line in out.splitlines() if line.startswith("{")]


def start_ours(paths, group):
    """Start one node process measuring ``paths`` as ``group``; finish it with ``finish_ours``.
    Its output goes to temporary files, so that it runs on while the caller does other work."""
    script = measure_script()
    assert script is not None, f"{MEASURE_SCRIPT} is missing: the listening kernels cannot be run"
    command = ["node", str(script), *[str(p) for p in paths], "--group", group]
    out, err = tempfile.TemporaryFile("w+"), tempfile.TemporaryFile("w+")
    process = subprocess.Popen(command, cwd=REPO_ROOT, stdout=out, stderr=err, text=True)
    return process, out, err, [str(p) for p in paths]


def finish_ours(started) -> dict[str, Track]:
    """The Track of each path (as given) from a process of ``start_ours``."""
    process, out, err, paths = started
    with out, err:
        process.wait(timeout=MEASURE_TIMEOUT_S)
        out.seek(0)
        err.seek(0)
        assert process.returncode == 0, (f"{MEASURE_SCRIPT} failed (exit {process.returncode}):"
                                         f"\n{err.read()[-3000:]}")
        rows: dict[str, list] = {path: [] for path in paths}
        for line in out:
            if line.strip():
                row = json.loads(line)
                rows[row.get("file", paths[0])].append(row)
    missing = [path for path, found in rows.items() if not found]
    assert not missing, f"{MEASURE_SCRIPT} printed nothing for {missing[:5]}"
    return {path: _track(found) for path, found in rows.items()}


def _track(rows) -> Track:
    def column(key):
        return np.array([np.nan if r.get(key) is None else r[key] for r in rows], dtype=float)

    formants = np.full((len(rows), 4), np.nan)
    for i, row in enumerate(rows):
        for k, value in enumerate((row.get("formants") or [])[:4]):
            formants[i, k] = np.nan if value is None else value
    f0 = column("f0")
    if "voiced" in rows[0]:
        f0[~np.array([bool(r["voiced"]) for r in rows])] = np.nan
    return Track(t=column("t"), f0=f0, intensity_db=column("intensity_db"), formants=formants,
                 centroid=column("centroid"))
