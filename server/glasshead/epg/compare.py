"""Compare two EPG sequences: electrode-by-electrode agreement and index differences per frame.

The first sequence (the "recording") sets the frames and times of the report. The second (the
"reference": a synthetic EPG of a target, or another recording) is brought onto those times:
- one reference frame (a static target) stands for every frame;
- otherwise reference frames are held from their own time until the next (sample and hold), on
  times measured from each sequence's first frame, so a take and a target line up at their
  starts whatever their absolute clocks or frame rates.

The raw agreement (the share of the 62 electrodes on or off in both) is mostly won by electrodes
that are off on both sides: a target with no contact at all agrees on 59 % of the electrodes of
the real s->k take sp1bescan (mean over its frames), 53 % at its fullest /k/ closure.
So two figures that an empty palatogram cannot win stand beside it, per frame:
- Cohen's kappa (Cohen 1960): (p_o - p_e) / (1 - p_e), the agreement beyond what the two
  contact shares would give by chance, p_e = p_a p_b + (1 - p_a)(1 - p_b). An empty side scores 0
  against anything but another empty frame; identical frames score 1 (also where kappa is 0/0:
  both empty or both full).
- contact agreement: electrodes on in both over electrodes on in either (Jaccard); 1 when
  neither has a contact.
"""

from dataclasses import dataclass

import numpy as np

from glasshead.constants import (
    EPG_CELLS,
    EPG_COLUMNS,
    EPG_COMPARE_BOTH_OFF,
    EPG_COMPARE_BOTH_ON,
    EPG_COMPARE_NO_ELECTRODE,
    EPG_COMPARE_ONLY_RECORDING,
    EPG_COMPARE_ONLY_REFERENCE,
    EPG_ELECTRODES,
    EPG_MISSING_CELLS,
    EPG_ROWS,
)
from glasshead.epg.indices import INDEX_SLOTS, as_frames, index_table

#: Per-electrode codes in ``Comparison.codes``.
BOTH_OFF, BOTH_ON = EPG_COMPARE_BOTH_OFF, EPG_COMPARE_BOTH_ON
ONLY_RECORDING, ONLY_REFERENCE = EPG_COMPARE_ONLY_RECORDING, EPG_COMPARE_ONLY_REFERENCE
NO_ELECTRODE = EPG_COMPARE_NO_ELECTRODE
#: Indices whose per-frame difference is reported (the percentages carry the counts).
COMPARED_INDICES = ("percent", "alveolar_percent", "palatal_percent", "velar_percent",
                    "cog", "anteriority", "centrality", "dorsopalatal")

_HAS_ELECTRODE = np.ones(EPG_CELLS, dtype=bool)
_HAS_ELECTRODE[list(EPG_MISSING_CELLS)] = False


@dataclass
class Comparison:
    """Agreement of a recording with a reference on the recording's frames.

    ``codes`` (n, 8, 8) uint8: per electrode BOTH_OFF, BOTH_ON, ONLY_RECORDING or ONLY_REFERENCE
    (NO_ELECTRODE at the R1 corners). ``agreement`` (n,): fraction of the 62 electrodes that
    agree. ``kappa`` (n,): Cohen's kappa of the two frames over the 62 electrodes.
    ``contact_agreement`` (n,): electrodes on in both over electrodes on in either.
    ``electrode_agreement`` (8, 8): fraction of frames in which each electrode agrees (NaN
    at the R1 corners). ``recording_indices`` / ``reference_indices`` / ``index_difference``:
    name -> (n,) (recording minus reference). ``reference_frame`` (n,) int: which reference frame
    was used for each recording frame.
    """

    t_s: np.ndarray
    codes: np.ndarray
    agreement: np.ndarray
    electrode_agreement: np.ndarray
    recording_indices: dict
    reference_indices: dict
    index_difference: dict
    reference_frame: np.ndarray
    kappa: np.ndarray
    contact_agreement: np.ndarray

    def summary(self) -> dict:
        """Whole-recording figures: mean agreement, kappa and contact agreement, and mean/max
        absolute index differences."""
        return {
            "mean_agreement": float(self.agreement.mean()),
            "min_agreement": float(self.agreement.min()),
            "mean_kappa": float(self.kappa.mean()),
            "mean_contact_agreement": float(self.contact_agreement.mean()),
            "identical_frames": int((self.agreement == 1.0).sum()),
            "mean_abs_difference": {k: float(np.abs(v).mean())
                                    for k, v in self.index_difference.items()},
            "max_abs_difference": {k: float(np.abs(v).max())
                                   for k, v in self.index_difference.items()},
        }


def align_reference(t_s: np.ndarray, ref_t_s: np.ndarray | None, n_ref: int) -> np.ndarray:
    """Which reference frame stands for each recording frame: ``(n,)`` int.

    ``t_s`` (n,) recording times; ``ref_t_s`` (m,) reference times, or None when m == 1 or the
    reference has exactly one frame per recording frame.
    """
    n = len(t_s)
    if n_ref == 1:
        return np.zeros(n, dtype=np.int64)
    if ref_t_s is None:
        if n_ref != n:
            raise ValueError(f"reference has {n_ref} frames for {n} recording frames and no "
                             "times to align them by")
        return np.arange(n)
    ref_t_s = np.asarray(ref_t_s, dtype=np.float64)
    if ref_t_s.shape != (n_ref,):
        raise ValueError(f"reference has {ref_t_s.size} times for {n_ref} frames")
    if (np.diff(ref_t_s) <= 0).any():
        raise ValueError("reference times must be strictly increasing")
    relative = np.asarray(t_s) - t_s[0]
    ref_relative = ref_t_s - ref_t_s[0]
    # a tolerance of a microsecond keeps float noise from stepping back a frame
    held = np.searchsorted(ref_relative, relative + 1e-6, side="right") - 1
    return np.clip(held, 0, n_ref - 1)


def agreement_beyond_chance(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(kappa (n,), contact agreement (n,)) of contact frames ``a`` and ``b`` (n, k) bool, over
    their k electrodes; see the module docstring."""
    k = a.shape[1]
    on_a = a.sum(axis=1) / k
    on_b = b.sum(axis=1) / k
    observed = (a == b).sum(axis=1) / k
    chance = on_a * on_b + (1 - on_a) * (1 - on_b)
    # chance == 1 only when both frames are empty or both full, and then they are identical
    undefined = chance >= 1.0
    kappa = np.where(undefined, 1.0, (observed - chance) / np.where(undefined, 1.0, 1 - chance))
    both = (a & b).sum(axis=1)
    either = (a | b).sum(axis=1)
    contact = np.where(either == 0, 1.0, both / np.maximum(either, 1))
    return kappa, contact


def compare(frames, t_s, ref_frames, ref_t_s=None) -> Comparison:
    """Compare a recording ``frames`` (n, 8, 8) at ``t_s`` (n,) with ``ref_frames`` (m, 8, 8).

    See the module docstring for how the reference is aligned; ``ref_t_s`` (m,) is needed when
    1 < m and m != n.
    """
    frames = as_frames(frames)
    ref_frames = as_frames(ref_frames)
    t_s = np.asarray(t_s, dtype=np.float64)
    if t_s.shape != (len(frames),):
        raise ValueError(f"{t_s.size} times for {len(frames)} frames")
    which = align_reference(t_s, ref_t_s, len(ref_frames))
    aligned = ref_frames[which]

    a = frames.reshape(len(frames), EPG_CELLS).astype(bool)
    b = aligned.reshape(len(frames), EPG_CELLS).astype(bool)
    codes = np.where(a & b, BOTH_ON, np.where(a, ONLY_RECORDING,
                                              np.where(b, ONLY_REFERENCE, BOTH_OFF)))
    codes[:, ~_HAS_ELECTRODE] = NO_ELECTRODE
    agree = (a == b) & _HAS_ELECTRODE
    agreement = agree.sum(axis=1) / EPG_ELECTRODES
    kappa, contact = agreement_beyond_chance(a[:, _HAS_ELECTRODE], b[:, _HAS_ELECTRODE])
    per_electrode = agree.mean(axis=0)
    per_electrode[~_HAS_ELECTRODE] = np.nan

    mine = index_table(frames)
    theirs = index_table(ref_frames)[which]
    slot = {name: i for i, name in enumerate(INDEX_SLOTS)}
    recording_indices = {k: mine[:, slot[k]] for k in COMPARED_INDICES}
    reference_indices = {k: theirs[:, slot[k]] for k in COMPARED_INDICES}
    return Comparison(
        t_s=t_s,
        codes=codes.reshape(-1, EPG_ROWS, EPG_COLUMNS).astype(np.uint8),
        agreement=agreement,
        electrode_agreement=per_electrode.reshape(EPG_ROWS, EPG_COLUMNS),
        recording_indices=recording_indices,
        reference_indices=reference_indices,
        index_difference={k: recording_indices[k] - reference_indices[k]
                          for k in COMPARED_INDICES},
        reference_frame=which,
        kappa=kappa,
        contact_agreement=contact,
    )


def phone_scores(comparison: Comparison, spans) -> tuple[list[dict], dict]:
    """Per phone (``spans``: (symbol, start_s, end_s) on the recording's clock, from its first
    frame): its frames and the means of agreement, kappa and contact agreement over them (None
    without frames); and the means over the phones that have frames, with their count."""
    relative = comparison.t_s - comparison.t_s[0]
    rows = []
    for symbol, start, end in spans:
        inside = (relative >= start - 1e-9) & (relative < end - 1e-9)
        n = int(inside.sum())
        rows.append({"symbol": symbol, "start_s": float(start), "end_s": float(end), "frames": n,
                     **{key: float(values[inside].mean()) if n else None
                        for key, values in (("mean_agreement", comparison.agreement),
                                            ("mean_kappa", comparison.kappa),
                                            ("mean_contact_agreement",
                                             comparison.contact_agreement))}})
    scored = [r for r in rows if r["frames"]]
    overall: dict = {key: float(np.mean([r[key] for r in scored])) if scored else None
                     for key in ("mean_agreement", "mean_kappa", "mean_contact_agreement")}
    overall["phones_scored"] = len(scored)
    return rows, overall
