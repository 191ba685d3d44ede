"""The listening goals as figures, ours and Praat's side by side (docs/listening.md).

Readings of the Hillenbrand tokens: F0 at the steady state; F1 and F2 at the steady state and at
20, 50 and 80 % of the vowel (the authors' four readings of each token, pooled in the medians); a
token's F1 and F2 are "within 15 %" when both are at the steady state. A reading the authors
found not measurable is left out; one the tracker has no value for (unvoiced, no formant) counts
as an error larger than any: it raises the median and fails every tolerance, and a missing F0
counts with the octave errors.
"""

import math
from dataclasses import dataclass

import numpy as np

from listening_support import Token, sample

#: Ours is "as close as Praat" when it trails Praat's figure by at most this (0.2 percentage
#: points): a token or two of 576 is not a difference between the trackers.
SLACK = 0.002

#: The issue's goals.
F0_MEDIAN_GOAL = 0.015
OCTAVE_GOAL = 0.01
#: An octave error: |log2(ours / theirs)| above this (the ratio off by more than about 40 %
#: from 2 or 1/2).
OCTAVE_LOG2 = 0.5
FORMANT_MEDIAN_GOAL = 0.03
WITHIN = 0.15
WITHIN_GOAL = 0.95
VOWEL_GOAL = 0.90
SIBILANT_GOAL = 0.90
R_F3_GOAL = 0.80

#: Talker groups as reported, and which tokens each takes.
GROUPS = {"all": ("man", "woman", "child"), "men": ("man",), "women": ("woman",),
          "adults": ("man", "woman"), "children": ("child",)}

#: The authors' readings of F1 and F2: steady state, 20, 50 and 80 %.
POINTS = ("ss", "20", "50", "80")


@dataclass
class Figure:
    """One figure of one group: ours, Praat's and, where it applies, the authors' own.

    ``limit`` is the goal (None: reported only); ``lower`` says whether lower is better;
    ``versus_praat`` whether ours must also be as close as Praat's (within SLACK).
    """

    goal: str
    group: str
    ours: float
    praat: float
    limit: float | None = None
    lower: bool = True
    versus_praat: bool = False
    authors: float = math.nan

    def meets(self, value):
        if self.limit is None:
            return True
        return value <= self.limit if self.lower else value >= self.limit

    @property
    def passes(self):
        return self.meets(self.ours)

    @property
    def as_close_as_praat(self):
        return self.ours <= self.praat + SLACK if self.lower else self.ours >= self.praat - SLACK

    def shortfall(self):
        """What the goal asks and by how much ours misses it (percentage points)."""
        sign = "<=" if self.lower else ">="
        text = f"{self.goal} ({self.group}): ours {_pct(self.ours)}, Praat {_pct(self.praat)}"
        if self.limit is not None and not self.passes:
            text += (f"; the goal is {sign} {_pct(self.limit)}, missed by "
                     f"{100 * abs(self.ours - self.limit):.2f} percentage points")
        if self.versus_praat and not self.as_close_as_praat:
            text += (f"; ours trails Praat by {100 * abs(self.ours - self.praat):.2f} percentage "
                     f"points (slack {100 * SLACK:.1f})")
        return text


def _pct(value):
    return "-" if value is None or math.isnan(value) else f"{100 * value:.2f} %"


def table(figures) -> str:
    """The figures as a text table."""
    lines = [f"{'figure':44} {'group':9} {'ours':>9} {'Praat':>9} {'authors':>9}  "
             f"{'goal':12} {'ours':5} {'Praat':5} {'ours vs Praat'}"]
    for f in figures:
        goal = "" if f.limit is None else f"{'<=' if f.lower else '>='} {_pct(f.limit)}"
        verdicts = ["" if f.limit is None or math.isnan(value) else
                    "pass" if f.meets(value) else "FAIL" for value in (f.ours, f.praat)]
        if f.versus_praat and not math.isnan(f.ours):
            verdicts.append("as close" if f.as_close_as_praat else "behind")
        lines.append(f"{f.goal:44} {f.group:9} {_pct(f.ours):>9} {_pct(f.praat):>9} "
                     f"{_pct(f.authors):>9}  {goal:12} " + " ".join(f"{v:5}" for v in verdicts))
    return "\n".join(lines)


def readings(tokens: list[Token], tracks) -> tuple[np.ndarray, np.ndarray]:
    """A tracker's readings of the tokens, ``tracks`` aligned with them: F0 (n,) at the steady
    state, and F1, F2 (n, 4, 2) at POINTS."""
    f0 = np.empty(len(tokens))
    formants = np.empty((len(tokens), len(POINTS), 2))
    for i, (token, track) in enumerate(zip(tokens, tracks, strict=True)):
        f0[i] = sample(track.t, track.f0, token.steady_s)
        times = [token.steady_s, *(token.at_share(s) for s in (0.2, 0.5, 0.8))]
        formants[i] = [sample(track.t, track.formants[:, :2], t) for t in times]
    return f0, formants


def published(tokens: list[Token]) -> tuple[np.ndarray, np.ndarray]:
    """The authors' readings, shaped as ``readings``' (NaN where not measurable)."""
    f0 = np.array([t.ref["f0_ss"] for t in tokens])
    formants = np.array([[[t.ref[f"F{k}_{p}"] for k in (1, 2)] for p in POINTS] for t in tokens])
    return f0, formants


def relative_errors(values, reference):
    """|values - reference| / reference; inf where a value is missing, NaN where the reference
    is."""
    errors = np.abs(values - reference) / reference
    return np.where(np.isnan(values) & ~np.isnan(reference), np.inf, errors)


def _median(errors):
    errors = errors[~np.isnan(errors)]
    return float(np.median(errors)) if errors.size else math.nan


def _share(flags, valid):
    return float(np.mean(flags[valid])) if valid.any() else math.nan


def hillenbrand_figures(tokens, ours, praat) -> list[Figure]:
    """F0, F1 and F2 figures per group; ``ours`` and ``praat`` are ``readings`` (ours may be
    None: its figures are NaN)."""
    ref_f0, ref_formants = published(tokens)
    group_of = np.array([t.group for t in tokens])
    blank = (np.full(len(tokens), np.nan), np.full(ref_formants.shape, np.nan))
    tracked = {"ours": blank if ours is None else ours, "praat": praat}
    stats: dict[str, dict] = {}
    for name, (f0, formants) in tracked.items():
        f0_errors = relative_errors(f0, ref_f0)
        octave = ~(np.abs(np.log2(f0 / ref_f0)) <= OCTAVE_LOG2)
        formant_errors = relative_errors(formants, ref_formants)
        steady = formant_errors[:, 0, :]
        within = np.all(steady <= WITHIN, axis=1)
        stats[name] = {"f0": f0_errors, "octave": octave, "formants": formant_errors,
                       "within": within, "within_valid": ~np.isnan(steady).any(axis=1)}
    figures = []

    def add(goal, group, compute, limit=None, lower=True):
        mask = np.isin(group_of, GROUPS[group])
        values = [math.nan if ours is None and name == "ours" else compute(stats[name], mask)
                  for name in ("ours", "praat")]
        figures.append(Figure(goal, group, *values, limit=limit, lower=lower,
                              versus_praat=limit is not None))

    for group in ("all", "men", "women", "children"):
        add("F0 median relative error (steady state)", group,
            lambda s, m: _median(s["f0"][m]), F0_MEDIAN_GOAL if group == "all" else None)
    for group in ("all", "men", "women", "children"):
        add("F0 octave errors or no F0", group,
            lambda s, m: _share(s["octave"], m), OCTAVE_GOAL if group == "all" else None)
    for k, formant in enumerate(("F1", "F2")):
        for group in ("adults", "children", "men", "women"):
            add(f"{formant} median relative error (4 readings)", group,
                lambda s, m, k=k: _median(s["formants"][m, :, k].ravel()),
                FORMANT_MEDIAN_GOAL if group in ("adults", "children") else None)
    for group in ("all", "men", "women", "children"):
        add("tokens with F1 and F2 within 15 %", group,
            lambda s, m: _share(s["within"], m & s["within_valid"]),
            WITHIN_GOAL if group == "all" else None, lower=False)
    return figures


def point_figures(tokens, ours, praat) -> list[Figure]:
    """Reported only: the F1 and F2 median errors at each of the four readings."""
    ref_formants = published(tokens)[1]
    blank = np.full(ref_formants.shape, np.nan)
    ours_errors = relative_errors(blank if ours is None else ours[1], ref_formants)
    praat_errors = relative_errors(praat[1], ref_formants)
    names = {"ss": "the steady state", "20": "20 %", "50": "50 %", "80": "80 %"}
    return [Figure(f"F{k + 1} median relative error at {names[point]}", "all",
                   math.nan if ours is None else _median(ours_errors[:, p, k]),
                   _median(praat_errors[:, p, k]))
            for k in (0, 1) for p, point in enumerate(POINTS)]


def f0_misses(tokens, ours, praat) -> list[str]:
    """The tokens where ours has an octave error or no F0 at the steady state: file, the
    authors', our and Praat's F0 (Hz)."""
    if ours is None:
        return []
    ref = published(tokens)[0]
    missed = ~(np.abs(np.log2(ours[0] / ref)) <= OCTAVE_LOG2)
    return [f"{tokens[i].file} at {tokens[i].steady_s:.3f} s: authors {ref[i]:.0f} Hz, ours "
            f"{ours[0][i]:.0f} Hz, Praat {praat[0][i]:.0f} Hz" for i in np.flatnonzero(missed)]
