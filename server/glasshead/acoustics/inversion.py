"""The tongue from the voice: acoustic-to-articulatory inversion by codebook (twin of
``web/src/core/listen/inversion.js``; ``tests/vectors/inversion.json`` holds both to the same
choices).

The codebook (``glasshead.pipeline.inversion_codebook``) holds poses of the head's vowel space,
each with the formants F1 to F3 of its own tract (``acoustics.tube``) and a prior: how far it lies
from its nearest anchor target. Inverting a frame picks the pose whose formants are nearest the
measured ones, in log frequency, with the prior and, over time, continuity added (Atal et al.
1978; Schroeter and Sondhi 1994 review the method):

- a frame's *acoustic cost* for a pose is the mean over F1 to F3 of
  ``(ln(F * scale / F_pose) / INVERSION_FORMANT_SD)^2``; ``scale`` (one factor per formant, from
  the norms) maps a speaker group's vowel space onto the head's;
- its *local cost* adds ``INVERSION_PRIOR_WEIGHT`` times the pose's prior;
- moving from one pose to the next costs ``INVERSION_CONTINUITY_WEIGHT`` times their mean
  squared distance in each parameter's spread over the anchors.

A live frame (``invert_frame``) takes the best pose given the frame before's. A whole track
(``invert_track``) keeps each frame's ``INVERSION_CANDIDATES`` best local poses and finds the
cheapest path through them (Viterbi). A frame with no voice or no F1 to F3 (silence, noise, a
voiceless fricative), or whose best acoustic cost passes ``INVERSION_REJECT_COST`` (formants the
tract cannot make), gets no pose, and a track's path starts again after it.
"""

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import numpy.typing as npt

from glasshead.constants import (
    INVERSION_CANDIDATES,
    INVERSION_CONTINUITY_WEIGHT,
    INVERSION_FORMANT_SD,
    INVERSION_PRIOR_WEIGHT,
    INVERSION_REJECT_COST,
)

Floats = npt.NDArray[np.float64]
#: A factor for every formant, or one for all three.
ScaleLike = float | Sequence[float] | Floats


@dataclass(frozen=True)
class Codebook:
    """Poses and their formants. parameters : the P parameters that vary; fixed : the others'
    values; values : (N, P); spread : (P,) each parameter's spread over the anchors; formants :
    (N, 3) Hz; prior : (N,); group_scale : {group: (F1, F2, F3) factors}; anchors : the anchor
    targets by IPA; blends : the indices in ``anchors`` of the targets each entry blends."""

    parameters: tuple[str, ...]
    fixed: Mapping[str, float]
    values: Floats
    spread: Floats
    formants: Floats
    prior: Floats
    group_scale: Mapping[str, Sequence[float]]
    anchors: tuple[str, ...]
    blends: tuple[tuple[int, ...], ...]

    @cached_property
    def log_formants(self) -> Floats:
        return np.log(self.formants)

    @cached_property
    def scaled_values(self) -> Floats:
        return self.values / self.spread

    def anchor_entry(self, ipa: str) -> int:
        """The entry that is the anchor ``ipa`` alone."""
        alone = (self.anchors.index(ipa),)
        return next(i for i, used in enumerate(self.blends) if tuple(used) == alone)

    def pose(self, index: int) -> dict[str, float]:
        """Entry ``index`` as the rigs' parameters by name."""
        params = dict(self.fixed)
        params.update(zip(self.parameters, map(float, self.values[index]), strict=True))
        return params

    def scale(self, group: str | None) -> Floats:
        """(3,) the factors that map ``group``'s F1 to F3 onto the head's (1 for None or
        "head")."""
        if group in (None, "head"):
            return np.ones(3)
        if group not in self.group_scale:
            raise ValueError(f"no formant scale for the group {group!r}: the codebook has "
                             f"{', '.join(sorted(self.group_scale))}")
        return np.asarray(self.group_scale[group], dtype=np.float64)


def codebook_from_document(document: Mapping) -> Codebook:
    """The Codebook of an ``inversion-codebook.json`` document."""
    entries = document["entries"]
    return Codebook(
        parameters=tuple(document["parameters"]), fixed=dict(document["fixed"]),
        values=np.asarray(entries["values"], dtype=np.float64),
        spread=np.asarray(document["spread"], dtype=np.float64),
        formants=np.asarray(entries["formants"], dtype=np.float64),
        prior=np.asarray(entries["prior"], dtype=np.float64),
        group_scale=dict(document["group_scale"]), anchors=tuple(document["anchors"]),
        blends=tuple(tuple(b) for b in entries["anchors"]))


def keep_to(codebook: Codebook, anchors: Sequence[str]) -> Codebook:
    """The codebook of the entries that blend only ``anchors`` (IPA), for example the vowels."""
    unknown = [a for a in anchors if a not in codebook.anchors]
    if unknown:
        raise ValueError(f"the codebook has no anchor {', '.join(unknown)}")
    allowed = {codebook.anchors.index(a) for a in anchors}
    rows = [i for i, used in enumerate(codebook.blends) if set(used) <= allowed]
    return Codebook(
        parameters=codebook.parameters, fixed=codebook.fixed, values=codebook.values[rows],
        spread=codebook.spread, formants=codebook.formants[rows], prior=codebook.prior[rows],
        group_scale=codebook.group_scale, anchors=codebook.anchors,
        blends=tuple(codebook.blends[i] for i in rows))


def estimable_formants(hop: Mapping) -> list[float] | None:
    """A listening hop's F1 to F3 (``scripts/measure.mjs``, ``core/listen/analyse.js``) when it
    is voiced and has all three, else None: silence, noise and voiceless sounds get no tongue."""
    formants = hop.get("formants") or []
    if not hop.get("voiced") or len(formants) < 3 or any(f is None for f in formants[:3]):
        return None
    return [float(f) for f in formants[:3]]


def _measurable(formants) -> Floats | None:
    if formants is None or len(formants) < 3:
        return None
    values = np.array([np.nan if f is None else f for f in formants[:3]], dtype=np.float64)
    return values if np.all(np.isfinite(values)) and np.all(values > 0) else None


def acoustic_costs(formants: Sequence[float | None] | None, codebook: Codebook,
                   scale: ScaleLike = 1.0) -> Floats | None:
    """(N,) each pose's acoustic cost for measured F1 to F3 (Hz), or None when the frame has
    no F1 to F3 or its best pose costs more than ``INVERSION_REJECT_COST``."""
    measured = _measurable(formants)
    if measured is None:
        return None
    logs = np.log(measured * np.asarray(scale, dtype=np.float64))
    z = (logs[None, :] - codebook.log_formants) / np.asarray(INVERSION_FORMANT_SD)
    costs = (z * z).mean(axis=1)
    return costs if costs.min() <= INVERSION_REJECT_COST else None


def _moves(scaled: Floats, from_rows: npt.NDArray[np.int64], to_rows: npt.NDArray[np.int64]
           ) -> Floats:
    """(len(from), len(to)) mean squared distances between scaled poses."""
    difference = scaled[from_rows][:, None, :] - scaled[to_rows][None, :, :]
    return (difference * difference).mean(axis=2)


def invert_frame(formants: Sequence[float | None] | None, codebook: Codebook,
                 scale: ScaleLike = 1.0, previous: int | None = None) -> int | None:
    """The entry for one live frame given the frame before's (None: none), or None."""
    costs = acoustic_costs(formants, codebook, scale)
    if costs is None:
        return None
    total = costs + INVERSION_PRIOR_WEIGHT * codebook.prior
    if previous is not None:
        step = codebook.scaled_values - codebook.scaled_values[previous]
        total = total + INVERSION_CONTINUITY_WEIGHT * (step * step).mean(axis=1)
    return int(np.argmin(total))


def _candidates(local: Floats) -> npt.NDArray[np.int64]:
    # The best by cost, ties to the lower index, as the twin sorts them.
    order = np.lexsort((np.arange(len(local)), local))
    return order[:INVERSION_CANDIDATES]


def _path(locals_: list[Floats], codebook: Codebook) -> list[int]:
    scaled = codebook.scaled_values
    rows = [_candidates(local) for local in locals_]
    score = locals_[0][rows[0]]
    back = []
    for k in range(1, len(rows)):
        moves: Floats = INVERSION_CONTINUITY_WEIGHT * _moves(scaled, rows[k - 1], rows[k])
        through: Floats = score[:, None] + moves
        best = np.argmin(through, axis=0)
        back.append(best)
        score = through[best, np.arange(len(rows[k]))] + locals_[k][rows[k]]
    at = int(np.argmin(score))
    path = [int(rows[-1][at])]
    for k in range(len(rows) - 1, 0, -1):
        at = int(back[k - 1][at])
        path.append(int(rows[k - 1][at]))
    return path[::-1]


def invert_track(frames: Sequence[Sequence[float | None] | None], codebook: Codebook,
                 scale: ScaleLike = 1.0) -> list[int | None]:
    """The entry of every frame of a track (F1 to F3 per frame, or None), None where no tongue
    can be estimated; the cheapest path through each run of estimable frames."""
    out: list[int | None] = [None] * len(frames)
    run: list[tuple[int, Floats]] = []

    def close_run():
        if run:
            path = _path([local for _, local in run], codebook)
            for (index, _), entry in zip(run, path, strict=True):
                out[index] = entry
            run.clear()

    for index, formants in enumerate(frames):
        costs = acoustic_costs(formants, codebook, scale)
        if costs is None:
            close_run()
        else:
            run.append((index, costs + INVERSION_PRIOR_WEIGHT * codebook.prior))
    close_run()
    return out
