"""Whether a short calibration (the learner's own "heed", "who'd" and "hod") would make the vowel
chart's targets personal: measured on Hillenbrand et al.'s (1995) talkers with the authors' own
steady-state F1 and F2, against the Peterson & Barney norms the chart draws (vowel-norms.json).

For each talker, every vowel but the three of the calibration is placed on the chart of the
talker's group, and scored by the chart's own measure (the Mahalanobis distance in log F1, log
F2, as web/src/ui/listen/listenScales.js ``normDistance``): is its nearest norm its own vowel,
and is it within the "in" and "near" zones of its own (``IN_TARGET``, ``NEAR_TARGET``). Three
charts:

- the group's norms as they are;
- shifted: every norm moved by the talker's mean log formants over /i u ɑ/ minus the norms'
  (Nearey's log-mean, from three tokens);
- mapped: the affine map of log (F1, F2) that takes the norms' /i u ɑ/ onto the talker's tokens
  exactly, applied to every mean and covariance.

Both calibrations place fewer vowels nearest their own norm than the plain norms, in every
group: three single tokens carry a talker's token-to-token scatter and their dialect's /ɑ/
(Michigan's is fronted, nearer /ʌ/) into every target. docs/listening.md gives the table.
"""

import json
import re
from pathlib import Path

import numpy as np
import pytest

#: Hillenbrand's vowel codes -> Peterson & Barney's (the norms'), for the 10 vowels both have.
TO_NORMS = {"iy": "iy", "ih": "ih", "eh": "eh", "ae": "ae", "ah": "aa", "aw": "ao", "uh": "ah",
            "oo": "uh", "uw": "uw", "er": "er"}
GROUPS = {"m": "man", "w": "woman", "b": "child", "g": "child"}
#: The calibration's words: heed, who'd, hod.
CALIBRATION = ("iy", "uw", "ah")
SCALES = Path(__file__).parents[1] / "web" / "src" / "ui" / "listen" / "listenScales.js"


def page_constant(name: str) -> float:
    """A number the chart's code exports (the zones), read from it so that both agree."""
    found = re.search(rf"export const {name} = ([\d.]+);", SCALES.read_text())
    assert found, f"{SCALES} no longer exports {name} as a number"
    return float(found.group(1))


IN_ZONE, NEAR_ZONE = page_constant("IN_TARGET"), page_constant("NEAR_TARGET")


@pytest.fixture(scope="module")
def talkers(data_dir) -> dict:
    """talker -> {"group": name, vowel code: (F1, F2)} from vowdata.dat's steady states."""
    path = data_dir / "speech" / "hillenbrand1995-dev" / "vowdata.dat"
    if not path.is_file():
        pytest.fail(f"Hillenbrand's measurements missing: expected {path}")
    out: dict = {}
    for line in path.read_text().splitlines():
        fields = line.split()
        if len(fields) < 5 or len(fields[0]) != 5 or fields[0][0] not in GROUPS:
            continue
        name, f1, f2 = fields[0], float(fields[3]), float(fields[4])
        if f1 > 0 and f2 > 0:
            out.setdefault(name[:3], {"group": GROUPS[name[0]]})[name[3:]] = (f1, f2)
    return {k: v for k, v in out.items() if all(c in v for c in CALIBRATION)}


@pytest.fixture(scope="module")
def norms(built_assets) -> dict:
    document = json.loads((built_assets / "vowel-norms.json").read_text())
    return {group: {code: entry["log_f1_f2"] for code, entry in vowels.items()}
            for group, vowels in document["groups"].items()}


def distance(point, norm) -> float:
    d = np.asarray(point) - np.asarray(norm["mean"])
    return float(np.sqrt(d @ np.linalg.solve(np.asarray(norm["cov"]), d)))


def shifted(norms: dict, talker: dict) -> dict:
    tokens = np.log([talker[c] for c in CALIBRATION])
    corners = np.array([norms[TO_NORMS[c]]["mean"] for c in CALIBRATION])
    shift = tokens.mean(axis=0) - corners.mean(axis=0)
    return {v: {"mean": np.asarray(n["mean"]) + shift, "cov": n["cov"]} for v, n in norms.items()}


def mapped(norms: dict, talker: dict) -> dict:
    tokens = np.log([talker[c] for c in CALIBRATION])
    corners = np.array([norms[TO_NORMS[c]]["mean"] for c in CALIBRATION])
    solution = np.linalg.solve(np.c_[corners, np.ones(3)], tokens)  # (3, 2): [A^T; b]
    a, b = solution[:2].T, solution[2]
    return {v: {"mean": a @ np.asarray(n["mean"]) + b, "cov": a @ np.asarray(n["cov"]) @ a.T}
            for v, n in norms.items()}


def scores(talkers: dict, norms: dict, calibrate) -> dict:
    """group -> (tokens, % nearest their own norm, % in its zone, % near it or in)."""
    results: dict = {}
    for talker in talkers.values():
        chart = calibrate(norms[talker["group"]], talker)
        for code, formants in talker.items():
            if code == "group" or code in CALIBRATION or code not in TO_NORMS:
                continue
            point = np.log(formants)
            own = distance(point, chart[TO_NORMS[code]])
            nearest = min(chart, key=lambda v: distance(point, chart[v]))
            results.setdefault(talker["group"], []).append(
                (nearest == TO_NORMS[code], own <= IN_ZONE, own <= NEAR_ZONE))
    return {group: (len(rows), *(100.0 * np.mean([row[k] for row in rows]) for k in range(3)))
            for group, rows in results.items()}


def test_the_affine_calibration_takes_the_norms_corners_onto_the_talkers_own(talkers, norms):
    talker = next(iter(talkers.values()))
    chart = mapped(norms[talker["group"]], talker)
    for code in CALIBRATION:
        np.testing.assert_allclose(chart[TO_NORMS[code]]["mean"], np.log(talker[code]),
                                   atol=1e-9)


def test_a_calibration_from_three_corner_vowels_places_fewer_vowels_nearest_their_own(
        talkers, norms):
    plain = scores(talkers, norms, lambda group_norms, _: group_norms)
    by_shift = scores(talkers, norms, shifted)
    by_map = scores(talkers, norms, mapped)
    print("\ngroup: tokens, % nearest own / in zone / near  (norms | shifted | mapped)")
    for group in sorted(plain):
        print(f"{group}: {plain[group][0]}, " + " | ".join(
            "{:.1f} / {:.1f} / {:.1f}".format(*table[group][1:])
            for table in (plain, by_shift, by_map)))
    assert sum(n for n, *_ in plain.values()) > 300  # every group, 48 talkers
    for group in plain:
        assert by_shift[group][1] < plain[group][1], group
        assert by_map[group][1] < plain[group][1], group
