"""Build step: vowel formant norms by speaker group, written to ``vowel-norms.json``.

The listening displays draw each vowel's target on the learner's vowel chart (F2 across, F1
down) from these norms until a calibration makes them personal. They are Peterson & Barney's
(1952) measurements of 10 American English vowels in /hVd/ words, two repetitions by each of
33 men, 28 women and 15 children: for each group and vowel, the mean and the standard deviation
of F0 and F1 to F3 (Hz) and the mean and covariance of (F1, F2) on a log scale, from which a
display draws an ellipse (formants spread in proportion to their size, so the log scale keeps
the ellipses alike across the chart).

The file (format version ``VOWEL_NORMS_FORMAT_VERSION``) holds ``groups``: {man, woman, child:
{vowel: {ipa, arpabet, n, f0, f1, f2, f3: {mean, sd}, log_f1_f2: {mean [2], cov [[2]]}}}} and
``source``. The step is skipped when the file records the same input and builder.
"""

import csv
import hashlib
import math
from pathlib import Path

import numpy as np

from glasshead.constants import VOWEL_NORMS_FILE, VOWEL_NORMS_FORMAT_VERSION, VOWEL_NORMS_VOWELS
from glasshead.pipeline.outputs import current_output, write_json
from glasshead.pipeline.sources import PETERSON_BARNEY

#: Bumped whenever the norms are computed differently.
BUILDER = 1
#: Peterson & Barney's speaker types, by the group names the listening kernels use.
GROUPS = {"m": "man", "w": "woman", "c": "child"}
MEASURES = ("f0", "f1", "f2", "f3")


class VowelNormsError(ValueError):
    """The measurements file is not what the step reads; the message names the row."""


def read_rows(path: Path) -> list[dict]:
    """The rows of pb1952.csv, numbers as floats; VowelNormsError naming a bad row."""
    rows = []
    with open(path, newline="", encoding="utf-8") as handle:
        for line, row in enumerate(csv.DictReader(handle), start=2):
            try:
                values = {m: float(row[m]) for m in MEASURES}
                kind, vowel, ipa = row["type"], row["vowel"], row["IPA"]
            except (KeyError, TypeError, ValueError) as exc:
                raise VowelNormsError(f"{path}, line {line}: {exc!r}") from None
            if kind not in GROUPS or vowel not in VOWEL_NORMS_VOWELS:
                raise VowelNormsError(f"{path}, line {line}: unknown speaker type or vowel "
                                      f"{kind!r}, {vowel!r}")
            if not all(math.isfinite(v) and v > 0 for v in values.values()):
                raise VowelNormsError(f"{path}, line {line}: a measure is not a positive number")
            rows.append({"type": kind, "vowel": vowel, "ipa": ipa, **values})
    return rows


def norms(rows: list[dict]) -> dict:
    """{group: {vowel: entry}} as the module docstring describes."""
    out: dict[str, dict] = {}
    for code, group in GROUPS.items():
        out[group] = {}
        for vowel in VOWEL_NORMS_VOWELS:
            mine = [r for r in rows if r["type"] == code and r["vowel"] == vowel]
            if len(mine) < 3:
                raise VowelNormsError(f"too few {group} tokens of {vowel!r}: {len(mine)}")
            # Their codes are ARPAbet in lower case.
            entry: dict = {"ipa": mine[0]["ipa"], "arpabet": vowel.upper(), "n": len(mine)}
            for m in MEASURES:
                values = np.array([r[m] for r in mine])
                entry[m] = {"mean": round(float(values.mean()), 1),
                            "sd": round(float(values.std(ddof=1)), 1)}
            logs = np.log([[r["f1"], r["f2"]] for r in mine])
            entry["log_f1_f2"] = {"mean": [round(float(v), 5) for v in logs.mean(axis=0)],
                                  "cov": [[round(float(v), 6) for v in row]
                                          for row in np.cov(logs.T)]}
            out[group][vowel] = entry
    return out


def build_vowel_norms(data_dir, assets_dir) -> tuple[dict, bool]:
    """Write the norms unless the file records the same input; returns (document, skipped)."""
    source = Path(data_dir) / PETERSON_BARNEY
    digest = hashlib.sha256(source.read_bytes()).hexdigest()
    out = Path(assets_dir) / VOWEL_NORMS_FILE
    existing = current_output(out, digest, BUILDER, VOWEL_NORMS_FORMAT_VERSION)
    if existing is not None:
        return existing, True
    document = {"format_version": VOWEL_NORMS_FORMAT_VERSION, "builder": BUILDER,
                "source": {"sha256": digest, "file": str(PETERSON_BARNEY),
                           "cite": "Peterson, G. E. & Barney, H. L. (1952). Control methods "
                                   "used in a study of the vowels. JASA 24(2):175-184."},
                "groups": norms(read_rows(source))}
    write_json(out, document)
    return document, False


def build_step(ctx) -> dict:
    """``glasshead build`` step: the count of vowels per group."""
    document, skipped = build_vowel_norms(ctx.data_dir, ctx.assets_dir)
    return {"step": "vowel-norms", "skipped": skipped,
            "vowels": {group: len(v) for group, v in document["groups"].items()}}
