"""The head against real articulography: driven by a recording's phone timings, how closely do
its flesh points follow the speaker's sensors?

For each EMA recording (``glasshead.ema``), the head speaks the recording's own phones on their
own times (``speech.coarticulation``, at the recording's sample rate) and its flesh points
(``geometry.flesh_points``) are read in the recording's frame: x anterior, y the speaker's left,
z up, in mm from the upper incisor (HPRC's own origin). Only the speech is compared: the frames
from the start of the first phone that is not a pause to the end of the last one.

Registration. A coil is glued where the experimenter could reach, not exactly at the rig's
point (HPRC's jaw coil sits on the gum below the lower incisors, about 15 mm under their edge),
and each head and speaker differ in size and in the tilt of their occlusal planes. So each
speaker's sensors are mapped onto the head's points by one affine map of the whole head (3 x 3
and a shift) with a fixed offset per sensor (where that coil sits from the rig's point), fitted
by least squares on *other* data than the recording scored: the speaker's other recordings, or,
for a speaker with one recording, the other half of it (two folds in time). ``scheme`` in the
report says which.

Figures, per recording:
- per sensor and direction (anterior, vertical): the correlation r and the RMSE in mm between
  the head's point and the registered sensor;
- the heights the training goals name (issue: tongue-tip height, dorsum height, jaw opening, lip
  aperture): r between the head's and the speaker's unregistered signals (a correlation needs no
  registration), with the range ratio head / speaker of the jaw opening and the lip aperture
  (ranges are read in each one's own millimetres, so no fitted map can hide a jaw that barely
  moves);
- the same heights for a step baseline (the tip raised during every coronal consonant, the jaw
  open during every vowel), and for another speaker saying the same sentence, warped onto this
  recording's timing by the phone boundaries.
"""

import dataclasses
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from glasshead.asset_store import AssetStore
from glasshead.ema import EmaRecording, project_axes, read_ema
from glasshead.ema.labels import PAUSE
from glasshead.flesh_point_assets import flesh_point_rig
from glasshead.geometry.flesh_points import FleshPointRig
from glasshead.phonemes import lookup
from glasshead.speech import coarticulation

Floats = npt.NDArray[np.float64]

#: The sensors compared, where the recordings have them (HPRC's TT, TB, TR, JAW, UL, LL).
COMPARED = ("tongue_tip", "tongue_blade", "tongue_dorsum", "lower_incisor", "upper_lip",
            "lower_lip")
#: Sensors a recording holds under another name: in the copy of HPRC's F01 fast-rate file the
#: column named JAWL holds the lower incisor (and JAW the mouth corner; docs/ema.md, "The HPRC
#: data"). The reader reports what the file says; the comparison takes the right coil.
SENSOR_FIXES = {"F01_B01_S01_R01_F": {"lower_incisor": "jaw_left"}}
#: Axes of the recording's frame compared (the lateral one carries little in mid-sagittal
#: speech, and the head's points lie in its mid-sagittal plane).
DIRECTIONS = {"anterior": 0, "vertical": 2}
#: Places of the coronal consonants of the step baseline (the bunched American /r/ is left out:
#: its tip is not raised).
CORONAL_PLACES = ("dental", "alveolar", "postalveolar")
#: The signals the training goals name: (name, what it is).
SIGNALS = {
    "tip_height": "tongue_tip vertical position",
    "dorsum_height": "tongue_dorsum vertical position",
    "jaw_opening": "lower_incisor distance below its highest point",
    "lip_aperture": "distance between the upper and the lower lip sensors",
}


class ComparisonError(ValueError):
    """A recording that cannot be compared (no speech, a sensor missing), naming it."""


@dataclass(frozen=True)
class Driven:
    """One recording and the head driven by its phones, both on the recording's samples."""

    recording: EmaRecording
    speaker: str
    #: name -> (n, 3) mm in the recording's frame: the speaker's sensors and the head's points
    measured: dict[str, Floats]
    head: dict[str, Floats]
    #: frames compared (the speech, pauses at either end left out)
    speech: npt.NDArray[np.bool_]
    #: the head's parameter tracks, name -> (n,) on the recording's samples
    tracks: dict[str, Floats] = dataclasses.field(default_factory=dict)


def speaker_of(recording: EmaRecording) -> str:
    """The speaker's code: HPRC's names begin with it (``F01_B01_S01_R01_N``)."""
    return recording.name.split("_")[0]


def with_fixed_sensors(recording: EmaRecording) -> EmaRecording:
    """``recording`` with the sensors of ``SENSOR_FIXES`` under their right names."""
    fixes = SENSOR_FIXES.get(recording.name)
    if not fixes or any(source not in recording.sensors for source in fixes.values()):
        return recording
    sensors = dict(recording.sensors)
    sensors.update({name: recording.sensors[source] for name, source in fixes.items()})
    return dataclasses.replace(recording, sensors=sensors)


def phones_of(recording: EmaRecording) -> list[dict]:
    """The recording's phones as ``coarticulate`` takes them."""
    return [{"symbol": p.symbol, "stress": p.stress, "start_s": p.start_s, "end_s": p.end_s}
            for p in recording.phones]


def speech_frames(recording: EmaRecording) -> npt.NDArray[np.bool_]:
    """True on the frames from the first spoken phone's start to the last one's end."""
    spoken = [p for p in recording.phones if p.symbol != PAUSE]
    if not spoken:
        raise ComparisonError(f"{recording.name}: no phone but pauses; nothing to compare")
    return (recording.t_s >= spoken[0].start_s) & (recording.t_s < spoken[-1].end_s)


def drive(recording: EmaRecording, targets: dict, rig: FleshPointRig,
          constants: dict | None = None) -> Driven:
    """The head speaking ``recording``'s phones on its timing; its flesh points at the
    recording's samples, in the recording's frame from the upper incisor."""
    recording = with_fixed_sensors(recording)
    missing = [name for name in COMPARED if name not in recording.sensors]
    if missing:
        raise ComparisonError(f"{recording.name}: no {', '.join(missing)} sensor")
    result = coarticulation.coarticulate_arrays(phones_of(recording), targets,
                                                rate_hz=recording.sample_rate_hz,
                                                constants=constants)
    tracks = dict(zip(result["names"], result["tracks"], strict=True))
    points = rig.tracks(tracks)
    n = recording.n_frames
    head = {}
    for name in COMPARED:
        # frame i of the tracks is at i / rate, as sample i of the recording; the tracks end
        # with the last phone, which may end a frame before the signal does
        relative = project_axes(points[name] - points["upper_incisor"])
        take = np.minimum(np.arange(n), len(relative) - 1)
        head[name] = relative[take]
    measured = {name: np.asarray(recording.sensors[name], dtype=np.float64) for name in COMPARED}
    take = np.minimum(np.arange(n), len(result["tracks"][0]) - 1)
    on_samples = {name: np.asarray(track, dtype=np.float64)[take] for name, track in tracks.items()}
    return Driven(recording, speaker_of(recording), measured, head, speech_frames(recording),
                  on_samples)


@dataclass(frozen=True)
class Registration:
    """Sensor positions of one speaker mapped onto the head's points: ``A @ p + offset[name]``."""

    matrix: Floats  # (3, 3)
    offsets: dict[str, Floats]  # name -> (3,)

    def apply(self, name: str, positions: Floats) -> Floats:
        return positions @ self.matrix.T + self.offsets[name]


def fit_registration(pairs: Sequence[tuple[Mapping[str, Floats], Mapping[str, Floats]]]
                     ) -> Registration:
    """The least-squares affine map with an offset per sensor that takes the measured positions
    of ``pairs`` ((measured, head) dicts of (n, 3) arrays, frames already chosen) onto the
    head's."""
    names = list(COMPARED)
    rows, targets = [], []
    for measured, head in pairs:
        for k, name in enumerate(names):
            p = measured[name]
            one_hot = np.zeros((len(p), len(names)))
            one_hot[:, k] = 1.0
            rows.append(np.hstack([p, one_hot]))
            targets.append(head[name])
    design, wanted = np.vstack(rows), np.vstack(targets)
    if len(design) < design.shape[1] * 3:
        raise ComparisonError(f"too few frames to register ({len(design)} sensor samples)")
    solution, *_ = np.linalg.lstsq(design, wanted, rcond=None)
    return Registration(solution[:3].T.copy(),
                        {name: solution[3 + k].copy() for k, name in enumerate(names)})


def _select(points: Mapping[str, Floats], mask) -> dict[str, Floats]:
    return {name: values[mask] for name, values in points.items()}


def correlation(a: npt.ArrayLike, b: npt.ArrayLike) -> float:
    """Pearson's r; NaN when either signal does not vary."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    da, db = a - a.mean(), b - b.mean()
    norm = float(np.sqrt(np.dot(da, da) * np.dot(db, db)))
    return float(np.dot(da, db) / norm) if norm > 1e-12 else float("nan")


def signals(points: Mapping[str, Floats]) -> dict[str, Floats]:
    """The signals of ``SIGNALS`` from sensor or flesh-point positions (one frame's axes)."""
    jaw = points["lower_incisor"][:, 2]
    return {
        "tip_height": points["tongue_tip"][:, 2],
        "dorsum_height": points["tongue_dorsum"][:, 2],
        "jaw_opening": jaw.max() - jaw,
        "lip_aperture": np.linalg.norm(points["upper_lip"] - points["lower_lip"], axis=1),
    }


def step_baseline(recording: EmaRecording) -> dict[str, Floats]:
    """The step baseline on every sample: 1 for the tip during coronal consonants and for the
    jaw during vowels, else 0 (the dorsum and the lips have no baseline)."""
    tip = np.zeros(recording.n_frames)
    jaw = np.zeros(recording.n_frames)
    for phone in recording.phones:
        if phone.symbol == PAUSE:
            continue
        during = (recording.t_s >= phone.start_s) & (recording.t_s < phone.end_s)
        kind = lookup(phone.symbol)
        if kind.kind == "consonant" and kind.place in CORONAL_PLACES \
                and kind.manner != "approximant":
            tip[during] = 1.0
        if kind.kind in ("vowel", "diphthong"):
            jaw[during] = 1.0
    return {"tip_height": tip, "jaw_opening": jaw}


def warp_onto(other: EmaRecording, onto: EmaRecording) -> dict[str, Floats] | None:
    """``other``'s sensors resampled onto ``onto``'s samples by a piecewise-linear map of time
    through the boundaries of their spoken phones; None when the two do not say the same
    number of phones (another sentence)."""
    mine = [p for p in onto.phones if p.symbol != PAUSE]
    theirs = [p for p in other.phones if p.symbol != PAUSE]
    if len(mine) != len(theirs) or not mine:
        return None
    # outside the speech, time runs on at its own pace from the nearest boundary
    knots_mine = np.array([mine[0].start_s - 1e3, mine[0].start_s] + [p.end_s for p in mine]
                          + [mine[-1].end_s + 1e3])
    knots_theirs = np.array([theirs[0].start_s - 1e3, theirs[0].start_s]
                            + [p.end_s for p in theirs] + [theirs[-1].end_s + 1e3])
    t = np.interp(onto.t_s, knots_mine, knots_theirs)
    return {name: np.column_stack([np.interp(t, other.t_s, other.sensors[name][:, axis])
                                   for axis in range(3)])
            for name in COMPARED if name in other.sensors}


def _folds(driven: Sequence[Driven], index: int):
    """(scheme, [(training pairs, scored mask)]) for recording ``index``: the speaker's other
    recordings, or the two halves of its speech in time."""
    this = driven[index]
    others = [d for k, d in enumerate(driven) if k != index and d.speaker == this.speaker]
    if others:
        pairs = [(_select(d.measured, d.speech), _select(d.head, d.speech)) for d in others]
        return "other recordings of the speaker", [(pairs, this.speech)]
    frames = np.flatnonzero(this.speech)
    half = frames[len(frames) // 2]
    first = this.speech & (np.arange(len(this.speech)) < half)
    second = this.speech & ~first
    folds = []
    for train, score in ((first, second), (second, first)):
        folds.append(([(_select(this.measured, train), _select(this.head, train))], score))
    return "the other half of the recording", folds


def compare_one(driven: Sequence[Driven], index: int) -> dict:
    """The report of recording ``index`` of ``driven`` (see the module docstring)."""
    this = driven[index]
    scheme, folds = _folds(driven, index)
    registered = {name: np.full_like(values, np.nan) for name, values in this.measured.items()}
    for pairs, scored in folds:
        registration = fit_registration(pairs)
        for name in COMPARED:
            registered[name][scored] = registration.apply(name, this.measured[name][scored])
    speech = this.speech
    sensors: dict[str, dict] = {}
    for name in COMPARED:
        sensors[name] = {}
        for direction, axis in DIRECTIONS.items():
            head = this.head[name][speech, axis]
            measured = registered[name][speech, axis]
            sensors[name][direction] = {
                "r": correlation(head, measured),
                "rmse_mm": float(np.sqrt(np.mean((head - measured) ** 2))),
            }
    head_signals = signals(_select(this.head, speech))
    speaker_signals = signals(_select(this.measured, speech))
    baseline = {k: v[speech] for k, v in step_baseline(this.recording).items()}
    heights = {}
    for name in SIGNALS:
        entry = {"r": correlation(head_signals[name], speaker_signals[name])}
        if name in baseline:
            entry["baseline_r"] = correlation(baseline[name], speaker_signals[name])
        if name in ("jaw_opening", "lip_aperture"):
            head_range = float(np.ptp(head_signals[name]))
            speaker_range = float(np.ptp(speaker_signals[name]))
            entry.update(head_range_mm=head_range, speaker_range_mm=speaker_range,
                         range_ratio=head_range / speaker_range if speaker_range > 0
                         else float("nan"))
        heights[name] = entry
    _add_other_speakers(driven, index, heights, speaker_signals)
    return {"recording": this.recording.name, "speaker": this.speaker,
            "frames": int(speech.sum()), "registration": scheme, "sensors": sensors,
            "signals": heights}


def _add_other_speakers(driven: Sequence[Driven], index: int, heights: dict,
                        speaker_signals: dict) -> None:
    """Each signal's r between this speaker and every other speaker of the same sentence (their
    mean is ``other_speaker_r``), warped onto this recording's timing."""
    this = driven[index]
    values: dict[str, list[float]] = {name: [] for name in SIGNALS}
    for other in driven:
        if other.speaker == this.speaker:
            continue
        warped = warp_onto(other.recording, this.recording)
        if warped is None or any(name not in warped for name in COMPARED):
            continue
        theirs = signals(_select(warped, this.speech))
        for name in SIGNALS:
            values[name].append(correlation(theirs[name], speaker_signals[name]))
    for name, rs in values.items():
        if rs:
            heights[name]["other_speaker_r"] = float(np.mean(rs))


def compare(recordings: Sequence[EmaRecording], targets: dict, rig: FleshPointRig,
            constants: dict | None = None) -> dict:
    """The comparison of every recording: ``{"recordings": [report, ...], "summary": ...}``;
    the summary holds, per signal and per sensor and direction, the mean over recordings."""
    driven = [drive(recording, targets, rig, constants) for recording in recordings]
    reports = [compare_one(driven, k) for k in range(len(driven))]
    return {"recordings": reports, "summary": summarise(reports)}


def summarise(reports: Sequence[dict]) -> dict:
    """Means over the recordings of every figure of their reports (NaN ones left out)."""
    def mean(values):
        finite = [v for v in values if v is not None and np.isfinite(v)]
        return float(np.mean(finite)) if finite else None

    summary: dict = {"signals": {}, "sensors": {}}
    for name in SIGNALS:
        keys = sorted({key for r in reports for key in r["signals"][name]})
        summary["signals"][name] = {key: mean([r["signals"][name].get(key) for r in reports])
                                    for key in keys}
    for name in COMPARED:
        summary["sensors"][name] = {
            direction: {key: mean([r["sensors"][name][direction][key] for r in reports])
                        for key in ("r", "rmse_mm")}
            for direction in DIRECTIONS}
    return summary


def hprc_recordings(data_dir) -> list:
    """The ``*_ema.csv`` files of ``data_dir/ema/hprc``, in name order (the default input)."""
    folder = Path(data_dir) / "ema" / "hprc"
    paths = sorted(folder.glob("*_ema.csv"))
    if not paths:
        raise ComparisonError(f"no HPRC recordings (*_ema.csv) in {folder}")
    return paths


def run(paths: Sequence, assets_dir) -> dict:
    """Read the EMA files at ``paths`` (any format ``ema.read_ema`` knows, labels beside them)
    and compare the head of the built assets in ``assets_dir`` with them."""
    recordings = [read_ema(path) for path in paths]
    store = AssetStore(assets_dir)
    return compare(recordings, store.get("phoneme_targets"), flesh_point_rig(store))


def format_report(report: dict) -> str:
    """The report as text tables: the signals (r of the head, of the step baseline and of
    another speaker; range ratios), then each sensor's r and RMSE, per recording and mean."""
    def number(value, digits=2):
        return "-" if value is None or not np.isfinite(value) else f"{value:.{digits}f}"

    lines = []
    rows = [(r["recording"], r["signals"], r["registration"]) for r in report["recordings"]]
    rows.append(("mean", report["summary"]["signals"], ""))
    lines.append("Signals: r of the head, of the step baseline and of another speaker; "
                 "range head / speaker")
    header = f"{'recording':<20} {'signal':<14} {'head r':>7} {'step r':>7} {'other r':>8} " \
             f"{'range':>6}"
    lines += [header, "-" * len(header)]
    for name, figures, _ in rows:
        for signal in SIGNALS:
            f = figures[signal]
            lines.append(f"{name:<20} {signal:<14} {number(f.get('r')):>7} "
                         f"{number(f.get('baseline_r')):>7} {number(f.get('other_speaker_r')):>8} "
                         f"{number(f.get('range_ratio')):>6}")
    lines += ["", "Sensors, registered (r / RMSE mm), mean over the recordings"]
    header = f"{'sensor':<15} {'anterior r':>10} {'RMSE':>6} {'vertical r':>11} {'RMSE':>6}"
    lines += [header, "-" * len(header)]
    for name, figures in report["summary"]["sensors"].items():
        a, v = figures["anterior"], figures["vertical"]
        lines.append(f"{name:<15} {number(a['r']):>10} {number(a['rmse_mm'], 1):>6} "
                     f"{number(v['r']):>11} {number(v['rmse_mm'], 1):>6}")
    lines += ["", "Registration: " + "; ".join(f"{name}: {scheme}" for name, _, scheme in rows
                                                if scheme)]
    return "\n".join(lines)
