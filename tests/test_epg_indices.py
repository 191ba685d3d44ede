"""EPG indices against values worked out by hand on real frames of the emuR engassim set.

Every expected number below comes from the arithmetic in its comment (emuR, R/epg.class.R):
  percent = 100 * contacts / 62
  cog     = sum_r w_r * rowsum_r / contacts, w = 7.5 (R1), 6.5, ..., 0.5 (R8); 0 if no contact
  ai      = ln(1 + 4921*R1/6 + 729*R2/8 + 81*R3/8 + 9*R4/8 + 1*R5/8) / ln(1 + 5741)
  ci      = ln(1 + 1*c18/14 + 17*c27/16 + 289*c36/16 + 4913*c45/16) / ln(1 + 5220),
            cXY = contacts in columns X and Y over all rows
  di      = (R6 + R7 + R8) / 24
The logarithms were evaluated on a calculator: ln 5742 = 8.655562860681, ln 5221 = 8.560444233411.
"""

import json

import numpy as np
import pytest

from glasshead.constants import EPG_ELECTRODES, EPG_MISSING_CELLS, EPG_ZONES
from glasshead.epg import indices
from glasshead.vectors.epg_indices import build_document
from glasshead.vectors.sources import emur_path
from vector_support import assert_generated, read_vectors, tol

LN_5742 = 8.655562860681009
LN_5221 = 8.560444233410552


@pytest.fixture(scope="module")
def segments():
    return json.loads(emur_path().read_text())["segments"]


def real_frame(segments, utterance, index):
    """Frame ``index`` of the segment of ``utterance`` as an (8, 8) uint8 array, R1 first."""
    segment = next(s for s in segments if s["utt"] == utterance)
    rows = segment["frames"][index]["rows"]
    return np.array([[int(ch) for ch in row] for row in rows], dtype=np.uint8)


def test_a_velar_s_to_k_frame_of_bescan_matches_hand_arithmetic(segments):
    # sp1bescan (s->k), frame 0, t = 155.965 s:
    #   R1 00000000  R2 10000000  R3 10000001  R4 10000000
    #   R5 10000000  R6 11000001  R7 11000001  R8 11000011
    # rows 0,1,2,1,1,3,3,4 -> 15 contacts; percent = 1500/62 = 24.193548387
    # zones: alveolar 0+1 = 1 (1/14), palatal 2+1+1 = 4 (4/24), velar 3+3+4 = 10 (10/24)
    # cog = (6.5*1 + 5.5*2 + 4.5*1 + 3.5*1 + 2.5*3 + 1.5*3 + 0.5*4) / 15 = 39.5/15 = 2.633333333
    # ai  = ln(1 + 729/8 + 81*2/8 + 9/8 + 1/8) / ln 5742 = ln 113.625 / ln 5742
    #     = 4.732903552 / 8.655562861 = 0.546804827
    # columns: c1 = 7 (R2-R8), c8 = 4 (R3, R6, R7, R8), c2 = 3 (R6-R8), c7 = 1 (R8), others 0
    # ci  = ln(1 + 11/14 + 17*4/16) / ln 5221 = ln 6.035714286 / ln 5221
    #     = 1.797694205 / 8.560444233 = 0.210000107
    # di  = 10/24 = 0.416666667
    values = indices.epg_indices(real_frame(segments, "sp1bescan", 0))
    expected = {"contacts": 15, "percent": 24.193548387, "alveolar": 1, "palatal": 4,
                "velar": 10, "alveolar_percent": 7.142857143, "palatal_percent": 16.666666667,
                "velar_percent": 41.666666667, "cog": 2.633333333, "anteriority": 0.546804827,
                "centrality": 0.210000107, "dorsopalatal": 0.416666667}
    for name, value in expected.items():
        np.testing.assert_allclose(values[name], value, rtol=1e-9, err_msg=name)
    np.testing.assert_array_equal(  # counts: exact
        [values[f"row{r}"][0] for r in range(1, 9)], [0, 1, 2, 1, 1, 3, 3, 4])


def test_an_alveolar_n_closure_of_grangate_matches_hand_arithmetic(segments):
    # sp1grangate (n->g), frame 10, t = 708.505 s:
    #   R1 01111110  R2 11100011  R3 11000001  R4 10000001
    #   R5 11000001  R6 11000001  R7 11000011  R8 11100111
    # rows 6,5,3,2,3,3,4,6 -> 32 contacts; percent = 3200/62 = 51.612903226
    # zones: alveolar 11 (78.571428571 %), palatal 8 (33.333333333 %), velar 13 (54.166666667 %)
    # cog = (7.5*6 + 6.5*5 + 5.5*3 + 4.5*2 + 3.5*3 + 2.5*3 + 1.5*4 + 0.5*6) / 32
    #     = (45 + 32.5 + 16.5 + 9 + 10.5 + 7.5 + 6 + 3) / 32 = 130/32 = 4.0625
    # ai  = ln(1 + 4921*6/6 + 729*5/8 + 81*3/8 + 9*2/8 + 1*3/8) / ln 5742
    #     = ln(1 + 4921 + 455.625 + 30.375 + 2.25 + 0.375) / ln 5742 = ln 5410.625 / ln 5742
    #     = 8.596119892 / 8.655562861 = 0.993132397
    # columns: c1 7, c8 7 -> 14; c2 7, c7 4 -> 11; c3 3, c6 2 -> 5; c4 1, c5 1 -> 2 (sum 32)
    # ci  = ln(1 + 14/14 + 17*11/16 + 289*5/16 + 4913*2/16) / ln 5221
    #     = ln(1 + 1 + 11.6875 + 90.3125 + 614.125) / ln 5221 = ln 718.125 / ln 5221
    #     = 6.576643649 / 8.560444233 = 0.768259622
    # di  = 13/24 = 0.541666667
    values = indices.epg_indices(real_frame(segments, "sp1grangate", 10))
    expected = {"contacts": 32, "percent": 51.612903226, "alveolar_percent": 78.571428571,
                "palatal_percent": 33.333333333, "velar_percent": 54.166666667, "cog": 4.0625,
                "anteriority": 0.993132397, "centrality": 0.768259622,
                "dorsopalatal": 0.541666667}
    for name, value in expected.items():
        np.testing.assert_allclose(values[name], value, rtol=1e-9, err_msg=name)


def test_a_velar_k_frame_of_duncourt_has_zero_anteriority_and_a_low_cog(segments):
    # sp1duncourt (n->k), frame 25, t = 685.075 s: R1-R5 empty,
    #   R6 10000000  R7 10000001  R8 11100111 -> rows 0,0,0,0,0,1,2,6, 9 contacts
    # percent = 900/62 = 14.516129032; velar 9/24 = 37.5 %
    # cog = (2.5*1 + 1.5*2 + 0.5*6) / 9 = 8.5/9 = 0.944444444
    # ai  = ln(1 + 0) / ln 5742 = 0
    # columns: c1 3, c8 2 -> 5; c2 1, c7 1 -> 2; c3 1, c6 1 -> 2; c4, c5 0
    # ci  = ln(1 + 5/14 + 17*2/16 + 289*2/16) / ln 5221 = ln 39.607142857 / ln 5221
    #     = 3.679009477 / 8.560444233 = 0.429768523
    # di  = 9/24 = 0.375
    values = indices.epg_indices(real_frame(segments, "sp1duncourt", 25))
    expected = {"contacts": 9, "percent": 14.516129032, "alveolar_percent": 0.0,
                "palatal_percent": 0.0, "velar_percent": 37.5, "cog": 0.944444444,
                "anteriority": 0.0, "centrality": 0.429768523, "dorsopalatal": 0.375}
    for name, value in expected.items():
        np.testing.assert_allclose(values[name], value, rtol=1e-9, atol=1e-12, err_msg=name)


def test_an_empty_palate_gives_zero_everywhere_including_the_cog():
    # emuR's epgcog returns 0 when a palate has no contact (it never divides by zero)
    values = indices.epg_indices(np.zeros((8, 8), dtype=np.uint8))
    for name, value in values.items():
        # counts are 0; ln(1 + 0) is 0 up to rounding
        assert value[0] == pytest.approx(0.0, abs=1e-12), name


def test_a_full_palate_gives_one_for_the_contact_indices_and_100_percent():
    # cog = (7.5*6 + (6.5 + 5.5 + 4.5 + 3.5 + 2.5 + 1.5 + 0.5)*8) / 62 = (45 + 196)/62 = 241/62
    full = np.ones((8, 8), dtype=np.uint8)
    full.reshape(-1)[list(EPG_MISSING_CELLS)] = 0
    values = indices.epg_indices(full)
    np.testing.assert_allclose(
        [values[k][0] for k in ("contacts", "percent", "anteriority", "centrality",
                                "dorsopalatal", "alveolar_percent", "velar_percent", "cog")],
        [62, 100, 1, 1, 1, 100, 100, 241 / 62], rtol=1e-12)


def test_the_table_columns_equal_the_single_index_functions_on_every_real_frame(segments):
    frames = np.array([[[int(ch) for ch in row] for row in f["rows"]]
                       for s in segments for f in s["frames"]], dtype=np.uint8)
    assert frames.shape == (1421, 8, 8)
    table = indices.index_table(frames)
    column = {name: table[:, i] for i, name in enumerate(indices.INDEX_SLOTS)}
    # The same formulae by two routes: a logarithm or a division may round differently (1e-12).
    for name, single in (("cog", indices.centre_of_gravity), ("anteriority",
                          indices.anteriority_index), ("centrality", indices.centrality_index),
                         ("dorsopalatal", indices.dorsopalatal_index),
                         ("percent", indices.percent_contact)):
        np.testing.assert_allclose(column[name], single(frames), rtol=1e-12, atol=1e-12,
                                   err_msg=name)
    np.testing.assert_array_equal(column["contacts"], frames.sum(axis=(1, 2)))  # counts
    # ln(x) / ln(x) may miss 1 by an ulp: indices lie in [0, 1] up to 1e-12
    assert 0 < column["anteriority"].max() <= 1 + 1e-12
    assert column["centrality"].min() >= -1e-12


@pytest.mark.parametrize("bad, message", [
    (np.zeros((3, 8, 7), dtype=np.uint8), "shape"),
    (np.full((1, 8, 8), 2, dtype=np.uint8), "other than 0 or 1"),
    (np.zeros((2, 8, 8), dtype=np.float32), "integers"),
])
def test_frames_of_the_wrong_shape_type_or_values_are_refused(bad, message):
    with pytest.raises(ValueError, match=message):
        indices.index_table(bad)


def test_a_contact_in_a_missing_r1_corner_is_refused_naming_the_frame():
    frames = np.zeros((3, 8, 8), dtype=np.uint8)
    frames[2, 0, 7] = 1
    with pytest.raises(ValueError, match="frame 2: R1 column 8 has no electrode"):
        indices.index_table(frames)


@pytest.mark.vectors
def test_the_shared_vectors_are_up_to_date_with_the_python_indices():
    vectors = read_vectors("epg-indices.json")
    index = tol(vectors, "index")  # relative above 1, absolute below
    assert_generated("epg-indices.json", build_document(emur_path()), vectors, atol=index,
                     rtol=index)
    assert vectors["constants"]["electrodes"] == EPG_ELECTRODES
    assert vectors["constants"]["zones"] == {k: list(v) for k, v in EPG_ZONES.items()}
    assert vectors["constants"]["slots"] == list(indices.INDEX_SLOTS)
    descriptions = [case["description"] for case in vectors["cases"]]
    assert len(set(descriptions)) == len(descriptions) >= 50
