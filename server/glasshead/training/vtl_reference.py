"""Reference articulation trajectories from VocalTractLab's gestural model, in our parameters.

For a timed phone sequence, VocalTractLab (``vocaltractlab-cython``) writes a gestural score
from a segment file (``phoneme_file_to_gesture_file``: its rules place the vowel, lip, tongue
tip, tongue body, velic and glottal gestures) and runs its target-approximation model over the
score into a motor file (``gesture_file_to_motor_file``): one vector of its 19 tract parameters
every 110 samples at 44,100 Hz (2.49 ms). ``reference_tracks`` carries those states into the
rigs' parameters by the mapping the phoneme targets carry VTL's stored shapes with
(``fitting.vtl_mapping``, docs/targets.md):

- lips: ``vtl_mapping.lips_from_vtl`` (LP, LD, JX) at the mapped jaw, per frame, as for a
  shape;
- velum: VO from -0.1 cm^2 (closed, VTL's rest) to 0.5 cm^2 (the opening VTL's rules give a
  nasal's velic gesture) onto 0..1 (``vtl_mapping.velum_from_vo``). The targets do not read VO
  (every JD3 shape holds it closed) and set 1 for nasals, which is what this gives at a nasal's
  velic target;
- tongue and jaw: a full 2D fit per frame (0.5-1 s each, 100 per second of speech) is too slow to
  train on, so each tongue parameter and the jaw is a linear function of VTL's tongue, jaw and
  hyoid parameters, learned by ridge regression from the shapes the targets are fitted to, with the
  targets' own fitted values (``TongueMap``): a VTL state equal to a stored shape maps onto that
  phoneme's target to within the regression's residual, so what remains between the reference and
  our tracks is timing, which is what the coarticulation constants are to learn. Its leave-one-out
  error is reported. The jaw is mapped so, not from JA alone, because the targets open it by the
  sound's class (``pipeline.jaw_openings``), far wider than JD3's JA does.

The VTL speaker is German (JD3): /w/ and American /ɹ/ have no gesture of their own, and its
diphthongs glide to /e/ and /o/ (aI: a then e) where ours glide to /ɪ/ and /ʊ/, so
``VTL_SYMBOLS`` leaves W, R and the diphthongs out and sequences with them cannot be
referenced.
"""

import json
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from glasshead.constants import (
    FACE_RIG_FILE,
    PHONEME_TARGETS_FILE,
    TONGUE_RIG_FILE,
    VELUM_PARAMETER,
    VELUM_RIG_FILE,
    VTL_OBSERVATIONS_FILE,
)
from glasshead.fitting import vtl_mapping
from glasshead.pipeline import vtl_speaker as vtl
from glasshead.speech.dominance import SILENCE

#: ARPAbet -> the SAMPA symbol VTL's segment rules take (JD3 shapes nearest, as ``phonemes.py``).
VTL_SYMBOLS = {
    "AA": "a", "AE": "E", "AH": "6", "AO": "O", "EH": "E", "ER": "@", "IH": "I", "IY": "i",
    "UH": "U", "UW": "u", "P": "p", "B": "b", "M": "m", "F": "f", "V": "v", "TH": "T",
    "DH": "D", "T": "t", "D": "d", "N": "n", "S": "s", "Z": "z", "L": "l", "SH": "S", "ZH": "Z",
    "CH": "tS", "JH": "dZ", "Y": "j", "K": "k", "G": "g", "NG": "N", "HH": "h",
    SILENCE: "",
}
#: Seconds per motor state: VTL writes one every 110 samples at 44,100 Hz.
STATE_S = 110.0 / 44100.0
#: The VTL parameters the tongue map reads: tongue, jaw and hyoid (cm and deg, as VTL stores).
TONGUE_INPUTS = ("TCX", "TCY", "TTX", "TTY", "TBX", "TBY", "TRX", "TRY", "TS1", "TS2", "TS3",
                 "JA", "JX", "HX", "HY")
#: Ridge penalties tried for the tongue map (standardised inputs); leave-one-out picks one.
RIDGE_CHOICES = (1e-3, 1e-2, 0.1, 0.3, 1.0, 3.0, 10.0)


class NoGestureError(ValueError):
    """A phone sequence VTL cannot make a reference for (a symbol it has no gesture for)."""


def segment_file_text(phones: list[dict]) -> str:
    """VTL's segment sequence file for timed phones (ARPAbet or "sil"): one line per phone,
    silence as VTL's empty name. A gap between phones is written as a silence."""
    lines, clock = [], 0.0
    for phone in phones:
        symbol = phone["symbol"]
        if symbol not in VTL_SYMBOLS:
            raise NoGestureError(f"VocalTractLab has no gesture for {symbol!r} (W, R and the "
                                 "diphthongs are not referenced)")
        if phone["start_s"] > clock + 1e-6:
            lines.append(f"name = ; duration_s = {phone['start_s'] - clock:.6f};")
        lines.append(f"name = {VTL_SYMBOLS[symbol]}; duration_s = "
                     f"{phone['end_s'] - phone['start_s']:.6f};")
        clock = phone["end_s"]
    return "\n".join(lines) + "\n"


def read_motor_file(text: str) -> np.ndarray:
    """The tract states of a VTL motor (tract sequence) file: (n_states, 19) float64, VTL units.
    Below the comment lines: the glottis model's name, the number of states, then per state a
    line of glottis parameters and a line of tract parameters."""
    lines = [line for line in text.splitlines() if line.strip() and not line.startswith("#")]
    count = int(lines[1])
    tract = [[float(v) for v in lines[3 + 2 * k].split()] for k in range(count)]
    states = np.asarray(tract, dtype=np.float64)
    if states.shape != (count, len(vtl.param_names())):
        raise ValueError(f"VTL motor file: expected {count} states of {len(vtl.param_names())} "
                         f"tract parameters, got {states.shape}")
    return states


def vtl_states(phones: list[dict]) -> np.ndarray:
    """VTL's tract states (n_states, 19) for timed phones: segment file -> gestural score ->
    motor file, in a temporary directory. State k is at t = k * STATE_S."""
    api = vtl.api()
    with tempfile.TemporaryDirectory(prefix="glasshead-vtl-") as tmp:
        segments, gestures, motor = (str(Path(tmp) / n) for n in ("seg.txt", "ges.txt",
                                                                  "motor.txt"))
        Path(segments).write_text(segment_file_text(phones))
        api.phoneme_file_to_gesture_file(segments, gestures)
        api.gesture_file_to_motor_file(gestures, motor)
        return read_motor_file(Path(motor).read_text())


@dataclass
class TongueMap:
    """Tongue parameters and the jaw as a linear function of VTL's ``TONGUE_INPUTS``:
    ``values = clip(mean + ((x - x_mean) / x_scale) @ weights, lower, upper)``."""

    names: list[str]
    x_mean: np.ndarray  # (n_inputs,)
    x_scale: np.ndarray  # (n_inputs,)
    mean: np.ndarray  # (n_params,)
    weights: np.ndarray  # (n_inputs, n_params)
    lower: np.ndarray
    upper: np.ndarray
    ridge: float
    loo_rms: dict  # per parameter, the leave-one-out RMS error (the parameter's unit)
    shapes: int

    def __call__(self, x: np.ndarray) -> np.ndarray:
        """(n, n_params) tongue values for (n, n_inputs) VTL inputs."""
        z = (np.asarray(x, dtype=np.float64) - self.x_mean) / self.x_scale
        return np.clip(self.mean + z @ self.weights, self.lower, self.upper)


def _ridge(z, y, penalty):
    mean = y.mean(axis=0)
    a = z.T @ z + penalty * np.eye(z.shape[1])
    return mean, np.linalg.solve(a, z.T @ (y - mean))


def _loo_rms(z, y, penalty) -> np.ndarray:
    errors = np.empty_like(y)
    for k in range(len(y)):
        keep = np.arange(len(y)) != k
        mean, weights = _ridge(z[keep], y[keep], penalty)
        errors[k] = mean + z[k] @ weights - y[k]
    return np.sqrt((errors ** 2).mean(axis=0))


def shape_pairs(targets: dict) -> dict[str, dict]:
    """Shape name -> the tongue values fitted to it, from the targets document: each measured
    consonant's context fits, and the vowels' own fits (a target adjusted after its fit, /æ/,
    is left out: its shape's fit is /ɛ/'s)."""
    pairs: dict[str, dict] = {}
    for target in targets["targets"]:
        for context in (target.get("contexts") or {}).values():
            pairs.setdefault(context["fit"]["shape"], context["params"])
        source = target["source"]
        if not target.get("contexts") and source.get("kind") == "fit" and source.get("shapes"):
            pairs.setdefault(source["main_shape"], target["params"])
    return pairs


def fit_tongue_map(targets: dict, observations: dict, rig_parameters: dict) -> TongueMap:
    """The ridge regression of the tongue parameters on VTL's ``TONGUE_INPUTS`` over every shape
    the targets are fitted to, the penalty picked by the lowest mean leave-one-out error
    relative to each parameter's range."""
    shapes = {s["name"]: s for s in observations["shapes"]}
    pairs = shape_pairs(targets)
    names = list(targets["parameters"]["tongue"])
    x = np.array([[shapes[s]["params"][k] for k in TONGUE_INPUTS] for s in pairs])
    y = np.array([[values[n] for n in names] for values in pairs.values()])
    x_mean, x_scale = x.mean(axis=0), x.std(axis=0)
    x_scale[x_scale == 0] = 1.0
    z = (x - x_mean) / x_scale
    spans = np.array([rig_parameters[n]["max"] - rig_parameters[n]["min"] for n in names])
    scored = [(float(np.mean(_loo_rms(z, y, p) / spans)), p) for p in RIDGE_CHOICES]
    penalty = min(scored)[1]
    mean, weights = _ridge(z, y, penalty)
    loo = _loo_rms(z, y, penalty)
    return TongueMap(names=names, x_mean=x_mean, x_scale=x_scale, mean=mean, weights=weights,
                     lower=np.array([rig_parameters[n]["min"] for n in names]),
                     upper=np.array([rig_parameters[n]["max"] for n in names]),
                     ridge=penalty, loo_rms={n: round(float(v), 4) for n, v in
                                             zip(names, loo, strict=True)},
                     shapes=len(pairs))


class ReferenceMapping:
    """What carries VTL states into our parameters: the built targets, rigs and observations
    (``assets_dir``) and the tongue map fitted from them."""

    def __init__(self, assets_dir: Path):
        assets_dir = Path(assets_dir)
        for name in (PHONEME_TARGETS_FILE, VTL_OBSERVATIONS_FILE, TONGUE_RIG_FILE, FACE_RIG_FILE,
                     VELUM_RIG_FILE):
            if not (assets_dir / name).is_file():
                raise FileNotFoundError(f"{assets_dir / name} is missing: run `glasshead build`")
        read = lambda name: json.loads((assets_dir / name).read_text())  # noqa: E731
        self.targets = read(PHONEME_TARGETS_FILE)
        rig = read(TONGUE_RIG_FILE)
        self.tongue_parameters = {p["name"]: p for p in rig["parameters"]}
        self.lip_table = {p["name"]: p for p in read(FACE_RIG_FILE)["parameters"]}
        self.velum_table = {p["name"]: p for p in read(VELUM_RIG_FILE)["parameters"]}
        self.ranges = {**self.tongue_parameters, **self.lip_table, **self.velum_table}
        self.tongue = fit_tongue_map(self.targets, read(VTL_OBSERVATIONS_FILE),
                                     self.tongue_parameters)
        self.names = [*self.targets["parameters"]["tongue"], *self.targets["parameters"]["lips"],
                      *self.targets["parameters"]["velum"]]

    def map_states(self, states: np.ndarray) -> dict[str, np.ndarray]:
        """Our parameters for VTL tract states (n, 19): {name: (n,)}."""
        index = {name: k for k, name in enumerate(vtl.param_names())}
        column = lambda name: states[:, index[name]]  # noqa: E731
        out = dict(zip(self.tongue.names, self.tongue(
            np.stack([column(k) for k in TONGUE_INPUTS], axis=1)).T, strict=True))
        jaw = out["jaw_opening"]
        lips = [vtl_mapping.lips_from_vtl(
            {"lips": {"LP": lp * vtl.CM_TO_MM, "LD": ld * vtl.CM_TO_MM},
             "jaw": {"JX": jx * vtl.CM_TO_MM}}, float(j), self.lip_table)
            for lp, ld, jx, j in zip(column("LP"), column("LD"), column("JX"), jaw, strict=True)]
        for name in self.targets["parameters"]["lips"]:
            out[name] = np.array([entry[name] for entry in lips])
        out[VELUM_PARAMETER] = vtl_mapping.velum_from_vo(column("VO"),
                                                         self.velum_table[VELUM_PARAMETER])
        return out

    def reference_tracks(self, phones: list[dict], times: np.ndarray) -> dict[str, np.ndarray]:
        """VTL's trajectories for ``phones`` in our parameters at ``times`` (s), linearly
        interpolated between its states: {name: (n_times,)}."""
        states = vtl_states(phones)
        mapped = self.map_states(states)
        state_times = np.arange(len(states)) * STATE_S
        return {name: np.interp(times, state_times, mapped[name]) for name in self.names}

