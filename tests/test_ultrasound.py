"""Real ultrasound contours of speaker it01 (/t/ against /k/) carried into the project frame
through the speaker's palate trace (pipeline.ultrasound), on the reference data."""

import numpy as np
import pytest

from glasshead.geometry.midsagittal import midline_section
from glasshead.pipeline.outputs import load_built_meshes
from glasshead.pipeline.ultrasound import (
    PALATE_FILE,
    TONGUE_FILE,
    UltrasoundDataError,
    highest_point,
    read_contours,
    read_palate,
    register_trace,
)


@pytest.fixture(scope="module")
def contours(data_dir):
    return read_contours(data_dir / TONGUE_FILE)


@pytest.fixture(scope="module")
def registered(data_dir, built_assets):
    vertices, faces, _ = load_built_meshes(built_assets, ["maxilla"])["maxilla"]
    return register_trace(read_palate(data_dir / PALATE_FILE), midline_section(vertices, faces))


def test_the_file_holds_35_contours_of_t_and_k_in_three_vowel_contexts(contours):
    assert len(contours) == 35
    assert {c.consonant for c in contours} == {"t", "k"}
    assert {c.vowel for c in contours} == {"a", "o", "u"}
    assert all(len(c.points) >= 20 and np.all(np.isfinite(c.points)) for c in contours)
    # Front first: fan line 1 is the front of the fan.
    assert all(c.points[0, 0] > c.points[-1, 0] for c in contours)


def test_the_palate_trace_lays_onto_our_vault_within_a_millimetre(registered):
    transform, report = registered
    assert transform.scale == 1.0  # both in mm: a rigid map
    assert report["vault_rms_mm"] < 1.0
    assert report["trace_over_vault"]["max_mm"] < 2.5


def test_in_the_project_frame_t_peaks_in_front_of_k_in_every_vowel_context(contours, registered):
    transform, _ = registered
    for vowel in ("a", "o", "u"):
        tops = {c: [transform.apply(highest_point(x.points)[None])[0]
                    for x in contours if x.consonant == c and x.vowel == vowel] for c in "tk"}
        assert tops["t"] and tops["k"], vowel
        assert np.mean([p[0] for p in tops["t"]]) > np.mean([p[0] for p in tops["k"]]) + 5.0


def test_bad_files_are_refused_naming_the_file_and_the_line(tmp_path, data_dir):
    rows = (data_dir / TONGUE_FILE).read_text().splitlines()
    bad = tmp_path / "tongue.csv"
    bad.write_text("\n".join([rows[0], rows[1].replace("max_TD", "max_XX", 1)]) + "\n")
    with pytest.raises(UltrasoundDataError, match="tongue.csv line 2: label 'max_XX'"):
        read_contours(bad)
    fields = rows[1].split(",")
    fields[15] = "abc"
    bad.write_text("\n".join([rows[0], ",".join(fields)]) + "\n")
    with pytest.raises(UltrasoundDataError, match="'abc' is not a number"):
        read_contours(bad)
    palate = tmp_path / "palate.tsv"
    palate.write_text("it01\t0\n")
    with pytest.raises(UltrasoundDataError, match="palate.tsv: expected 84 values"):
        read_palate(palate)
