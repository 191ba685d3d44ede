"""GET /observations and /observations/{name}: the JD3 shapes with their 2D fits, served from the
built observations and fit report through the asset store, in the shape the workbench reads."""

import json
import shutil
import xml.etree.ElementTree as ET
from urllib.parse import quote

import numpy as np
import pytest

from glasshead.api.routes.observations import MAX_SURFACE_VERTICES, evenly
from glasshead.constants import FIT_REPORT_FILE, REBUILD_COMMAND, VTL_OBSERVATIONS_FILE
from glasshead.fitting.objective2d import MidSagittalSection, Rays
from glasshead.geometry.tongue_surface import TongueRig

NAME = "tt-alveolar-closure(a)"


@pytest.fixture(scope="module")
def report(built_assets) -> dict:
    return json.loads((built_assets / FIT_REPORT_FILE).read_text())


@pytest.fixture(scope="module")
def observations(built_assets) -> dict:
    return json.loads((built_assets / VTL_OBSERVATIONS_FILE).read_text())


@pytest.fixture
def client(built_assets, start_app):
    _, client = start_app(built_assets)
    return client


def one(client, name=NAME):
    response = client.get(f"/api/v1/observations/{quote(name, safe='')}")
    assert response.status_code == 200, response.text
    return response.json()


def test_the_list_gives_every_shape_in_the_observations_order_with_its_fit_error(
        client, observations, report):
    response = client.get("/api/v1/observations")
    assert response.status_code == 200
    listed = response.json()["observations"]
    assert [o["name"] for o in listed] == [s["name"] for s in observations["shapes"]]
    fits = {e["name"]: e for e in report["shapes"]}
    for item in listed:
        assert set(item) >= {"name", "source", "label", "has_surface", "rms_mm"}
        assert item["source"] == "vtl-jd3" and item["has_surface"] is True
        assert item["label"] == fits[item["name"]]["label"]
        assert item["rms_mm"] == pytest.approx(fits[item["name"]]["rms_mm"], abs=1e-12)
        assert client.get(item["url"]).status_code == 200
    by_name = {o["name"]: o for o in listed}
    assert by_name[NAME]["label"] == "JD3 /t d n/ alveolar closure (tongue tip) in /a/ context"


def test_one_shape_has_the_contracts_fields_and_sizes(client, report, observations, built_assets):
    body = one(client)
    entry = next(e for e in report["shapes"] if e["name"] == NAME)
    rig = json.loads((built_assets / "tongue-rig.json").read_text())
    names = {p["name"] for p in rig["parameters"]}
    assert body["name"] == NAME and body["source"] == "vtl-jd3"
    assert len(body["origin"]) == 3 and body["origin"][2] == 0.0
    assert len(body["outline"]) == entry["rays"] and all(len(p) == 2 for p in body["outline"])
    shape = next(s for s in observations["shapes"] if s["name"] == NAME)
    assert len(body["surface"]) == len(shape["tongue_surface_vertices"]) == 407
    assert all(len(v) == 3 for v in body["surface"])
    assert set(body["before"]["params"]) == names and "jaw_opening" in names
    after = body["after"]
    assert set(after["params"]) == names
    assert {"rms_mm", "max_error_mm", "evaluations", "seconds", "method", "volume_change_pct",
            "at_limit"} <= set(after)
    assert after["method"] == "bobyqa" and isinstance(after["evaluations"], int)
    assert after["rms_mm"] == pytest.approx(entry["rms_mm"], abs=1e-12)
    assert body["before"]["params"]["jaw_opening"] == after["params"]["jaw_opening"]
    assert body["before"]["params"] != after["params"]


def test_the_plot_url_serves_the_overlay_as_svg(client):
    for name in (NAME, "E:", "@"):
        url = one(client, name)["plot_url"]
        assert url.startswith("/assets/build/fit-plots/")
        response = client.get(url)
        assert response.status_code == 200, url
        assert response.headers["content-type"].startswith("image/svg+xml")
        assert name in ET.fromstring(response.text).find("{http://www.w3.org/2000/svg}title").text


def test_the_rays_the_browser_casts_reproduce_the_fit_error(client, built_assets):
    """The contract's error vectors, computed as the browser does from the route's origin,
    outline and fitted parameters (rays to the posed tongue's z = 0 section), give the reported
    RMS within the outline's stored precision."""
    rig = TongueRig(json.loads((built_assets / "tongue-rig.json").read_text()))
    section = MidSagittalSection(rig)
    for name in (NAME, "i", "u"):
        body = one(client, name)
        rays = Rays(body["origin"][:2], body["outline"])
        for pose, rms in ((body["after"], body["after"]["rms_mm"]), (body["before"], None)):
            values = np.array([pose["params"][n] for n in rig.parameter_names])
            errors = rays.errors(section.outline(values))
            if rms is not None:
                assert np.sqrt(np.mean(errors**2)) == pytest.approx(rms, abs=2e-4), name
            else:
                assert np.sqrt(np.mean(errors**2)) > body["after"]["rms_mm"], name


def test_an_unknown_name_is_a_404_naming_it(client):
    response = client.get("/api/v1/observations/no-such-shape(a)")
    assert response.status_code == 404
    detail = response.json()["detail"]
    assert "'no-such-shape(a)'" in detail and "/api/v1/observations" in detail


@pytest.mark.parametrize("file", [FIT_REPORT_FILE, VTL_OBSERVATIONS_FILE])
def test_a_missing_built_file_is_a_503_naming_it(tmp_path, built_assets, start_app, file):
    for name in (FIT_REPORT_FILE, VTL_OBSERVATIONS_FILE, "manifest.json", "tongue-rig.json"):
        if name != file:
            shutil.copy(built_assets / name, tmp_path / name)
    _, client = start_app(tmp_path)
    for path in ("/api/v1/observations", f"/api/v1/observations/{quote(NAME, safe='')}"):
        response = client.get(path)
        assert response.status_code == 503, path
        assert response.json()["file"] == file and response.json()["command"] == REBUILD_COMMAND


def test_a_surface_is_subsampled_evenly_to_at_most_the_limit():
    points = [[float(k), 0.0, 0.0] for k in range(4000)]
    kept = evenly(points)
    assert len(kept) == MAX_SURFACE_VERTICES
    assert kept[0] == points[0] and kept[-1] == points[-1]
    gaps = np.diff([p[0] for p in kept])
    assert gaps.min() >= 2 and gaps.max() <= 3
    assert evenly(points[:407]) == points[:407]
