"""The tongue from the voice (glasshead.acoustics.inversion) with the built codebook
(pipeline.inversion_codebook): the shared vectors; a round trip through the head's own voice;
Hillenbrand's vowels on the right side of the mouth; the HPRC speakers' dorsum; and no tongue
for silence, noise or a fricative.

Listening is by the listening kernels (``scripts/measure.mjs``), as the browser listens.
"""

import csv
import json
import math

import numpy as np
import pytest

from glasshead.acoustics import inversion
from glasshead.constants import INVERSION_CODEBOOK_FILE
from glasshead.ema.hprc import read_hprc
from glasshead.geometry.flesh_points import midline_outline
from glasshead.pipeline.inversion_codebook import (
    MONOPHTHONGS,
    anchor_params,
    random_vowel_poses,
)
from glasshead.settings import get_settings
from glasshead.speech import tract_voice
from glasshead.speech.audio import write_wav
from glasshead.vectors.inversion import build_document
from listening_support import GROUP_OF_KIND, measure_hops, require
from vector_support import assert_generated, read_vectors

#: Random vowel poses of the round trip (issue 31: 200), each held this many 10 ms frames.
ROUND_TRIP_POSES = 200
HOLD_FRAMES = 5
#: Median tongue-surface error of the round trip, mm (measured: 1.21).
ROUND_TRIP_MM = 2.0
#: Share of Hillenbrand's tokens whose inverted tongue is on the right side (measured: 94.0 %).
RIGHT_SIDE_SHARE = 0.90
#: Hillenbrand's vowels by side (their codes: ah is /ɑ/, aw /ɔ/, oo /ʊ/, oa /o/).
FRONT, BACK = {"iy", "ih", "ei", "eh", "ae"}, {"uw", "oo", "oa", "aw", "ah"}
HIGH, LOW = {"iy", "ih", "uw", "oo"}, {"ae", "ah", "aw"}
#: The correlation the issue asks of the HPRC dorsum (measured: see the test).
HPRC_DORSUM_R = 0.7
ARPABET_VOWELS = {"AA", "AE", "AH", "AO", "AW", "AY", "EH", "ER", "EY", "IH", "IY", "OW", "OY",
                  "UH", "UW"}


@pytest.fixture(scope="module")
def codebook(built_assets):
    document = json.loads((built_assets / INVERSION_CODEBOOK_FILE).read_text())
    return inversion.codebook_from_document(document)


@pytest.fixture(scope="module")
def vowels(codebook):
    return inversion.keep_to(codebook, MONOPHTHONGS)


@pytest.fixture(scope="module")
def anchors(built_store):
    return anchor_params(built_store.get("phoneme_targets")["targets"])


def test_the_vectors_are_what_the_generator_writes():
    vectors = read_vectors("inversion.json")
    assert_generated("inversion.json", build_document(), vectors)


def test_an_unknown_group_or_anchor_is_named(codebook):
    with pytest.raises(ValueError, match="teenager"):
        codebook.scale("teenager")
    with pytest.raises(ValueError, match="ø"):
        inversion.keep_to(codebook, ["i", "ø"])
    assert np.array_equal(codebook.scale("head"), np.ones(3))


def test_the_codebook_keeps_its_anchors_and_a_childs_formants_scale_down(codebook, anchors):
    for ipa, params in anchors.items():
        pose = codebook.pose(codebook.anchor_entry(ipa))
        assert all(pose[k] == pytest.approx(v, abs=1e-4) for k, v in params.items()), ipa
    man, child = codebook.scale("man"), codebook.scale("child")
    assert np.all(child < man) and np.all(child > 0.6), (man, child)


def _outline(rig, params):
    return midline_outline(rig, rig.values_clipped(params))


def test_random_vowel_poses_said_by_the_tract_voice_are_found_again(head_tract, vowels,
                                                                    anchors, tmp_path):
    """Issue 31: 200 random vowel poses, synthesised, measured and inverted: the tongue's
    mid-sagittal outline within 2 mm (mean point distance) at the median. Control: the same
    poses matched to one another's formants (shuffled) are far off."""
    poses = random_vowel_poses(anchors, ROUND_TRIP_POSES, np.random.default_rng(2026))
    frames = [area for pose in poses for area in [head_tract.area_function(pose)] * HOLD_FRAMES]
    seconds = len(frames) / 100.0
    samples, rate = tract_voice.synthesize(
        tract_voice.tubes_of_frames(frames), 100.0,
        [{"symbol": "AA", "stress": 1, "start_s": 0.0, "end_s": seconds}])
    write_wav(tmp_path / "vowels.wav", samples, rate)
    hops = measure_hops(tmp_path / "vowels.wav", "man")
    times = np.array([h["t"] for h in hops])
    rig = head_tract.tongue
    errors, shuffled = [], []
    order = np.random.default_rng(1).permutation(len(poses))
    measured = []
    for k in range(len(poses)):
        # The middle of each held pose: its first frames still move from the one before.
        start_s = k * HOLD_FRAMES / 100
        inside = (times >= start_s + 0.3 * HOLD_FRAMES / 100) \
            & (times <= start_s + 0.75 * HOLD_FRAMES / 100)
        found = [f for h, keep in zip(hops, inside, strict=True) if keep
                 for f in [inversion.estimable_formants(h)] if f is not None]
        assert found, f"pose {k}: no voiced hop with F1 to F3"
        measured.append(np.median(found, axis=0))
    for k, pose in enumerate(poses):
        entry = inversion.invert_frame(measured[k], vowels)
        other = inversion.invert_frame(measured[order[k]], vowels)
        assert entry is not None and other is not None, k
        truth = _outline(rig, pose)
        errors.append(np.linalg.norm(truth - _outline(rig, vowels.pose(entry)), axis=1).mean())
        shuffled.append(np.linalg.norm(truth - _outline(rig, vowels.pose(other)), axis=1).mean())
    median = float(np.median(errors))
    assert median <= ROUND_TRIP_MM, f"median {median:.2f} mm, 90th {np.percentile(errors, 90):.2f}"
    assert np.median(shuffled) > 2 * median, (np.median(shuffled), median)


def _tongue_top(rig, params):
    outline = _outline(rig, params)
    return outline[np.argmax(outline[:, 1])]


def _hillenbrand_rows():
    folder = require(get_settings().data_dir / "speech" / "hillenbrand1995-dev")
    with (folder / "tokens.csv").open(newline="") as handle:
        return list(csv.DictReader(handle))


def _right_sides(rows, vowels, rig, labels):
    """Per token that has a side: is its inverted tongue's highest point on its side?"""
    top = {ipa: _tongue_top(rig, vowels.pose(vowels.anchor_entry(ipa)))
           for ipa in ("i", "ɪ", "ɛ", "æ", "u", "ʊ", "ɔ", "ɑ")}
    # Between the head's own front and back targets, and its high and low ones.
    front_x = (np.mean([top[v][0] for v in ("i", "ɪ", "ɛ", "æ")])
               + np.mean([top[v][0] for v in ("u", "ʊ", "ɔ", "ɑ")])) / 2
    high_y = (np.mean([top[v][1] for v in ("i", "ɪ", "u", "ʊ")])
              + np.mean([top[v][1] for v in ("æ", "ɑ", "ɔ")])) / 2
    results = []
    for row, vowel in zip(rows, labels, strict=True):
        if vowel not in FRONT | BACK | HIGH | LOW:
            continue
        formants = [float(row[k]) if row[k] else math.nan for k in ("F1_ss", "F2_ss", "F3_ss")]
        entry = inversion.invert_frame(formants, vowels,
                                       vowels.scale(GROUP_OF_KIND[row["file"][0]]))
        if entry is None:
            results.append(False)
            continue
        x, y = _tongue_top(rig, vowels.pose(entry))
        results.append((vowel not in FRONT or x > front_x) and (vowel not in BACK or x < front_x)
                       and (vowel not in HIGH or y > high_y) and (vowel not in LOW or y < high_y))
    return results


def test_hillenbrands_vowels_put_the_tongue_on_the_right_side(head_tract, vowels):
    """Issue 31: the inverted tongue of each of Hillenbrand et al.'s (1995) vowels, children
    included, from the authors' steady-state F1 to F3 and the group's scale: front or back,
    high or low, as the vowel is, in at least 90 % of tokens. Control: the labels shuffled."""
    rows = _hillenbrand_rows()
    labels = [r["vowel"] for r in rows]
    right = _right_sides(rows, vowels, head_tract.tongue, labels)
    share = float(np.mean(right))
    by_group = {g: float(np.mean([ok for r, ok in zip(
        [r for r in rows if r["vowel"] in FRONT | BACK | HIGH | LOW], right, strict=True)
        if GROUP_OF_KIND[r["file"][0]] == g])) for g in ("man", "woman", "child")}
    assert len(right) >= 400
    assert share >= RIGHT_SIDE_SHARE, (share, by_group)
    assert min(by_group.values()) >= 0.8, by_group
    shuffled = list(np.random.default_rng(3).permutation(labels))
    assert np.mean(_right_sides(rows, vowels, head_tract.tongue, shuffled)) < 0.6


def _hprc_dorsum_pairs(vowels, flesh):
    """{speaker: (inverted dorsum heights, measured TR heights)} over the voiced hops in the
    middle half of every vowel of the HPRC utterances."""
    folder = require(get_settings().data_dir / "ema" / "hprc")
    pairs: dict[str, tuple[list, list]] = {}
    for csv_path in sorted(folder.glob("*_ema.csv")):
        recording = read_hprc(csv_path)
        group = "woman" if recording.name.startswith("F") else "man"
        hops = measure_hops(csv_path.with_name(f"{recording.name}.wav"), group)
        times = np.array([h["t"] for h in hops])
        path = inversion.invert_track([inversion.estimable_formants(h) for h in hops], vowels,
                                      vowels.scale(group))
        measured = recording.sensors["tongue_dorsum"][:, 2]
        ours, theirs = pairs.setdefault(recording.name[:3], ([], []))
        for phone in recording.phones:
            if phone.symbol not in ARPABET_VOWELS:
                continue
            quarter = (phone.end_s - phone.start_s) / 4
            for k in np.flatnonzero((times >= phone.start_s + quarter)
                                    & (times <= phone.end_s - quarter)):
                if path[k] is not None:
                    ours.append(flesh.frame(vowels.pose(path[k]))["tongue_dorsum"][1])
                    theirs.append(float(np.interp(times[k], recording.t_s, measured)))
    return pairs


@pytest.fixture(scope="module")
def hprc_correlations(head_tract, vowels):
    pairs = _hprc_dorsum_pairs(vowels, head_tract.flesh)
    return {speaker: (len(ours), float(np.corrcoef(ours, theirs)[0, 1]))
            for speaker, (ours, theirs) in pairs.items()}


def test_the_hprc_vowels_are_inverted_for_every_speaker(hprc_correlations):
    assert set(hprc_correlations) == {"F01", "M01", "M04"}
    assert all(count >= 20 for count, _ in hprc_correlations.values()), hprc_correlations


@pytest.mark.xfail(strict=True, reason=(
    "known shortfall (issue 31): the inverted dorsum's height follows the HPRC speakers' TR "
    "sensor at r = 0.39 (F01), -0.47 (M01) and 0.46 (M04) over the vowels' voiced hops; the "
    "measured F1 alone gives -0.55 to -0.79 but 0.0 for M01, and the head's dorsum point "
    "(40 mm behind the apex) follows F1 at only r = -0.41 over the codebook"))
def test_the_inverted_dorsum_follows_the_hprc_speakers_dorsum(hprc_correlations):
    assert all(r >= HPRC_DORSUM_R for _, r in hprc_correlations.values()), hprc_correlations


def test_silence_noise_and_a_fricative_get_no_tongue(head_tract, built_store, vowels, tmp_path):
    rate = 16000
    rng = np.random.default_rng(5)
    quiet = np.zeros(rate // 2)
    noise = rng.normal(0, 0.3, rate // 2)
    phones = [{"symbol": "S", "stress": 0, "start_s": 0.0, "end_s": 0.5}]
    target = next(t for t in built_store.get("phoneme_targets")["targets"] if t["ipa"] == "s")
    areas = [head_tract.area_function(target["params"])] * 50
    hiss, hiss_rate = tract_voice.synthesize(
        tract_voice.tubes_of_frames(areas, np.ones(50, dtype=bool)), 100.0, phones)
    for name, samples, at in (("silence", quiet, rate), ("noise", noise, rate),
                              ("/s/", hiss, hiss_rate)):
        write_wav(tmp_path / "sound.wav", samples, at)
        hops = measure_hops(tmp_path / "sound.wav", "man")
        frames = [inversion.estimable_formants(h) for h in hops]
        assert len(hops) >= 40, name
        assert inversion.invert_track(frames, vowels) == [None] * len(hops), name
    # Control: a voiced vowel of the same voice is estimated.
    vowel = [head_tract.area_function(vowels.pose(vowels.anchor_entry("ɑ")))] * 50
    aa, aa_rate = tract_voice.synthesize(tract_voice.tubes_of_frames(vowel), 100.0,
                                         [{"symbol": "AA", "stress": 1, "start_s": 0.0,
                                           "end_s": 0.5}])
    write_wav(tmp_path / "aa.wav", aa, aa_rate)
    frames = [inversion.estimable_formants(h) for h in measure_hops(tmp_path / "aa.wav", "man")]
    assert sum(e is not None for e in inversion.invert_track(frames, vowels)) >= 30
