"""The EPG error: how far a tongue is from a wanted electropalatographic pattern, in mm.

For each electrode of a layout (``epg.contacts.Probes``: the electrode E on the palate and its unit
normal n toward the tongue) the **signed distance** d along n from E to the tongue's upper
surface: the ray E + t n is cut with the tongue's triangles (two-sided Moller-Trumbore,
``geometry.ray_triangle``, with the collision kernels' barycentric slack) and d is the t of the
crossing where the line *enters* the tongue (the triangle's outward normal faces against n)
nearest to E. d > 0: the tongue lies d mm in front of the electrode; d < 0: the tongue reaches
|d| mm past the electrode, into the palate.

**Uncorrected surface.** The synthetic EPG (``epg.synthetic``) probes the tongue after the
collision correction has moved it back onto the palate; this error reads the tongue *before* it.
A tongue pushed d mm past the palate then reads d < 0, which the contact test of the corrected
tongue also counts as contact (its vertices are moved onto the palate, where the probe reaches 0.5
mm behind the electrode); but the error keeps its slope there: an electrode that should stay free
is pulled back in proportion to how far the tongue overshoots, where the corrected surface would
sit at the palate whatever the overshoot and give the optimiser a flat error. It also costs a
third less (no correction per evaluation). The two differ only where the correction reshapes the
surface near an electrode: an electrode within a fraction of a millimetre of the tolerance, or a
side electrode that the uncorrected tongue overshoots by about 4 mm, where the correction (which
moves vertices along rays toward its centre, not along n) can leave the corrected surface just
beyond the probe's 0.5 mm behind it. ``tests/test_objective_epg.py`` checks that they agree on
at least 99 % of the electrodes over poses raised toward the palate (the contact fits add a
margin and keep wanted contacts within ``press_mm`` of the palate for this reason).

**Misses.** A ray that meets no entering triangle within [-BACK_MM, REACH_MM] (a side electrode
whose normal passes beside a narrow tongue) reads the distance the tongue would have to come to
meet it: min over the tongue's vertices of (max(along, 0) + across), with along the vertex's
distance along n and across its distance from the ray. Near a grazing hit that is the hit's t to
within an edge of the mesh, so the error does not drop when a ray slips off the tongue's edge.

**The error.** With the contact tolerance tau (the probe's reach, ``EPG_CONTACT_TOLERANCE_MM``)
and a margin m >= 0, a squared hinge per electrode:

    contact wanted:     h = max(0, d - (tau - m_c))        m_c = contact_margin, default m
    no contact wanted:  h = max(0, (tau + m) - d)

A wanted contact may be given its own margin (``contact_margin``, default m): above tau it aims
the tongue past the electrode, into the palate, so that the contact holds when the pose moves a
little (a target that only grazes its row loses it when the jaw opens a fifth of a degree).

and the error is sqrt(sum w_i h_i^2 / sum w_i) mm: 0 exactly when every electrode is on its
wanted side (with margin 0: when the uncorrected tongue's contacts are the wanted pattern), and
continuous with a continuous slope in the tongue's vertices wherever the ray's crossing moves
smoothly, as the derivative-free optimisers want. ``press_mm`` optionally also penalises a
wanted contact that the tongue overshoots by more than that (d < -press_mm), which would
otherwise cost nothing.
"""

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from glasshead.constants import COLLISION_TOL
from glasshead.epg.contacts import Probes
from glasshead.geometry.ray_triangle import inside_triangle, ray_triangle

#: mm. How far behind each electrode (into the palate) a crossing is looked for: a tongue pushed
#: further than this past the palate reads as a miss.
BACK_MM = 12.0
#: mm. How far in front of each electrode (toward the tongue) a crossing is looked for.
REACH_MM = 30.0
#: Barycentric slack of the crossing test (the collision and contact kernels' own).
SLACK = COLLISION_TOL.barycentric
#: mm. Bounding spheres are widened by this, so that the cull never drops a hit the slack takes.
PAD_MM = 1e-3
#: Triangles per matrix product of the cull: OpenBLAS runs a product of m * n * k up to 4 * 65536
#: on the calling thread (here n = 62 electrodes, k = 3).
CULL_BLOCK = 1024

Floats = npt.NDArray[np.float64]


class EpgObjective:
    """The EPG error of tongue surfaces against one wanted pattern.

    probes: the layout's electrodes (``epg.contacts.probes_from_layout``); wanted: contact (1) or
    not (0) per electrode, (k,) in the probes' order, or an (rows, columns) grid read at the
    probes' cells; weights: (k,) or (rows, columns) non-negative, default 1; triangles: the
    tongue's (m, 3) triangles, wound counter-clockwise seen from outside (the rig's are).
    """

    def __init__(self, probes: Probes, wanted: npt.ArrayLike, triangles: npt.ArrayLike, *,
                 weights: npt.ArrayLike | None = None, margin: float = 0.0,
                 contact_margin: float | None = None, tolerance: float | None = None,
                 press_mm: float | None = None,
                 back_mm: float = BACK_MM, reach_mm: float = REACH_MM):
        self.probes = probes
        self.wanted = self._per_electrode(wanted, "wanted").astype(bool)
        self.weights = np.ones(probes.count) if weights is None \
            else self._per_electrode(weights, "weights").astype(np.float64)
        if np.any(self.weights < 0) or not self.weights.sum() > 0:
            raise ValueError("weights must be non-negative and not all zero")
        if margin < 0:
            raise ValueError("the margin cannot be negative")
        self.tolerance = float(probes.tolerance if tolerance is None else tolerance)
        self.margin = float(margin)
        self.contact_margin = self.margin if contact_margin is None else float(contact_margin)
        if self.contact_margin < 0:
            raise ValueError("the contact margin cannot be negative")
        self.press_mm = None if press_mm is None else float(press_mm)
        self.triangles = np.asarray(triangles, dtype=np.int64)
        self.back, self.reach = float(back_mm), float(reach_mm)
        o, n = probes.origins, probes.directions
        near, far = o - self.back * n, o + self.reach * n
        self._box_low, self._box_high = np.minimum(near, far), np.maximum(near, far)
        self._all_low, self._all_high = self._box_low.min(axis=0), self._box_high.max(axis=0)
        self._origin2 = np.einsum("ij,ij->i", o, o)
        self._origin_along = np.einsum("ij,ij->i", o, n)
        # Work arrays of the cull, made once and viewed as (triangles near, probes): made fresh
        # on every call, arrays of a megabyte or more were mapped and faulted in anew each time
        # whenever the heap had been trimmed below them (1,400 page faults a call, three times
        # the time).
        size = probes.count * len(self.triangles)
        self._rel2, self._along, self._across2 = (np.empty(size) for _ in range(3))
        self._meet, self._within = (np.empty(size, dtype=bool) for _ in range(2))

    def _per_electrode(self, values, what) -> np.ndarray:
        values = np.asarray(values)
        if values.shape == (self.probes.rows, self.probes.columns):
            return values.reshape(-1)[self.probes.cells]
        if values.shape != (self.probes.count,):
            raise ValueError(f"{what} must be ({self.probes.count},) per electrode or a "
                             f"({self.probes.rows}, {self.probes.columns}) grid, got "
                             f"{values.shape}")
        return values

    # --- distances ------------------------------------------------------------------------------

    def distances(self, vertices: npt.ArrayLike) -> Floats:
        """Signed distance (k,) mm along each electrode's normal to the tongue (see the module
        docstring): vertices (n, 3) of the tongue, project frame, uncorrected or corrected."""
        v = np.asarray(vertices, dtype=np.float64)
        tri = self.triangles
        a, b, c = v[tri[:, 0]], v[tri[:, 1]], v[tri[:, 2]]
        low = np.minimum(np.minimum(a, b), c)
        high = np.maximum(np.maximum(a, b), c)
        # Only the triangles within reach of some probe; then those whose bounding sphere (about
        # the centroid) the probe's line passes through, within its reach along it.
        near = np.flatnonzero(np.all((high >= self._all_low) & (low <= self._all_high), axis=1))
        k = self.probes.count
        out = np.full(k, np.inf)
        if len(near):
            ta, tb, tc = a[near], b[near], c[near]
            centre = (ta + tb + tc) / 3.0
            radius = np.sqrt(np.max([np.einsum("ij,ij->i", p - centre, p - centre)
                                     for p in (ta, tb, tc)], axis=0)) + PAD_MM
            o, n = self.probes.origins, self.probes.directions
            which, probe = self._cull(centre, radius)
            tri_index = near[which]
            ta, tb, tc = a[tri_index], b[tri_index], c[tri_index]
            e1, e2 = tb - ta, tc - ta
            s = o[probe] - ta
            d = n[probe]
            det, u, w, t = ray_triangle(s[:, 0], s[:, 1], s[:, 2], d[:, 0], d[:, 1], d[:, 2],
                                        e1[:, 0], e1[:, 1], e1[:, 2], e2[:, 0], e2[:, 1], e2[:, 2])
            # det = e1 . (d x e2) = -d . (e1 x e2): positive when the ray enters the tongue.
            hit = inside_triangle(det, u, w, SLACK) & (det > 0) \
                & (t >= -self.back) & (t <= self.reach)
            if hit.any():
                score = np.where(hit, np.abs(t), np.inf)
                order = np.lexsort((score, probe))
                probe_sorted, score_sorted = probe[order], score[order]
                first = np.ones(len(order), dtype=bool)
                first[1:] = probe_sorted[1:] != probe_sorted[:-1]
                best = order[first & np.isfinite(score_sorted)]
                out[probe[best]] = t[best]
        missed = ~np.isfinite(out)
        if missed.any():
            out[missed] = self._miss_distances(v, np.flatnonzero(missed))
        return out

    def _cull(self, centre: Floats, radius: Floats) -> tuple[np.ndarray, np.ndarray]:
        """(triangle, probe) index pairs, triangle-major, whose bounding sphere (centre (m, 3),
        radius (m,)) the probe's line passes through within [-back - r, reach + r] along it. For
        each probe its triangles come in increasing order, as the first-hit sort expects."""
        shape = (len(centre), self.probes.count)
        size = shape[0] * shape[1]
        rel2, along, across2 = (a[:size].reshape(shape)
                                for a in (self._rel2, self._along, self._across2))
        meet, within = (a[:size].reshape(shape) for a in (self._meet, self._within))
        # In blocks small enough that BLAS runs them on this thread: larger products start its
        # worker threads, which then spin beside every later call and contend with the other
        # fits running in parallel (twice the CPU time for a tenth less wall time).
        for first in range(0, shape[0], CULL_BLOCK):
            block = slice(first, first + CULL_BLOCK)
            np.matmul(centre[block], self.probes.origins.T, out=rel2[block])
            np.matmul(centre[block], self.probes.directions.T, out=along[block])
        rel2 *= -2.0
        rel2 += np.einsum("ij,ij->i", centre, centre)[:, None]
        rel2 += self._origin2[None, :]
        along -= self._origin_along[None, :]
        np.multiply(along, along, out=across2)
        np.subtract(rel2, across2, out=across2)
        np.less_equal(across2, (radius**2)[:, None], out=meet)
        np.greater_equal(along, (-self.back - radius)[:, None], out=within)
        meet &= within
        np.less_equal(along, (self.reach + radius)[:, None], out=within)
        meet &= within
        triangles, probes = np.nonzero(meet)
        return triangles, probes

    def _miss_distances(self, v: Floats, probes: np.ndarray) -> Floats:
        rel = v[None, :, :] - self.probes.origins[probes, None, :]
        along = np.einsum("pvi,pi->pv", rel, self.probes.directions[probes])
        across2 = np.einsum("pvi,pvi->pv", rel, rel) - along**2
        score = np.maximum(along, 0.0) + np.sqrt(np.maximum(across2, 0.0))
        return score.min(axis=1)

    # --- the error ------------------------------------------------------------------------------

    def hinges(self, distances: npt.ArrayLike) -> Floats:
        """Per electrode (k,) mm: how far each distance is on the wrong side of its threshold."""
        d = np.asarray(distances, dtype=np.float64)
        h = np.where(self.wanted, np.maximum(0.0, d - (self.tolerance - self.contact_margin)),
                     np.maximum(0.0, (self.tolerance + self.margin) - d))
        if self.press_mm is not None:
            h = np.where(self.wanted, h + np.maximum(0.0, -self.press_mm - d), h)
        return h

    def error_from_distances(self, distances: npt.ArrayLike) -> float:
        h = self.hinges(distances)
        return float(np.sqrt(np.sum(self.weights * h**2) / np.sum(self.weights)))

    def __call__(self, vertices: npt.ArrayLike) -> float:
        """The EPG error, mm, of a tongue surface (vertices (n, 3))."""
        return self.error_from_distances(self.distances(vertices))

    def predicted(self, vertices: npt.ArrayLike) -> npt.NDArray[np.uint8]:
        """Contact (1) or not per electrode as this error reads it: distance <= tolerance."""
        return (self.distances(vertices) <= self.tolerance).astype(np.uint8)


def wanted_from_rows(rows: Sequence[str] | npt.ArrayLike) -> npt.NDArray[np.uint8]:
    """An (8, 8) pattern from emuR row strings (R1 first) or an (8, 8) array."""
    if isinstance(rows, (list, tuple)) and rows and isinstance(rows[0], str):
        return np.array([[int(c) for c in r] for r in rows], dtype=np.uint8)
    return np.asarray(rows, dtype=np.uint8)
