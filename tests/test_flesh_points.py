"""Flesh points: the rig's EMA sensor points, material points of the tongue, the incisors and the
lips, tracked through an utterance and sent by POST /utterances with ``"flesh_points": true``."""

import numpy as np
import pytest

from glasshead.asset_store import AssetStore
from glasshead.geometry.flesh_points import (
    FLESH_POINT_NAMES,
    TONGUE_SENSOR_ARC_MM,
    midline_outline,
    tongue_anchors,
    tongue_points,
)

API = "/api/v1"
#: A consonant between open vowels, 150 ms each: /ɑ C ɑ/ for every C in CONSONANTS.
CONSONANTS = ("T", "D", "N", "P", "B", "M")
PHONE_S = 0.15


@pytest.fixture(scope="module")
def store(built_store):
    return built_store


@pytest.fixture(scope="module")
def rig(store):
    from glasshead.flesh_point_assets import flesh_point_rig

    return flesh_point_rig(store)


@pytest.fixture
def client(built_assets, start_app, tmp_path, monkeypatch):
    monkeypatch.setenv("GLASSHEAD_SPEECH_CACHE_DIR", str(tmp_path / "utterances"))
    return start_app(built_assets)[1]


def _phones():
    symbols = ["sil", "AA"] + [s for c in CONSONANTS for s in (c, "AA")] + ["sil"]
    return [{"symbol": s, "start_s": round(k * PHONE_S, 6), "end_s": round((k + 1) * PHONE_S, 6)}
            for k, s in enumerate(symbols)]


@pytest.fixture(scope="module")
def spoken(built_assets, tmp_path_factory):
    """The /ɑ C ɑ/ utterance with its flesh points, as the compute worker makes it."""
    import json

    from glasshead.api.routes.utterances import UtteranceRequest, speak

    request = UtteranceRequest(phones=_phones(), audio={"kind": "none"}, flesh_points=True)
    cache = tmp_path_factory.mktemp("utterances")
    body = json.loads(speak(AssetStore(built_assets), {"request": request.model_dump(mode="json"),
                                                       "cache_dir": str(cache)}))
    return body


def _middle(body, symbol):
    """Frame indices of the middle 60 ms of every phone ``symbol``."""
    frames = []
    for phone in body["phones"]:
        if phone["symbol"] == symbol:
            middle = 0.5 * (phone["start_s"] + phone["end_s"]) * body["rate_hz"]
            frames.extend(range(int(middle) - 3, int(middle) + 4))
    return frames


def test_the_tongue_sensors_lie_at_their_arc_lengths_from_the_apex_on_the_upper_outline(rig):
    tongue = rig.tongue
    outline = midline_outline(tongue, tongue.neutral)
    points = tongue_points(outline, rig.anchors)
    apex = outline[np.argmax(outline[:, 0])]
    assert np.all(points[:, 2] == 0.0)
    # walking from the apex to each sensor along the outline: the sensors come in order, go
    # back and stay above the apex (the upper surface, not the underside)
    assert np.all(np.diff(points[:, 0]) < 0) and np.all(points[:, 1] > apex[1])
    first, second, weight = rig.anchors
    assert np.all((weight >= 0) & (weight < 1))
    for (arc, k) in zip(TONGUE_SENSOR_ARC_MM.values(), range(4), strict=True):
        # the arc to the sensor, summed over the segments walked
        n = len(outline)
        step = 1 if (second[k] - first[k]) % n == 1 else -1
        apex_index = int(np.argmax(outline[:, 0]))
        walked, i = 0.0, apex_index
        while i != first[k]:
            walked += np.linalg.norm(outline[(i + step) % n] - outline[i])
            i = (i + step) % n
        walked += weight[k] * np.linalg.norm(outline[second[k]] - outline[first[k]])
        assert walked == pytest.approx(arc, abs=1e-9)


def test_an_arc_longer_than_half_the_outline_is_refused(rig):
    with pytest.raises(ValueError, match="sensor arcs"):
        tongue_anchors(rig.tongue, (10.0, 1000.0))


def test_at_rest_the_incisors_are_their_landmarks_and_the_lips_their_reference_vertices(rig,
                                                                                        store):
    points = rig.frame({})
    marks = {m["name"]: m["position"] for m in store.get("landmarks")["landmarks"]}
    np.testing.assert_allclose(points["upper_incisor"], marks["upper_incisor_edge"])
    np.testing.assert_allclose(points["lower_incisor"], marks["lower_incisor_edge"])
    for name in ("upper_lip", "lower_lip"):
        rest = store.get(f"{name}_mesh")[0][rig.lips[name]["reference_vertex"]]
        # at the neutral lip parameters and jaw only the incisors' push may move them
        assert np.linalg.norm(points[name] - rest) < 1.0


def test_the_lower_incisor_turns_with_the_jaw_and_the_upper_stays(rig):
    shut, open_ = rig.frame({"jaw_opening": 0.0}), rig.frame({"jaw_opening": 10.0})
    np.testing.assert_array_equal(shut["upper_incisor"], open_["upper_incisor"])
    drop = shut["lower_incisor"][1] - open_["lower_incisor"][1]
    assert drop > 5.0  # 10 degrees about a condyle some 80 mm behind: about 8 mm down
    pivot = np.asarray(rig.tongue.jaw["pivot"])
    # a rotation about the pivot and a slide: the distance from the pivot changes only by the
    # slide, 10 * |(0.5, -0.15)| mm at most
    r0, r1 = (np.linalg.norm(p["lower_incisor"][:2] - pivot) for p in (shut, open_))
    assert abs(r1 - r0) <= 10 * np.hypot(0.5, 0.15)


def test_a_track_past_its_bound_by_a_rounding_is_clipped_not_refused(rig):
    tongue = rig.tongue
    tip = tongue.parameters["tip_height"]["max"]
    over = rig.frame({"tip_height": tip * (1 + 1e-15) + 1e-12, "lip_opening": -1e-16})
    at = rig.frame({"tip_height": tip, "lip_opening": 0.0})
    for name in FLESH_POINT_NAMES:
        np.testing.assert_array_equal(over[name], at[name])


def test_the_answer_has_every_point_with_one_position_per_frame(spoken):
    points = spoken["flesh_points"]
    assert tuple(points) == FLESH_POINT_NAMES
    for track in points.values():
        assert len(track) == spoken["n_frames"]
        assert all(len(p) == 3 and all(np.isfinite(p)) for p in track)
    tongue = np.array([points[n] for n in TONGUE_SENSOR_ARC_MM])
    assert np.all(tongue[..., 2] == 0.0)


def test_the_tip_rises_in_t_d_n_and_not_in_the_open_vowel(spoken):
    tip = np.array(spoken["flesh_points"]["tongue_tip"])[:, 1]
    vowel = tip[_middle(spoken, "AA")]
    for symbol in ("T", "D", "N"):
        alveolar = tip[_middle(spoken, symbol)]
        # measured: about 11 mm in /t d n/, about -4 mm in /ɑ/
        assert alveolar.min() > vowel.max() + 10.0, symbol


def test_the_lower_incisor_drops_with_the_jaw_in_the_open_vowel(spoken):
    incisor = np.array(spoken["flesh_points"]["lower_incisor"])[:, 1]
    jaw = np.array(spoken["tracks"]["jaw_opening"])
    vowel, stops = _middle(spoken, "AA"), _middle(spoken, "T") + _middle(spoken, "P")
    assert jaw[vowel].mean() > jaw[stops].mean()
    # measured: about 1 mm lower in /ɑ/ than in /t/ and /p/ (the targets' jaw differs by 0.7 deg)
    assert incisor[vowel].mean() < incisor[stops].mean() - 0.5
    # lower where the jaw is more open, frame by frame
    assert np.corrcoef(jaw, incisor)[0, 1] < -0.99
    np.testing.assert_array_equal(np.array(spoken["flesh_points"]["upper_incisor"]),
                                  np.array(spoken["flesh_points"]["upper_incisor"][:1]
                                           * spoken["n_frames"]))


def test_the_lips_meet_in_p_b_m_and_part_in_the_vowel(spoken):
    upper = np.array(spoken["flesh_points"]["upper_lip"])
    lower = np.array(spoken["flesh_points"]["lower_lip"])
    gap = upper[:, 1] - lower[:, 1]
    for symbol in ("P", "B", "M"):
        # measured: 0.05 mm between the vermilion midpoints at the closure's middle
        assert gap[_middle(spoken, symbol)].min() < 0.2, symbol
    assert gap[_middle(spoken, "AA")].min() > 4.0  # measured: about 4.6 mm


def test_without_the_flag_there_are_no_flesh_points_and_the_flag_is_its_own_request(client):
    body = {"phones": _phones()[:4], "audio": {"kind": "none"}}
    without = client.post(f"{API}/utterances", json=body)
    assert without.status_code == 200
    assert without.json().get("flesh_points") is None
    with_ = client.post(f"{API}/utterances", json={**body, "flesh_points": True})
    assert with_.status_code == 200
    answer = with_.json()
    assert answer["id"] != without.json()["id"]
    assert set(answer["flesh_points"]) == set(FLESH_POINT_NAMES)
    assert all(len(t) == answer["n_frames"] for t in answer["flesh_points"].values())
    assert answer["tracks"] == without.json()["tracks"]


@pytest.mark.vectors
def test_the_shared_vectors_are_what_the_reference_computes_from_their_fixtures():
    from glasshead.vectors.common import read
    from glasshead.vectors.flesh_points import make_rig

    vectors = read("flesh-points.json")
    fixtures = vectors["fixtures"]
    rig = make_rig(read(fixtures["tongue_rig"])["fixtures"]["rig"],
                   read(fixtures["face_rig"])["fixtures"], fixtures["incisors"])
    anchors = fixtures["anchors"]
    assert rig.anchors[0].tolist() == anchors["first"]
    assert rig.anchors[1].tolist() == anchors["second"]
    np.testing.assert_allclose(rig.anchors[2], anchors["weight"], atol=1e-7)
    stored = vectors["tolerance"]["stored_mm"]["value"]
    assert len(vectors["cases"]) > 100
    for vector in vectors["cases"]:
        points = rig.frame(vector["input"]["params"])
        for name, expected in vector["expected"]["points"].items():
            np.testing.assert_allclose(points[name], expected, rtol=0, atol=stored,
                                       err_msg=f"{vector['description']}: {name}")
