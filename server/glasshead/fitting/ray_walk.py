"""First crossings of rays from one origin with a deforming mesh of fixed topology: a walk over
the triangle adjacency from the previous hits, certified by counting crossings (most rays) or
against a refitted sphere hierarchy.

Definition (the reference, ``first_hits.exhaustive_first_hits``): for ray i, origin O and
direction d_i, every triangle is tested with the project's two-sided Moller-Trumbore kernel
(``geometry.ray_triangle``, op by op) in origin-relative coordinates (s = O - a computed as
-(a - O), e1 = b - a, e2 = c - a from the shifted vertices, as ``first_hits_from_origin`` does),
with the barycentric slack ``COLLISION_TOL.barycentric`` and t > 0; the first hit is the smallest
(t, triangle index). ``RayWalker.first_hits`` returns exactly that triangle and that t.

Method, per evaluation (vertices change, triangles never do):

1. Walk. Each ray starts at its previous hit triangle and, in lockstep with the others, steps
   across the edge opposite the most negative barycentric (sign-corrected by t, so that the step
   goes toward the ray's direction in the cone from O) until the kernel reports a hit, for at
   most ``WALK_STEPS`` steps (the last ``TAIL`` rays one at a time, in Python floats). This gives
   a hit T at t_w, nearly always in 0 to 2 steps.
2. Crossing count (most rays). The mesh is closed and consistently oriented (checked once), so
   along any ray from O (exits) - (entries) = w(O), the winding number of the surface around O.
   A crossing of a triangle with (a - O) . n > 0 at t > 0 is an exit (t (d . n) = (a - O) . n).
   B, per pose, is every other triangle (with a margin: O behind the plane by more than
   ``FACING`` rad), and N(B) the triangles sharing a vertex with B. A ray that meets no triangle
   of N(B) (bounding spheres, then the kernel with the wider ``BACK_SLACK``, grazing rays
   counted) has no entry, so exactly w(O) crossings. An upper bound on w(O) comes from the
   triangles' solid angles (``_facing``); when it is at most 1 such a ray's only crossing is the
   walk's T (w = 1), or it has none (w = 0, computed exactly when needed). The kernel's slack
   also accepts a ray passing just outside a triangle; for a triangle outside N(B) every
   triangle round its corners faces away from O, so their projections from O tile a
   neighbourhood of it and such a ray crosses one of them there: every kernel hit lies within
   the slack of the one crossing, on a triangle sharing a corner with T. So when T's hit is
   within ``TIE`` (barycentric) of an edge, the triangles round T's corners are tested too, and
   the smallest (t, index) kept.
3. Certificate (the other rays: those meeting N(B), a walk without a hit, a winding number that
   may exceed 1). A hierarchy of bounding spheres over fixed groups of triangles
   (``fitting.sphere_tree``: built once per topology from the rest pose, a k-d split so groups
   are compact; leaves are two triangles sharing their longest edge, mid nodes ``MID`` leaves,
   top nodes ``TOP`` mid nodes) is refitted to the current vertices: a leaf's sphere holds its
   triangles' vertices, a parent's holds its children's spheres, every radius widened by
   ``MARGIN_MM`` plus ``MARGIN_REL`` of its distance from O. A triangle can only be crossed at
   distance r along a ray if that ray meets each enclosing sphere, at a distance from O no
   smaller than |c| - R. The search keeps the top spheres the ray meets no farther than
   r_w = t_w |d| (widened), then the mid and leaf spheres it meets, and tests every triangle of
   every kept leaf with the same kernel.
   Up to ``BRUTE_RAYS`` such rays are tested against every triangle instead (cheaper than the
   refit). Answer: the smallest (t, index) among the walk's T and the tested triangles.

Why the certificate is exact: the triangles never tested are those in a sphere the ray misses,
or meets only beyond r_w. Neither can hold a hit with t <= t_w (a hit point lies in the triangle,
widened by the slack, so in every enclosing sphere, at distance t |d| from O), so every triangle
that could tie with or beat T is tested, with bit-identical arithmetic to the exhaustive search
(numpy's elementwise operations, and Python's float operations, round alike whatever the array
layout). The minimum over that set is the exhaustive minimum. The walk only sets the bound r_w; a
wrong walk (a fold in front of T, a tie on a shared edge) costs extra tests, never a wrong
answer. Rays whose walk found no hit (a step limit, a ray leaving the mesh) fall back to the
same search with no distance bound, which is exhaustive over the hierarchy; the very first
evaluation is brute force.

The margins cover the kernel's rounding: with the slack 1e-9, a hit lies within 1e-9 of two
edge lengths of its triangle, and the computed barycentrics err by about 1e-16 |O - a| /
(sin(theta) sin(gamma)) edge lengths, theta the angle between the ray and the triangle's plane,
gamma the triangle's smallest angle; the 1e-5 mm margin covers that for sin(theta) sin(gamma) >
1e-8 at 100 mm, i.e. every ray but one grazing a triangle's plane within 1e-8 rad, where the
kernel's own answer is rounding noise. The crossing count's margins are wider: B takes every
triangle seen within 1e-6 rad of edge-on, and rays are tested against N(B) with a slack of 1e-6
and counted as crossing when within 1e-6 rad of its planes.
"""

import math

import numpy as np
import numpy.typing as npt

from glasshead.fitting.first_hits import (
    SLACK,
    FirstHits,
    check_rays,
    exhaustive_first_hits,
    points,
)
from glasshead.fitting.sphere_tree import (
    MARGIN_MM,
    MARGIN_REL,
    SphereTree,
    gather,
    norm2,
    rows,
)
from glasshead.geometry.mesh_topology import closed_and_oriented, triangle_adjacency, vertex_stars
from glasshead.geometry.ray_triangle import inside_triangle, ray_triangle

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]

#: Steps a walk may take before the ray falls back to the unbounded search.
WALK_STEPS = 8
#: Rays left in the walk below which it goes on one ray at a time.
TAIL = 16
#: Up to this many rays to certify are searched exhaustively rather than through the hierarchy
#: (whose refit alone costs about as much as four exhaustive rays).
BRUTE_RAYS = 4
#: Relative widening of the walk's distance bound, so that ties with T are always tested.
BOUND_REL = 1e-9
#: A triangle faces away from O when O lies behind its plane by more than this angle (rad):
#: (a - O) . n > FACING |a - O| |n|; every other triangle is back-facing (the set B).
FACING = 1e-6
#: The solid-angle sum must lie this close to an integer for the winding number to be trusted.
WINDING_TOL = 1e-6
#: Barycentric slack, and the angle (rad) between a ray and a triangle's plane below which the
#: ray counts as grazing, when rays are tested against B's neighbourhood: wider than the
#: definition's, so that every ray that could cross it, or hit it within the slack, is caught.
BACK_SLACK = 1e-6
GRAZE = 1e-6
#: A walk's hit with a barycentric below this lies near an edge or a vertex: the triangles round
#: that hit's corners are tested too, for ties.
TIE = 1e-6


class RayWalker:
    """Exact first hits of rays from one origin with a mesh whose triangles never change.

    ``RayWalker(triangles, rest_vertices)`` builds the adjacency and the sphere hierarchy once;
    ``first_hits(origin, directions, vertices, start)`` answers for one pose, walking from
    ``start`` (the previous hits, (k,) int64) or searching exhaustively when ``start`` is None.
    """

    #: Per pose (``_facing``): an upper bound on the winding number around O, and the exact one
    #: once computed (False: not an integer).
    _w_max: int | None
    _exact_winding: int | bool | None

    def __init__(self, triangles: npt.ArrayLike, rest_vertices: npt.ArrayLike):
        tri = np.asarray(triangles)
        rest = np.asarray(rest_vertices, dtype=np.float64)
        if tri.ndim != 2 or tri.shape[1] != 3 or len(tri) == 0:
            raise ValueError(f"triangles must have shape (m, 3), got {tri.shape}")
        if rest.ndim != 2 or rest.shape[1] != 3:
            raise ValueError(f"rest vertices must have shape (n, 3), got {rest.shape}")
        if not np.issubdtype(tri.dtype, np.integer) or tri.min() < 0 or tri.max() >= len(rest):
            raise ValueError(f"triangles must index the {len(rest)} vertices")
        self.triangles = tri.astype(np.int64)
        self.vertex_count = len(rest)
        self.adjacency = triangle_adjacency(self.triangles)
        self.tree = SphereTree(self.triangles, self.adjacency, rest)
        self._triangles_t = np.ascontiguousarray(self.triangles.T)
        # the crossing-count certificate needs every edge used once in each direction
        self._oriented = closed_and_oriented(self.triangles)
        self._star, self._star_start = vertex_stars(self.triangles, self.vertex_count)

    # --- per pose -------------------------------------------------------------------------------

    def _prepare(self, origin: Floats, vertices: npt.ArrayLike, facing: bool = True) -> None:
        v = np.asarray(vertices, dtype=np.float64)
        if v.shape != (self.vertex_count, 3):
            raise ValueError(f"vertices must have shape ({self.vertex_count}, 3), got {v.shape}")
        if not np.all(np.isfinite(v)):
            raise ValueError("vertices must be finite")
        rel = v - origin
        # corners by coordinate, corner and triangle: every array below is a contiguous row
        rel_t = np.ascontiguousarray(rel.T)
        g = np.take(rel_t, self._triangles_t, axis=1)  # (3, 3, m)
        a, b, c = g[:, 0], g[:, 1], g[:, 2]
        # rows: s (= -a), e1, e2, each xyz, as first_hits_from_origin builds them
        soa = np.empty((9, len(self.triangles)))
        np.negative(a, out=soa[0:3])
        np.subtract(b, a, out=soa[3:6])
        np.subtract(c, a, out=soa[6:9])
        self._soa = soa
        self._tri = rows(soa.T)
        self._rel = rows(rel)
        if facing:
            self._facing(g, soa, rel_t)

    def _facing(self, g: Floats, soa: Floats, rel_t: Floats) -> None:
        """Per pose: the triangles that do not face away from O (``_back``, the set B), and
        an integer upper bound on the winding number of the surface around O (``_w_max``, None
        when there is none).

        w(O) is the sum of the triangles' signed solid angles over 4 pi, the solid angle of a
        triangle (a, b, c) seen from O being 2 atan2(D, den) (van Oosterom and Strackee 1983),
        D = det[a - O, b - O, c - O] and den = |a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|
        (corners relative to O). Negative terms only lower the sum and atan2(D, den) <=
        min(D / den, pi / 2) for D, den > 0, <= pi otherwise, so the sum of those bounds, below
        8 pi, proves w(O) <= 1 with one division per triangle; only when it does not is the exact
        sum taken (``_winding``). Needs a closed, consistently oriented mesh."""
        e1, e2 = soa[3:6], soa[6:9]
        n = np.empty((3, soa.shape[1]))
        np.subtract(e1[1] * e2[2], e1[2] * e2[1], out=n[0])
        np.subtract(e1[2] * e2[0], e1[0] * e2[2], out=n[1])
        np.subtract(e1[0] * e2[1], e1[1] * e2[0], out=n[2])
        facing = (g[:, 0] * n).sum(axis=0)  # D = (a - O) . n
        self._volume = float(facing.sum()) / 6.0  # each D is six times a signed tetrahedron
        n2 = (n * n).sum(axis=0)
        self._n2 = n2
        vertex_r2 = (rel_t * rel_t).sum(axis=0)  # |v - O|^2 per vertex
        # B: O in front of the plane, or behind it by no more than FACING rad
        back = facing * facing <= (FACING * FACING) * vertex_r2[self._triangles_t[0]] * n2
        back |= facing <= 0.0
        self._back = back
        self._w_max = None
        self._exact_winding = None
        if not self._oriented:
            return
        r = np.take(np.sqrt(vertex_r2), self._triangles_t)  # (3, m)
        dots = (g * g[:, [1, 2, 0]]).sum(axis=0)  # a.b, b.c, c.a
        den = r[0] * r[1] * r[2] + (dots * r[[2, 0, 1]]).sum(axis=0)
        with np.errstate(divide="ignore", invalid="ignore"):
            x = facing / den
        each = np.where(den > 0.0, np.minimum(x, 0.5 * np.pi), np.pi)
        bound = float(np.where(facing > 0.0, each, 0.0).sum()) / (2.0 * np.pi)  # >= w(O)
        self._w_max = int(np.floor(bound + WINDING_TOL))
        self._solid = (facing, den)
        if self._w_max > 1:
            self._w_max = self._winding()

    def _winding(self) -> int | None:
        """The winding number of the surface around O (exact sum of solid angles), None when
        the sum is not within ``WINDING_TOL`` of an integer (O on the surface) or the mesh is not
        closed and consistently oriented."""
        if self._exact_winding is None and self._oriented:
            facing, den = self._solid
            w = float(np.arctan2(facing, den).sum()) / (2.0 * np.pi)
            self._exact_winding = int(round(w)) if abs(w - round(w)) <= WINDING_TOL else False
        return self._exact_winding if self._exact_winding is not False else None

    def _mt(self, d: Floats, tris: Ints) -> tuple[Floats, npt.NDArray[np.bool_], Floats, Floats]:
        """t, hit, u, v (n,) of rays d (n, 3) against triangles ``tris`` (n,): the kernel."""
        g = gather(self._tri, tris, 9)
        det, u, v, t = ray_triangle(g[:, 0], g[:, 1], g[:, 2], d[:, 0], d[:, 1], d[:, 2],
                                    g[:, 3], g[:, 4], g[:, 5], g[:, 6], g[:, 7], g[:, 8])
        return t, inside_triangle(det, u, v, SLACK) & (t > 0.0), u, v

    def _walk(self, d: Floats, start: npt.ArrayLike) -> tuple[Ints, Floats, npt.NDArray[np.bool_]]:
        """Lockstep walk from ``start``: (triangle, t) of the first hit met, -1 / inf if none,
        and whether that hit lies within ``TIE`` (barycentric) of an edge of its triangle."""
        k = len(d)
        cur = np.asarray(start, dtype=np.int64).copy()
        if cur.shape != (k,):
            raise ValueError(f"start must have shape ({k},), got {cur.shape}")
        cur[(cur < 0) | (cur >= len(self.triangles))] = 0
        walk_tri = np.full(k, -1, dtype=np.int64)
        walk_t = np.full(k, np.inf)
        near = np.zeros(k, dtype=bool)
        active = np.arange(k)
        for step in range(WALK_STEPS + 1):
            if len(active) <= TAIL:
                self._walk_tail(d, active, cur, WALK_STEPS + 1 - step, walk_tri, walk_t, near)
                break
            t, hit, u, v = self._mt(d[active], cur[active])
            walk_tri[active[hit]] = cur[active[hit]]
            walk_t[active[hit]] = t[hit]
            near[active[hit]] = np.minimum(np.minimum(u[hit], v[hit]), 1.0 - u[hit] - v[hit]) < TIE
            # step across the edge opposite the most negative barycentric toward d's cone
            sign = np.sign(t)
            w0, w1, w2 = (1.0 - u - v) * sign, u * sign, v * sign
            edge = np.where(w1 < w0, 1, 0)
            edge = np.where(w2 < np.minimum(w0, w1), 2, edge)
            ok = ~hit & np.isfinite(w0 + w1 + w2)
            active = active[ok]
            nxt = self.adjacency[cur[active], edge[ok]]
            cur[active] = nxt
            active = active[nxt >= 0]
        return walk_tri, walk_t, near

    def _walk_tail(self, d: Floats, rays: Ints, cur: Ints, steps: int, walk_tri: Ints,
                   walk_t: Floats, near: npt.NDArray[np.bool_]) -> None:
        """The walk's last few rays, one at a time in Python floats (whose operations round as
        numpy's elementwise ones do): the same kernel, hit test and steps as the lockstep walk,
        without numpy's per-call cost on tiny arrays. (The kernel written out here instead of
        called saved 0.02 to 0.03 ms of a 1.1 to 1.5 ms evaluation, 1,000 rays on the built rig
        as bench/ray_walk.py poses it: not worth a second copy.)"""
        records = self._tri.view(np.float64).reshape(-1, 9)
        adjacency = self.adjacency
        for ray in rays.tolist():
            dx, dy, dz = d[ray].tolist()
            tri = int(cur[ray])
            for _ in range(steps):
                sx, sy, sz, e1x, e1y, e1z, e2x, e2y, e2z = records[tri].tolist()
                try:
                    _det, u, v, t = ray_triangle(sx, sy, sz, dx, dy, dz,
                                                 e1x, e1y, e1z, e2x, e2y, e2z)
                except ZeroDivisionError:  # det == 0 in Python floats: a flat triangle
                    break
                w0 = 1.0 - u - v
                if u >= -SLACK and v >= -SLACK and u + v <= 1.0 + SLACK and t > 0.0:
                    walk_tri[ray] = tri
                    walk_t[ray] = t
                    near[ray] = min(min(u, v), w0) < TIE
                    break
                sign = 1.0 if t > 0.0 else -1.0 if t < 0.0 else 0.0 if t == 0.0 else math.nan
                w0, w1, w2 = w0 * sign, u * sign, v * sign
                if not math.isfinite(w0 + w1 + w2):
                    break
                edge = 1 if w1 < w0 else 0
                if w2 < min(w0, w1):
                    edge = 2
                tri = int(adjacency[tri, edge])
                if tri < 0:
                    break

    def naive_walk(self, origin: npt.ArrayLike, directions: npt.ArrayLike,
                   vertices: npt.ArrayLike, start: npt.ArrayLike) -> tuple[Ints, Floats]:
        """The walk alone, with no certificate: (triangle, t), -1 / inf where it found no hit.
        A hit, not necessarily the first: for comparison only."""
        o, d = check_rays(origin, directions)
        self._prepare(o, vertices, facing=False)
        return self._walk(d, start)[:2]

    def _back_rays(self, unit: Floats, d: Floats) -> npt.NDArray[np.bool_]:
        """(k,) bool: rays that may cross, or hit within the slack, a triangle of B or one
        sharing a vertex with B (B's neighbourhood): the ray meets the triangle's widened bounding
        sphere, and the kernel accepts it with ``BACK_SLACK`` at t > -BACK_SLACK or the ray
        grazes the triangle's plane within ``GRAZE`` rad."""
        k = len(unit)
        out = np.zeros(k, dtype=bool)
        if not np.any(self._back):
            return out
        marked = np.zeros(self.vertex_count, dtype=bool)
        marked[self.triangles[self._back].ravel()] = True
        near = np.flatnonzero(marked[self._triangles_t].any(axis=0))
        g = self._soa[:, near]
        e1, e2 = g[3:6], g[6:9]
        # a sphere round each triangle's centroid through its farthest corner, widened
        centre = (e1 + e2) * (1.0 / 3.0) - g[0:3]
        spread = np.stack([e1 + e2, e1 + e1 - e2, e2 + e2 - e1])
        radius = np.sqrt((spread * spread).sum(axis=1).max(axis=0)) * (1.0 / 3.0)
        dist2 = (centre * centre).sum(axis=0)
        radius = radius * (1.0 + MARGIN_REL) + MARGIN_MM + MARGIN_REL * np.sqrt(dist2)
        q = dist2 - radius * radius
        h = np.where(q > 0.0, np.sqrt(np.maximum(q, 0.0)), -np.inf)
        pair = np.flatnonzero(unit @ centre >= h)
        if len(pair) == 0:
            return out
        ri, which = np.divmod(pair, len(near))
        tris = near[which]
        tg = gather(self._tri, tris, 9)
        dd = d[ri]
        det, bu, bv, t = ray_triangle(tg[:, 0], tg[:, 1], tg[:, 2], dd[:, 0], dd[:, 1], dd[:, 2],
                                      tg[:, 3], tg[:, 4], tg[:, 5], tg[:, 6], tg[:, 7], tg[:, 8])
        graze = det * det <= GRAZE * GRAZE * norm2(dd) * self._n2[tris]
        with np.errstate(invalid="ignore"):
            hit = inside_triangle(det, bu, bv, BACK_SLACK) & (t > -BACK_SLACK)
        out[ri[hit | graze]] = True
        return out

    def _ties(self, d: Floats, rays: Ints, walk_tri: Ints) -> tuple[Ints, Ints, Floats]:
        """(ray, triangle, t) of every kernel hit among the triangles round the corners of the
        walk's triangle, for ``rays`` whose hit lies near an edge or a vertex."""
        corners = self.triangles[walk_tri[rays]].ravel()
        lo, hi = self._star_start[corners], self._star_start[corners + 1]
        count = hi - lo
        owner = np.repeat(np.repeat(rays, 3), count)
        offset = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
        tris = self._star[np.repeat(lo, count) + offset]
        t, hit = self._mt(d[owner], tris)[:2]
        return owner[hit], tris[hit], t[hit]

    def _brute(self, d: Floats, rays: Ints) -> tuple[Ints, Ints, Floats]:
        """(ray, triangle, t) of the exhaustive first hit of each of a few ``rays`` (none where
        there is none): every triangle, the reference's arithmetic."""
        soa = self._soa
        dd = d[rays][:, None, :]
        det, u, v, t = ray_triangle(soa[0], soa[1], soa[2], dd[..., 0], dd[..., 1], dd[..., 2],
                                    soa[3], soa[4], soa[5], soa[6], soa[7], soa[8])
        t = np.where(inside_triangle(det, u, v, SLACK) & (t > 0.0), t, np.inf)
        idx = np.argmin(t, axis=1)  # the first of equal minima: the smallest index
        best = t[np.arange(len(rays)), idx]
        hit = np.isfinite(best)
        return rays[hit], idx[hit], best[hit]

    def _certified(self, d: Floats, unit: Floats, length: Floats, rays: Ints, walk_tri: Ints,
                   walk_t: Floats) -> tuple[Ints, Ints, Floats]:
        """(ray, triangle, t) candidates from the sphere hierarchy for ``rays``, bounded by the
        walk's hit where there is one, that hit included."""
        if len(rays) <= BRUTE_RAYS:
            return self._brute(d, rays)
        found = walk_tri[rays] >= 0
        bound = np.where(found, walk_t[rays] * length[rays] * (1.0 + BOUND_REL) + MARGIN_MM,
                         np.inf)
        local, tris = self.tree.search(self._rel, unit[rays], bound)
        owner = rays[local]
        t, hit = self._mt(d[owner], tris)[:2]
        walked = rays[found]
        return (np.r_[owner[hit], walked], np.r_[tris[hit], walk_tri[walked]],
                np.r_[t[hit], walk_t[walked]])

    def first_hits(self, origin: npt.ArrayLike, directions: npt.ArrayLike,
                   vertices: npt.ArrayLike, start: npt.ArrayLike | None = None) -> FirstHits:
        """First hits of rays O + t d with the mesh at ``vertices``; see the module docstring.

        origin (3,), directions (k, 3) finite and non-zero, vertices (n, 3); start (k,) int64
        triangles to walk from (the previous hits; -1 entries start anywhere) or None for the
        exhaustive search. Raises ValueError for bad shapes or values.
        """
        o, d = check_rays(origin, directions)
        k = len(d)
        self._prepare(o, vertices)
        back = int(self._back.sum())
        if start is None:
            triangle, t = exhaustive_first_hits(o, d, vertices, self.triangles)
            none = np.zeros(k, dtype=bool)
            return FirstHits(triangle, t, points(o, d, t), none, none.copy(), none.copy(),
                             back, self._volume)
        walk_tri, walk_t, near = self._walk(d, start)
        found = walk_tri >= 0
        length = np.sqrt(norm2(d))
        unit = d / length[:, None]
        triangle = walk_tri.copy()
        best_t = walk_t.copy()
        shortcut = np.zeros(k, dtype=bool)
        if self._w_max is not None and self._w_max <= 1:
            # rays with no entry cross the surface exactly w(O) times, w(O) <= 1
            clear = ~self._back_rays(unit, d)
            w: int | None = self._w_max
            if w == 1 and np.any(clear & ~found):
                w = self._winding()
            if w is not None and w <= 0:
                shortcut = clear & ~found  # no crossing at all (a walk's hit here: certified)
            elif w == 1:
                shortcut = clear & found  # one crossing, the walk's
        certify = np.flatnonzero(~shortcut)
        ties = np.flatnonzero(shortcut & near)
        parts = [self._ties(d, ties, walk_tri)] if len(ties) else []
        if len(certify):
            parts.append(self._certified(d, unit, length, certify, walk_tri, walk_t))
            triangle[certify] = -1
            best_t[certify] = np.inf
        if parts:
            rays = np.concatenate([p[0] for p in parts] + [ties])
            tris = np.concatenate([p[1] for p in parts] + [walk_tri[ties]])
            t = np.concatenate([p[2] for p in parts] + [walk_t[ties]])
            order = np.lexsort((tris, t, rays))
            rays, tris, t = rays[order], tris[order], t[order]
            first = np.r_[True, rays[1:] != rays[:-1]]
            triangle[rays[first]] = tris[first]
            best_t[rays[first]] = t[first]
        return FirstHits(triangle, best_t, points(o, d, best_t), ~found & ~shortcut,
                         found & (triangle != walk_tri), shortcut, back, self._volume)
