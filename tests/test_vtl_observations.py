"""VocalTractLab's JD3 shapes as observations, against the real bindings and the built maxilla."""

import json

import numpy as np
import pytest

from glasshead.geometry.midsagittal import palate_clearance, point_to_polylines
from glasshead.pipeline import vtl_speaker as vtl
from glasshead.pipeline.vtl_observations import build_vtl_observations

PLACES = ("labial", "dental", "alveolar", "postalveolar", "palatal", "velar", "uvular")
#: Tongue contour length (mm, root at the hyoid to the tip, project frame). VTL's contour starts
#: at the hyoid body, not at the vallecula, so it is longer than an oral dorsum: 101-154 mm over
#: the 69 shapes, the longest in bunched back shapes (/o u/, velar and uvular in /u/).
#: Adult mid-sagittal tongue contours from hyoid to tip measure about 100-150 mm on MRI.
TONGUE_LENGTH_MM = (90.0, 165.0)
#: Registration bounds: the two palates are different speakers' (VTL's JD3 and Badin's), so
#: they cannot coincide; the residual (RMS 2.57, max 5.49 mm now) stays within about one
#: between-speaker standard deviation of palatal vault height (2-3 mm) in RMS, and the worst
#: point is where JD3's vault stands higher, on the slope down to the incisors.
MIDLINE_RMS_MM, MIDLINE_MAX_MM = 3.5, 7.0
#: Contact of the alveolar closures' tongue with VTL's own palate in the project frame: VTL's
#: midline palate is a polyline through ribs 7-10 mm apart and its closures are closed in 3D
#: (cross-section area 0), not necessarily on the midline; 0.6-1.1 mm now.
CONTACT_MM = 1.5
#: The same against the project's maxilla midline, widened by the registration residual there.
MAXILLA_CONTACT_MM = 2.5


@pytest.fixture(scope="module")
def document(built_assets, tmp_path_factory):
    out = tmp_path_factory.mktemp("vtl") / "vtl-observations.json"
    build_vtl_observations(built_assets, out, force=True)
    return json.loads(out.read_text())


@pytest.fixture(scope="module")
def shapes(document):
    return {shape["name"]: shape for shape in document["shapes"]}


def test_shape_list_has_vowels_and_consonants_at_every_place():
    names = vtl.shape_names()
    classes = {name: vtl.classify(name) for name in names}
    assert len(names) == 69
    vowels = {c["vowel"] for c in classes.values() if c["kind"] == "vowel" and not c["raw"]}
    assert {"a", "e", "i", "o", "u", "@"} <= vowels
    consonants = [c for c in classes.values() if c["kind"] == "consonant"]
    assert {c["place"] for c in consonants} == set(PLACES)
    assert {c["manner"] for c in consonants} == {"closure", "fricative", "lateral"}
    for c in consonants:  # every place/manner comes in /a i u/ context
        contexts = {d["context"] for d in consonants
                    if (d["place"], d["manner"], d["articulator"])
                    == (c["place"], c["manner"], c["articulator"])}
        assert contexts == {"a", "i", "u"}
    assert classes["tt-alveolar-closure(a)"] == {
        "kind": "consonant", "articulator": "tongue tip", "place": "alveolar",
        "manner": "closure", "context": "a"}
    assert classes["a-raw"] == {"kind": "vowel", "vowel": "a", "raw": True}
    assert all(c["kind"] != "other" for c in classes.values())


def test_records_in_vtl_frame_are_finite_and_plausible():
    record = vtl.observe("a")
    outline = record["tongue_outline"]
    assert outline.ndim == 2 and outline.shape[1] == 2 and len(outline) >= 30
    assert np.isfinite(outline).all()
    vertices, triangles = record["tongue_surface"]
    assert vertices.shape[1] == 3 and triangles.max() < len(vertices)
    width = vertices[:, 2].max() - vertices[:, 2].min()
    assert 25.0 < width < 60.0  # tongue breadth
    assert set(record["settings"]) == {"jaw", "lips", "velum", "hyoid", "tongue"}
    assert record["settings"]["jaw"]["JA"] == pytest.approx(record["params"]["JA"])
    assert record["settings"]["lips"]["LD"] == pytest.approx(10.0 * record["params"]["LD"])


def test_every_shape_in_the_project_frame_is_finite_and_tongue_sized(document, shapes):
    assert document["shape_count"] == len(shapes) == 69
    lo, hi = TONGUE_LENGTH_MM
    for shape in shapes.values():
        outline = np.array(shape["tongue_outline"])
        surface = np.array(shape["tongue_surface_vertices"])
        assert np.isfinite(outline).all() and np.isfinite(surface).all()
        assert lo < shape["tongue_length_mm"] < hi, shape["name"]
        assert np.abs(outline).max() < 120.0  # within the head
        assert np.abs(surface[:, 2]).max() < 30.0  # half-breadth
    assert len(document["tongue_surface_triangles"]) > 500


def test_closures_are_closed_and_vowels_open(shapes):
    for name, shape in shapes.items():
        c = vtl.classify(name)
        if c["kind"] == "consonant" and c["manner"] == "closure":
            assert shape["constriction"]["min_area_cm2"] == 0.0, name
        if c["kind"] == "vowel":
            assert shape["constriction"]["min_area_cm2"] > 0.05, name


def test_i_is_higher_and_fronter_than_a(shapes):
    a, i = (np.array(shapes[n]["tongue_outline"]) for n in ("a", "i"))
    top_a, top_i = a[np.argmax(a[:, 1])], i[np.argmax(i[:, 1])]
    assert top_i[1] > top_a[1] + 5.0  # higher dorsum
    assert top_i[0] > top_a[0] + 10.0  # its highest point further forward
    assert i[:, 0].mean() > a[:, 0].mean() + 5.0  # the whole body further forward


def test_alveolar_closure_tip_touches_the_registered_palate(document, shapes):
    palate = document["palate"]
    vtl_palate = np.vstack([palate["vault_outline"], palate["incisor_outline"][1:3]])
    maxilla = [np.array(p) for p in palate["maxilla_midline"]]
    for context in "aiu":
        tongue = np.array(shapes[f"tt-alveolar-closure({context})"]["tongue_outline"])
        front = tongue[tongue[:, 0] > tongue[:, 0].max() - 15.0]  # the front 15 mm
        assert point_to_polylines(front, [vtl_palate]).min() < CONTACT_MM, context
        assert point_to_polylines(front, maxilla).min() < MAXILLA_CONTACT_MM, context
    # ... and the open /a/ stays well clear of it.
    a = np.array(shapes["a"]["tongue_outline"])
    assert np.nanmin(palate_clearance(a, np.array(palate["vault_outline"]))) > 8.0


def test_registration_residual_is_bounded(document):
    reg = document["registration"]
    assert reg["midline"]["rms_mm"] < MIDLINE_RMS_MM
    assert reg["midline"]["max_mm"] < MIDLINE_MAX_MM
    assert reg["palate_surface_to_maxilla"]["rms_mm"] < MIDLINE_RMS_MM
    transform = reg["transform"]
    assert 0.9 < transform["scale"] < 1.2  # two adult palates
    assert abs(transform["rotation_deg"]) < 10.0


def test_tongue_surface_faces_up_at_the_dorsum(document, shapes):
    vertices = np.array(shapes["a"]["tongue_surface_vertices"])
    triangles = np.array(document["tongue_surface_triangles"])
    tri = vertices[triangles]
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    top = tri[:, :, 1].mean(axis=1) > vertices[:, 1].max() - 5.0
    assert (normals[top, 1] > 0).mean() > 0.9


def test_source_records_the_inputs(document):
    source = document["source"]
    assert len(source["sha256"]) == 64 and len(source["speaker_sha256"]) == 64
    assert source["speaker_file"] == "JD3.speaker"
    assert "Birkholz" in document["credit"]


def test_unknown_shape_raises_a_clear_error():
    with pytest.raises(vtl.UnknownShapeError) as caught:
        vtl.observe("tt-alveolar-clo(a)")
    message = str(caught.value)
    assert "tt-alveolar-clo(a)" in message and "JD3.speaker" in message
    assert "did you mean 'tt-alveolar-closure(a)'" in message
    assert isinstance(caught.value, vtl.VtlError)
