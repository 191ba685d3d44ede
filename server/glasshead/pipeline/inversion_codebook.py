"""Build step: the inversion's codebook, ``inversion-codebook.json``: poses of the head's vowel
space with the formants of their own tract, for ``acoustics.inversion`` and
``web/src/core/listen/inversion.js``.

The vowel space is spanned by *anchors*, the phoneme targets of the ten monophthongs with /ɹ/ and
/l/. Its poses are blends of anchors' parameters:

- every anchor alone;
- every pair, at 1/5 to 4/5 of the way from one to the other;
- blends of three anchors drawn at random (weights uniform on the simplex), up to
  ``ENTRY_COUNT`` poses in all, from a fixed seed, so that a build gives the same codebook.

Each entry names the anchors it blends, so that an inversion can keep to the vowels (a vowel's
formants can also be made by a tongue on its way to /l/, whose tip closes the tract and lowers
F1 with the dorsum low: with /l/ in the codebook, running speech's vowels were given low dorsums).

Each pose's formants are its tube's (``TractShape.acoustics``); its prior is its mean squared
distance, in each parameter's spread over the anchors, from its nearest anchor. ``group_scale``
maps a speaker group's formants onto the head's, one factor per formant: the geometric mean, over
the norms' vowels that are anchors, of the head's formant over the group's mean (Peterson and
Barney's norms, ``vowel-norms.json``). One factor for all three formants, a uniform
vocal-tract-length factor (Nordström and Lindblom 1975), put 89 % of Hillenbrand's vowels on the
right side, against 93 % with one per formant: a child's pharynx is shorter for its mouth than a
man's (Fitch and Giedd 1999), so its formants do not scale alike.
"""

import hashlib
import itertools
import json
import time
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from glasshead.asset_store import AssetStore
from glasshead.constants import (
    INVERSION_CODEBOOK_FILE,
    INVERSION_CODEBOOK_FORMAT_VERSION,
    VOWEL_NORMS_FILE,
)
from glasshead.flesh_point_assets import FLESH_POINT_ASSETS
from glasshead.pipeline.forked import forked_map
from glasshead.pipeline.outputs import current_output, write_json
from glasshead.tract_assets import TRACT_ASSETS, tract_shape

#: Bumped whenever the codebook is computed differently.
BUILDER = 1
#: The vowels whose targets span the vowel space, by IPA.
MONOPHTHONGS = ("i", "ɪ", "ɛ", "æ", "ʌ", "ɑ", "ɔ", "ʊ", "u", "ɝ")
#: The anchors: the monophthongs with the approximants the inversion also estimates.
ANCHORS = MONOPHTHONGS + ("ɹ", "l")
#: Shares of the way from one anchor to the other, for every pair.
PAIR_SHARES = (0.2, 0.4, 0.6, 0.8)
#: Poses in all: the anchors, the pairs, and blends of three to fill.
ENTRY_COUNT = 1500
#: The seed of the three-anchor blends.
SEED = 31
#: Parameters that vary by less than this over the anchors are fixed at the first anchor's value.
VARIES = 1e-9


def anchor_params(targets: Sequence[Mapping], anchors: Sequence[str] = ANCHORS
                  ) -> dict[str, dict[str, float]]:
    """{ipa: params} of the anchors among the phoneme targets' ``targets``."""
    by_ipa = {t["ipa"]: t["params"] for t in targets}
    missing = [ipa for ipa in anchors if ipa not in by_ipa]
    if missing:
        raise ValueError(f"the phoneme targets lack the anchors {', '.join(missing)}")
    return {ipa: dict(by_ipa[ipa]) for ipa in anchors}


def blend(params: Sequence[Mapping[str, float]], weights: Sequence[float] | np.ndarray
          ) -> dict[str, float]:
    """The weighted mean of poses (every pose has the same parameter names)."""
    names = list(params[0])
    values = np.array([[p[n] for n in names] for p in params], dtype=np.float64)
    return dict(zip(names, map(float, np.asarray(weights) @ values), strict=True))


def random_blends(anchors: Mapping[str, Mapping[str, float]], count: int,
                  rng: np.random.Generator, vowels: Sequence[str] = MONOPHTHONGS,
                  size: int = 3) -> list[tuple[dict[str, float], tuple[str, ...]]]:
    """``count`` (pose, the anchors it blends): blends of ``size`` distinct vowels' targets,
    weights uniform on the simplex."""
    out = []
    for _ in range(count):
        chosen = tuple(vowels[i] for i in rng.choice(len(vowels), size=size, replace=False))
        out.append((blend([anchors[v] for v in chosen], rng.dirichlet(np.ones(size))), chosen))
    return out


def random_vowel_poses(anchors: Mapping[str, Mapping[str, float]], count: int,
                       rng: np.random.Generator) -> list[dict[str, float]]:
    """``count`` random poses of the vowel space (blends of three monophthongs)."""
    return [pose for pose, _ in random_blends(anchors, count, rng)]


def codebook_poses(anchors: Mapping[str, Mapping[str, float]], count: int = ENTRY_COUNT,
                   seed: int = SEED) -> list[tuple[dict[str, float], tuple[str, ...]]]:
    """(pose, the anchors it blends): the anchors, every pair's blends at ``PAIR_SHARES`` and
    blends of three, ``count`` in all."""
    names = list(anchors)
    poses: list[tuple[dict[str, float], tuple[str, ...]]] = [(dict(anchors[n]), (n,))
                                                             for n in names]
    for first, second in itertools.combinations(names, 2):
        poses += [(blend([anchors[first], anchors[second]], [1 - s, s]), (first, second))
                  for s in PAIR_SHARES]
    rng = np.random.default_rng(seed)
    poses += random_blends(anchors, max(0, count - len(poses)), rng, vowels=names)
    return poses[:count]


def _formants(shape, pose: Mapping[str, float]) -> list[float]:
    return [float(f) for f in shape.acoustics(pose)["formants"][:3]]


def group_scales(anchor_formants: Mapping[str, Sequence[float]], norms: Mapping) -> dict:
    """{group: [F1, F2, F3 factors]} mapping each group's formants onto the head's (see the
    module)."""
    scales = {}
    for group, vowels in norms["groups"].items():
        shared = [v for v in vowels.values() if v["ipa"] in anchor_formants]
        if not shared:
            raise ValueError(f"the norms of {group} share no vowel with the anchors")
        scales[group] = [round(float(np.exp(np.mean(
            [np.log(anchor_formants[v["ipa"]][k] / v[f"f{k + 1}"]["mean"]) for v in shared]))), 5)
            for k in range(3)]
    return scales


def build_codebook(shape, anchors: Mapping[str, Mapping[str, float]], norms: Mapping,
                   count: int = ENTRY_COUNT) -> dict:
    """The codebook's document (without its source) for a TractShape and anchor poses."""
    blends = codebook_poses(anchors, count)
    poses = [pose for pose, _ in blends]
    index = {ipa: i for i, ipa in enumerate(anchors)}
    names = list(poses[0])
    matrix = np.array([[p[n] for n in names] for p in poses], dtype=np.float64)
    first = len(anchors)
    spread = matrix[:first].std(axis=0)
    varying = [i for i, s in enumerate(spread) if s > VARIES]
    values = matrix[:, varying]
    scaled = values / spread[varying]
    to_anchor = ((scaled[:, None, :] - scaled[None, :first, :]) ** 2).mean(axis=2)
    formants = np.array(forked_map(_formants, poses, shape))
    anchor_formants = {ipa: formants[i] for i, ipa in enumerate(anchors)}
    return {
        "parameters": [names[i] for i in varying],
        "fixed": {names[i]: round(float(matrix[0, i]), 6) for i in range(len(names))
                  if i not in varying},
        "spread": np.round(spread[varying], 6).tolist(),
        "anchors": list(anchors),
        "group_scale": group_scales(anchor_formants, norms),
        "count": len(poses),
        "entries": {"values": np.round(values, 5).tolist(),
                    "formants": np.round(formants, 2).tolist(),
                    "prior": np.round(to_anchor.min(axis=1), 6).tolist(),
                    "anchors": [sorted(index[a] for a in used) for _, used in blends]},
    }


def build_inversion_codebook(assets_dir: Path) -> tuple[dict, bool]:
    """(document, skipped): write the codebook unless it records the same inputs."""
    assets_dir = Path(assets_dir)
    store = AssetStore(assets_dir)
    names = ("phoneme_targets", *FLESH_POINT_ASSETS, *TRACT_ASSETS)
    norms_bytes = (assets_dir / VOWEL_NORMS_FILE).read_bytes()
    digest = hashlib.sha256("".join(store.entry(n).sha256 for n in names).encode()
                            + norms_bytes).hexdigest()
    path = assets_dir / INVERSION_CODEBOOK_FILE
    existing = current_output(path, digest, BUILDER, INVERSION_CODEBOOK_FORMAT_VERSION)
    if existing is not None:
        return existing, True
    started = time.perf_counter()
    anchors = anchor_params(store.get("phoneme_targets")["targets"])
    body = build_codebook(tract_shape(store), anchors, json.loads(norms_bytes))
    document = {"format_version": INVERSION_CODEBOOK_FORMAT_VERSION, "builder": BUILDER,
                "source": {"sha256": digest, "assets": list(names),
                           "norms": VOWEL_NORMS_FILE, "seed": SEED},
                **body, "build_seconds": round(time.perf_counter() - started, 1)}
    write_json(path, document)
    return document, False


def build_step(ctx) -> dict:
    """``glasshead build`` step: the codebook's size and the groups' formant scales."""
    document, skipped = build_inversion_codebook(ctx.assets_dir)
    return {"step": "inversion-codebook", "skipped": skipped, "entries": document["count"],
            "parameters": len(document["parameters"]), "group_scale": document["group_scale"]}
