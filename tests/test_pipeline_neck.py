"""The neck (pipeline.neck, taken into the head shell): the built skin covers the hyoid, the
larynx and the upper spine down to where the neck ends, and ends there in a flat cut.

Measured: 96 % of their vertices lie inside the skin; the rest, the front of the thyroid and
cricoid cartilages just under the chin, stand at most 2.6 mm (median 1.2 mm) proud of it. They
lie, seen from the head's centre, beyond the face mask's own skin under the chin, which the
shell (a surface of rays from that centre) cannot pass.
"""

import numpy as np
import pytest
import trimesh

from glasshead.pipeline.anatomy import NECK_COVERS
from glasshead.pipeline.neck import BELOW_MM, UNDER_MM, Neck, fit_neck
from glasshead.pipeline.outputs import load_built_meshes

#: The flat cut's vertices lie within this height of the shell's lowest one, mm.
CUT_MM = 3.0
#: The shell's bottom may lie this far below the neck's (the smooth union of the shell's shapes
#: swells where two meet), mm; measured 6.4.
SWELL_MM = 10.0
#: Share of the covered meshes' vertices inside the skin, and how far the others may stand out,
#: mm (measured: 96 %, 2.6 mm).
INSIDE_SHARE, PROUD_MM = 0.95, 3.5


@pytest.fixture(scope="module")
def built(built_assets):
    return load_built_meshes(built_assets, ("face_skin", "head_shell", *NECK_COVERS))


@pytest.fixture(scope="module")
def skin(built):
    """The face skin and the head shell as one mesh (their seam's vertices are doubled, which
    does not change how often a ray crosses the skin)."""
    parts = [trimesh.Trimesh(built[name][0], built[name][1], process=False)
             for name in ("face_skin", "head_shell")]
    return trimesh.util.concatenate(parts)


def _crossings_backward(mesh, points):
    """How often a ray from each point toward the back of the head (-x) crosses the skin."""
    directions = np.tile([-1.0, 0.0, 0.0], (len(points), 1))
    _, rays, _ = mesh.ray.intersects_location(points, directions, multiple_hits=True)
    return np.bincount(rays, minlength=len(points))


def test_the_skin_covers_the_hyoid_the_larynx_and_the_upper_spine(built, skin):
    bottom = built["head_shell"][0][:, 1].min()
    covered = np.vstack([built[name][0] for name in NECK_COVERS])
    above = covered[covered[:, 1] > bottom + CUT_MM]
    assert len(above) > 5000
    sample = above[np.random.default_rng(4).choice(len(above), 3000, replace=False)]
    inside = _crossings_backward(skin, sample) % 2 == 1
    assert inside.mean() >= INSIDE_SHARE, f"{(~inside).sum()} outside, e.g. {sample[~inside][:3]}"
    _, proud, _ = trimesh.proximity.closest_point(skin, sample[~inside])
    assert proud.max() <= PROUD_MM, (proud.max(), sample[~inside][np.argmax(proud)])
    # Control: the same points 150 mm to the side, beside the neck, are outside.
    beside = sample + [0.0, 0.0, 150.0]
    assert (_crossings_backward(skin, beside) % 2 == 1).mean() == 0.0


def test_the_neck_ends_in_a_flat_cut_under_the_cricoid_and_the_spine(built):
    shell = built["head_shell"][0]
    covered = np.vstack([built[name][0] for name in NECK_COVERS])
    neck_bottom = min(built["cricoid"][0][:, 1].min() - BELOW_MM,
                      covered[:, 1].min() - UNDER_MM)
    bottom = shell[:, 1].min()
    assert neck_bottom - SWELL_MM <= bottom <= neck_bottom, (bottom, neck_bottom)
    # A flat cut: many shell vertices lie at its height, spread front to back.
    cut = shell[shell[:, 1] < bottom + CUT_MM]
    assert len(cut) >= 20 and np.ptp(cut[:, 0]) > 40.0, (len(cut), np.ptp(cut[:, 0]))


def test_a_neck_fitted_to_points_holds_them_all_and_misses_a_ray_that_passes_beside():
    rng = np.random.default_rng(1)
    points = np.column_stack([rng.uniform(-60, -20, 400), rng.uniform(-90, -30, 400),
                              rng.uniform(-15, 15, 400)])
    neck = fit_neck(points, points[points[:, 1] < -80], top_y=-30.0)
    kept = points[points[:, 1] >= neck.bottom_y]
    assert isinstance(neck, Neck) and neck.inside(kept).all()
    origin = np.array([-40.0, 0.0, 0.0])
    down, aside = np.array([[0.0, -1.0, 0.0]]), np.array([[0.0, 0.0, 1.0]])
    assert neck.far_radius(origin, down)[0] == pytest.approx(-neck.bottom_y, abs=0.5)
    assert neck.far_radius(origin, aside)[0] == 0.0
