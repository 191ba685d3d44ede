"""Coarticulation (speech.coarticulation, after Cohen and Massaro 1993) on the built phoneme
targets: the issue's two examples, ranges, targets, the velum, cues, bad input and the frame
convention; a brute-force per-frame loop as the reference. Phones are timed by the training's
duration rule (training.coarticulation.timed: stressed vowels 140 ms, stops 70 ms, fricatives
100 ms, 150 ms of silence at each end)."""

import json
import math

import numpy as np
import pytest

from glasshead.fitting.objective2d import MidSagittalSection
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.phonemes import INVENTORY
from glasshead.speech import coarticulation, dominance
from glasshead.speech.coarticulation import (
    GLIDE_SHARE,
    coarticulate,
    phone_contexts,
    sample,
    segments,
    target_matrix,
)
from glasshead.training.coarticulation import timed

#: The shipped (trained) constants and the hand-set ones: the examples must hold with both.
CONSTANT_SETS = {"trained": None, "hand-set": dominance.DEFAULTS}


@pytest.fixture(scope="module")
def targets(built_assets):
    return json.loads((built_assets / "phoneme-targets.json").read_text())


@pytest.fixture(scope="module")
def ranges(built_assets):
    specs = {}
    for name in ("tongue-rig.json", "face-rig.json", "velum-rig.json"):
        for p in json.loads((built_assets / name).read_text())["parameters"]:
            specs[p["name"]] = p
    return specs


def target_of(targets, symbol):
    return next(t for t in targets["targets"] if t["arpabet"] == symbol)


def centre_frame(phone, rate=100.0):
    return round(0.5 * (phone["start_s"] + phone["end_s"]) * rate)


def first_crossing_s(track, level, rate=100.0):
    """Time of the first frame at or above ``level``; infinity when none is."""
    above = np.flatnonzero(np.asarray(track) >= level)
    return above[0] / rate if len(above) else math.inf


@pytest.mark.parametrize("which", CONSTANT_SETS)
def test_the_lips_round_for_u_before_the_vowel_in_stew_and_not_in_stee(targets, which):
    constants = CONSTANT_SETS[which]
    half = 0.5 * target_of(targets, "UW")["params"]["lip_rounding"]
    stew, stee = timed("S T UW"), timed("S T IY")
    vowel_start = stew[3]["start_s"]
    assert stee[3]["start_s"] == pytest.approx(vowel_start)
    rounding_stew = coarticulate(stew, targets, constants=constants)["tracks"]["lip_rounding"]
    rounding_stee = coarticulate(stee, targets, constants=constants)["tracks"]["lip_rounding"]
    crossing_stew = first_crossing_s(rounding_stew, half)
    crossing_stee = first_crossing_s(rounding_stee, half)
    # The rounding of /u/ is anticipated across /s t/: half of it before the vowel starts.
    assert crossing_stew < vowel_start - 0.02, (crossing_stew, vowel_start)
    assert crossing_stee > crossing_stew + 0.1
    # During /t/ the lips are rounded more for "stew" than for "stee" by over 2 mm.
    t_mid = centre_frame(stew[2])
    assert rounding_stew[t_mid] - rounding_stee[t_mid] > 2.0


@pytest.fixture(scope="module")
def section(built_assets):
    """The built rig's mid-sagittal section."""
    return MidSagittalSection(TongueRig(json.loads((built_assets / "tongue-rig.json").read_text())))


def dorsum_top_x(section, params):
    """x (mm, + toward the lips) of the highest point of the tongue's mid-sagittal outline for
    a mapping of parameter values (missing tongue parameters neutral): where /k/ closes."""
    rig = section.rig
    values = rig.neutral.copy()
    for name, value in params.items():
        if name in rig.parameters:
            values[rig.parameter_names.index(name)] = value
    outline = section.outline(np.clip(values, rig.minimum, rig.maximum))
    return float(outline[np.argmax(outline[:, 1]), 0])


@pytest.mark.parametrize("which", CONSTANT_SETS)
def test_k_is_fronted_before_i_against_before_u(targets, section, which):
    """The dorsum's highest point at /k/'s centre lies further forward in "key" than in "coo"."""
    constants = CONSTANT_SETS[which]
    key, coo = timed("K IY"), timed("K UW")
    k_key, k_coo = centre_frame(key[1]), centre_frame(coo[1])
    tracks_key = coarticulate(key, targets, constants=constants)["tracks"]
    tracks_coo = coarticulate(coo, targets, constants=constants)["tracks"]
    top_key = dorsum_top_x(section, {n: track[k_key] for n, track in tracks_key.items()})
    top_coo = dorsum_top_x(section, {n: track[k_coo] for n, track in tracks_coo.items()})
    assert top_key - top_coo > 0.4, (top_key, top_coo)
    # It is the context variant that fronts it: /k/ takes its /i/-context target before /i/.
    contexts = target_of(targets, "K")["contexts"]
    assert dorsum_top_x(section, contexts["i"]["params"]) \
        > dorsum_top_x(section, contexts["u"]["params"]) + 0.5


def test_a_consonant_takes_the_context_of_the_vowel_after_it_else_before_it():
    assert phone_contexts(["sil", "K", "IY", "sil"]) == [None, "i", None, None]
    assert phone_contexts(["S", "T", "UW"]) == ["u", "u", None]
    assert phone_contexts(["AA", "T", "sil", "K", "IY"]) == [None, "a", None, "i", None]
    assert phone_contexts(["UW", "K"]) == [None, "u"]
    assert phone_contexts(["sil", "K", "sil"]) == [None, None, None]


def test_a_consonant_variant_is_its_context_fit_and_silence_is_the_rest_pose(targets):
    names = ["dorsum_advancement", "lip_rounding", "velum_opening"]
    rows = target_matrix(["sil", "K", "IY"], targets, names)
    k_i = target_of(targets, "K")["contexts"]["i"]["params"]
    rest = target_of(targets, "HH")["params"]
    np.testing.assert_allclose(rows[1], [k_i[n] for n in names], atol=0)
    np.testing.assert_allclose(rows[0], [rest[n] for n in names], atol=0)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_tracks_never_leave_their_parameter_ranges(targets, ranges, seed):
    rng = np.random.default_rng(seed)
    symbols = [p.arpabet for p in INVENTORY] + ["sil"]
    phones, clock = [], 0.0
    for _ in range(40):
        duration = float(rng.uniform(0.02, 0.25))
        phones.append({"symbol": str(rng.choice(symbols)), "stress": None,
                       "start_s": clock, "end_s": clock + duration})
        clock += duration + float(rng.choice([0.0, 0.0, 0.05]))
    result = coarticulate(phones, targets)
    assert set(result["tracks"]) == set(ranges)
    for name, track in result["tracks"].items():
        values = np.asarray(track)
        assert len(values) == result["n_frames"]
        assert values.min() >= ranges[name]["min"] - 1e-9, (seed, name, values.min())
        assert values.max() <= ranges[name]["max"] + 1e-9, (seed, name, values.max())
    for name, cue in result["cues"].items():
        assert 0.0 <= min(cue) and max(cue) <= 1.0, name


def test_a_single_long_phone_reaches_its_target(targets, ranges):
    alone = coarticulate([{"symbol": "AA", "stress": 1, "start_s": 0.0, "end_s": 1.0}], targets)
    aa = target_of(targets, "AA")["params"]
    for name, track in alone["tracks"].items():
        np.testing.assert_allclose(track, aa[name], atol=1e-9, err_msg=name)
    phones = [{"symbol": "sil", "stress": None, "start_s": 0.0, "end_s": 0.2},
              {"symbol": "AA", "stress": 1, "start_s": 0.2, "end_s": 1.2},
              {"symbol": "sil", "stress": None, "start_s": 1.2, "end_s": 1.4}]
    framed = coarticulate(phones, targets)
    middle = centre_frame(phones[1])
    for name, track in framed["tracks"].items():
        span = ranges[name]["max"] - ranges[name]["min"]
        assert abs(track[middle] - aa[name]) <= 0.01 * span, name


def test_the_velum_lowers_during_m_n_ng_and_is_raised_elsewhere(targets):
    phones = timed("M AA N S IY NG K AH0 T")
    velum = coarticulate(phones, targets)["tracks"]["velum_opening"]
    for phone in phones:
        value = velum[centre_frame(phone)]
        if phone["symbol"] in ("M", "N", "NG"):
            assert value > 0.5, (phone["symbol"], value)
        elif phone["symbol"] in ("S", "K", "T"):
            assert value < 0.2, (phone["symbol"], value)
    oral = coarticulate(timed("S T IY K AE T"), targets)["tracks"]["velum_opening"]
    assert max(oral) < 0.05


def test_the_cues_follow_the_phones_features(targets):
    phones = timed("S AA M")
    cues = coarticulate(phones, targets)["cues"]
    s, a, m = (centre_frame(p) for p in phones[1:4])
    assert cues["frication"][s] == pytest.approx(1.0) and cues["voicing"][s] == 0.0
    assert cues["voicing"][a] == pytest.approx(1.0) and cues["frication"][a] == 0.0
    assert cues["nasal_airflow"][m] == pytest.approx(1.0) and cues["voicing"][m] == 1.0
    assert cues["nasal_airflow"][a] == 0.0 and cues["voicing"][0] == 0.0
    # Smoothed: at the /s/-/a/ boundary (a frame exactly on it) voicing is half on.
    boundary = round(phones[2]["start_s"] * 100)
    assert cues["voicing"][boundary] == pytest.approx(0.5, abs=1e-9)


def brute_force_tracks(phones, targets, constants):
    """The model written out per frame, per segment and per parameter."""
    names = [*targets["parameters"]["tongue"], *targets["parameters"]["lips"],
             *targets["parameters"]["velum"]]
    symbols, starts, ends, _ = segments(phones)
    values = target_matrix(symbols, targets, names)
    n = math.ceil(phones[-1]["end_s"] * 100.0 - 1e-9)
    out = {name: [] for name in names}
    for i in range(n):
        t = i / 100.0
        for k, name in enumerate(names):
            group = dominance.parameter_group(name)
            numerator = denominator = 0.0
            for j, symbol in enumerate(symbols):
                entry = constants["classes"][dominance.phone_class(symbol)]
                alpha = (constants["velum_alpha"][dominance.velum_class(symbol)]
                         if group == "velum" else entry["alpha"][group])
                tau = t - 0.5 * (starts[j] + ends[j])
                theta = entry["theta_anticipation"] if tau < 0 else entry["theta_carryover"]
                d = alpha * math.exp(-theta * abs(tau) ** constants["c"])
                numerator += d * values[j, k]
                denominator += d
            out[name].append(numerator / denominator)
    return out


@pytest.mark.parametrize("which", CONSTANT_SETS)
def test_tracks_equal_the_dominance_weighted_average_computed_frame_by_frame(targets, which):
    constants = CONSTANT_SETS[which] or dominance.load_constants()
    phones = timed("K AH0 T DH AH0 CH IY Z AY W OW")
    fast = coarticulate(phones, targets, constants=constants)
    slow = brute_force_tracks(phones, targets, constants)
    for name, track in slow.items():
        np.testing.assert_allclose(fast["tracks"][name], track, rtol=1e-9, atol=1e-9,
                                   err_msg=name)


@pytest.mark.parametrize("which", CONSTANT_SETS)
def test_a_long_utterance_blends_only_near_segments_and_gives_the_full_blend(targets, which,
                                                                              monkeypatch):
    """Far segments are left out of a frame's blend (linear time in the length): 90 s of
    phones and a 6 s silence give the tracks of every segment blended, to 1e-9."""
    constants = CONSTANT_SETS[which] or dominance.load_constants()
    rng = np.random.default_rng(7)
    symbols = [p.arpabet for p in INVENTORY]
    phones, t = [], 0.0
    for k in range(800):
        length = 6.0 if k == 400 else float(rng.uniform(0.04, 0.2))
        phones.append({"symbol": "sil" if k == 400 else str(rng.choice(symbols)),
                       "stress": None, "start_s": t, "end_s": t + length})
        t += length
    blended: list[int] = []
    blend = coarticulation.blend
    monkeypatch.setattr(coarticulation, "blend",
                        lambda values, *rest: blended.append(len(values)) or blend(values, *rest))
    windowed = coarticulation.coarticulate_arrays(phones, targets, constants=constants)
    monkeypatch.setattr(coarticulation, "blend", blend)
    n_segments = len(segments(phones)[0])
    assert len(blended) > 1 and max(blended) < n_segments / 2, (blended, n_segments)
    parts, starts, ends, _ = segments(phones)
    alpha, before, after = coarticulation.dominance_arrays(parts, constants)
    e = coarticulation.decay(0.5 * (starts + ends), windowed["times"], before, after,
                             float(constants["c"]))
    full = blend(target_matrix(parts, targets, windowed["names"]), alpha, windowed["groups"], e)
    np.testing.assert_allclose(windowed["tracks"], full, rtol=1e-9, atol=1e-9)


def test_a_diphthong_glides_from_its_first_element_to_its_second(targets):
    """/aɪ/ in "buy": tip_advancement (AA -0.2 mm, IH 13.9 mm) rises across the phone."""
    phones = timed("B AY")
    assert segments(phones)[0] == ["sil", "B", "AY", "IH", "sil"]
    ay = phones[2]
    glide_start = ay["end_s"] - GLIDE_SHARE * (ay["end_s"] - ay["start_s"])
    assert segments(phones)[1][3] == pytest.approx(glide_start)
    track = coarticulate(phones, targets)["tracks"]["tip_advancement"]
    early = track[round((ay["start_s"] + 0.3 * (ay["end_s"] - ay["start_s"])) * 100)]
    late = track[round((ay["end_s"] - 0.01) * 100)]
    aa, ih = (target_of(targets, s)["params"]["tip_advancement"] for s in ("AA", "IH"))
    assert late - early > 0.3 * (ih - aa)
    # A consonant after a diphthong takes the context of its second element.
    assert phone_contexts(["B", "AY", "IH", "T"])[3] == "i"
    dominance_rows = coarticulate(phones, targets, constants={"return_dominance": True})
    assert len(dominance_rows["dominance"]["jaw_opening"]) == len(phones)


def test_dominance_is_returned_per_parameter_and_phone_only_when_asked(targets):
    phones = timed("M UW")
    plain = coarticulate(phones, targets)
    assert "dominance" not in plain
    asked = coarticulate(phones, targets, constants={"return_dominance": True})
    assert asked["tracks"] == plain["tracks"]
    lips = np.asarray(asked["dominance"]["lip_opening"])
    assert lips.shape == (len(phones), asked["n_frames"])
    m, u = centre_frame(phones[1]), centre_frame(phones[2])
    assert lips[1, m] > lips[2, m] and lips[2, u] > lips[1, u]
    # The returned dominances reproduce the track.
    values = target_matrix([p["symbol"] for p in phones], targets, ["lip_opening"])[:, 0]
    np.testing.assert_allclose((lips * values[:, None]).sum(0) / lips.sum(0),
                               asked["tracks"]["lip_opening"], rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize(("duration", "rate", "frames"), [
    (0.3, 100.0, 30), (0.305, 100.0, 31), (1.0 / 3.0, 100.0, 34), (0.5, 60.0, 30),
    (0.3, 120.0, 36), (0.001, 100.0, 1)])
def test_n_frames_is_the_ceiling_of_duration_times_rate(targets, duration, rate, frames):
    """Frame i is at t = i / rate_hz, the last one within the last phone's end."""
    result = coarticulate([{"symbol": "AA", "stress": 1, "start_s": 0.0, "end_s": duration}],
                          targets, rate_hz=rate)
    assert result["n_frames"] == frames
    assert result["rate_hz"] == rate and result["duration_s"] == duration
    assert all(len(track) == frames for track in result["tracks"].values())
    assert all(len(cue) == frames for cue in result["cues"].values())
    assert (frames - 1) / rate < duration


def test_sample_interpolates_between_frames(targets):
    result = coarticulate(timed("S T UW"), targets)
    rounding = result["tracks"]["lip_rounding"]
    assert sample(result, 0.2)["lip_rounding"] == pytest.approx(rounding[20], abs=1e-12)
    assert sample(result, 0.205)["lip_rounding"] == pytest.approx(
        0.5 * (rounding[20] + rounding[21]), abs=1e-12)
    assert sample(result, -1.0)["lip_rounding"] == rounding[0]
    assert sample(result, 99.0)["voicing"] == result["cues"]["voicing"][-1]


@pytest.mark.parametrize(("phones", "message"), [
    ([{"symbol": "S", "start_s": 0.0, "end_s": 0.1}, {"symbol": "T", "start_s": 0.05,
                                                       "end_s": 0.2}],
     r"phone 1 \('T'\) overlaps the phone before it"),
    ([{"symbol": "S", "start_s": 0.2, "end_s": 0.1}], r"phone 0 \('S'\) runs backwards"),
    ([{"symbol": "S", "start_s": 0.0, "end_s": 0.1}, {"symbol": "QX", "start_s": 0.1,
                                                       "end_s": 0.2}],
     r"phone 1 \('QX'\): unknown symbol"),
    ([{"symbol": "S", "start_s": -0.1, "end_s": 0.1}], r"phone 0 \('S'\) starts before 0"),
    ([{"symbol": "S", "start_s": 0.0, "end_s": float("nan")}], r"end_s must be a finite"),
    ([{"start_s": 0.0, "end_s": 0.1}], r"phone 0: symbol must be a string"),
    ([], r"non-empty list"),
])
def test_bad_phones_raise_value_error_naming_the_phone(targets, phones, message):
    with pytest.raises(ValueError, match=message):
        coarticulate(phones, targets)


def test_a_bad_rate_or_constants_raise_value_error(targets):
    phones = timed("AA")
    with pytest.raises(ValueError, match="rate_hz"):
        coarticulate(phones, targets, rate_hz=0)
    with pytest.raises(ValueError, match="c must be"):
        coarticulate(phones, targets, constants={"c": -1})
    with pytest.raises(ValueError, match="format version 2"):
        coarticulate(phones, targets, constants={"format_version": 2})
    with pytest.raises(ValueError, match="velum_alpha.nasal"):
        coarticulate(phones, targets, constants={"velum_alpha": {"silence": 1.0}})


def test_the_shipped_constants_are_trained_and_say_how_they_were_made():
    stored = json.loads(dominance.CONSTANTS_FILE.read_text())
    assert "VocalTractLab's gestural trajectories" in stored["header"]
    dominance.validate_constants(stored)
    assert dominance.load_constants()["c"] == stored["c"]
    held = stored["training"]["held_out_rms"]
    assert held["after"] < held["before"]
    assert set(stored["training"]["held_out_sequences"]).isdisjoint(
        stored["training"]["training_sequences"])
