"""Building the liner and voxel tables from the real Badin maxilla, and the tables file format.

Every promise the tables make (radius bounds per cell, plane cells, node radii, voxel classes) is
checked against exact raycasts from O over the full mesh, with seeded random samples.
"""

import json

import numpy as np
import pytest

from collision_support import ExactRays, badin_mesh
from glasshead.constants import (
    CELL_EMPTY,
    CELL_PLANE,
    COLLISION_TABLES_FORMAT_VERSION,
    COLLISION_TABLES_MAGIC,
    VOXEL_NOT_OK,
    VOXEL_OK,
)
from glasshead.geometry.collision_format import (
    CollisionTablesError,
    decode_collision_tables,
    encode_collision_tables,
)
from glasshead.geometry.spherical import angles_to_direction
from glasshead.pipeline.collision_tables import (
    TABLES_FILE,
    build_collision_tables,
    collision_origin,
)


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    v, f = badin_mesh("maxilla")
    out = tmp_path_factory.mktemp("collision")
    summary = build_collision_tables(v, f, out)
    data = (out / TABLES_FILE).read_bytes()
    tables = decode_collision_tables(data)
    return {"v": v, "f": f, "summary": summary, "data": data, "tables": tables,
            "rays": ExactRays(v, f, tables.header["origin"])}


def _cells(tables):
    liner = tables.header["liner"]
    return liner, (liner["nlat"], liner["nlon"])


def test_origin_lies_in_the_mid_sagittal_plane_at_the_lowest_point_of_the_maxilla(built):
    o = np.array(built["tables"].header["origin"])
    v = built["v"]
    # Set by the rule, not computed: z is 0 and y is one of the vertices' own values.
    assert o[2] == 0.0
    assert o[1] == v[:, 1].min() == built["tables"].header["floor_y"]
    assert v[:, 0].min() < o[0] < v[:, 0].max()
    # Straight up from O is the palate vault, about 2 cm away.
    r = built["rays"].radius(o[None] + [[0.0, 1.0, 0.0]])[0]
    assert 15.0 < r < 30.0


def test_cell_radius_bounds_enclose_the_exact_first_hit_of_random_rays(built):
    seed = 21
    tables, rays = built["tables"], built["rays"]
    liner, _ = _cells(tables)
    rng = np.random.default_rng(seed)
    theta = rng.uniform(liner["lon0"], liner["lon0"] + liner["nlon"] * liner["step"], 20000)
    phi = rng.uniform(liner["lat0"], liner["lat0"] + liner["nlat"] * liner["step"], 20000)
    o = np.array(tables.header["origin"])
    exact = rays.radius(o + angles_to_direction(theta, phi) * 100.0)
    i = np.floor((theta - liner["lon0"]) / liner["step"]).astype(int)
    j = np.floor((phi - liner["lat0"]) / liner["step"]).astype(int)
    rmin, rmax = tables["cell_rmin"][j, i], tables["cell_rmax"][j, i]
    kind = tables["cell_kind"][j, i]
    hit = np.isfinite(exact)
    assert hit.mean() > 0.5, f"seed {seed}: the sample should mostly see the maxilla"
    assert np.all(rmin[hit] <= exact[hit] + 1e-4), f"seed {seed}"
    assert np.all(exact[hit] <= rmax[hit] + 1e-4), f"seed {seed}"
    assert not np.any(hit & (kind == CELL_EMPTY)), f"seed {seed}: an empty cell was hit"
    # Where one plane covers the cell, the bounds are tight.
    plane = hit & (kind == CELL_PLANE)
    assert np.median((rmax - rmin)[plane]) < 0.5


def test_plane_cells_hold_the_triangle_every_ray_in_them_hits_first(built):
    seed = 4
    tables = built["tables"]
    liner, shape = _cells(tables)
    rng = np.random.default_rng(seed)
    cells = rng.choice(np.flatnonzero(tables["cell_kind"].ravel() == CELL_PLANE), 500)
    j, i = np.unravel_index(cells, shape)
    theta = liner["lon0"] + (i + rng.uniform(size=500)) * liner["step"]
    phi = liner["lat0"] + (j + rng.uniform(size=500)) * liner["step"]
    o = np.array(tables.header["origin"])
    d = angles_to_direction(theta, phi)
    planes = tables["planes"][tables["cell_triangles"][tables["cell_offsets"][cells]]]
    radius_on_plane = planes[:, 3] / np.einsum("ij,ij->i", planes[:, :3], d)
    np.testing.assert_allclose(radius_on_plane, built["rays"].radius(o + d * 100.0), atol=1e-4)


def test_node_radii_are_the_exact_first_hits_of_the_grid_rays(built):
    tables = built["tables"]
    liner, _ = _cells(tables)
    rng = np.random.default_rng(6)
    j = rng.integers(0, liner["nlat"] + 1, 3000)
    i = rng.integers(0, liner["nlon"] + 1, 3000)
    theta, phi = liner["lon0"] + i * liner["step"], liner["lat0"] + j * liner["step"]
    o = np.array(tables.header["origin"])
    exact = built["rays"].radius(o + angles_to_direction(theta, phi) * 100.0)
    node = tables["node_radius"][j, i]
    # Hit or miss is compared on rays clear of the maxilla's outline: a ray grazing an edge can
    # hit in float64 and miss in Embree's float32 (or on another CPU). A ray is clear when
    # turning it by 1e-7 rad (5e-6 mm at 50 mm) either way in both angles keeps its answer.
    clear = np.ones(len(j), dtype=bool)
    for dt, dp in ((1e-7, 0.0), (-1e-7, 0.0), (0.0, 1e-7), (0.0, -1e-7)):
        turned = built["rays"].radius(o + angles_to_direction(theta + dt, phi + dp) * 100.0)
        clear &= np.isfinite(turned) == np.isfinite(exact)
    assert clear.mean() > 0.99, f"only {clear.sum()} of {len(clear)} rays clear of an edge"
    np.testing.assert_array_equal(np.isfinite(node)[clear], np.isfinite(exact)[clear])
    both = np.isfinite(node) & np.isfinite(exact)
    # mm: float32 table values and Embree's float32 hits (a few 1e-6 mm at 50 mm).
    np.testing.assert_allclose(node[both], exact[both], rtol=0, atol=1e-4)


def test_ok_voxels_hold_only_outside_points_and_not_ok_voxels_only_inside_points(built):
    seed = 9
    tables, rays = built["tables"], built["rays"]
    vox = tables.header["voxels"]
    bmin, bmax = np.array(vox["bounds"]["min"]), np.array(vox["bounds"]["max"])
    shape = np.array(vox["shape"])
    rng = np.random.default_rng(seed)
    size = (bmax - bmin) / shape
    for cls, expect_inside in ((VOXEL_OK, False), (VOXEL_NOT_OK, True)):
        idx = np.argwhere(tables["voxels"] == cls)
        if cls == VOXEL_OK:
            assert len(idx) > 10000
        if len(idx) == 0:
            continue  # not-ok voxels need a cell proven covered; see the flat-palate test
        pick = idx[rng.integers(0, len(idx), 4000)]
        points = bmin + (pick + rng.uniform(size=(4000, 3))) * size
        r = np.linalg.norm(points - tables.header["origin"], axis=1)
        inside = r > rays.radius(points)
        assert np.all(inside == expect_inside), f"seed {seed}, class {cls}"


def test_voxel_table_is_32_cubed_around_the_palate_and_mostly_decided(built):
    tables = built["tables"]
    assert tables["voxels"].shape == (32, 32, 32)
    stats = built["summary"]["stats"]
    assert stats["voxels_ok"] > 10000
    v = built["v"]
    bmin = np.array(tables.header["voxels"]["bounds"]["min"])
    bmax = np.array(tables.header["voxels"]["bounds"]["max"])
    assert bmin[1] == tables.header["floor_y"]
    assert bmax[1] < v[:, 1].max(), "the box ends above the palate, not at the nasal walls"


def test_the_file_round_trips_every_array_and_records_format_and_origin(built):
    tables = decode_collision_tables(built["data"])
    again = decode_collision_tables(encode_collision_tables(
        {k: v for k, v in tables.header.items()
         if k not in ("arrays", "payload_bytes", "payload_crc32", "format", "format_version",
                      "byte_order")},
        tables.arrays))
    for name, array in tables.arrays.items():
        np.testing.assert_array_equal(again[name], array)  # a round trip of bytes: exact
    h = tables.header
    assert h["format_version"] == COLLISION_TABLES_FORMAT_VERSION
    assert built["data"][:8] == COLLISION_TABLES_MAGIC
    assert h["voxels"]["shape"] == [32, 32, 32] and len(h["origin"]) == 3


def test_a_flat_palate_gives_not_ok_voxels_above_it_and_ok_voxels_below(tmp_path):
    # One wide triangle as the "palate" 12 mm up, and a "tooth" at y = 0 that sets the floor.
    v = np.array([[-60.0, 12.0, -60.0], [60.0, 12.0, -60.0], [0.0, 12.0, 90.0],
                  [-2.0, 0.0, 25.0], [2.0, 0.0, 25.0], [0.0, 4.0, 25.0]])
    f = np.array([[0, 1, 2], [3, 4, 5]])
    build_collision_tables(v, f, tmp_path, step_deg=2.0, voxels=16)
    tables = decode_collision_tables((tmp_path / TABLES_FILE).read_bytes())
    vox = tables.header["voxels"]
    bmin, bmax = np.array(vox["bounds"]["min"]), np.array(vox["bounds"]["max"])
    size = (bmax - bmin) / 16
    centres = bmin + (np.argwhere(np.ones((16, 16, 16))) + 0.5) * size
    classes = tables["voxels"].reshape(-1)
    assert np.any(classes == VOXEL_NOT_OK)
    assert np.all(centres[classes == VOXEL_NOT_OK][:, 1] > 12.0)
    ok = centres[classes == VOXEL_OK]
    r = np.linalg.norm(ok - tables.header["origin"], axis=1)
    assert np.all(r < ExactRays(v, f, tables.header["origin"]).radius(ok))


def _patched(data, offset, new):
    data = bytearray(data)
    data[offset:offset + len(new)] = new
    return bytes(data)


@pytest.mark.parametrize("mutate, message", [
    (lambda d: _patched(d, 8, (COLLISION_TABLES_FORMAT_VERSION + 1).to_bytes(4, "little")),
     "format version 2 is not supported"),
    (lambda d: _patched(d, 0, b"NOTATABL"), "magic"),
    (lambda d: d[:-1], "truncated or padded"),
    (lambda d: _patched(d, len(d) - 100, b"\x7f"), "CRC-32"),
    (lambda d: d[:40], "truncated inside its header"),
])
def test_a_damaged_or_foreign_file_is_refused_with_a_reason(built, mutate, message):
    with pytest.raises(CollisionTablesError, match=message):
        decode_collision_tables(mutate(built["data"]))


def test_a_header_whose_shapes_disagree_with_the_grid_is_refused(built):
    tables = decode_collision_tables(built["data"])
    header = {k: v for k, v in tables.header.items() if k != "arrays"}
    header = json.loads(json.dumps(header))
    header["liner"]["nlon"] += 1
    with pytest.raises(CollisionTablesError, match="shape"):
        decode_collision_tables(encode_collision_tables(header, tables.arrays))


def test_origin_rule_takes_the_middle_in_x_and_the_lowest_point_in_y():
    v = np.array([[-10.0, 5.0, 3.0], [30.0, -2.0, -4.0], [0.0, 8.0, 1.0]])
    np.testing.assert_allclose(collision_origin(v), [10.0, -2.0, 0.0], rtol=0, atol=1e-12)


def test_the_builder_refuses_non_finite_vertices_and_bad_faces(tmp_path):
    v, f = badin_mesh("maxilla")
    bad = v.copy()
    bad[3, 1] = np.nan
    with pytest.raises(ValueError, match="finite"):
        build_collision_tables(bad, f, tmp_path)
    with pytest.raises(ValueError, match="do not exist"):
        build_collision_tables(v, f + len(v), tmp_path)
    with pytest.raises(ValueError, match=r"\(m, 3\) integers"):
        build_collision_tables(v, f.astype(float), tmp_path)


def test_the_builder_refuses_a_maxilla_wound_inside_out(tmp_path):
    v, f = badin_mesh("maxilla")
    with pytest.raises(ValueError, match="wound inside out"):
        build_collision_tables(v, f[:, ::-1], tmp_path)


def test_the_builder_refuses_a_maxilla_in_metres_where_the_origin_has_no_room(tmp_path):
    v, f = badin_mesh("maxilla")
    with pytest.raises(ValueError, match="must be at least 3.0 mm inside"):
        build_collision_tables(v / 1000.0, f, tmp_path)
