"""A hierarchy of bounding spheres over a deforming mesh of fixed topology, refitted per pose:
which triangles a ray from the origin O can cross, up to a distance from O.

Built once per topology from the rest pose (``SphereTree``): leaves are two triangles sharing
their longest edge (the quads of a quad-dominant mesh) or single triangles, ordered by a k-d
split so that consecutive blocks are compact; mid nodes hold ``MID`` leaves, top nodes ``TOP``
mid nodes. Per pose (``spheres``), a leaf's sphere holds its triangles' vertices, a parent's
holds its children's spheres, every radius widened by ``MARGIN_MM`` plus ``MARGIN_REL`` of its
distance from O. A triangle can only be crossed at distance r along a ray if that ray meets each
enclosing sphere, at a distance from O no smaller than |c| - R (``search``). The exactness
argument is ``fitting.ray_walk``'s.
"""

import numpy as np
import numpy.typing as npt

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]

#: Leaves (two triangles) per mid node, mid nodes per top node.
MID, TOP = 4, 8
#: Widening of every bounding sphere: absolute (mm) and relative to its distance from O.
MARGIN_MM = 1e-5
MARGIN_REL = 1e-9


def kd_order(centroids: Floats, units: tuple[int, ...]) -> Ints:
    """Order in which consecutive blocks of each size in ``units`` are spatially compact: median
    splits on the longest axis, each split rounded to the largest unit that fits."""
    out: list[Ints] = []
    stack = [np.arange(len(centroids))]
    while stack:
        idx = stack.pop()
        n = len(idx)
        if n <= units[-1]:
            out.append(idx)
            continue
        unit = next(u for u in units if 2 * u <= n)
        left = max(unit, int(round(n / 2 / unit)) * unit)
        pts = centroids[idx]
        axis = int(np.argmax(np.ptp(pts, axis=0)))
        part = np.argpartition(pts[:, axis], left - 1)
        stack.append(idx[part[left:]])
        stack.append(idx[part[:left]])
    return np.concatenate(out)


def leaves(triangles: Ints, adjacency: Ints, rest: Floats) -> tuple[Ints, Ints]:
    """Leaves of the hierarchy: pairs of triangles that share their longest edge (the quads of a
    quad-dominant mesh), else single triangles. Returns (triangles (n, 2), vertices (n, 4));
    a single triangle repeats itself and a corner."""
    corners = rest[triangles]
    # edge k is opposite corner k
    length = np.stack([np.linalg.norm(corners[:, (k + 2) % 3] - corners[:, (k + 1) % 3], axis=1)
                       for k in range(3)], axis=1)
    longest = np.argmax(length, axis=1)
    rows = np.arange(len(triangles))
    partner = adjacency[rows, longest]
    mutual = (partner >= 0) & (adjacency[np.maximum(partner, 0), longest[np.maximum(partner, 0)]]
                               == rows)
    first = mutual & (rows < partner)
    single = ~mutual
    pair_a, pair_b = rows[first], partner[first]
    tris = np.concatenate([np.stack([pair_a, pair_b], 1),
                           np.stack([rows[single], rows[single]], 1)])
    far = triangles[pair_b, longest[pair_b]]
    verts = np.concatenate([np.column_stack([triangles[pair_a], far]),
                            np.column_stack([triangles[single], triangles[single][:, 0]])])
    return tris, verts


def rows(a: Floats) -> np.ndarray:
    """A contiguous (n, c) float64 array viewed as n opaque records, so that ``np.take`` gathers
    whole rows at the cost of one element each."""
    a = np.ascontiguousarray(a)
    return a.view(np.dtype((np.void, a.shape[1] * 8))).ravel()


def gather(records: np.ndarray, index: Ints, width: int) -> Floats:
    return np.take(records, index).view(np.float64).reshape(-1, width)


def norm2(x: Floats) -> Floats:
    """|x|^2 over the last axis (of length 3), without a slow small-axis reduction."""
    return x[..., 0] * x[..., 0] + x[..., 1] * x[..., 1] + x[..., 2] * x[..., 2]


class SphereTree:
    """The hierarchy of one topology: ``leaf_triangles`` (leaves, 2), ``leaf_vertices`` (4,
    leaves), ``mid_children`` (MID, mids) and ``top_children`` (TOP, tops), built from the rest
    pose ``rest`` (n, 3) of ``triangles`` (m, 3) with their ``adjacency``."""

    def __init__(self, triangles: Ints, adjacency: Ints, rest: Floats):
        leaf_tris, leaf_verts = leaves(triangles, adjacency, rest)
        block = MID * TOP
        order = kd_order(rest[leaf_verts].mean(axis=1), (block, MID, 1))
        order = np.r_[order, np.repeat(order[-1], -len(order) % block)]  # repeats are harmless
        self.leaf_triangles = leaf_tris[order]
        self.leaf_vertices = np.ascontiguousarray(leaf_verts[order].T)  # (4, leaves)
        self.mid_children = np.ascontiguousarray(np.arange(len(order)).reshape(-1, MID).T)
        self.top_children = np.ascontiguousarray(
            np.arange(len(order) // MID).reshape(-1, TOP).T)

    def spheres(self, rel: np.ndarray) -> list[tuple[Floats, Floats]]:
        """Refitted (centres (n, 3), widened radii (n,)) of the leaves, mid and top nodes, for
        the vertices relative to O ``rel`` (``rows`` of (n, 3))."""
        pts = np.take(rel, self.leaf_vertices).view(np.float64).reshape(
            *self.leaf_vertices.shape, 3)  # (4, leaves, 3)
        centre = 0.5 * (pts.min(axis=0) + pts.max(axis=0))
        radius = np.sqrt(norm2(pts - centre).max(axis=0))
        levels = []
        for children in (None, self.mid_children, self.top_children):
            if children is not None:
                c, r = centre[children], radius[children]  # (width, n, 3), (width, n)
                centre = c.mean(axis=0)
                radius = (np.sqrt(norm2(c - centre)) + r).max(axis=0)
            radius = radius * (1.0 + MARGIN_REL) + MARGIN_MM \
                + MARGIN_REL * np.sqrt(norm2(centre))
            levels.append((centre, radius))
        return levels

    @staticmethod
    def cone(centre: Floats, radius: Floats) -> Floats:
        """(n, 4) rows (c, -h): a ray of unit direction u meets the sphere (c, r) only if
        u . c >= h, h = sqrt(|c|^2 - r^2) (-inf when O is inside: always)."""
        q = norm2(centre) - radius * radius
        h = np.where(q > 0.0, np.sqrt(np.maximum(q, 0.0)), -1e300)
        return np.column_stack([centre, -h])

    def search(self, rel: np.ndarray, unit: Floats, bound: Floats) -> tuple[Ints, Ints]:
        """(ray, triangle) pairs to test: every triangle in a leaf whose enclosing spheres the ray
        of unit direction ``unit`` (k, 3) meets, the top sphere within ``bound`` (k,) (distance
        from O) of the origin; ``rel``: the vertices relative to O, as for ``spheres``."""
        (lc, lr), (mc, mr), (tc, tr) = self.spheres(rel)
        near = np.sqrt(norm2(tc)) - tr
        top = self.cone(tc, tr)
        meet = (unit @ top[:, :3].T >= -top[:, 3]) & (near <= bound[:, None])
        ri, node = np.nonzero(meet)
        for cones, children in ((self.cone(mc, mr), self.top_children),
                                (self.cone(lc, lr), self.mid_children)):
            width = len(children)
            kids = children.T[node]  # (p, width)
            g = np.take(rows(cones), kids).view(np.float64).reshape(len(node), width, 4)
            u = unit[ri]
            dot = g[..., 0] * u[:, 0, None] + g[..., 1] * u[:, 1, None] \
                + g[..., 2] * u[:, 2, None] + g[..., 3]
            keep = dot >= 0.0
            ri, node = np.broadcast_to(ri[:, None], keep.shape)[keep], kids[keep]
        return np.repeat(ri, 2), self.leaf_triangles[node].ravel()
