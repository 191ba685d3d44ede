"""Training the jaw's coarticulation against real articulography (HPRC), one speaker left out.

The head's jaw in running speech moves too little: driven by the HPRC recordings' phones, its
lower incisor drops 5.4 mm where the speakers' drop 9.2 (docs/ema.md). The targets open the jaw
as speakers do (``pipeline/jaw_openings.py``); what flattens it is the coarticulation, which
blends each phone's opening with its neighbours' by their dominance over the jaw. This trains
that dominance: per dominance class the jaw's magnitude alpha (``dominance``; the vowel's held,
as only ratios count), in log space within [``ALPHA_MIN``, ``ALPHA_MAX``], from the constants
the speech uses now (``dominance.load_constants``).

The error of a recording is that of the jaw-opening signal over its speech (the lower incisor's
drop below its highest point, as ``speech.ema_comparison.signals``; read in each one's own
millimetres, so no registration is needed):

    (1 - r)  +  RANGE_WEIGHT * ln(range head / range speaker)^2

and a pull toward the starting magnitudes, ``PULL`` * sum(ln(alpha / alpha0)^2). BOBYQA
(``fitting.optimizer``) minimises the mean over the training recordings. Each speaker is held
out in turn (F01's two recordings together, M01, M04) and scored before and after; the constants
trained on every speaker are what ``glasshead train --ema`` reports (and, with ``--write``,
writes to ``speech/constants.json``).

The head's lower incisor moves with the jaw pose alone (``geometry.jaw``), so the signal is
computed from the jaw track directly (``incisor_heights``), without the lips and the tongue:
one evaluation over the four recordings takes a few milliseconds.
"""

import copy
import math
import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from glasshead.ema import EmaRecording
from glasshead.fitting import optimizer
from glasshead.geometry.flesh_points import FleshPointRig
from glasshead.speech import coarticulation, dominance
from glasshead.speech import ema_comparison as cmp

Floats = npt.NDArray[np.float64]

#: The group trained.
GROUP = "jaw"
#: The class whose magnitude is held (the scale: only ratios of dominance count).
HELD_CLASS = "vowel"
#: Bounds of a trained magnitude.
ALPHA_MIN, ALPHA_MAX = 0.02, 20.0
#: Weight of the squared log range ratio against 1 - r.
RANGE_WEIGHT = 0.5
#: Bounds of a class's gain on its targets' jaw openings.
GAIN_MIN, GAIN_MAX = 0.25, 4.0
#: Weight of the pull toward the starting magnitudes and gains (per squared log ratio).
PULL = 0.01
MAX_EVALS = 400


def incisor_heights(jaw_deg: npt.ArrayLike, incisor: npt.ArrayLike, jaw: dict) -> Floats:
    """(n,) the height (project y, mm) of the rest lower incisor ``incisor`` (x, y) moved by the
    jaw pose of each opening in ``jaw_deg`` (``geometry.jaw.jaw_pose``, vectorised)."""
    opening = np.asarray(jaw_deg, dtype=np.float64)
    angle = -np.radians(opening)
    c, s = np.cos(angle), np.sin(angle)
    px, py = jaw["pivot"]
    ty = jaw["translation_per_degree"][1]
    x0, y0 = (float(v) for v in np.asarray(incisor, dtype=np.float64)[:2])
    return s * x0 + c * y0 + py - (s * px + c * py) + opening * ty


@dataclass
class Recording:
    """One recording ready to score: its phones, the speaker's jaw-opening signal over the
    speech, and which samples that is."""

    name: str
    speaker: str
    phones: list[dict]
    rate_hz: float
    n_frames: int
    speech: npt.NDArray[np.bool_]
    measured: Floats

    @classmethod
    def of(cls, recording: EmaRecording) -> "Recording":
        recording = cmp.with_fixed_sensors(recording)
        if "lower_incisor" not in recording.sensors:
            raise cmp.ComparisonError(f"{recording.name}: no lower_incisor sensor")
        speech = cmp.speech_frames(recording)
        jaw = np.asarray(recording.sensors["lower_incisor"], dtype=np.float64)[speech, 2]
        return cls(recording.name, cmp.speaker_of(recording), cmp.phones_of(recording),
                   recording.sample_rate_hz, recording.n_frames, speech, jaw.max() - jaw)


@dataclass
class JawModel:
    """What the training changes: the coarticulation constants and a gain per dominance class on
    its targets' jaw openings (1 where none is named)."""

    constants: dict
    gains: dict[str, float]


class JawScorer:
    """The head's jaw-opening signal on a recording's samples for a ``JawModel``, and its
    figures against the speaker's."""

    def __init__(self, targets: dict, incisor: npt.ArrayLike, jaw: dict,
                 jaw_range: tuple[float, float]):
        self.targets, self.incisor, self.jaw, self.jaw_range = targets, incisor, jaw, jaw_range

    @classmethod
    def of(cls, targets: dict, rig: FleshPointRig) -> "JawScorer":
        """The scorer of the phoneme ``targets`` on the flesh points' rig: its rest lower
        incisor, its jaw and the jaw's range."""
        tongue = rig.tongue
        k = tongue.jaw_parameter
        return cls(targets, rig.incisors["lower_incisor"][:2], tongue.jaw,
                   (float(tongue.minimum[k]), float(tongue.maximum[k])))

    def head_signal(self, recording: Recording, model: JawModel) -> Floats:
        targets = with_jaw_gains(self.targets, model.gains, self.jaw_range)
        result = coarticulation.coarticulate_arrays(recording.phones, targets,
                                                    rate_hz=recording.rate_hz,
                                                    constants=model.constants)
        track = result["tracks"][result["names"].index("jaw_opening")]
        take = np.minimum(np.arange(recording.n_frames), len(track) - 1)
        heights = incisor_heights(track[take], self.incisor, self.jaw)[recording.speech]
        return heights.max() - heights

    def figures(self, recording: Recording, model: JawModel) -> dict:
        head = self.head_signal(recording, model)
        head_range, speaker_range = float(np.ptp(head)), float(np.ptp(recording.measured))
        return {"r": cmp.correlation(head, recording.measured), "head_range_mm": head_range,
                "speaker_range_mm": speaker_range,
                "range_ratio": head_range / speaker_range if speaker_range > 0 else math.nan}

    def error(self, recording: Recording, model: JawModel) -> float:
        f = self.figures(recording, model)
        r = f["r"] if math.isfinite(f["r"]) else 0.0
        ratio = max(f["range_ratio"], 1e-3) if math.isfinite(f["range_ratio"]) else 1e-3
        return (1.0 - r) + RANGE_WEIGHT * math.log(ratio) ** 2


def present_classes(recordings: Sequence[Recording]) -> list[str]:
    """The dominance classes of the recordings' phones, silence left out, in ``CLASSES`` order."""
    present = {dominance.phone_class(p["symbol"]) for r in recordings for p in r.phones}
    return [c for c in dominance.CLASSES if c in present and c != "silence"]


def with_alphas(base: dict, classes: Sequence[str], log_alphas: npt.ArrayLike) -> dict:
    """``base`` with the jaw magnitudes of ``classes`` set to exp(``log_alphas``)."""
    out = copy.deepcopy(base)
    for name, value in zip(classes, np.asarray(log_alphas, dtype=np.float64), strict=True):
        out["classes"][name]["alpha"][GROUP] = round(float(math.exp(value)), 4)
    return out


def with_jaw_gains(targets: dict, gains: dict[str, float], jaw_range: tuple[float, float]
                   ) -> dict:
    """The targets with every jaw opening (each context's too) of a phoneme of class c
    multiplied by ``gains[c]`` (1 for a class not named), within ``jaw_range``. Shallow copies:
    the targets given are not changed."""
    low, high = jaw_range

    def opened(params: dict, gain: float) -> dict:
        value = min(max(params["jaw_opening"] * gain, low), high)
        return {**params, "jaw_opening": round(value, 4)}

    out = dict(targets)
    made = []
    for target in targets["targets"]:
        gain = gains.get(dominance.phone_class(target["arpabet"]), 1.0)
        if gain == 1.0:
            made.append(target)
            continue
        made.append({**target, "params": opened(target["params"], gain),
                     "contexts": {c: {**v, "params": opened(v["params"], gain)}
                                  for c, v in target.get("contexts", {}).items()}})
    out["targets"] = made
    return out


def train(scorer: JawScorer, recordings: Sequence[Recording], base: dict, *,
          max_evals: int = MAX_EVALS) -> dict:
    """The model trained on ``recordings`` from ``base`` (constants) and gains of 1: {model,
    alpha_classes, gain_classes, error_before, error_after, evaluations, seconds}."""
    classes = present_classes(recordings)
    alpha_classes = [c for c in classes if c != HELD_CLASS]
    x0 = np.concatenate([np.log([base["classes"][c]["alpha"][GROUP] for c in alpha_classes]),
                         np.zeros(len(classes))])
    lower = np.concatenate([np.full(len(alpha_classes), math.log(ALPHA_MIN)),
                            np.full(len(classes), math.log(GAIN_MIN))])
    upper = np.concatenate([np.full(len(alpha_classes), math.log(ALPHA_MAX)),
                            np.full(len(classes), math.log(GAIN_MAX))])
    x0 = np.clip(x0, lower, upper)

    def model_of(x) -> JawModel:
        x = np.asarray(x, dtype=np.float64)
        gains = {c: round(float(math.exp(v)), 4) for c, v in zip(classes, x[len(alpha_classes):],
                                                                 strict=True)}
        return JawModel(with_alphas(base, alpha_classes, x[:len(alpha_classes)]), gains)

    def objective(x) -> float:
        model = model_of(x)
        mean = float(np.mean([scorer.error(r, model) for r in recordings]))
        return mean + PULL * float(np.sum((np.asarray(x) - x0) ** 2))

    started = time.perf_counter()
    before = objective(x0)
    result = optimizer.minimize(objective, x0, lower, upper, method="bobyqa",
                                max_evals=max_evals)
    return {"model": model_of(result.x), "alpha_classes": alpha_classes, "gain_classes": classes,
            "error_before": before, "error_after": float(result.error),
            "evaluations": result.evaluations, "seconds": time.perf_counter() - started}


def held_out(scorer: JawScorer, recordings: Sequence[Recording], base: dict, *,
             max_evals: int = MAX_EVALS) -> dict:
    """Each speaker left out in turn: trained on the others, their recordings' figures before
    and after, and the means over the held-out recordings."""
    start = JawModel(base, {})
    folds = []
    for speaker in sorted({r.speaker for r in recordings}):
        scored = [r for r in recordings if r.speaker == speaker]
        trained = train(scorer, [r for r in recordings if r.speaker != speaker], base,
                        max_evals=max_evals)
        folds.append({"speaker": speaker, "recordings": [
            {"name": r.name, "before": scorer.figures(r, start),
             "after": scorer.figures(r, trained["model"])} for r in scored],
            "evaluations": trained["evaluations"]})
    rows = [row for fold in folds for row in fold["recordings"]]
    return {"folds": folds, "mean": {when: {key: float(np.mean([row[when][key] for row in rows]))
                                            for key in ("r", "range_ratio", "head_range_mm")}
                                     for when in ("before", "after")}}


def run(paths: Sequence, targets: dict, rig: FleshPointRig, *,
        max_evals: int = MAX_EVALS) -> dict:
    """The held-out report and the model trained on every recording at ``paths``, for the
    phoneme ``targets`` on the flesh points' ``rig``."""
    from glasshead.ema import read_ema

    recordings = [Recording.of(read_ema(path)) for path in paths]
    scorer = JawScorer.of(targets, rig)
    base = dominance.load_constants()
    report = held_out(scorer, recordings, base, max_evals=max_evals)
    everyone = train(scorer, recordings, base, max_evals=max_evals)
    model = everyone["model"]
    report["trained"] = {"alpha": {c: model.constants["classes"][c]["alpha"][GROUP]
                                   for c in everyone["alpha_classes"]},
                         "alpha_before": {c: base["classes"][c]["alpha"][GROUP]
                                          for c in everyone["alpha_classes"]},
                         "jaw_gain": model.gains,
                         "error_before": everyone["error_before"],
                         "error_after": everyone["error_after"],
                         "evaluations": everyone["evaluations"],
                         "seconds": everyone["seconds"]}
    report["model"] = model
    return report


def format_report(report: dict) -> str:
    """The held-out figures per recording, before and after, their means, and the values
    trained on every speaker, as text."""
    lines = ["Jaw opening, each speaker held out: r and range head / speaker, before -> after"]
    for fold in report["folds"]:
        for row in fold["recordings"]:
            b, a = row["before"], row["after"]
            lines.append(f"  {row['name']:<20} r {b['r']:.2f} -> {a['r']:.2f}   range "
                         f"{b['range_ratio']:.2f} -> {a['range_ratio']:.2f} "
                         f"({b['head_range_mm']:.1f} -> {a['head_range_mm']:.1f} mm of "
                         f"{b['speaker_range_mm']:.1f})")
    b, a = report["mean"]["before"], report["mean"]["after"]
    lines.append(f"  {'mean':<20} r {b['r']:.2f} -> {a['r']:.2f}   range "
                 f"{b['range_ratio']:.2f} -> {a['range_ratio']:.2f}")
    trained = report["trained"]
    lines.append("Trained on every speaker: jaw dominance "
                 + ", ".join(f"{c} {trained['alpha_before'][c]:g} -> {v:g}"
                             for c, v in trained["alpha"].items()))
    lines.append("  jaw target gains " + ", ".join(f"{c} {g:g}"
                                                    for c, g in trained["jaw_gain"].items()))
    lines.append(f"  error {trained['error_before']:.3f} -> {trained['error_after']:.3f}, "
                 f"{trained['evaluations']} evaluations, {trained['seconds']:.1f} s")
    return "\n".join(lines)
