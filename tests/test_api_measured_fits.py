"""Fits to flesh points (kind ``ema``) and to several measurements at once (kind ``combined``).

The flesh points are the head's own at a phoneme target (``FleshPointRig.frame``), so the fit
has a known answer: the target's jaw and sensor positions. The contour is JD3's /a/ outline and
the EPG frames engassim's /n/, as in test_api_fits.py.
"""

import json

import numpy as np
import pytest

from accounts_support import signed_in
from glasshead.asset_store import AssetStore
from glasshead.flesh_point_assets import flesh_point_rig
from glasshead.store.fit_jobs import FitJob
from glasshead.uploads import ObservationError, read_observation
from test_api_fits import API, contour_csv, post_fit, vtl_outline, wait_until_finished


@pytest.fixture(scope="module")
def store(built_assets):
    return AssetStore(built_assets)


@pytest.fixture(scope="module")
def targets(store):
    return {t["ipa"]: t for t in store.get("phoneme_targets")["targets"]}


@pytest.fixture(scope="module")
def outline(built_assets):
    return vtl_outline(built_assets, "a")


@pytest.fixture
def client(start_app, built_assets):
    return signed_in(start_app()[1], "clinician")


def flesh_csv(points: dict, names=None, shift=(0.0, 0.0, 0.0)) -> bytes:
    rows = [f"{name},{p[0] + shift[0]:.4f},{p[1] + shift[1]:.4f},{p[2] + shift[2]:.4f}\n"
            for name, p in points.items() if names is None or name in names]
    return ("point,x_mm,y_mm,z_mm\n" + "".join(rows)).encode()


def post_combined(client, parts: dict, **fields):
    files = {f"{part}_file": (name, content) for part, (name, content) in parts.items()}
    data = {"kind": "combined", **{k: str(v) for k, v in fields.items()}}
    return client.post(f"{API}/fits", data=data, files=files)


def test_the_heads_own_sensors_at_t_fit_back_to_its_jaw_and_sensors(client, store, targets):
    rig = flesh_point_rig(store)
    wanted = rig.frame(targets["t"]["params"])
    answer = post_fit(client, flesh_csv(wanted), "ema", "t-sensors.csv", name="/t/ sensors")
    assert answer.status_code == 202, answer.json()
    job = answer.json()
    assert job["kind"] == "ema" and job["method"] == "bobyqa"
    assert job["source"]["points"] == list(wanted) and job["source"]["referenced"] is True
    done = wait_until_finished(client, job["id"])
    assert done["state"] == "done", done["message"]
    terms = done["report"]["terms"]
    assert set(terms) == {"ema"} and terms["ema"]["weight"] == 10.0
    # The head's own /t/ sensors: its reference is its own incisor, so nothing is shifted.
    assert terms["ema"]["shift_mm"] == pytest.approx([0, 0, 0], abs=1e-3)
    # Measured 0.68 mm RMS over the seven moving points (the rest outline holds the tongue's
    # unmeasured parts near rest); the jaw within 0.01 degrees.
    assert terms["ema"]["rms_mm"] < 1.0
    assert set(terms["ema"]["errors_mm"]) == set(wanted) - {"upper_incisor"}
    params = done["params"]
    assert params["jaw_opening"] == pytest.approx(targets["t"]["params"]["jaw_opening"], abs=0.3)
    posed = rig.frame(params)
    for name in ("lower_incisor", "upper_lip", "lower_lip"):
        assert np.linalg.norm(posed[name] - wanted[name]) < 0.5, name
    assert {"lip_opening", "velum_opening", "tip_height"} <= set(params)
    listed = client.get(f"{API}/fits", params={"state": "done"}).json()
    assert [f["name"] for f in listed["fits"]] == ["/t/ sensors"]


def test_sensors_relative_to_the_speakers_upper_incisor_are_shifted_onto_the_heads(
        client, store, targets):
    rig = flesh_point_rig(store)
    wanted = rig.frame(targets["ɑ"]["params"])
    incisor = wanted["upper_incisor"]
    # As EMA gives them: the origin at the speaker's upper incisor, in the mid-sagittal plane.
    codes = {"TT": "tongue_tip", "TD": "tongue_dorsum", "LI": "lower_incisor"}
    content = ("".join(f"{code},{x:.4f},{y:.4f}\n" for code, name in codes.items()
                       for x, y in [(wanted[name] - incisor)[:2]]) + "UI,0,0\n").encode()
    answer = post_fit(client, content, "ema", "hprc-frame.csv", max_evals=600)
    assert answer.status_code == 202, answer.json()
    done = wait_until_finished(client, answer.json()["id"])
    assert done["state"] == "done", done["message"]
    ema = done["report"]["terms"]["ema"]
    assert ema["shift_mm"][:2] == pytest.approx(list(incisor[:2]), abs=1e-3)
    assert set(ema["errors_mm"]) == {"tongue_tip", "tongue_dorsum", "lower_incisor"}
    assert ema["rms_mm"] < 1.0
    assert done["params"]["jaw_opening"] == pytest.approx(targets["ɑ"]["params"]["jaw_opening"],
                                                          abs=0.3)


def test_a_contour_and_sensors_fit_together_and_report_each_terms_weight_and_error(
        client, store, outline):
    rig = flesh_point_rig(store)
    sensors = rig.frame({"jaw_opening": 6.0, "lip_opening": 0.6})
    answer = post_combined(client, {"contour": ("a.csv", contour_csv(outline)),
                                    "ema": ("jaw.csv", flesh_csv(sensors, ("lower_incisor",
                                                                          "upper_lip",
                                                                          "lower_lip")))},
                           ema_weight=2, max_evals=800)
    assert answer.status_code == 202, answer.json()
    job = answer.json()
    assert job["kind"] == "combined" and job["method"] == "bobyqa"
    assert job["name"] == "a.csv + jaw.csv"
    assert set(job["source"]["parts"]) == {"contour", "ema"}
    assert job["source"]["options"]["weights"] == {"ema": 2.0}
    done = wait_until_finished(client, job["id"])
    assert done["state"] == "done", done["message"]
    terms = done["report"]["terms"]
    assert list(terms) == ["contour", "ema"]
    assert terms["contour"]["weight"] == 1.0 and terms["ema"]["weight"] == 20.0
    assert terms["contour"]["rms_mm"] == pytest.approx(done["report"]["rms_mm"])
    # JD3's /a/ alone fits to about 1 mm; the jaw the sensors ask for costs the outline little.
    assert terms["contour"]["rms_mm"] < 2.5
    assert terms["ema"]["rms_mm"] < 0.5
    assert done["params"]["jaw_opening"] == pytest.approx(6.0, abs=0.3)


def test_epg_frames_and_a_tongue_tip_sensor_fit_together_with_subplex(client, data_dir, store,
                                                                      targets):
    document = json.loads((data_dir / "epg" / "emur-engassim.json").read_bytes())
    document["segments"] = [s for s in document["segments"] if s["label"].startswith("n")][:3]
    tip = flesh_point_rig(store).frame(targets["n"]["params"])
    answer = post_combined(client, {"epg": ("n.json", json.dumps(document).encode()),
                                    "ema": ("tip.csv", flesh_csv(tip, ("tongue_tip",)))},
                           max_evals=1500)
    assert answer.status_code == 202, answer.json()
    assert answer.json()["method"] == "sbplx"
    done = wait_until_finished(client, answer.json()["id"])
    assert done["state"] == "done", done["message"]
    terms = done["report"]["terms"]
    assert list(terms) == ["epg", "ema"]
    assert terms["epg"]["weight"] == 30.0 and len(terms["epg"]["rows"]) == 8
    # The rest tongue agrees on 0.74 of the electrodes and the EPG fit alone on 0.89; held to
    # the /n/ target's tip as well, measured 0.79 with the tip 0.33 mm from its sensor.
    assert terms["epg"]["agreement"] >= 0.76
    assert terms["ema"]["errors_mm"]["tongue_tip"] < 1.0
    assert abs(done["report"]["volume_change_pct"]) < 5.0


@pytest.mark.parametrize(("content", "words"), [
    (b"point,x_mm,y_mm\ntongue_nose,1,2\n", "line 2: 'tongue_nose' is not a flesh point"),
    (b"tongue_tip,1\n", "line 1: expected point,x_mm,y_mm[,z_mm], got 2 columns"),
    (b"tongue_tip,1,nan\n", "line 1: a coordinate is not finite"),
    (b"tongue_tip,1,2\nTT,3,4\n", "line 2: tongue_tip is given twice"),
    (b"upper_incisor,30,0\n", "no flesh point that moves"),
    (b"tongue_tip,1000,2\n", "beyond 150 mm"),
    (b'{"tongue_tip": [1, "two"]}', "point 'tongue_tip': expected [x, y] or [x, y, z]"),
    (b'{"tongue_tip": [1, 2', "not valid JSON"),
    (b'[1, 2, 3]', "expected an object of flesh points"),
])
def test_a_bad_flesh_point_file_is_422_naming_the_line_or_point_and_stores_nothing(
        client, content, words):
    answer = post_fit(client, content, "ema", "sensors.csv")
    assert answer.status_code == 422, answer.json()
    assert words in answer.json()["detail"]
    assert client.get(f"{API}/fits").json()["total"] == 0


def test_combined_fields_that_do_not_fit_the_kind_are_422_and_store_nothing(client, outline):
    contour = ("a.csv", contour_csv(outline))
    one = post_combined(client, {"contour": contour})
    assert one.status_code == 422 and "at least two" in one.json()["detail"]
    unweighed = post_combined(client, {"contour": contour, "ema": ("e.csv", b"TT,20,10\n")},
                              epg_weight=2)
    assert unweighed.status_code == 422
    assert "field epg_weight: there is no epg_file" in unweighed.json()["detail"]
    with_file = client.post(f"{API}/fits", data={"kind": "combined"},
                            files={"file": contour, "contour_file": contour,
                                   "ema_file": ("e.csv", b"TT,20,10\n")})
    assert with_file.status_code == 422 and "not file" in with_file.json()["detail"]
    weighed = post_fit(client, contour_csv(outline), "contour", contour_weight=2)
    assert weighed.status_code == 422
    assert "contour_weight: only a combined fit" in weighed.json()["detail"]
    bad_part = post_combined(client, {"contour": contour, "ema": ("e.csv", b"TT,20\n")})
    assert bad_part.status_code == 422
    assert bad_part.json()["detail"].startswith("ema_file: line 1: expected point")
    negative = post_combined(client, {"contour": contour, "ema": ("e.csv", b"TT,20,10\n")},
                             ema_weight=-1)
    assert negative.status_code == 422 and "ema_weight" in json.dumps(negative.json())
    assert client.get(f"{API}/fits").json()["total"] == 0


def test_flesh_point_tracks_of_an_utterance_are_read_at_the_chosen_frame():
    tracks = {"flesh_points": {"tongue_tip": [[10, 1, 0], [12, 3, 0]],
                               "lower_incisor": [[24, -6, 0], [24, -8, 0]]}}
    content = json.dumps({"frames": 2, **tracks}).encode()
    observation = read_observation("ema", content, "utterance.json", frame=1)
    assert observation.source["frame"] == 1 and observation.source["frames"] == 2
    assert observation.points[:, 1:].tolist() == [[12, 3, 0], [24, -8, 0]]
    with pytest.raises(ObservationError, match="field frame: 2 is not a frame index"):
        read_observation("ema", content, "utterance.json", frame=2)


def test_a_combined_observation_is_stored_and_read_back_part_by_part():
    job = FitJob()
    parts = {"contour": np.arange(10.0).reshape(5, 2), "ema": np.array([[0, 1, 2, np.nan]])}
    job.set_observation(parts)
    back = job.get_observation()
    assert list(back) == ["contour", "ema"]
    assert np.array_equal(back["contour"], parts["contour"])
    assert np.array_equal(back["ema"], parts["ema"], equal_nan=True)
