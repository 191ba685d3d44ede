"""Training the coarticulation constants against VocalTractLab's gestural trajectories.

The paper fits the dominance functions' constants by minimisation (DESIGN.md part 7); here the
measurements are the trajectories VocalTractLab's gestural model makes for the same timed phone
sequences, carried into our parameters (``training.vtl_reference``). For every sequence of
``SEQUENCES``, timed by the duration rule ``DURATIONS_S`` between two silences, the error is
the RMS over the speech frames (100 Hz, the silences left out) of the difference between our
tracks and the reference, each parameter divided by its rig range, over ``COMPARED`` (the
sagittal tongue, the jaw, the lips and the velum: what VTL's outline and settings determine).

Free: the shared exponent c, and per dominance class the anticipation and carry-over time
constants T (theta = T^-c, so that c does not change the time scale) and a scale of all its
magnitudes alpha but the velum's (the vowel's held at 1: only ratios of dominance count).
Classes absent from the training sequences, and silence (``UNTRAINED``), keep their values; so
do the velum's magnitudes, which phonetics sets (a nasal lowers it, an oral obstruent must
close it) and VTL's short velic gestures would only trade against the other articulators.
BOBYQA (``fitting.optimizer``) from the hand-set
``dominance.DEFAULTS``; every fourth sequence is held out and reported before and after.

``glasshead train [--max-evals N]`` prints the report and writes ``speech/constants.json``,
which ``coarticulate`` loads by default (docs/coarticulation.md).
"""

import copy
import json
import math
import time
from pathlib import Path

import numpy as np

from glasshead.fitting import optimizer
from glasshead.phonemes import lookup
from glasshead.speech import coarticulation, dominance
from glasshead.training.vtl_reference import ReferenceMapping

#: Frames per second of the comparison.
RATE_HZ = 100.0
#: Seconds of silence before and after each sequence.
EDGE_SILENCE_S = 0.15
#: Phone durations (s) by kind and manner: a plain rule of an unhurried speaker (stressed
#: vowels about 140 ms, consonants 60-110 ms; Klatt's (1979) inherent durations, rounded).
DURATIONS_S = {"vowel": 0.14, "unstressed": 0.08, "stop": 0.07, "nasal": 0.07,
               "fricative": 0.10, "affricate": 0.11, "lateral": 0.06, "approximant": 0.06}
#: Parameters compared: what VTL's outline and settings determine (the coronal sections are
#: read from side elevations alone and are left out).
COMPARED = ("tip_advancement", "tip_height", "tip_thickness", "blade_advancement",
            "blade_height", "dorsum_advancement", "dorsum_height", "back_dorsum_height",
            "root_advancement", "body_height", "jaw_opening", "lip_opening", "lip_rounding",
            "lip_protrusion", "lower_lip_tuck", "velum_opening")
#: Words and phrases (ARPAbet; "0" after a vowel marks it unstressed) of phones VTL has
#: gestures for (no W, R or diphthongs): rounding and spreading around coronals and velars,
#: labials, nasals, fricatives and /h/.
SEQUENCES = (
    ("stew", "S T UW"), ("stee", "S T IY"), ("key", "K IY"), ("coo", "K UW"),
    ("mom", "M AA M"), ("noon", "N UW N"), ("beat", "B IY T"), ("book", "B UH K"),
    ("sheep", "SH IY P"), ("foot", "F UH T"), ("talk", "T AO K"), ("dog", "D AO G"),
    ("city", "S IH T IY0"), ("movie", "M UW V IY0"), ("copy", "K AA P IY0"), ("need", "N IY D"),
    ("loose", "L UW S"), ("goose", "G UW S"), ("zoo", "Z UW"), ("think", "TH IH NG K"),
    ("then", "DH EH N"), ("cheese", "CH IY Z"), ("jump", "JH AH M P"), ("you", "Y UW"),
    ("who", "HH UW"), ("he", "HH IY"), ("spoon", "S P UW N"), ("ski", "S K IY"),
    ("tooth", "T UW TH"), ("feet", "F IY T"), ("pasta", "P AA S T AH0"), ("cat", "K AE T"),
    ("meeting", "M IY T IH0 NG"), ("soup", "S UW P"), ("leaf", "L IY F"),
    ("see the moon", "S IY DH AH0 M UW N"), ("cut the cheese", "K AH T DH AH0 CH IY Z"),
    ("a good book", "AH0 G UH D B UH K"), ("look at the sea", "L UH K AE T DH AH0 S IY"),
    ("fish", "F IH SH"), ("coffee", "K AA F IY0"), ("vast", "V AE S T"),
    ("give it back", "G IH V IH0 T B AE K"),
)
#: Every HELD_OUT_EVERY-th sequence (from the second) is held out of the training.
HELD_OUT_EVERY = 4
#: Bounds of the free variables: c, log T (s), log alpha scale.
C_BOUNDS = (0.6, 2.0)
T_BOUNDS_S = (0.01, 0.5)
SCALE_BOUNDS = (0.1, 10.0)
MAX_EVALS = 4000
#: A restart of BOBYQA from its best point is kept going while it lowers the error by more than
#: this share.
RESTART_GAIN = 0.005
#: Classes kept as set by hand. Silence: its frames are not compared (VTL's silences are its
#: own rest, not ours), so only its reach into the speech would be trained, toward nothing.
#: /h/: its magnitudes are negligible by design (it takes its neighbours' articulation), so its
#: time constants would wander without changing a track.
UNTRAINED = ("silence", "glottal")
OUTPUT = dominance.CONSTANTS_FILE
#: The command that runs the training (``glasshead.cli``), named in the constants it writes.
COMMAND = "glasshead train"


def timed(text: str, edge_s: float = EDGE_SILENCE_S) -> list[dict]:
    """Phones of an ARPAbet string timed by ``DURATIONS_S``, with a silence at each end."""
    phones = [{"symbol": "sil", "stress": None, "start_s": 0.0, "end_s": edge_s}]
    clock = edge_s
    for token in text.split():
        p = lookup(token)
        stress = int(token[-1]) if token[-1].isdigit() else (1 if p.kind != "consonant" else None)
        if p.kind != "consonant":
            duration = DURATIONS_S["vowel" if stress else "unstressed"]
        else:
            duration = DURATIONS_S.get(p.manner, DURATIONS_S["approximant"])
        phones.append({"symbol": p.arpabet, "stress": stress, "start_s": round(clock, 6),
                       "end_s": round(clock + duration, 6)})
        clock += duration
    phones.append({"symbol": "sil", "stress": None, "start_s": round(clock, 6),
                   "end_s": round(clock + edge_s, 6)})
    return phones


def split(sequences=SEQUENCES) -> tuple[list, list]:
    """(training, held out): every ``HELD_OUT_EVERY``-th sequence from the second is held out."""
    held = [s for k, s in enumerate(sequences) if k % HELD_OUT_EVERY == 1]
    return [s for s in sequences if s not in held], held


class Case:
    """One sequence prepared for the objective: its phones, targets, classes, centres, frame
    times, the speech frames and the reference on them (COMPARED x frames)."""

    def __init__(self, name: str, text: str, mapping: ReferenceMapping):
        self.name, self.text = name, text
        self.phones = timed(text)
        targets = mapping.targets
        self.names = coarticulation.parameter_names(targets)
        symbols, starts, ends, _ = coarticulation.segments(self.phones)
        self.values = coarticulation.target_matrix(symbols, targets, self.names)
        self.groups = coarticulation.parameter_groups(self.names, targets)
        self.classes = [dominance.phone_class(s) for s in symbols]
        self.velum_classes = [dominance.velum_class(s) for s in symbols]
        self.centres = 0.5 * (starts + ends)
        n = coarticulation.frame_count(float(ends[-1]), RATE_HZ)
        times = np.arange(n) / RATE_HZ
        speech = (times >= ends[0]) & (times < starts[-1])
        self.times = times
        self.speech = speech
        self.rows = [self.names.index(name) for name in COMPARED]
        reference = mapping.reference_tracks(self.phones, times[speech])
        self.reference = np.array([reference[name] for name in COMPARED])
        self.spans = np.array([mapping.ranges[name]["max"] - mapping.ranges[name]["min"]
                               for name in COMPARED])

    def tracks(self, constants: dict) -> np.ndarray:
        """Our tracks of COMPARED on the speech frames for ``constants``."""
        classes = constants["classes"]
        velum = constants["velum_alpha"]
        alpha = np.array([[*(classes[c]["alpha"][g] for g in dominance.CLASS_GROUPS), velum[v]]
                          for c, v in zip(self.classes, self.velum_classes, strict=True)])
        before = np.array([classes[c]["theta_anticipation"] for c in self.classes])
        after = np.array([classes[c]["theta_carryover"] for c in self.classes])
        e = coarticulation.decay(self.centres, self.times[self.speech], before, after,
                                 float(constants["c"]))
        return coarticulation.blend(self.values, alpha, self.groups, e)[self.rows]

    def squared_errors(self, constants: dict) -> np.ndarray:
        """(len(COMPARED), n_speech_frames): squared differences, in shares of each range."""
        return ((self.tracks(constants) - self.reference) / self.spans[:, None]) ** 2


def rms(cases: list[Case], constants: dict) -> float:
    """The RMS error over every case's speech frames and COMPARED, in shares of the ranges."""
    total = sum(float(c.squared_errors(constants).sum()) for c in cases)
    count = sum(c.reference.size for c in cases)
    return math.sqrt(total / count)


def rms_by_parameter(cases: list[Case], constants: dict) -> dict:
    """Per compared parameter, the RMS error in its own unit (mm, deg or ratio)."""
    sums = sum(c.squared_errors(constants).sum(axis=1) * c.spans ** 2 for c in cases)
    frames = sum(c.reference.shape[1] for c in cases)
    return {name: round(math.sqrt(float(v) / frames), 4)
            for name, v in zip(COMPARED, sums, strict=True)}


class Packing:
    """The free variables x of ``constants``: [c, per trained class log T_anticipation,
    log T_carryover, and (but the vowel's) log alpha scale]. A class not trained keeps its time
    constants T as c changes."""

    def __init__(self, classes: list[str], base: dict, scales: bool = False):
        self.classes = classes
        self.scaled = [c for c in classes if c != "vowel"] if scales else []
        self.base = base

    def x0(self) -> np.ndarray:
        c = float(self.base["c"])
        x = [c]
        for name in self.classes:
            entry = self.base["classes"][name]
            for key in ("theta_anticipation", "theta_carryover"):
                x.append(math.log(entry[key] ** (-1.0 / c)))  # theta = T^-c
        x.extend(0.0 for _ in self.scaled)
        return np.clip(np.array(x), *self.bounds())

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        n_t, n_s = 2 * len(self.classes), len(self.scaled)
        lower = [C_BOUNDS[0], *[math.log(T_BOUNDS_S[0])] * n_t,
                 *[math.log(SCALE_BOUNDS[0])] * n_s]
        upper = [C_BOUNDS[1], *[math.log(T_BOUNDS_S[1])] * n_t,
                 *[math.log(SCALE_BOUNDS[1])] * n_s]
        return np.array(lower), np.array(upper)

    def constants(self, x: np.ndarray) -> dict:
        out = copy.deepcopy(self.base)
        c, c_base = float(x[0]), float(self.base["c"])
        out["c"] = c
        for name, entry in out["classes"].items():
            if name not in self.classes:  # keep T = theta^(-1/c)
                for key in ("theta_anticipation", "theta_carryover"):
                    entry[key] = entry[key] ** (c / c_base)
        k = 1
        for name in self.classes:
            entry = out["classes"][name]
            for key in ("theta_anticipation", "theta_carryover"):
                entry[key] = math.exp(x[k]) ** (-c)
                k += 1
        for name in self.scaled:
            scale = math.exp(x[k])
            k += 1
            entry = out["classes"][name]
            entry["alpha"] = {g: a * scale for g, a in entry["alpha"].items()}
        return out


def _rounded(constants: dict) -> dict:
    out = copy.deepcopy(constants)
    out["c"] = round(out["c"], 4)
    for entry in out["classes"].values():
        entry["theta_anticipation"] = round(entry["theta_anticipation"], 4)
        entry["theta_carryover"] = round(entry["theta_carryover"], 4)
        entry["alpha"] = {g: round(a, 4) for g, a in entry["alpha"].items()}
    return out


def train(assets_dir: Path, sequences=SEQUENCES, *, held_out=None, max_evals: int = MAX_EVALS,
          base: dict | None = None, scales: bool = False, progress=None) -> dict:
    """Fit the constants on ``sequences`` (held out: ``held_out``, default ``split``'s) from
    ``base`` (default ``dominance.DEFAULTS``). Returns ``{"constants", "report"}``: the trained
    constants (a constants document with a ``training`` record) and the report (RMS before and
    after on the training and held-out sets, per parameter on the held-out set)."""
    started = time.perf_counter()
    mapping = ReferenceMapping(assets_dir)
    if held_out is None:
        training_set, held_set = split(sequences)
    else:
        training_set, held_set = list(sequences), list(held_out)
    train_cases = [Case(n, t, mapping) for n, t in training_set]
    held_cases = [Case(n, t, mapping) for n, t in held_set]
    base = dominance.validate_constants(copy.deepcopy(base or dominance.DEFAULTS))
    present = sorted({c for case in train_cases for c in case.classes} - set(UNTRAINED),
                     key=dominance.CLASSES.index)
    packing = Packing(present, base, scales)
    lower, upper = packing.bounds()
    objective = lambda x: rms(train_cases, packing.constants(x))  # noqa: E731
    result = optimizer.minimize(objective, packing.x0(), lower, upper, method="bobyqa",
                                max_evals=max_evals, progress=progress)
    evaluations, restarts, seconds = result.evaluations, 0, result.seconds
    # BOBYQA's quadratic models stall on the bounds; restart from the best point while that
    # gains more than RESTART_GAIN and evaluations remain.
    while evaluations < max_evals:
        again = optimizer.minimize(objective, result.x, lower, upper, method="bobyqa",
                                   max_evals=max_evals - evaluations, progress=progress)
        evaluations += again.evaluations
        seconds += again.seconds
        gain = (result.error - again.error) / result.error
        if again.error < result.error:
            result = again
        restarts += 1
        if gain <= RESTART_GAIN:
            break
    trained = _rounded(packing.constants(result.x))
    report = {
        "training_sequences": [n for n, _ in training_set],
        "held_out_sequences": [n for n, _ in held_set],
        "trained_classes": present,
        "error": "RMS over the speech frames (100 Hz) and the compared parameters, each "
                 "divided by its rig range",
        "compared": list(COMPARED),
        "training_rms": {"before": round(rms(train_cases, base), 5),
                         "after": round(rms(train_cases, trained), 5)},
        "held_out_rms": {"before": round(rms(held_cases, base), 5) if held_cases else None,
                         "after": round(rms(held_cases, trained), 5) if held_cases else None},
        "held_out_by_parameter": {
            "before": rms_by_parameter(held_cases, base) if held_cases else {},
            "after": rms_by_parameter(held_cases, trained) if held_cases else {}},
        "evaluations": evaluations, "restarts": restarts, "stop": result.stop,
        "optimizer_seconds": round(seconds, 2),
        "seconds": round(time.perf_counter() - started, 2),
        "tongue_map": {"shapes": mapping.tongue.shapes, "ridge": mapping.tongue.ridge,
                       "leave_one_out_rms": mapping.tongue.loo_rms},
    }
    trained["header"] = (f"Made once by `{COMMAND}` (BOBYQA against VocalTractLab's gestural "
                         "trajectories) and committed: a small definition file that "
                         "coarticulate loads by default. docs/coarticulation.md")
    trained["training"] = report
    return {"constants": trained, "report": report}


def write_constants(constants: dict, path: Path = OUTPUT) -> Path:
    path = Path(path)
    path.write_text(json.dumps(constants, indent=1, ensure_ascii=False) + "\n")
    dominance._stored.cache_clear()
    return path


def print_report(report: dict) -> None:
    t, h = report["training_rms"], report["held_out_rms"]
    print(f"training ({len(report['training_sequences'])} sequences): RMS "
          f"{t['before']:.2%} -> {t['after']:.2%} of the ranges")
    if h["before"] is not None:
        print(f"held out ({len(report['held_out_sequences'])} sequences: "
              f"{', '.join(report['held_out_sequences'])}): RMS {h['before']:.2%} -> "
              f"{h['after']:.2%} of the ranges")
        before, after = (report["held_out_by_parameter"][k] for k in ("before", "after"))
        for name in report["compared"]:
            print(f"  {name:20s} {before[name]:7.3f} -> {after[name]:7.3f}")
    print(f"{report['evaluations']} evaluations, {report['restarts']} restarts "
          f"({report['stop']}), "
          f"{report['optimizer_seconds']:.1f} s; all {report['seconds']:.1f} s")
    m = report["tongue_map"]
    print(f"tongue map: ridge {m['ridge']} over {m['shapes']} shapes; leave-one-out RMS "
          + ", ".join(f"{k} {v:.2f}" for k, v in m["leave_one_out_rms"].items()
                      if k in COMPARED))

