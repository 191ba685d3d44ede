"""The CBCT maxilla: registration, levels of detail and the scene maxilla's error bound."""

from itertools import pairwise

import fast_simplification
import numpy as np
import pytest
import trimesh

from glasshead.geometry.surface_distance import SampledSurface, SurfaceDistance, hausdorff
from glasshead.pipeline import sources
from glasshead.pipeline.maxilla_lods import (
    LOD_TARGETS,
    MOUTH_FACING_BOUND_MM,
    mouth_facing,
    mouth_point,
    simplify_keeping_borders,
)


def _glb(built_assets, manifest, name):
    entry = next(m for m in manifest["meshes"] if m["name"] == name)
    mesh = trimesh.load(built_assets / entry["file"], force="mesh", process=False)
    return np.asarray(mesh.vertices, dtype=np.float64), np.asarray(mesh.faces, dtype=np.int64)


@pytest.fixture(scope="session")
def badin_maxilla(data_dir):
    return sources.read_badin_mesh(data_dir, "maxilla")


def test_every_level_records_its_count_errors_and_time(build_report):
    levels = build_report["anatomy"]["cbct_lods"]
    assert [lod["target"] for lod in levels] == list(LOD_TARGETS)
    for lod in levels:
        assert abs(lod["triangles"] - lod["target"]) <= 0.02 * lod["target"]
        assert lod["mouth_hausdorff_mm"] <= lod["hausdorff_mm"] + 1e-9
        assert lod["seconds"] > 0


def test_coarser_levels_are_farther_from_the_full_mesh_on_the_mouth_facing_surface(build_report):
    levels = build_report["anatomy"]["cbct_lods"]
    mouth = [lod["mouth_hausdorff_mm"] for lod in levels]
    assert all(a <= b for a, b in pairwise(mouth))
    assert levels[-1]["hausdorff_mm"] > levels[0]["hausdorff_mm"]


def test_the_coarsest_level_error_recomputed_from_the_glbs_matches_the_report(
        built_assets, manifest, build_report, badin_maxilla):
    anatomy = build_report["anatomy"]
    coarsest = anatomy["cbct_lods"][-1]
    name = next(m["name"] for m in manifest["meshes"]
                if m["lod"] == str(coarsest["level"])
                and m["source"].startswith("artisynth-dynjaw"))
    full_v, full_f = _glb(built_assets, manifest, "maxilla_cbct_full")
    lod_v, lod_f = _glb(built_assets, manifest, name)
    assert len(lod_f) == coarsest["triangles"]
    point = mouth_point(badin_maxilla[0])
    arch = (badin_maxilla[0].min(axis=0), badin_maxilla[0].max(axis=0))
    _, mouth = hausdorff(SampledSurface(full_v, full_f), SampledSurface(lod_v, lod_f),
                         mouth_facing(full_v, full_f, point, arch),
                         mouth_facing(lod_v, lod_f, point, arch))
    np.testing.assert_allclose(mouth, coarsest["mouth_hausdorff_mm"], atol=0.02)


def test_the_scene_maxilla_is_within_the_bound_of_the_speakers_palate(
        built_assets, manifest, build_report, badin_maxilla):
    # Measured against the Badin maxilla, the surface the tongue and the EPG are built on: a CBCT
    # level would carry the other subject's registration residual and fail here.
    scene = [m for m in manifest["meshes"] if m["scene"] and m["role"] == "bone"
             and m["name"] == "maxilla"]
    assert len(scene) == 1
    v, f = _glb(built_assets, manifest, "maxilla")
    bv, bf = badin_maxilla
    point = mouth_point(bv)
    arch = (bv.min(axis=0), bv.max(axis=0))
    _, mouth = hausdorff(SampledSurface(bv, bf), SampledSurface(v, f),
                         mouth_facing(bv, bf, point, arch), mouth_facing(v, f, point, arch))
    assert mouth <= MOUTH_FACING_BOUND_MM
    assert build_report["anatomy"]["scene_maxilla"]["reason"]


def test_a_registered_cbct_maxilla_is_not_within_the_bound_of_the_speakers_palate(
        built_assets, manifest, badin_maxilla):
    # The same measure on the finest CBCT level: the other subject's palate is millimetres off,
    # which is why the scene does not use it.
    v, f = _glb(built_assets, manifest, "maxilla_cbct_full")
    bv, bf = badin_maxilla
    point = mouth_point(bv)
    arch = (bv.min(axis=0), bv.max(axis=0))
    _, mouth = hausdorff(SampledSurface(bv, bf), SampledSurface(v, f),
                         mouth_facing(bv, bf, point, arch), mouth_facing(v, f, point, arch))
    assert mouth > 1.0


def test_fenced_simplification_keeps_the_cbct_borders_in_place(built_assets, manifest):
    # The CBCT mesh is open; plain quadric simplification pulls its borders inward by
    # millimetres, the fenced one keeps them where they were.
    v, f = _glb(built_assets, manifest, "maxilla_cbct_full")
    mesh = trimesh.Trimesh(v, f, process=False)
    border = v[np.unique(mesh.edges_sorted[trimesh.grouping.group_rows(mesh.edges_sorted,
                                                                        require_count=1)])]
    plain = fast_simplification.simplify(v.astype(np.float32), f.astype(np.int32),
                                         target_count=5000)
    fenced = simplify_keeping_borders(v, f, 5000)
    assert abs(len(fenced[1]) - 5000) <= 50
    plain_gap = SurfaceDistance(plain[0].astype(float), plain[1].astype(np.int64)).distance(border)
    fenced_gap = SurfaceDistance(*fenced).distance(border)
    assert np.percentile(fenced_gap, 95) < 0.5 < np.percentile(plain_gap, 95)
    assert fenced_gap.max() < plain_gap.max()


def test_the_registration_puts_the_cbct_on_the_badin_palate(build_report):
    registration = build_report["anatomy"]["cbct_registration"]
    assert 0.7 < registration["scale"] < 1.4
    assert registration["badin_to_cbct"]["mean_mm"] < 5.0
    assert registration["icp_trimmed_rms_mm"] < registration["runner_up_trimmed_rms_mm"]
