"""Training the coarticulation constants (training.coarticulation) against VocalTractLab's
gestural trajectories carried into our parameters (training.vtl_reference): a short run on two
sequences, and the mapping checked against the phoneme targets it reuses."""

import json

import numpy as np
import pytest

from glasshead.pipeline import vtl_speaker as vtl
from glasshead.speech import dominance
from glasshead.training import coarticulation as training
from glasshead.training.vtl_reference import (
    STATE_S,
    NoGestureError,
    ReferenceMapping,
    segment_file_text,
    vtl_states,
)


@pytest.fixture(scope="module")
def mapping(built_assets):
    return ReferenceMapping(built_assets)


def test_a_short_training_run_lowers_the_training_error_and_reports_both_sets(built_assets,
                                                                              tmp_path):
    made = training.train(built_assets, [("stew", "S T UW"), ("key", "K IY")],
                          held_out=[("coo", "K UW")], max_evals=40)
    report = made["report"]
    assert report["training_rms"]["after"] <= report["training_rms"]["before"]
    assert 0 < report["training_rms"]["after"] < 1
    assert report["held_out_sequences"] == ["coo"]
    assert set(report["held_out_by_parameter"]["after"]) == set(training.COMPARED)
    assert report["evaluations"] <= 40
    constants = dominance.validate_constants(made["constants"])
    assert training.C_BOUNDS[0] <= constants["c"] <= training.C_BOUNDS[1]
    # Untrained classes (absent here: /w/) keep their time constants T = theta^(-1/c).
    base = dominance.DEFAULTS
    t_before = base["classes"]["labial_velar"]["theta_anticipation"] ** (-1.0 / base["c"])
    t_after = constants["classes"]["labial_velar"]["theta_anticipation"] ** (-1.0 / constants["c"])
    assert t_after == pytest.approx(t_before, rel=1e-3)
    assert constants["header"].startswith("Made once by `glasshead train`")
    path = training.write_constants(made["constants"], tmp_path / "constants.json")
    assert json.loads(path.read_text())["c"] == constants["c"]


def test_the_duration_rule_times_phones_between_two_silences():
    phones = training.timed("S T UW")
    assert [p["symbol"] for p in phones] == ["sil", "S", "T", "UW", "sil"]
    durations = [round(p["end_s"] - p["start_s"], 6) for p in phones]
    assert durations == [0.15, 0.10, 0.07, 0.14, 0.15]
    assert all(a["end_s"] == b["start_s"] for a, b in zip(phones, phones[1:], strict=False))
    assert training.timed("AH0")[1]["end_s"] - training.timed("AH0")[1]["start_s"] \
        == pytest.approx(0.08)


def test_every_training_sequence_has_a_vtl_gesture_for_each_phone_and_held_out_ones_differ():
    train_set, held = training.split()
    assert held and set(held).isdisjoint(train_set)
    for _, text in training.SEQUENCES:
        segment_file_text(training.timed(text))  # raises for a phone VTL has no gesture for


def test_phones_vtl_has_no_gesture_for_are_refused_by_name():
    with pytest.raises(NoGestureError, match="'W'"):
        segment_file_text(training.timed("W IY"))


def test_a_gap_between_phones_is_written_as_silence():
    text = segment_file_text([{"symbol": "S", "start_s": 0.1, "end_s": 0.2}])
    assert text.splitlines() == ["name = ; duration_s = 0.100000;",
                                 "name = s; duration_s = 0.100000;"]


def test_vtl_states_last_as_long_as_the_phones(mapping):
    phones = training.timed("S T UW")
    states = vtl_states(phones)
    assert states.shape[1] == len(vtl.param_names())
    assert abs(len(states) * STATE_S - phones[-1]["end_s"]) < 0.02


def test_a_stored_shape_maps_onto_its_targets_lips_and_near_its_jaw_and_tongue(mapping,
                                                                              built_assets):
    """The mapping reuses the targets' own: VTL's /u/ state gives /u/'s rounding, protrusion and
    tuck exactly, and its jaw (opened by class, not by VTL's JA), its lip opening (VTL's lip
    distance over the gap at that jaw) and its tongue within the regression's error."""
    observations = json.loads((built_assets / "vtl-observations.json").read_text())
    shape = next(s for s in observations["shapes"] if s["name"] == "u")
    state = np.array([[shape["params"][name] for name in vtl.param_names()]])
    mapped = mapping.map_states(state)
    uw = next(t for t in mapping.targets["targets"] if t["arpabet"] == "UW")["params"]
    for name in ("lip_rounding", "lip_protrusion", "lower_lip_tuck"):
        assert mapped[name][0] == pytest.approx(uw[name], abs=0.02), name
    jaw_error = mapping.tongue.loo_rms["jaw_opening"]
    assert abs(mapped["jaw_opening"][0] - uw["jaw_opening"]) < max(3 * jaw_error, 0.3)
    assert mapped["lip_opening"][0] == pytest.approx(uw["lip_opening"], abs=0.1)
    assert mapped["velum_opening"][0] == 0.0
    sagittal = [n for n in training.COMPARED if n in mapping.tongue.names]
    errors = np.array([mapped[n][0] - uw[n] for n in sagittal])
    assert np.sqrt((errors ** 2).mean()) < 5.0
    assert mapping.tongue.shapes == 41
