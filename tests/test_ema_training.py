"""Training the jaw against real articulography (training.ema_training): the vectorised incisor,
the gains on the targets' jaw, a made-up speaker whose answer is known, and the held-out report
on the four HPRC recordings."""

import copy
import dataclasses

import numpy as np
import pytest

from glasshead.asset_store import AssetStore
from glasshead.cli import main
from glasshead.ema import read_ema
from glasshead.flesh_point_assets import flesh_point_rig
from glasshead.geometry.jaw import apply_jaw_pose, jaw_pose
from glasshead.speech import dominance
from glasshead.speech import ema_comparison as cmp
from glasshead.training import ema_training as et


@pytest.fixture(scope="module")
def setting(built_assets, data_dir):
    store = AssetStore(built_assets)
    rig = flesh_point_rig(store)
    scorer = et.JawScorer.of(store.get("phoneme_targets"), rig)
    recordings = [et.Recording.of(read_ema(p)) for p in cmp.hprc_recordings(data_dir)]
    return scorer, recordings, rig


def test_the_incisor_heights_are_the_jaw_poses_of_the_rig(setting):
    _, _, rig = setting
    incisor = rig.incisors["lower_incisor"]
    openings = np.linspace(-1.0, 12.0, 27)
    expected = [apply_jaw_pose(incisor[None], jaw_pose(a, rig.tongue.jaw))[0, 1] for a in openings]
    heights = et.incisor_heights(openings, incisor[:2], rig.tongue.jaw)
    assert np.allclose(heights, expected, atol=1e-9)
    assert heights[-1] < heights[0] - 5.0  # opening drops the incisor


def test_jaw_gains_scale_each_class_within_the_range_and_leave_the_targets_alone(setting):
    scorer, _, _ = setting
    targets = scorer.targets
    kept = copy.deepcopy(targets)
    gained = et.with_jaw_gains(targets, {"vowel": 2.0, "coronal": 100.0}, scorer.jaw_range)
    assert targets == kept
    by_symbol = {t["arpabet"]: t for t in gained["targets"]}
    original = {t["arpabet"]: t for t in targets["targets"]}
    assert by_symbol["AA"]["params"]["jaw_opening"] == pytest.approx(
        min(2.0 * original["AA"]["params"]["jaw_opening"], scorer.jaw_range[1]), abs=1e-4)
    assert by_symbol["T"]["params"]["jaw_opening"] <= scorer.jaw_range[1]
    assert by_symbol["T"]["contexts"]["i"]["params"]["jaw_opening"] <= scorer.jaw_range[1]
    assert by_symbol["K"] is original["K"]  # a class without a gain is not copied


def test_a_speaker_whose_vowels_open_the_jaw_half_again_trains_to_that(setting):
    """A made-up speaker whose jaw signal is the head's own with the vowels' jaw targets 1.5
    times as open: trained on it, the head's range comes to the speaker's."""
    scorer, recordings, _ = setting
    base = dominance.load_constants()
    truth = et.JawModel(base, {"vowel": 1.5, "rounded_vowel": 1.5})
    made = [dataclasses.replace(r, measured=scorer.head_signal(r, truth)) for r in recordings]
    before = [scorer.figures(r, et.JawModel(base, {})) for r in made]
    trained = et.train(scorer, made, base, max_evals=300)
    after = [scorer.figures(r, trained["model"]) for r in made]
    assert np.mean([f["range_ratio"] for f in before]) < 0.85
    assert np.mean([f["range_ratio"] for f in after]) == pytest.approx(1.0, abs=0.1)
    assert np.mean([f["r"] for f in after]) > 0.97
    assert trained["error_after"] < trained["error_before"]


def test_each_speaker_held_out_is_scored_before_and_after_and_the_command_prints_it(
        setting, data_dir, capsys):
    scorer, recordings, _ = setting
    report = et.held_out(scorer, recordings, dominance.load_constants(), max_evals=60)
    assert [fold["speaker"] for fold in report["folds"]] == ["F01", "M01", "M04"]
    rows = [row for fold in report["folds"] for row in fold["recordings"]]
    assert len(rows) == 4
    for row in rows:
        for when in ("before", "after"):
            assert np.isfinite(row[when]["r"]) and row[when]["range_ratio"] > 0
    # Before training the head's jaw is the one compare-ema scores (its jaw-opening r).
    alone = cmp.compare([read_ema(p) for p in cmp.hprc_recordings(data_dir)], scorer.targets,
                        setting[2])
    by_name = {r["recording"]: r["signals"]["jaw_opening"]["r"] for r in alone["recordings"]}
    for row in rows:
        assert row["before"]["r"] == pytest.approx(by_name[row["name"]], abs=1e-6), row["name"]
    assert main(["train", "--ema", "--max-evals", "40"]) == 0
    out = capsys.readouterr().out
    assert "each speaker held out" in out and "M04_B02_S44_R01_N" in out
    assert "jaw target gains" in out
