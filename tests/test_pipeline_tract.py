"""The vocal tract and neck in the build: the frame change checked on anatomy, the velum's poses,
the CBCT neck's registration, the vertebrae's transform, and bad tract input.

Distances are in millimetres, measured on the GLBs as the browser loads them (float32).
"""

import hashlib
import json

import numpy as np
import pytest
import trimesh

from assets_support import copy_built_assets
from glasshead.cli import main
from glasshead.geometry.meshio import MeshFormatError
from glasshead.pipeline import larynx, sources, tract_checks
from glasshead.pipeline.tract import ORDER, SCENE_MESHES

#: Project mesh name -> role, for every mesh this step adds.
ROLES = {name: role for name, role, _unit in sources.TRACT_MESHES.values()}
ROLES |= dict(sources.CBCT_NECK_MESHES.values())
CBCT_NAMES = [name for name, _role in sources.CBCT_NECK_MESHES.values()]


@pytest.fixture(scope="session")
def entries(manifest):
    return {m["name"]: m for m in manifest["meshes"]}


@pytest.fixture(scope="session")
def tract(built_assets, entries):
    """name -> trimesh.Trimesh of the tract, neck and head meshes, loaded from their GLBs."""
    names = [*ORDER, "maxilla", "tongue_rest", "cranium"]
    return {name: trimesh.load(built_assets / entries[name]["file"], force="mesh", process=False)
            for name in names}


@pytest.fixture(scope="session")
def report(build_report):
    return build_report["anatomy"]["tract"]


def test_every_tract_and_neck_mesh_has_a_glb_and_a_manifest_entry_in_or_out_of_the_scene(
        built_assets, entries):
    assert set(ORDER) == set(ROLES)
    for name in ORDER:
        entry = entries[name]
        for key in ("name", "file", "sha256", "triangles", "vertices", "lod", "frame", "role",
                    "scene"):
            assert key in entry, f"{name} lacks {key}"
        assert entry["scene"] is (name in SCENE_MESHES), name
        assert entry["role"] == ROLES[name]
        assert entry["frame"] == "project-mm"
        data = (built_assets / entry["file"]).read_bytes()
        assert hashlib.sha256(data).hexdigest() == entry["sha256"], name


def test_the_head_shows_the_speakers_own_tract_and_one_velum_pose(entries):
    shown = {name for name in ORDER if entries[name]["scene"]}
    assert {"airway", "velum_rest", "pharynx", "hyoid", "vertebrae", "thyroid"} <= shown
    for name in ("hyoid_cbct", "velum_raised", "velum_lowered", "palate"):
        assert name not in shown, name


def test_every_mesh_keeps_its_sources_triangles_at_full_resolution(data_dir, entries):
    # The data README's counts for the tract; the CBCT neck counted from its files.
    expected = {"airway": 15315, "palate": 2366, "pharynx": 2630, "hyoid": 1160,
                "velum_raised": 7570, "velum_rest": 7570, "velum_lowered": 7570}
    for stem, (name, _role) in sources.CBCT_NECK_MESHES.items():
        expected[name] = len(sources.read_cbct_mesh(data_dir, stem)[1])
    for name, triangles in expected.items():
        assert entries[name]["triangles"] == triangles, name
        assert entries[name]["lod"] == "full"


def test_the_three_velum_poses_keep_one_topology_and_vertex_order_in_their_glbs(
        data_dir, tract, entries):
    rest = tract["velum_rest"]
    assert len(rest.vertices) == 3787 and len(rest.faces) == 7570
    for name in sources.VELUM_POSES:
        pose = tract[name]
        np.testing.assert_array_equal(pose.faces, rest.faces)
        # Vertex k of each GLB is vertex k of its source (on the GLB lattice: within 0.002 mm).
        source = sources.read_tract_mesh(data_dir, name)[0]
        np.testing.assert_allclose(pose.vertices, source, atol=2e-3)
        assert entries[name]["pose_set"] == "velum"
        assert entries[name]["poses"] == list(sources.VELUM_POSES)


def test_the_raised_velum_rises_above_rest_and_the_lowered_one_hangs_below_it(tract):
    top = {name: tract[name].vertices[:, 1].max() for name in sources.VELUM_POSES}
    tip = {name: tract[name].vertices[:, 1].min() for name in sources.VELUM_POSES}
    assert top["velum_raised"] > top["velum_rest"] + 3.0  # mm: 33.2 against 28.0
    assert tip["velum_lowered"] < tip["velum_rest"] - 1.0  # mm: -22.0 against -20.3


def hugging(fit):
    """The parts whose surface lies within 2 mm (median) and 4 mm (95th percentile) of the
    airway's wall."""
    return {part for part, s in fit.items() if s["median_mm"] < 2.0 and s["p95_mm"] < 4.0}


def test_the_airway_hugs_the_rest_tongue_and_the_palate(tract, report):
    fit = tract_checks.airway_fit(tract)
    # Measured median/p95: tongue 1.3/2.9, maxilla vault 0.2/1.6, tract palate 1.0/3.0, velum
    # 1.4/2.9, pharynx 0.0/1.2.
    assert hugging(fit) == set(fit)
    for part, summary in fit.items():
        # The build report holds the same numbers (same seeds; float32 GLBs: 0.05 mm).
        for key in ("median_mm", "p95_mm"):
            assert abs(report["airway_fit"][part][key] - summary[key]) < 0.05, (part, key)


@pytest.mark.parametrize("mistake", ["x not flipped", "y and z swapped", "10 mm too low"])
def test_an_airway_in_a_wrong_frame_would_not_hug_them(tract, mistake):
    # The check has teeth: each mistake leaves at least one part 3 mm or more off.
    wrong = {"x not flipped": lambda v: v * [-1.0, 1.0, 1.0],
             "y and z swapped": lambda v: v[:, [0, 2, 1]],
             "10 mm too low": lambda v: v - [0.0, 10.0, 0.0]}[mistake]
    airway = tract["airway"].copy()
    airway.vertices = wrong(np.asarray(airway.vertices))
    fit = tract_checks.airway_fit(tract | {"airway": airway})
    assert hugging(fit) != set(fit)


def test_the_velum_continues_the_hard_palate_backwards(tract, report):
    meets = tract_checks.velum_continuation(tract["velum_rest"], tract["maxilla"])
    assert meets["front_gap_to_maxilla_mm"] < 4.0  # measured 2.0
    assert abs(meets["front_x_mm"] - meets["maxilla_back_x_mm"]) < 3.0  # starts at its edge
    assert meets["reaches_behind_maxilla_mm"] > 20.0  # measured 30.7
    assert report["velum_continuation"] == pytest.approx(meets, abs=0.05)


def test_the_pharyngeal_wall_lies_behind_the_tongue_root(report):
    clearance = report["relations"]["tongue_root_in_front_of_pharynx_mm"]
    assert clearance["slices"] >= 5
    assert clearance["min_mm"] > 5.0  # measured 9.3: the oropharyngeal airway's depth


def test_the_larynx_sits_below_the_hyoid_and_in_front_of_the_vertebrae(tract):
    hyoid_y = tract["hyoid"].vertices[:, 1].mean()
    for name in ("thyroid", "cricoid", "arytenoid_left", "arytenoid_right"):
        assert tract[name].vertices[:, 1].mean() < hyoid_y - 15.0, name  # measured 21 to 34
    cartilages = np.vstack([tract[name].vertices for name in ("thyroid", "cricoid",
                                                              "arytenoid_left",
                                                              "arytenoid_right")])
    clearance = larynx.midline_clearance(cartilages, tract["vertebrae"].vertices)
    assert clearance["slices"] >= 3
    assert clearance["min_mm"] > 5.0  # measured 12.3


def test_the_left_arytenoid_lies_on_the_subjects_left(tract):
    assert tract["arytenoid_left"].vertices[:, 2].mean() > 3.0
    assert tract["arytenoid_right"].vertices[:, 2].mean() < -3.0


def test_closed_tract_and_neck_meshes_have_outward_normals(tract):
    for name in (*sources.VELUM_POSES, "hyoid", "hyoid_cbct", "cricoid", "arytenoid_left",
                 "arytenoid_right"):
        assert tract[name].is_watertight, name
        assert tract[name].volume > 0, f"{name} is wound inward"
    assert tract["vertebrae"].volume > 0


def test_the_spine_lies_upright_behind_the_pharynx_and_below_the_cranium(tract, report):
    vertebrae = tract["vertebrae"].vertices
    assert larynx.long_axis_tilt_deg(vertebrae) < 20.0  # measured 10.9
    assert vertebrae[:, 1].max() < tract["cranium"].vertices[:, 1].min()
    behind = larynx.midline_clearance(tract["pharynx"].vertices, vertebrae)
    assert behind["median_mm"] > 0.0
    # Two subjects' necks: the CBCT spine reaches up to 4.5 mm into the Badin pharyngeal wall.
    assert behind["min_mm"] > -larynx.NECK_OVERLAP_TOLERANCE_MM
    placement = report["vertebrae_transform"]
    assert placement["placement"] == "as_stored"
    assert placement["checks"]["moved_by_transform"]["ok"] is False
    assert placement["checks"]["moved_by_transform"]["long_axis_from_vertical_deg"] > 60.0


def test_the_vertebrae_transform_is_read_column_by_column(data_dir, tmp_path):
    matrix = sources.read_amira_transform(data_dir / sources.VERTEBRAE_TRANSFORM)
    np.testing.assert_allclose(matrix[3], [0, 0, 0, 1], atol=1e-12)
    linear = matrix[:3, :3]
    assert np.cbrt(np.linalg.det(linear)) == pytest.approx(1.2, abs=1e-4)
    rotation = linear / 1.2
    assert np.degrees(np.arctan2(rotation[2, 1], rotation[1, 1])) == pytest.approx(94.31, abs=0.01)
    np.testing.assert_allclose(matrix[:3, 3], [0.0983981, 5.97012, -7.36276], atol=1e-6)
    # Written row by row, the translation would sit in the last row: refused.
    numbers = " ".join(repr(float(x)) for x in matrix.ravel())  # row-major order
    (tmp_path / "rows.transform").write_text(f"setTransform {numbers}\n")
    with pytest.raises(MeshFormatError, match="0 0 0 1"):
        sources.read_amira_transform(tmp_path / "rows.transform")


def test_a_spine_not_yet_moved_is_moved_by_its_transform_to_the_same_place(data_dir, tract,
                                                                            report):
    stored, _ = sources.read_cbct_mesh(data_dir, "vertebrae")
    matrix = sources.read_amira_transform(data_dir / sources.VERTEBRAE_TRANSFORM)
    moving = larynx.amira_to_mm(matrix)
    unmoved = larynx.transform_points(np.linalg.inv(moving), stored)
    to_project = np.array(report["cbct_to_project"])
    others = {name: np.asarray(tract[name].vertices) for name in ("pharynx", "cricoid",
                                                                   "cranium")}
    placed, placement = larynx.place_vertebrae(unmoved, matrix, to_project, others, "t")
    assert placement["placement"] == "moved_by_transform"
    np.testing.assert_allclose(placed, stored, atol=1e-9)


def test_the_registrations_affine_map_is_recovered_exactly():
    rng = np.random.default_rng(3)
    linear = 1.08 * np.diag([1.0, 1.0, -1.0]) @ np.linalg.qr(rng.normal(size=(3, 3)))[0]
    points = rng.normal(size=(500, 3)) * 40.0
    moved = points @ linear.T + [3.0, -50.0, 0.5]
    affine = larynx.cbct_affine(points, moved)
    np.testing.assert_allclose(affine[:3, :3], linear, atol=1e-9)
    np.testing.assert_allclose(affine[:3, 3], [3.0, -50.0, 0.5], atol=1e-9)
    with pytest.raises(ValueError, match="not an affine image"):
        larynx.cbct_affine(points, moved + rng.normal(size=moved.shape))


def test_front_and_back_are_compared_slice_by_slice_near_the_midline():
    front = np.array([[10.0, 0.0, 0.0], [10.0, 4.0, 0.0], [12.0, 5.0, 1.0], [12.0, 9.0, 0.0],
                      [-50.0, 3.0, 40.0]])  # the last lies off the band
    back = np.array([[4.0, 0.0, 0.0], [4.0, 4.0, 0.0], [7.0, 5.0, -2.0], [7.0, 9.0, 0.0]])
    clearance = larynx.midline_clearance(front, back, band=15.0, slice_mm=5.0)
    # mm, differences of the coordinates above: equal up to rounding
    assert clearance == {"min_mm": pytest.approx(5.0, abs=1e-9),
                         "median_mm": pytest.approx(5.5, abs=1e-9), "slices": 2}
    assert larynx.midline_clearance(front, back + [0, 50, 0])["slices"] == 0


def test_each_cbct_mesh_reports_the_registration_it_was_carried_by(report, build_report):
    maxilla = build_report["anatomy"]["cbct_registration"]
    for name in CBCT_NAMES:
        residual = report["meshes"][name]["registration"]
        assert residual["maxilla_icp_trimmed_rms_mm"] == maxilla["icp_trimmed_rms_mm"]
        assert residual["maxilla_mouth_facing_rms_mm"] > 0
        assert residual["distance_from_registered_maxilla_mm"] > 30.0
        assert residual["hyoid_centroid_offset_mm"] < 10.0  # measured 5.3
    for name in ORDER:
        if name not in CBCT_NAMES:
            assert "registration" not in report["meshes"][name], name


def test_the_scene_uses_the_speakers_own_hyoid(report, entries):
    assert report["scene_hyoid"]["mesh"] == "hyoid"
    assert entries["hyoid"]["source"].startswith("artisynth-badin-tract/")
    assert entries["hyoid_cbct"]["source"].startswith("artisynth-dynjaw/")
    assert report["nasal_cavity"].startswith("no mesh")
    assert not any("nasal" in name for name in entries)


# --- Bad input --------------------------------------------------------------------------------


def build(data, out):
    return main(["build", "--data-dir", str(data), "--out", str(out)])


def test_a_missing_tract_mesh_is_named_and_no_manifest_is_written(data_copy, tmp_path, capsys):
    (data_copy / sources.TRACT / "airway.obj").unlink()
    assert build(data_copy, tmp_path / "out") == 2
    assert "artisynth-badin-tract/airway.obj" in capsys.readouterr().err
    assert not (tmp_path / "out" / "manifest.json").exists()


def test_a_missing_vertebrae_transform_is_named(data_copy, tmp_path, capsys):
    (data_copy / sources.VERTEBRAE_TRANSFORM).unlink()
    assert build(data_copy, tmp_path / "out") == 2
    assert "vertebrae.transform" in capsys.readouterr().err


@pytest.mark.parametrize("cut", ["half the bytes", "the last tenth of the faces"])
def test_a_truncated_tract_mesh_is_named_and_no_manifest_is_written(data_copy, tmp_path, capsys,
                                                                   cut):
    path = data_copy / sources.TRACT / "palate.obj"
    if cut == "half the bytes":
        data = path.read_bytes()
        path.write_bytes(data[: len(data) // 2])
    else:
        lines = path.read_text().splitlines()
        faces = [k for k, line in enumerate(lines) if line.startswith("f ")]
        path.write_text("\n".join(lines[: faces[int(0.9 * len(faces))]]) + "\n")
    assert build(data_copy, tmp_path / "out") == 3
    assert "palate.obj" in capsys.readouterr().err
    assert not (tmp_path / "out" / "manifest.json").exists()


def test_a_velum_pose_that_lost_a_face_is_named(data_copy, tmp_path, capsys):
    path = data_copy / sources.TRACT / "velum_lowered.obj"
    lines = path.read_text().splitlines()
    last_face = max(k for k, line in enumerate(lines) if line.startswith("f "))
    path.write_text("\n".join(lines[:last_face] + lines[last_face + 1:]) + "\n")
    assert build(data_copy, tmp_path / "out") == 3
    message = capsys.readouterr().err
    assert "velum_lowered.obj" in message and "velum_rest.obj" in message


def test_a_velum_in_metres_is_named(data_copy, tmp_path, capsys):
    path = data_copy / sources.TRACT / "velum_rest.obj"
    lines = []
    for line in path.read_text().splitlines():  # millimetres -> metres: 1000 times too small
        if line.startswith("v "):
            x, y, z = (float(value) / 1000 for value in line.split()[1:4])
            line = f"v {x} {y} {z}"
        lines.append(line)
    path.write_text("\n".join(lines) + "\n")
    assert build(data_copy, tmp_path / "out") == 3
    message = capsys.readouterr().err
    assert "velum_rest.obj" in message and "units" in message


def test_a_corrupt_vertebrae_transform_is_named(data_copy, tmp_path, capsys):
    (data_copy / sources.VERTEBRAE_TRANSFORM).write_text("setTransform 1.2 0 0\n")
    assert build(data_copy, tmp_path / "out") == 3
    assert "vertebrae.transform" in capsys.readouterr().err


def test_a_failed_rebuild_leaves_the_previous_complete_build_untouched(
        data_copy, built_assets, tmp_path, capsys):
    out = tmp_path / "out"
    copy_built_assets(built_assets, out)
    before = (out / "manifest.json").read_bytes()
    (data_copy / sources.TRACT / "pharynx.obj").write_text("v 0 0 0\nv 1 0 0\nf 1 2 3\n")
    assert build(data_copy, out) == 3
    assert "pharynx.obj" in capsys.readouterr().err
    assert (out / "manifest.json").read_bytes() == before
    manifest = json.loads(before)
    assert all((out / m["file"]).is_file() for m in manifest["meshes"])
    assert not list(out.glob(".stage-*"))
