"""The lossy tube (glasshead.acoustics.tube): the textbook uniform tube, the losses where theory
puts them, VocalTractLab's own tubes giving VocalTractLab's own formants, bad tubes refused, and
the shared vectors."""

import numpy as np
import pytest

from glasshead.acoustics import tube
from glasshead.constants import TUBE_AIR
from glasshead.pipeline import vtl_speaker
from glasshead.vectors.tube_acoustics import build_document
from vector_support import assert_generated, read_vectors, tol

UNIFORM_MM = 175.0
#: Of VocalTractLab's formants, how far ours may be, median over its vowel shapes (measured:
#: F1 4.3 %, F2 0.2 %, F3 0.2 %; F1 is ours higher in the closest vowels, where the walls' own
#: resonance holds it up: VocalTractLab's walls yield more).
VTL_MEDIAN = {"F1": 0.10, "F2": 0.01, "F3": 0.01}


def uniform(area_mm2=300.0, count=35):
    return [UNIFORM_MM / count] * count, [area_mm2] * count


def test_a_lossless_uniform_tube_of_17_5_cm_gives_500_1500_2500_and_3500_hz():
    frequencies, _ = tube.formants(*uniform(), lossy=False)
    np.testing.assert_allclose(frequencies, [500.0, 1500.0, 2500.0, 3500.0], rtol=0.005)


@pytest.mark.parametrize("area_mm2", [100.0, 300.0, 500.0])
def test_with_losses_the_lips_lengthen_the_tube_and_the_walls_hold_the_first_resonance_up(area_mm2):
    frequencies, bandwidths = tube.formants(*uniform(area_mm2))
    radius_mm = np.sqrt(area_mm2 / np.pi)
    # The radiation's inertance adds 8a/(3π) to the length (a piston in a baffle).
    longer = UNIFORM_MM + 8.0 * radius_mm / (3.0 * np.pi)
    quarter = TUBE_AIR["sound_speed"] * 1e3 / (4.0 * longer)
    np.testing.assert_allclose(frequencies[1:3], [3 * quarter, 5 * quarter], rtol=0.02)
    assert quarter < frequencies[0] < 1.15 * 500.0
    assert np.all((bandwidths > 10.0) & (bandwidths < 200.0)), bandwidths


def test_a_narrowing_at_the_lips_lowers_the_formants_and_a_narrow_back_gives_the_low_f2_of_a():
    lengths, areas = uniform()
    rounded = tube.formants(lengths, areas[:-4] + [30.0] * 4)[0]
    assert np.all(rounded[:3] < tube.formants(lengths, areas)[0][:3])
    open_a = tube.formants([87.5, 87.5], [100.0, 700.0])[0]
    front_i = tube.formants([90.0, 60.0], [800.0, 100.0])[0]
    assert open_a[0] > 600 > front_i[0] and front_i[1] > 1800 > open_a[1]




def test_vocaltractlabs_own_tubes_of_its_vowels_give_its_own_formants():
    api = vtl_speaker.api()
    names = [n for n in vtl_speaker.shape_names() if vtl_speaker.classify(n)["kind"] == "vowel"]
    assert len(names) >= 18
    errors = []
    for name in names:
        state = vtl_speaker.tract_params(name)
        tubes = api.tract_state_to_tube_state(state)
        lengths = np.asarray(tubes["tube_length"]) * 10.0  # cm -> mm
        areas = np.asarray(tubes["tube_area"]) * 100.0  # cm² -> mm²
        ours = tube.formants(lengths, areas)[0][:3]
        theirs = vtl_speaker.formant_peaks(state)
        errors.append(np.abs(ours - theirs) / theirs)
    medians = np.median(errors, axis=0)
    for k, name in enumerate(("F1", "F2", "F3")):
        assert medians[k] <= VTL_MEDIAN[name], f"{name}: median {medians[k]:.3f}"


@pytest.mark.parametrize(("lengths", "areas", "message"), [
    ([10.0, 10.0], [100.0], "as many section lengths as areas"),
    ([], [], "at least one"),
    ([10.0], [0.0], "positive length and area"),
    ([-1.0], [50.0], "positive length and area"),
])
def test_a_tube_without_sections_or_with_a_closed_or_negative_one_is_refused(lengths, areas,
                                                                             message):
    with pytest.raises(ValueError, match=message):
        tube.formants(lengths, areas)


@pytest.mark.vectors
def test_the_shared_vectors_are_what_the_model_gives():
    vectors = read_vectors("tube-acoustics.json")
    assert_generated("tube-acoustics.json", build_document(), vectors,
                     atol=tol(vectors, "frequency"), rtol=tol(vectors, "transfer"))
