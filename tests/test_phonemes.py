"""The phoneme inventory: CMUdict's 39 ARPAbet phonemes with IPA, features, examples and the
measured JD3 shape (or the reasoning) each target comes from."""

import json

import pytest

from glasshead.phonemes import CONTEXTS, INVENTORY, UnknownPhonemeError, lookup

#: CMUdict's phoneme set (cmudict.phones).
CMUDICT = ("AA AE AH AO AW AY B CH D DH EH ER EY F G HH IH IY JH K L M N NG OW OY P R S SH T "
           "TH UH UW V W Y Z ZH").split()


def test_the_inventory_is_cmudicts_39_phonemes_each_once_with_distinct_ipa():
    assert sorted(p.arpabet for p in INVENTORY) == sorted(CMUDICT)
    assert len({p.ipa for p in INVENTORY}) == 39


def test_nasals_and_only_nasals_lower_the_velum():
    assert {p.arpabet for p in INVENTORY if p.velum_lowered} == {"M", "N", "NG"}


@pytest.mark.parametrize(("symbol", "arpabet"), [
    ("t", "T"), ("T", "T"), ("iy1", "IY"), ("IY0", "IY"), ("ŋ", "NG"), ("ʃ", "SH"), ("ɡ", "G"),
    ("g", "G"), ("tʃ", "CH"), ("ʧ", "CH"), ("ɹ", "R"), ("θ", "TH"), ("aɪ", "AY"), (" k ", "K")])
def test_symbols_are_found_in_arpabet_or_ipa(symbol, arpabet):
    assert lookup(symbol).arpabet == arpabet


@pytest.mark.parametrize("symbol", ["Q", "", "  ", "tt", "IY3", 5])
def test_an_unknown_symbol_is_refused_naming_it_and_the_choices(symbol):
    with pytest.raises(UnknownPhonemeError) as refusal:
        lookup(symbol)
    message = str(refusal.value)
    assert "ARPAbet" in message or "non-empty" in message


def test_every_measured_shape_exists_in_the_vtl_observations_in_every_context(built_assets):
    path = built_assets / "vtl-observations.json"
    names = {s["name"] for s in json.loads(path.read_text())["shapes"]}
    for p in INVENTORY:
        if p.shape is None:
            assert p.reasoning, f"{p.arpabet} has neither a measured shape nor reasoning"
        elif p.kind == "consonant":
            assert {f"{p.shape}({c})" for c in CONTEXTS} <= names, p.arpabet
        else:
            assert p.shape in names, p.arpabet


def test_the_mapping_the_targets_document():
    shape = {p.arpabet: p.shape for p in INVENTORY}
    assert {shape[s] for s in ("T", "D", "N")} == {"tt-alveolar-closure"}
    assert {shape[s] for s in ("S", "Z")} == {"tt-alveolar-fricative"}
    assert {shape[s] for s in ("SH", "ZH")} == {"tt-postalveolar-fricative"}
    assert {shape[s] for s in ("CH", "JH")} == {"tt-postalveolar-closure"}
    assert shape["L"] == "tt-alveolar-lateral"
    assert {shape[s] for s in ("TH", "DH")} == {"tt-dental-fricative"}
    assert {shape[s] for s in ("K", "G", "NG")} == {"tb-velar-closure"}
    assert shape["Y"] == "tb-palatal-fricative"
    assert all(len(p.examples) >= 2 for p in INVENTORY)
