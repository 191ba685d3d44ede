"""Comparing EPG sequences (agreement, index differences, alignment) and plotting index tracks."""

import xml.etree.ElementTree as ET

import numpy as np
import pytest

from glasshead.epg import compare as cmp
from glasshead.epg.formats import parse
from glasshead.epg.indices import epg_indices
from glasshead.epg.plot import PANEL_HEIGHT, Track, index_tracks_svg, panel_geometry, to_xy
from glasshead.vectors.sources import emur_path

SVG = "{http://www.w3.org/2000/svg}"


@pytest.fixture(scope="module")
def sequences():
    return parse(emur_path().read_bytes(), "emur-json")


def frame_with(cells):
    """An (8, 8) frame with contacts at the given (row, column) cells, 0-based."""
    frame = np.zeros((8, 8), dtype=np.uint8)
    for r, c in cells:
        frame[r, c] = 1
    return frame


def test_a_recording_agrees_fully_with_itself(sequences):
    seq = sequences[3]
    result = cmp.compare(seq.frames, seq.t_s, seq.frames, seq.t_s)
    # The same frames on both sides: full agreement and no difference, up to rounding.
    np.testing.assert_allclose(result.agreement, 1.0, rtol=0, atol=1e-12)
    assert result.summary()["identical_frames"] == seq.n_frames
    for name, d in result.index_difference.items():
        np.testing.assert_allclose(d, 0.0, rtol=0, atol=1e-12, err_msg=name)
    assert np.isnan(result.electrode_agreement[0, 0]) and np.isnan(result.electrode_agreement[0, 7])
    np.testing.assert_allclose(result.electrode_agreement[1:], 1.0, rtol=0, atol=1e-12)


def test_codes_say_which_side_has_each_contact():
    mine = frame_with([(7, 0), (7, 1), (0, 3)])
    theirs = frame_with([(7, 0), (6, 4)])
    result = cmp.compare(mine[None], [0.0], theirs[None])
    codes = result.codes[0]
    assert codes[7, 0] == cmp.BOTH_ON
    assert codes[7, 1] == cmp.ONLY_RECORDING and codes[0, 3] == cmp.ONLY_RECORDING
    assert codes[6, 4] == cmp.ONLY_REFERENCE
    assert codes[0, 0] == codes[0, 7] == cmp.NO_ELECTRODE
    assert (codes == cmp.BOTH_OFF).sum() == 62 - 4
    # 3 of 62 electrodes disagree (ratios of small integers: equal up to rounding, 1e-12)
    np.testing.assert_allclose(result.agreement, [59 / 62], rtol=1e-12)
    # percent differs by (3 - 2) contacts of 62; dorsopalatal by (2 - 2)/24 = 0
    np.testing.assert_allclose(result.index_difference["percent"], [100 / 62], rtol=1e-12)
    np.testing.assert_allclose(result.index_difference["dorsopalatal"], [0.0], rtol=0, atol=1e-12)


def test_a_static_target_stands_for_every_frame_of_a_recording(sequences):
    seq = sequences[0]
    target = seq.frames[20]
    result = cmp.compare(seq.frames, seq.t_s, target[None])
    np.testing.assert_array_equal(result.reference_frame, 0)
    # frame 20 is the target itself: agreement 1 up to rounding; others fall short by 1/62 or more
    assert result.agreement[20] == pytest.approx(1.0, abs=1e-12)
    assert result.agreement.min() < 1.0 - 1 / 124
    expected_cog = epg_indices(target[None])["cog"][0]
    np.testing.assert_allclose(result.reference_indices["cog"], expected_cog, rtol=1e-12)


def test_a_reference_at_another_rate_is_held_from_frame_to_frame_by_time():
    # recording at 200 Hz from 10 s; reference at 100 Hz from 0 s: each reference frame
    # stands for two recording frames
    t = 10.0 + np.arange(6) * 0.005
    ref_t = np.arange(3) * 0.010
    which = cmp.align_reference(t, ref_t, 3)
    np.testing.assert_array_equal(which, [0, 0, 1, 1, 2, 2])


def test_a_reference_longer_in_time_is_cut_and_a_shorter_one_holds_its_last_frame():
    np.testing.assert_array_equal(cmp.align_reference(np.arange(3) * 0.01, np.arange(9) * 0.01,
                                                      9), [0, 1, 2])
    np.testing.assert_array_equal(cmp.align_reference(np.arange(4) * 0.01, np.arange(2) * 0.01,
                                                      2), [0, 1, 1, 1])


def test_a_reference_of_another_length_without_times_is_refused(sequences):
    seq = sequences[0]
    with pytest.raises(ValueError, match="no times to align them by"):
        cmp.compare(seq.frames, seq.t_s, seq.frames[:5])


def test_the_index_plot_draws_one_line_per_track_and_panel_at_the_right_place(sequences):
    a, b = sequences[0], sequences[1]
    tracks = [Track(a.name, a.t_s, epg_indices(a.frames)),
              Track(b.name, b.t_s, epg_indices(b.frames))]
    root = ET.fromstring(index_tracks_svg(tracks, ("percent", "cog"), title="a & b"))
    panels = root.findall(f"{SVG}g")
    assert [p.get("data-index") for p in panels] == ["percent", "cog"]
    lines = panels[1].findall(f"{SVG}polyline")
    assert [line.get("data-track") for line in lines] == ["0", "1"]
    assert lines[1].get("stroke-dasharray") and not lines[0].get("stroke-dasharray")
    points = [tuple(map(float, p.split(","))) for p in lines[0].get("points").split()]
    assert len(points) == a.n_frames
    # the first cog of track 0 is 2.6333 (see test_epg_indices): 2.6333/8 of the panel height
    # above the bottom of panel 1, at the left edge
    top, bottom = panel_geometry(1)
    # pixels, printed with two decimals in the SVG
    assert points[0][0] == pytest.approx(64.0, abs=0.01)
    assert points[0][1] == pytest.approx(bottom - 2.633333333 / 8 * PANEL_HEIGHT, abs=0.01)
    span = max(a.t_s[-1] - a.t_s[0], b.t_s[-1] - b.t_s[0])
    x, y = to_xy(np.array([a.t_s[-1] - a.t_s[0]]), np.array([8.0]), span, 1, 0.0, 8.0)
    assert points[-1][0] == pytest.approx(x[0], abs=0.01) and y[0] == pytest.approx(top, abs=1e-9)


def test_an_unknown_panel_is_refused():
    track = Track("x", np.array([0.0]), {"percent": np.array([1.0])})
    with pytest.raises(ValueError, match="no panel for"):
        index_tracks_svg([track], ("loudness",))


def _fullest_velar_frame(seq):
    """The frame of ``seq`` with the most contacts in rows 6 to 8 (its /k/ closure)."""
    return seq.frames[int(np.argmax(seq.frames[:, 5:].sum(axis=(1, 2))))]


def test_an_empty_target_against_a_real_k_closure_scores_zero_kappa(sequences):
    seq = sequences[0]
    assert seq.name.startswith("sp1bescan")
    k = _fullest_velar_frame(seq)
    assert k[5:].sum() >= 12, "the take has a velar closure"
    result = cmp.compare(k[None], [0.0], np.zeros((1, 8, 8), dtype=np.uint8))
    # The raw share is won by the electrodes off on both sides; kappa and contact agreement not.
    assert result.agreement[0] > 0.5
    np.testing.assert_allclose(result.kappa, [0.0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(result.contact_agreement, [0.0], rtol=0, atol=1e-12)
    whole = cmp.compare(seq.frames, seq.t_s, np.zeros((1, 8, 8), dtype=np.uint8)).summary()
    assert whole["mean_agreement"] > 0.5
    np.testing.assert_allclose(whole["mean_kappa"], 0.0, rtol=0, atol=1e-12)


def test_identical_frames_score_kappa_one_even_when_empty_or_full(sequences):
    seq = sequences[0]
    result = cmp.compare(seq.frames, seq.t_s, seq.frames, seq.t_s)
    np.testing.assert_allclose(result.kappa, 1.0, rtol=0, atol=1e-12)
    np.testing.assert_allclose(result.contact_agreement, 1.0, rtol=0, atol=1e-12)
    full = np.ones((1, 8, 8), dtype=np.uint8)
    full[0, 0, [0, 7]] = 0
    for frame in (np.zeros((1, 8, 8), dtype=np.uint8), full):
        same = cmp.compare(frame, [0.0], frame)
        np.testing.assert_allclose(same.kappa, [1.0], rtol=0, atol=1e-12)
        np.testing.assert_allclose(same.contact_agreement, [1.0], rtol=0, atol=1e-12)


def test_kappa_is_cohens_formula_on_a_small_exact_case():
    # recording: 4 contacts; reference: 2 of those and 2 others. Of 62: observed 58/62 agree.
    mine = frame_with([(7, 0), (7, 1), (7, 2), (7, 3)])
    theirs = frame_with([(7, 0), (7, 1), (6, 0), (6, 1)])
    result = cmp.compare(mine[None], [0.0], theirs[None])
    p_o, p_a, p_b = 58 / 62, 4 / 62, 4 / 62
    p_e = p_a * p_b + (1 - p_a) * (1 - p_b)
    np.testing.assert_allclose(result.kappa, [(p_o - p_e) / (1 - p_e)], rtol=1e-12)
    np.testing.assert_allclose(result.contact_agreement, [2 / 6], rtol=1e-12)
    # A target with every contact on the other side: kappa below zero.
    other = frame_with([(0, 3), (0, 4), (1, 3), (1, 4)])
    assert cmp.compare(mine[None], [0.0], other[None]).kappa[0] < 0
