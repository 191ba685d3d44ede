"""inversion.json: a small codebook and tracks of formants through the inversion, with the entry
each frame is given, live and over the whole track.

pytest (tests/test_inversion.py) checks that the file is what this module makes, and
``tests/js/inversion.test.js`` that the JavaScript twin makes the same choices. The codebook is
made here, not read from the build, so that the vectors stay put when the head changes: a 7 x 7
grid of two parameters whose formants are smooth functions of them, with three anchors at three
corners and the grid's middle row blending the first two.
"""

import numpy as np

from glasshead.acoustics.inversion import (
    codebook_from_document,
    invert_frame,
    invert_track,
    keep_to,
)
from glasshead.constants import (
    INVERSION_CANDIDATES,
    INVERSION_CONTINUITY_WEIGHT,
    INVERSION_FORMANT_SD,
    INVERSION_PRIOR_WEIGHT,
    INVERSION_REJECT_COST,
)
from glasshead.vectors.common import case, document

NAME = "inversion.json"
FORMAT_VERSION = 1
#: The grid's steps along each parameter.
STEPS = 7
SEED = 7


def _formants(a, b):
    return [300.0 + 70.0 * a, 900.0 + 180.0 * b + 30.0 * a, 2300.0 + 40.0 * a - 25.0 * b]


def codebook_document() -> dict:
    """The hand-made codebook, in the layout of ``inversion-codebook.json``."""
    grid = [(float(a), float(b)) for a in range(STEPS) for b in range(STEPS)]
    corners = {"i": (0.0, 6.0), "u": (0.0, 0.0), "a": (6.0, 3.0)}
    values = np.array(grid)
    spread = np.array([list(c) for c in corners.values()]).std(axis=0)
    anchors_scaled = np.array(list(corners.values())) / spread
    prior = (((values / spread)[:, None, :] - anchors_scaled[None]) ** 2).mean(axis=2).min(axis=1)
    names = list(corners)
    blends = []
    for a, b in grid:
        alone = [k for k, c in enumerate(corners.values()) if c == (a, b)]
        blends.append(alone if alone else [0, 1] if a == 0.0 else [0, 1, 2])
    return {"parameters": ["height", "front"], "fixed": {"jaw_opening": 2.0},
            "spread": spread.tolist(), "anchors": names,
            "group_scale": {"man": [1.0, 1.0, 1.0], "child": [0.75, 0.8, 0.78]},
            "entries": {"values": values.tolist(),
                        "formants": [_formants(a, b) for a, b in grid],
                        "prior": prior.tolist(), "anchors": blends}}


def _tracks(rng):
    glide = [_formants(0.5 + 0.4 * k, 5.5 - 0.45 * k) for k in range(12)]
    noisy = [[f * (1 + rng.normal(0, 0.02)) for f in frame] for frame in glide]
    child = [[f / s for f, s in zip(frame, (0.75, 0.8, 0.78), strict=True)] for frame in glide]
    with_gaps: list[list | None] = list(noisy)
    with_gaps[4] = None
    with_gaps[5] = [400.0, None, 2400.0]
    with_gaps[8] = [90.0, 300.0, 9000.0]  # nothing the codebook can make
    return [("a glide from near /i/ toward /a/, 2 % noise", noisy, None, None),
            ("the same with a silent frame, a frame without F2 and one out of reach", with_gaps,
             None, None),
            ("the glide as a child says it, scaled back by the child's factors", child, "child",
             None),
            ("the noisy glide kept to the entries blending only /i/ and /u/", noisy, None,
             ["i", "u"])]


def build_document():
    source = codebook_document()
    full = codebook_from_document(source)
    cases = []
    for description, frames, group, kept in _tracks(np.random.default_rng(SEED)):
        codebook = keep_to(full, kept) if kept else full
        scale = codebook.scale(group)
        live, previous = [], None
        for frame in frames:
            entry = invert_frame(frame, codebook, scale, previous)
            live.append(entry)
            previous = entry if entry is not None else previous
        cases.append(case(description,
                          {"frames": frames, "group": group, "keep_to": kept},
                          {"live": live, "track": invert_track(frames, codebook, scale),
                           "kept_entries": len(codebook.values)}))
    return document(
        NAME, "A hand-made codebook (a grid of two parameters with smooth formants, three "
              "anchors) and tracks of F1 to F3 (Hz; null for a frame without them): each "
              "frame's entry live (given the frame before's, the last estimated one) and over "
              "the whole track; null where no tongue is estimated. With a group, the frames "
              "are scaled by its factors; with keep_to, only the entries blending those "
              "anchors are searched, and entries are numbered among them",
        FORMAT_VERSION, cases,
        constants={"formant_sd": list(INVERSION_FORMANT_SD), "prior_weight": INVERSION_PRIOR_WEIGHT,
                   "continuity_weight": INVERSION_CONTINUITY_WEIGHT,
                   "candidates": INVERSION_CANDIDATES, "reject_cost": INVERSION_REJECT_COST},
        fixtures={"codebook": source})


def files():
    return {NAME: build_document()}
