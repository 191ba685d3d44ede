"""The fit report (pipeline.fit_report): the 2D fit of every JD3 shape on the real build, its
overlay plots (pipeline.overlay_svg) and its page. No mocks: the report is the one
`glasshead build` wrote, checked against the objective recomputed from the built rig."""

import json
import xml.etree.ElementTree as ET
from html.parser import HTMLParser
from types import SimpleNamespace
from urllib.parse import unquote

import numpy as np
import pytest

from glasshead.constants import FIT_REPORT_FILE, FIT_REPORT_PAGE, VTL_OBSERVATIONS_FILE
from glasshead.fitting import fit2d, vtl_mapping
from glasshead.fitting.objective2d import MidSagittalSection, Objective2D
from glasshead.geometry.tongue_surface import TongueRig
from glasshead.pipeline.fit_report import build_step, shape_label
from glasshead.pipeline.overlay_svg import svg_overlay

SVG = "{http://www.w3.org/2000/svg}"
#: mm. The report keeps outline points and errors to 1e-4 mm, the SVG error vectors to 1e-4 mm.
STORED_MM = 2e-4


@pytest.fixture(scope="module")
def report(built_assets) -> dict:
    return json.loads((built_assets / FIT_REPORT_FILE).read_text())


@pytest.fixture(scope="module")
def observations(built_assets) -> dict:
    return json.loads((built_assets / VTL_OBSERVATIONS_FILE).read_text())


@pytest.fixture(scope="module")
def rig(built_assets) -> TongueRig:
    return TongueRig(json.loads((built_assets / "tongue-rig.json").read_text()))


@pytest.fixture(scope="module")
def section(rig) -> MidSagittalSection:
    return MidSagittalSection(rig)


def error_lines(svg_text):
    root = ET.fromstring(svg_text)
    group = root.find(f".//{SVG}g[@id='errors']")
    assert group is not None, "no group of error vectors"
    lines = group.findall(f"{SVG}line")
    assert all(line.get("class") == "error" for line in lines)
    return np.array([[float(line.get(k)) for k in ("x1", "y1", "x2", "y2")] for line in lines])


def values_of(rig, params):
    return np.array([params[name] for name in rig.parameter_names])


def test_every_jd3_shape_is_fitted_in_the_observations_order(report, observations):
    names = [s["name"] for s in observations["shapes"]]
    assert len(names) == 69
    assert [e["name"] for e in report["shapes"]] == names
    assert report["count"] == 69 and report["method"] == "bobyqa"
    for entry in report["shapes"]:
        assert entry["rms_mm"] is not None, entry.get("error")
        assert 0 < entry["rms_mm"] <= entry["max_error_mm"] < 15, entry["name"]
        assert entry["evaluations"] > 10 and entry["seconds"] > 0
        assert abs(entry["volume_change_pct"]) <= 5.0
        assert entry["rays"] == len(entry["outline"]) == len(entry["errors"]) >= 8
        assert entry["origin"][2] == 0.0 and entry["label"].startswith("JD3 ")
    summary = report["summary"]
    rms = [e["rms_mm"] for e in report["shapes"]]
    assert summary["median_rms_mm"] == pytest.approx(np.median(rms), abs=1e-4)
    assert summary["within_1mm"] == sum(r <= 1.0 for r in rms)


def test_the_reported_rms_is_the_objective_recomputed_at_the_fitted_values(report, observations,
                                                                           rig, section):
    """Objective2D made afresh from the start the report gives, evaluated at the fitted values,
    gives the reported RMS (1e-9 mm: the same arithmetic), origin and compared outline."""
    shapes = {s["name"]: s for s in observations["shapes"]}
    free = fit2d.outline_parameters(rig)
    for entry in report["shapes"]:
        shape = shapes[entry["name"]]
        base = values_of(rig, entry["start_params"])
        assert entry["start_params"]["jaw_opening"] == vtl_mapping.jaw_opening_from_vtl(shape, rig)
        objective = Objective2D(rig, shape["tongue_outline"], free, base=base, section=section)
        fitted = values_of(rig, entry["params"])
        assert objective.rms(fitted[objective.index]) == pytest.approx(entry["rms_mm"],
                                                                       abs=1e-9), entry["name"]
        np.testing.assert_allclose(entry["origin"][:2], objective.origin, atol=1e-12)
        np.testing.assert_allclose(entry["outline"], objective.rays.points, atol=STORED_MM)
        stored = np.asarray(entry["errors"])
        assert np.sqrt(np.mean(stored**2)) == pytest.approx(entry["rms_mm"], abs=STORED_MM)
        assert np.abs(stored).max() == pytest.approx(entry["max_error_mm"], abs=STORED_MM)


def test_each_plot_is_an_svg_with_one_error_vector_per_compared_ray(report, built_assets):
    for entry in report["shapes"]:
        text = (built_assets / entry["plot"]).read_text(encoding="utf-8")
        lines = error_lines(text)
        assert len(lines) == entry["rays"], entry["name"]
        np.testing.assert_allclose(lines[:, :2], entry["outline"], atol=STORED_MM)
        lengths = np.linalg.norm(lines[:, 2:] - lines[:, :2], axis=1)
        np.testing.assert_allclose(lengths, np.abs(entry["errors"]), atol=STORED_MM)
        title = ET.fromstring(text).find(f"{SVG}title").text
        assert entry["name"] in title and f"{entry['rms_mm']:.2f} mm" in title
        assert f"{entry['evaluations']} evaluations" in title


@pytest.mark.parametrize("name", ["a", "i", "tt-alveolar-closure(a)", "tb-velar-closure(u)"])
def test_each_error_vector_ends_on_the_fitted_outline(report, rig, section, built_assets, name):
    """Q, the vector's end read from the plot, lies on the rig's z = 0 section at the fitted
    values (within the stored precision), on the ray from the origin through P."""
    entry = next(e for e in report["shapes"] if e["name"] == name)
    lines = error_lines((built_assets / entry["plot"]).read_text(encoding="utf-8"))
    outline = section.outline(values_of(rig, entry["params"]))
    a, b = outline, np.roll(outline, -1, axis=0)
    for q in lines[:, 2:]:
        t = np.clip(np.einsum("ij,ij->i", q - a, b - a) / np.einsum("ij,ij->i", b - a, b - a),
                    0, 1)
        gap = np.linalg.norm(a + t[:, None] * (b - a) - q, axis=1).min()
        assert gap < 1e-3, (name, q, gap)
    origin = np.asarray(entry["origin"][:2])
    p, q = lines[:, :2] - origin, lines[:, 2:] - origin
    np.testing.assert_allclose(p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0], 0, atol=0.02)


def test_svg_overlay_draws_each_vector_from_the_point_to_its_crossing():
    """Origin at 0; P = (10, 0), (0, 10), (-6, 8); errors +1, -2, +0.5 along the rays put Q at
    (11, 0), (0, 8) and (-6.3, 8.4)."""
    text = svg_overlay(observed=[[10, 0], [0, 10], [-6, 8]], compared=[[10, 0], [0, 10], [-6, 8]],
                       errors=[1.0, -2.0, 0.5], origin=[0, 0],
                       fitted=[[11, 0], [0, 8], [-6.3, 8.4], [0, -5]], title="hand <case>")
    lines = error_lines(text)
    np.testing.assert_allclose(lines, [[10, 0, 11, 0], [0, 10, 0, 8], [-6, 8, -6.3, 8.4]],
                               atol=1e-4)
    root = ET.fromstring(text)
    assert root.find(f"{SVG}title").text == "hand <case>"
    assert root.find(f".//{SVG}path[@id='start']") is None
    assert root.find(f".//{SVG}line[@id='scale-bar']") is not None
    # The drawing group maps mm to px at 6 px per mm with +y up.
    transform = root.find(f".//{SVG}g[@id='mm']").get("transform")
    assert "scale(6 -6)" in transform


def test_svg_overlay_refuses_errors_that_do_not_match_the_points():
    with pytest.raises(ValueError, match="one per compared point"):
        svg_overlay(observed=[[0, 1], [1, 1]], compared=[[0, 1], [1, 1]], errors=[0.1],
                    origin=[0, 0], fitted=[[0, 2], [2, 0]])


def test_labels_name_the_phonemes_place_manner_and_context(observations):
    shapes = {s["name"]: s for s in observations["shapes"]}
    assert shape_label(shapes["tt-alveolar-closure(a)"]) == (
        "JD3 /t d n/ alveolar closure (tongue tip) in /a/ context")
    assert shape_label(shapes["a"]) == "JD3 vowel /a/ (SAMPA)"
    assert shape_label(shapes["a-raw"]) == "JD3 vowel /a/ (SAMPA, VTL's raw version)"
    assert "/k ɡ ŋ/ velar closure" in shape_label(shapes["tb-velar-closure(u)"])


class _Images(HTMLParser):
    def __init__(self):
        super().__init__()
        self.sources, self.rows = [], 0

    def handle_starttag(self, tag, attrs):
        self.sources += [value for key, value in attrs if tag == "img" and key == "src"]
        self.rows += tag == "tr"


def test_the_page_has_a_row_and_a_plot_for_every_shape(report, built_assets):
    parser = _Images()
    text = (built_assets / FIT_REPORT_PAGE).read_text(encoding="utf-8")
    parser.feed(text)
    assert parser.rows == 69 + 1
    assert [unquote(s) for s in parser.sources] == [e["plot"] for e in report["shapes"]]
    assert all((built_assets / unquote(s)).is_file() for s in parser.sources)
    assert f"median RMS {report['summary']['median_rms_mm']:.2f} mm" in text


def test_the_build_records_the_step_and_skips_it_when_nothing_changed(built_assets, report,
                                                                      build_report):
    step = build_report["fit-report"]
    assert step["count"] == 69 and step["build_seconds"] > 0 and step["wall_seconds"] >= 0
    assert set(step["shapes"]) == {e["name"] for e in report["shapes"]}
    again = build_step(SimpleNamespace(assets_dir=built_assets))
    assert again["skipped"] is True and again["summary"] == report["summary"]
