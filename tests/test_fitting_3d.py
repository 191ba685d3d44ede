"""3D surface fits of the tongue rig: the rig's own surface at a known pose, the real
VocalTractLab tongue sheets against the built rig, the mask, progress and bad input."""

import json

import numpy as np
import pytest

from glasshead.constants import TONGUE_RIG_FILE, VTL_OBSERVATIONS_FILE
from glasshead.fitting.fit3d import (
    MIN_RAYS,
    VTL_POINTS,
    VTL_RIBS,
    Objective3D,
    ShapeFit3D,
    SurfaceFit,
    fit_shape3d,
    fit_surface,
    free_groups,
    shape_vertices,
    surface_parameters,
    tip_rib,
    visible_mask,
)
from glasshead.fitting.objective2d import ROOT_CUT_DEG, MidSagittalSection
from glasshead.fitting.vtl_mapping import jaw_opening_from_vtl
from glasshead.geometry.tongue_surface import TongueRig

SEED = 1998
#: Each sagittal and coronal parameter is moved by up to this fraction of its range.
POSE_SPREAD = 0.12
RECOVERY_RMS_MM = 0.3
#: The recovered surface's vertices against the posed ones, RMS mm: the parameters themselves
#: need not come back (several poses give nearly the same surface).
RECOVERY_VERTEX_MM = 0.6
VOLUME_LIMIT_PCT = 5.0


@pytest.fixture(scope="module")
def rig(built_assets):
    return TongueRig(json.loads((built_assets / TONGUE_RIG_FILE).read_text()))


@pytest.fixture(scope="module")
def shapes(built_assets):
    document = json.loads((built_assets / VTL_OBSERVATIONS_FILE).read_text())
    return {shape["name"]: shape for shape in document["shapes"]}


@pytest.fixture(scope="module")
def section(rig):
    return MidSagittalSection(rig)


@pytest.fixture(scope="module")
def known_pose(rig):
    """Sagittal and coronal parameters moved at random (seeded) about neutral, the volume within
    3 % of rest so that the volume terms cannot be what stops the recovery."""
    rng = np.random.default_rng(SEED)
    index = [rig.parameter_names.index(name) for name in surface_parameters(rig)]
    span = rig.maximum - rig.minimum
    rest = rig.volume(rig.neutral)
    for _ in range(20):
        pose = rig.neutral.copy()
        pose[index] += rng.uniform(-POSE_SPREAD, POSE_SPREAD, len(index)) * span[index]
        pose = np.clip(pose, rig.minimum, rig.maximum)
        if abs(rig.volume(pose) / rest - 1.0) < 0.03:
            return pose
    raise AssertionError(f"no pose within 3 % volume in 20 draws (seed {SEED})")


@pytest.fixture(scope="module")
def synthetic_fit(rig, section, known_pose):
    calls = []
    # The surface is exact, so neither pull is needed; they would bias the recovery (toward the
    # rest volume and neutral, from a pose 1.2 % smaller than rest).
    options = SurfaceFit(section=section, name="synthetic", volume_weight=0.0,
                         neutral_weight=0.0)
    report = fit_surface(rig, rig.vertices(known_pose), options,
                         progress=lambda evaluations, best: calls.append((evaluations, best)))
    return report, calls


@pytest.fixture(scope="module")
def vowel_fits(rig, shapes, section):
    return {name: fit_shape3d(rig, shapes[name], ShapeFit3D(section=section))
            for name in ("a", "i")}


def test_the_rigs_own_surface_at_a_known_pose_is_recovered_from_neutral(rig, known_pose,
                                                                         synthetic_fit):
    report, _ = synthetic_fit
    assert report.start_rms_mm > 2 * RECOVERY_RMS_MM, "the pose must start measurably off"
    assert report.rms_mm < RECOVERY_RMS_MM, f"seed {SEED}: RMS {report.rms_mm:.3f} mm"
    fitted = rig.vertices(rig.values_from(report.params))
    posed = rig.vertices(known_pose)
    vertex_rms = float(np.sqrt(np.mean(np.sum((fitted - posed) ** 2, axis=1))))
    assert vertex_rms < RECOVERY_VERTEX_MM, f"seed {SEED}: vertices {vertex_rms:.3f} mm off"
    assert abs(report.volume_change_pct) < VOLUME_LIMIT_PCT


def test_a_surface_with_more_vertices_than_the_ray_limit_is_fitted_on_a_subset(synthetic_fit):
    report, _ = synthetic_fit
    assert report.rays == 1000


def test_progress_is_called_after_every_evaluation_with_the_best_error_so_far(synthetic_fit):
    report, calls = synthetic_fit
    counts = [n for n, _ in calls]
    assert counts == list(range(1, report.evaluations + 1))
    best = np.array([b for _, b in calls])
    assert np.all(np.diff(best) <= 0.0)
    assert best[-1] < best[0]


@pytest.mark.parametrize("name", ["a", "i"])
def test_a_real_vowel_sheet_fits_better_than_its_start_and_fills_the_report(rig, shapes,
                                                                           vowel_fits, name):
    report = vowel_fits[name]
    assert report.shape == name and report.method == "bobyqa"
    assert report.rms_mm < report.start_rms_mm - 0.5, (report.rms_mm, report.start_rms_mm)
    assert report.max_error_mm >= report.rms_mm > 0
    assert abs(report.volume_change_pct) < VOLUME_LIMIT_PCT
    assert report.evaluations > 0 and report.seconds > 0 and report.cpu_seconds > 0
    assert report.start_evaluations > 0 and report.start_seconds > 0
    assert MIN_RAYS <= report.rays < VTL_RIBS * VTL_POINTS
    assert report.stop
    assert list(report.params) == rig.parameter_names
    values = rig.values_from(report.params)  # raises when a value is out of range
    # the jaw is not fitted: it stays where fit2d maps VTL's jaw angle
    assert values[rig.jaw_parameter] == jaw_opening_from_vtl(shapes[name], rig)
    groups = {group for group, _ in free_groups(rig, symmetric=True)}
    assert set(report.at_limit) <= groups
    json.dumps(report.to_json())


def test_symmetric_fits_keep_left_and_right_alike_and_the_asymmetries_neutral(vowel_fits):
    for report in vowel_fits.values():
        for section in ("front", "middle", "back"):
            p = report.params
            assert p[f"{section}_left_edge_height"] == p[f"{section}_right_edge_height"]
            assert p[f"{section}_asymmetry"] == 0.0


def test_the_vtl_mask_leaves_out_the_underside_after_the_tip_and_the_root_below_the_cut(
        rig, shapes):
    shape = shapes["i"]
    vertices = shape_vertices(shape)
    base = rig.neutral.copy()
    base[rig.jaw_parameter] = jaw_opening_from_vtl(shape, rig)
    origin = np.append(rig.control_points(base)[1], 0.0)
    keep = visible_mask(vertices, origin, grid=(VTL_RIBS, VTL_POINTS)).reshape(VTL_RIBS,
                                                                               VTL_POINTS)
    grid = vertices.reshape(VTL_RIBS, VTL_POINTS, 3)
    tip = tip_rib(grid[:, VTL_POINTS // 2])
    # /i/'s sheet: its highest rib is on the dorsum, the tip follows, then VTL's underside
    assert 25 < tip < VTL_RIBS - 1
    assert not keep[tip + 1:].any()
    offset = grid[..., :2] - origin[:2]
    below = (offset[..., 0] < 0) & (np.degrees(np.arctan2(offset[..., 1],
                                                          -offset[..., 0])) < -ROOT_CUT_DEG)
    assert below[0].all(), "the root's first rib lies below the cut"
    np.testing.assert_array_equal(keep[:tip + 1], ~below[:tip + 1])


def test_the_tip_rib_is_the_first_after_the_highest_from_which_the_ribs_turn_back():
    middles = np.array([[-40, -30], [-30, 0], [0, 10], [10, 5], [20, 0], [19, -5], [15, -9]])
    assert tip_rib(middles) == 4
    assert tip_rib(middles[:5]) == 4


def test_an_ungridded_surface_keeps_everything_above_the_root_cut():
    origin = np.zeros(3)
    angle = np.radians(np.linspace(-179, 179, 60))
    points = np.stack([30 * np.cos(angle), 30 * np.sin(angle), np.zeros(60)], axis=1)
    keep = visible_mask(points, origin)
    behind_below = (points[:, 0] < 0) & (np.degrees(np.arctan2(points[:, 1], -points[:, 0]))
                                         < -ROOT_CUT_DEG)
    np.testing.assert_array_equal(keep, ~behind_below)
    assert behind_below.any() and keep.any()


@pytest.mark.parametrize("observed, message", [
    (np.zeros((MIN_RAYS - 1, 3)) + [10.0, 0.0, 0.0], "at least"),
    (np.full((100, 2), 10.0), r"\(k, 3\)"),
    (np.full((100, 3, 1), 10.0), r"\(k, 3\)"),
    (np.where(np.arange(300).reshape(100, 3) == 7, np.nan, 10.0), "non-finite"),
])
def test_a_malformed_surface_is_refused_with_what_is_wrong(rig, observed, message):
    with pytest.raises(ValueError, match=message):
        fit_surface(rig, observed)


def test_a_mask_of_the_wrong_shape_or_leaving_too_few_vertices_is_refused(rig, known_pose):
    observed = rig.vertices(known_pose)
    with pytest.raises(ValueError, match="mask must be"):
        fit_surface(rig, observed, mask=np.ones(10, dtype=bool))
    few = np.zeros(len(observed), dtype=bool)
    few[:MIN_RAYS - 1] = True
    with pytest.raises(ValueError, match="leaves"):
        fit_surface(rig, observed, mask=few)


def test_the_objective_takes_the_exact_volume_that_the_walk_summed(rig, section, known_pose):
    points = rig.vertices(known_pose)
    origin = np.append(rig.control_points(rig.neutral)[1], 0.0)
    objective = Objective3D(rig, points, visible_mask(points, origin), free_groups(rig),
                            base=rig.neutral, origin=origin, section=section,
                            volume_bound_pct=0.5, volume_bound_weight=1.0)
    x = objective.x0 + 0.5 * (np.array([known_pose[rig.parameter_names.index(n)]
                                        for n in objective.names]) - objective.x0)
    value = objective(x)
    change = objective.volume_change(x)  # the exact surface's, as reports give it
    assert abs(change) > 0.5
    r = objective.residuals(x)
    share = (x - objective.neutral) / (objective.upper - objective.lower)
    expected = float(np.mean(r * r)) + objective.volume_weight * change**2 \
        + (abs(change) - 0.5) ** 2 + objective.neutral_weight * float(np.sum(share**2))
    assert value == pytest.approx(expected, rel=1e-12)
