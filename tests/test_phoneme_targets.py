"""Phoneme targets (pipeline.phoneme_targets, with target_fits, target_contact and
target_realism): built from the real rig and JD3 observations, read through the asset store and
served by GET /phonemes. No mocks: the targets are the ones the build made from the built assets
(``built_assets`` builds them when they are stale), read from a copy whose inputs are checked to
give the same cache key."""

import json
import shutil

import numpy as np
import pytest
from fastapi.testclient import TestClient

from glasshead.constants import (
    FACE_RIG_LIP_PARAMETERS,
    PHONEME_TARGETS_FILE,
    PHONEME_TARGETS_FORMAT_VERSION,
    TONGUE_RIG_FILE,
    VELUM_PARAMETER,
)
from glasshead.epg import classes as obs
from glasshead.epg import synthetic
from glasshead.phonemes import INVENTORY
from glasshead.pipeline.outputs import current_output
from glasshead.pipeline.phoneme_targets import (
    BUILDER,
    CODE,
    INPUT_FILES,
    build_phoneme_targets,
    input_key,
)
from glasshead.pipeline.target_contact import (
    HELD_OF_GOAL,
    JAW_SLACK_OF_GOAL,
    PENETRATION_OF_GOAL,
)
from glasshead.pipeline.target_fits import (
    HELD_IN_TARGETS,
    TARGET_CORONAL_RANGES,
    VOLUME_GOAL_PCT,
    Context,
)


@pytest.fixture(scope="module")
def built(built_assets, data_dir, tmp_path_factory):
    """A copy of the built inputs and of the targets the build made from them, and what building
    again in that copy gives (skipped: the inputs and the code are the same)."""
    directory = tmp_path_factory.mktemp("targets")
    for name in (*INPUT_FILES, PHONEME_TARGETS_FILE):
        shutil.copy(built_assets / name, directory / name)
    document = json.loads((directory / PHONEME_TARGETS_FILE).read_text())
    again, skipped_again = build_phoneme_targets(directory, data_dir)
    return {"dir": directory, "document": document, "again": again,
            "skipped_again": skipped_again}


@pytest.fixture(scope="module")
def targets(built):
    return {t["arpabet"]: t for t in built["document"]["targets"]}


def grid(target):
    return np.array([[int(c) for c in row] for row in target["epg"]["rows"]], dtype=np.uint8)


def test_every_phoneme_has_a_target_with_every_parameter_in_range(built, targets, built_assets):
    rig = json.loads((built_assets / "tongue-rig.json").read_text())["parameters"]
    face = json.loads((built_assets / "face-rig.json").read_text())["parameters"]
    velum = json.loads((built_assets / "velum-rig.json").read_text())["parameters"]
    specs = {p["name"]: p for p in [*rig, *face, *velum]}
    assert set(targets) == {p.arpabet for p in INVENTORY} and len(targets) == 39
    for symbol, target in targets.items():
        assert set(target["params"]) == set(specs), symbol
        for name, value in target["params"].items():
            assert specs[name]["min"] - 1e-9 <= value <= specs[name]["max"] + 1e-9, (symbol, name)
        assert len(target["epg"]["rows"]) == 8 and all(len(r) == 8 for r in target["epg"]["rows"])
        assert "percent" in target["epg"]["indices"]
        assert target["examples"] and target["source"]["kind"]
    assert set(FACE_RIG_LIP_PARAMETERS) <= set(specs)


def test_nasals_lower_the_velum_and_no_others(targets):
    for p in INVENTORY:
        value = targets[p.arpabet]["params"][VELUM_PARAMETER]
        assert value == (1.0 if p.nasal else 0.0), p.arpabet
    assert {p.arpabet for p in INVENTORY if p.nasal} == {"M", "N", "NG"}


def test_every_target_keeps_the_volume_within_five_percent(targets):
    for symbol, target in targets.items():
        assert abs(target["volume_change_pct"]) <= VOLUME_GOAL_PCT, symbol
        for context, variant in target["contexts"].items():
            assert abs(variant["volume_change_pct"]) <= VOLUME_GOAL_PCT, (symbol, context)


def test_measured_consonants_keep_their_a_i_u_variants(targets):
    for p in INVENTORY:
        if p.shape and p.kind == "consonant":
            contexts = targets[p.arpabet]["contexts"]
            assert set(contexts) == {"a", "i", "u"}, p.arpabet
            assert contexts["i"]["fit"]["shape"] == f"{p.shape}(i)"
            assert targets[p.arpabet]["source"]["shapes"] == [f"{p.shape}({c})" for c in "aiu"]


def test_reasoned_targets_say_why(targets):
    for symbol in ("W", "R", "HH"):
        assert targets[symbol]["source"]["kind"] == "reasoning"
        assert targets[symbol]["source"]["reasoning"]
    assert targets["W"]["params"]["lip_rounding"] > targets["UW"]["params"]["lip_rounding"] or \
        targets["UW"]["params"]["lip_rounding"] == 10.0


def test_the_open_vowel_has_little_contact(targets):
    assert grid(targets["AA"]).sum() <= 6


def test_the_realism_report_matches_the_patterns(built, targets):
    """The report's verdicts are the rules applied to the built patterns."""
    realism = built["document"]["realism"]
    verdict = {r["phoneme"]: r["pass"] for r in realism["rules"]}
    assert verdict["T"] == (obs.front_closure(grid(targets["T"]))
                            and obs.side_contact(grid(targets["T"])))
    assert verdict["S"] == obs.central_groove(grid(targets["S"]))
    assert verdict["K"] == obs.back_closure(grid(targets["K"]))
    assert verdict["AA"] is True
    assert set(realism["agreement"]) == {"alveolar_stop", "alveolar_fricative", "velar_stop"}
    for entry in realism["agreement"].values():
        for symbol, share in entry["agreement"].items():
            assert 0 <= share <= 1
            majority = np.array([[int(c) for c in r] for r in entry["majority"]])
            assert share == pytest.approx(obs.agreement(grid(targets[symbol]), majority), abs=1e-4)


def test_the_contact_fits_meet_the_realism_rules(built, targets):
    """/t d n/ close a front row with side contact, /s z/ keep a groove between side contacts,
    /i/ touches the sides only and /a/ nothing: through the fits, no pattern written in."""
    g = {symbol: grid(targets[symbol]) for symbol in ("T", "D", "N", "S", "Z", "IY", "AA")}
    for symbol in ("T", "D", "N"):
        assert obs.front_closure(g[symbol]) and obs.side_contact(g[symbol]), symbol
    for symbol in ("S", "Z"):
        assert obs.central_groove(g[symbol]), symbol
    assert obs.side_contact(g["IY"]) and g["IY"][:, 2:6].sum() <= 2
    assert g["AA"].sum() <= 6
    realism = built["document"]["realism"]
    assert realism["passed"] >= 7 and realism["passed_before_contact_fit"] <= 2


def test_sh_zh_keep_a_postalveolar_groove_in_every_context_as_published_descriptions_say(
        targets):
    """/ʃ ʒ/ used to close R1-R3 across (no groove). Fitted to the pattern published EPG
    describes, the middle four columns stay free in R1-R4 between side contacts in R2-R5, and
    the groove is wider than /s/'s (which keeps columns 3 and 6 touched in a front row)."""
    for symbol in ("SH", "ZH"):
        grids = [grid(targets[symbol])] + [
            np.array([[int(c) for c in row] for row in context["epg"]["rows"]])
            for context in targets[symbol]["contexts"].values()]
        for g in grids:
            assert g[:4, 2:6].sum() <= 1, g
            assert g[1:5, 0].sum() >= 3 and g[1:5, 7].sum() >= 3, g
    s = grid(targets["S"])
    assert s[:4, [2, 5]].sum() > grid(targets["SH"])[:4, [2, 5]].sum()
    assert targets["SH"]["source"]["contact"]["goal"] == "rule: postalveolar groove"


def test_l_touches_the_ridge_with_free_sides_and_ch_jh_close_behind_t(targets):
    """/l/ had no contact at all, /tʃ dʒ/ none either: fitted to what published EPG describes,
    /l/ touches R1-R2 in the middle with its sides free behind, /tʃ dʒ/ close R2 across with
    contact along both sides, with less contact in R1 than /t/'s."""
    lateral = grid(targets["L"])
    assert max(lateral[0, 2:6].sum(), lateral[1, 2:6].sum()) >= 3, lateral
    assert lateral[2:, [0, 1, 6, 7]].sum() <= 2, lateral
    for symbol in ("CH", "JH"):
        g = grid(targets[symbol])
        assert g[1:3].all(axis=1).any() and obs.side_contact(g), g
        assert g[0].sum() < grid(targets["T"])[0].sum(), g


def test_each_target_says_what_its_palatogram_was_fitted_to(targets):
    assert {targets[s]["epg_basis"] for s in ("T", "S", "K")} == {"real EPG"}
    assert {targets[s]["epg_basis"] for s in ("SH", "ZH", "IY", "L", "CH", "JH", "R")} == {
        "published descriptions"}
    assert {targets[s]["epg_basis"] for s in ("W", "AA", "F")} == {"not fitted"}


def test_r_touches_the_sides_of_the_back_rows_and_keeps_its_reasoned_shape(targets):
    """/ɹ/ is reasoned from /ʃ/'s fit (the tip and blade lowered), which touched nothing; its
    contact fit, with its own outline held, gives it the lateral contact of a real /r/."""
    r = targets["R"]
    g = grid(r)
    assert not g[:2].any() and g[:, 2:6].sum() <= 2, g
    assert g[3:, 0].sum() >= 3 and g[3:, 7].sum() >= 3, g
    contact = r["source"]["contact"]
    assert contact["goal"] == "rule: rhotic lateral" and contact["agreement"] >= 0.9
    assert contact["before"]["rows"] == ["00000000"] * 8
    # The outline it was given is its own reasoned pose's: the fit moves it little.
    assert contact["rms_mm"] < 2.0 and abs(r["volume_change_pct"]) < 5.0
    assert r["source"]["kind"] == "reasoning" and r["source"]["from"] == "SH"


def test_k_g_ng_close_a_back_row_in_every_context_fitted_to_the_real_frames_that_do(built,
                                                                                    targets):
    """Most real /k g/ frames close behind the palate's last row, so the class's majority has no
    complete back row; the velar goal is the majority of the frames that close one, and every
    fitted velar target closes one too, within the volume goal."""
    velar = built["document"]["realism"]["agreement"]["velar_stop"]
    assert velar["majority_passes_rule"] is False and velar["real_frames_passing_rule"] < 0.5
    for symbol in ("K", "G", "NG"):
        assert obs.back_closure(grid(targets[symbol])), symbol
        for context, variant in targets[symbol]["contexts"].items():
            rows = variant["epg"]["rows"]
            assert obs.back_closure(grid(variant)), (symbol, context, rows)
            assert abs(variant["volume_change_pct"]) <= VOLUME_GOAL_PCT
            contact = variant["fit"]["contact"]
            assert contact["goal"] == "velar_stop" and contact["goal_frames"] == 8
            # fronted before /i/: R6 and R7 wanted closed too (FRONTED_ROWS_OF_GOAL)
            assert contact["fronted_rows"] == ([6, 7] if context == "i" else []), context


def test_the_velar_closure_holds_when_the_jaw_or_the_body_moves_a_little(built, targets):
    """The velar targets of /a/ and /u/ context close their back row with a margin
    (``PENETRATION_OF_GOAL``), not by grazing it: /k g ng/ there keep a full row in R6-R8 with
    the jaw 0.3 deg more open or closed, or one body parameter 0.3 mm up or down. Fitted to reach
    R8 only just (no margin), /k/(a) lost R8 with the jaw 0.3 deg more open. /k/(i) has only a
    0.15 mm margin (more would draw the dorsum back and undo the fronting before /i/), so it is not
    asked here. Every context keeps it with the jaw ``JAW_SLACK_OF_GOAL`` more open, as its
    neighbours leave the jaw in running speech."""
    contexts = {c for c, mm in PENETRATION_OF_GOAL["velar_stop"].items() if mm >= 0.3}
    assert contexts == {"a", "u"}
    ctx = Context(built["dir"])
    rig = ctx.rig
    moves = [("jaw_opening", d) for d in (-0.3, 0.3)] + [
        (name, d) for name in ("dorsum_height", "back_dorsum_height", "body_height",
                               "dorsum_advancement") for d in (-0.3, 0.3)]
    slack = [("jaw_opening", JAW_SLACK_OF_GOAL["velar_stop"])]
    assert slack[0][1] >= 1.0
    failed = []
    for symbol in ("K", "G", "NG"):
        for context in ("a", "i", "u"):
            variant = targets[symbol]["contexts"][context]
            tongue = {n: v for n, v in variant["params"].items() if n in rig.parameter_names}
            for name, change in (moves if context in contexts else []) + slack:
                k = rig.parameter_names.index(name)
                moved = {**tongue, name: float(np.clip(tongue[name] + change, rig.minimum[k],
                                                       rig.maximum[k]))}
                epg = ctx.epg(moved)
                if not obs.back_closure(epg["grid"]):
                    failed.append((symbol, context, name, change, epg["rows"][5:]))
    assert failed == []


def test_the_velars_keep_the_tip_below_the_alveolars_in_every_context(built, targets):
    """The velar contact fits hold the tip where the 2D fit put it (``HELD_OF_GOAL``): the
    frontmost point of the corrected tongue, the tip the speech player follows, lies at least
    0.5 mm lower in /k g ng/ than in /t d n/ of the same vowel context. With the tip free the
    fits raised it (/k/(i) 4.4 mm above /t/(i)), and in "and Kim" it peaked in /k/."""
    assert built["document"]["contact_fit"]["held_of_goal"]["velar_stop"] \
        == list(HELD_OF_GOAL["velar_stop"]) == ["tip_advancement", "tip_height", "tip_thickness"]
    ctx = Context(built["dir"])

    def tip_y(params):
        tongue = {n: v for n, v in params.items() if n in ctx.rig.parameters}
        corrected, _ = synthetic.corrected_tongue(ctx.rig, ctx.rig.values_from(tongue),
                                                  ctx.tables)
        return corrected[np.argmax(corrected[:, 0]), 1]

    for context in ("a", "i", "u"):
        alveolar = tip_y(targets["T"]["contexts"][context]["params"])
        for symbol in ("K", "G", "NG"):
            velar = tip_y(targets[symbol]["contexts"][context]["params"])
            assert velar <= alveolar - 0.5, (symbol, context, velar, alveolar)


def test_the_contact_fits_raise_the_agreement_and_keep_the_volume(built, targets):
    shares = built["document"]["realism"]["agreement"]
    for name, entry in shares.items():
        for symbol, share in entry["agreement"].items():
            before = entry["agreement_before_contact_fit"][symbol]
            assert share >= 0.78 and share >= before + 0.2, (name, symbol, before, share)
    for symbol in ("T", "D", "N", "S", "Z", "K", "G", "NG"):
        for context, variant in targets[symbol]["contexts"].items():
            contact = variant["fit"]["contact"]
            assert contact["goal"] in shares
            assert contact["epg_error_mm"] < contact["before"]["epg_error_mm"], (symbol, context)
            # /k/ before /i/ closes further forward (R6 to R8, fronted and held on a looser
            # jaw) than the majority of the real closing frames (R8): 0.71-0.74 measured.
            least = 0.68 if (symbol in ("K", "G", "NG") and context == "i") else 0.75
            assert contact["agreement"] >= least, (symbol, context, contact["agreement"])
            assert abs(variant["volume_change_pct"]) <= VOLUME_GOAL_PCT
            assert variant["fit"]["rms_mm"] > 0
    iy = targets["IY"]["source"]["contact"]
    assert iy["goal"].startswith("rule") and iy["agreement"] >= 0.9
    assert "contact" not in targets["AA"]["source"]


def test_every_target_holds_the_turn_of_the_body_and_the_radial_moves(built, targets):
    held = ["tongue_retraction", "dorsum_front_lowering", "root_base_advancement"]
    assert built["document"]["contact_fit"]["held"] == list(HELD_IN_TARGETS) == held
    for symbol, target in targets.items():
        variants = [target["params"]] + [v["params"] for v in target["contexts"].values()]
        assert all(v[name] == 0.0 for v in variants for name in held), symbol


def test_the_build_report_lists_each_contact_fit(built, built_assets, data_dir):
    from types import SimpleNamespace

    from glasshead.pipeline.phoneme_targets import build_step
    report = build_step(SimpleNamespace(assets_dir=built["dir"], data_dir=data_dir))
    assert report["skipped"] is True
    t = report["targets"]["T"]
    assert {"rms_mm", "epg_error_mm", "agreement", "volume_change_pct", "before"} <= set(t)
    assert report["realism"]["passed"] == built["document"]["realism"]["passed"]


def test_the_second_build_is_skipped(built, data_dir):
    assert built["skipped_again"] is True and built["again"] == built["document"]
    assert built["document"]["source"]["sha256"] == input_key(built["dir"], data_dir)
    # The time is reported (build report, docs/targets.md), not asserted: it depends on the load.
    assert built["document"]["build_seconds"] > 0


def test_the_cache_key_reads_the_code_of_every_module_the_targets_are_made_with():
    from glasshead.fitting import vtl_mapping
    from glasshead.pipeline import target_contact, target_fits, target_realism

    assert {target_fits, target_contact, target_realism, vtl_mapping} <= set(CODE)


def test_a_changed_input_changes_the_cache_key_so_the_targets_are_built_again(built, data_dir,
                                                                              tmp_path):
    for name in (*INPUT_FILES, PHONEME_TARGETS_FILE):
        shutil.copy(built["dir"] / name, tmp_path / name)
    before = input_key(tmp_path, data_dir)
    rig = json.loads((tmp_path / TONGUE_RIG_FILE).read_text())
    rig["parameters"][0]["max"] += 1.0
    (tmp_path / TONGUE_RIG_FILE).write_text(json.dumps(rig))
    assert input_key(tmp_path, data_dir) != before
    assert current_output(tmp_path / PHONEME_TARGETS_FILE, input_key(tmp_path, data_dir),
                          BUILDER, PHONEME_TARGETS_FORMAT_VERSION) is None


@pytest.fixture()
def client(built):
    from glasshead.api.app import create_app
    from glasshead.asset_store import ASSETS, AssetStore
    app = create_app()
    app.state.assets = AssetStore(built["dir"], specs=ASSETS)
    with TestClient(app) as c:
        yield c


def test_the_list_and_each_target_are_served(client):
    listed = client.get("/api/v1/phonemes")
    assert listed.status_code == 200
    body = listed.json()
    assert body["count"] == 39 and body["phonemes"][0]["arpabet"] == "AA"
    assert {"arpabet", "ipa", "kind", "voiced", "manner", "examples", "source"} <= set(
        body["phonemes"][0])
    by_symbol = {p["arpabet"]: p for p in body["phonemes"]}
    # The cue layer sets the glottis from these: open for /s/, half open for /z/.
    assert (by_symbol["S"]["voiced"], by_symbol["S"]["manner"]) == (False, "fricative")
    assert (by_symbol["Z"]["voiced"], by_symbol["M"]["manner"]) == (True, "nasal")
    for symbol in ("T", "t", "ah1", "Ah0", "%CA%83", "ʃ", "tʃ"):
        response = client.get(f"/api/v1/phonemes/{symbol}")
        assert response.status_code == 200, symbol
    assert client.get("/api/v1/phonemes/ah1").json()["arpabet"] == "AH"
    assert client.get("/api/v1/phonemes/%CA%83").json()["arpabet"] == "SH"
    one = client.get("/api/v1/phonemes/N").json()
    assert one["params"][VELUM_PARAMETER] == 1.0 and len(one["epg"]["rows"]) == 8
    assert set(one["contexts"]) == {"a", "i", "u"}


def test_an_unknown_symbol_is_a_404_pointing_to_the_list(client):
    response = client.get("/api/v1/phonemes/QQ")
    assert response.status_code == 404
    assert "'QQ'" in response.json()["detail"] and "/api/v1/phonemes" in response.json()["detail"]


def test_an_unbuilt_file_is_a_503(built, tmp_path):
    from glasshead.api.app import create_app
    from glasshead.asset_store import AssetStore
    for name in INPUT_FILES:
        shutil.copy(built["dir"] / name, tmp_path / name)
    app = create_app()
    app.state.assets = AssetStore(tmp_path)
    with TestClient(app) as c:
        app.state.assets = AssetStore(tmp_path)
        for path in ("/api/v1/phonemes", "/api/v1/phonemes/T"):
            response = c.get(path)
            assert response.status_code == 503
            assert response.json()["file"] == PHONEME_TARGETS_FILE


def test_every_target_keeps_the_coronal_ranges_of_the_targets(built_assets, targets):
    """The targets' fits keep ``TARGET_CORONAL_RANGES``, narrower than the rig's (widened for the
    3D fits): every coronal value of every target and context lies within them, and they lie
    within the rig's."""
    from glasshead.fitting.fit_contact import SECTIONS, free_groups

    rig = Context(built_assets).rig
    members = dict(free_groups(rig, jaw=False))
    for group, (low, high) in TARGET_CORONAL_RANGES.items():
        names = [n for section in SECTIONS for n in members[f"{section}_{group}"]]
        assert len(names) >= 3, group
        for name in names:
            spec = rig.parameters[name]
            assert spec["min"] <= low < high <= spec["max"], name
            for symbol, target in targets.items():
                for params in [target["params"]] + [v["params"] for v in
                                                     target["contexts"].values()]:
                    assert low - 1e-9 <= params[name] <= high + 1e-9, (symbol, name)
