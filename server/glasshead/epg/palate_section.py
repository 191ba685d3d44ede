"""Plane sections of a triangle mesh as ordered polylines, and walks along them.

The electrode layout measures the palate along curves: the mid-sagittal profile and, at each row,
the section across the palate's arc. A section is found exactly, triangle by triangle: every
triangle whose corners lie on both sides of the plane contributes one segment, whose two ends lie
on two of its edges. A section point is therefore identified by the mesh edge it lies on, and two
segments that share an edge are neighbours, so the segments join into polylines by topology, with
no distance tolerance. A vertex exactly on the plane counts as lying on its positive side
(symbolic perturbation), so no segment is ever degenerate.

Each point also carries the interpolation weight along its edge, so that per-vertex values (the
tooth weight, say) can be read off at any point of a section.
"""

from dataclasses import dataclass

import numpy as np

#: mm. Section points closer than this are the same point (parts of a mesh that meet at a seam).
SEAM_MM = 1e-6
#: mm. An open end of a section curve is joined to the nearest open end of another within this
#: distance: meshes stitched from scans leave seams whose two sides do not share vertices.
BRIDGE_MM = 0.75


@dataclass
class Polyline:
    """An ordered section curve.

    points (k, 3) float64 mm; edges (k, 2) int64 mesh vertex pairs the points lie on; weights
    (k,) float64, the point is ``(1 - w) * v[a] + w * v[b]``; triangles (k - 1,) int64, the mesh
    triangle of each segment (-1 for a bridge across a seam, see BRIDGE_MM); closed: True when
    the curve is a loop (the last point joins the first through ``triangles[-1]``, which then has
    k entries).
    """

    points: np.ndarray
    edges: np.ndarray
    weights: np.ndarray
    triangles: np.ndarray
    closed: bool = False

    def arc_lengths(self) -> np.ndarray:
        """(k,) cumulative length along the curve from its first point, mm."""
        steps = np.linalg.norm(np.diff(self.points, axis=0), axis=1)
        return np.concatenate([[0.0], np.cumsum(steps)])

    def interpolate(self, values) -> np.ndarray:
        """Per-vertex ``values`` (n,) or (n, d) read off at every point: (k,) or (k, d)."""
        values = np.asarray(values, dtype=np.float64)
        a, b = values[self.edges[:, 0]], values[self.edges[:, 1]]
        w = self.weights if values.ndim == 1 else self.weights[:, None]
        return (1.0 - w) * a + w * b

    def reversed(self) -> "Polyline":
        triangles = self.triangles[::-1]
        if self.closed:
            triangles = np.roll(triangles, -1)
        return Polyline(self.points[::-1].copy(), self.edges[::-1].copy(),
                        self.weights[::-1].copy(), triangles.copy(), self.closed)


class Section:
    """The section of mesh (vertices (n, 3), faces (m, 3)) by the plane through ``origin`` with
    unit ``normal``: its segments, joined into polylines on demand."""

    def __init__(self, vertices, faces, origin, normal):
        vertices = np.asarray(vertices, dtype=np.float64)
        faces = np.asarray(faces, dtype=np.int64)
        normal = np.asarray(normal, dtype=np.float64)
        normal = normal / np.linalg.norm(normal)
        distance = (vertices - np.asarray(origin, dtype=np.float64)) @ normal
        above = distance >= 0.0
        side = above[faces]
        crossing = np.flatnonzero(side.any(axis=1) & ~side.all(axis=1))
        tri = faces[crossing]
        # The two crossing edges of each crossing triangle, as (a, b) with a < b.
        ends = []
        for k in range(3):
            a, b = tri[:, k], tri[:, (k + 1) % 3]
            cut = side[crossing, k] != side[crossing, (k + 1) % 3]
            ends.append((np.minimum(a, b), np.maximum(a, b), cut))
        first = np.empty((len(tri), 2), dtype=np.int64)
        second = np.empty((len(tri), 2), dtype=np.int64)
        seen = np.zeros(len(tri), dtype=bool)
        for a, b, cut in ends:
            take_first = cut & ~seen
            first[take_first] = np.stack([a, b], axis=1)[take_first]
            take_second = cut & seen
            second[take_second] = np.stack([a, b], axis=1)[take_second]
            seen |= cut
        n = len(vertices)
        keys = np.concatenate([first[:, 0] * n + first[:, 1], second[:, 0] * n + second[:, 1]])
        unique_edges, edge_of = np.unique(keys, return_inverse=True)
        edges = np.stack([unique_edges // n, unique_edges % n], axis=1)
        da, db = distance[edges[:, 0]], distance[edges[:, 1]]
        weights = da / (da - db)
        va, vb = vertices[edges[:, 0]], vertices[edges[:, 1]]
        points = va + weights[:, None] * (vb - va)
        # Meshes made of parts (a left and a right half, say) repeat the vertices of their
        # seams; points that coincide to SEAM_MM are one node, so the curve crosses the seam.
        _, first_of, node_of = np.unique(np.round(points / SEAM_MM).astype(np.int64), axis=0,
                                         return_index=True, return_inverse=True)
        node_of = node_of.ravel()
        self.node_edges = edges[first_of]
        self.node_weights = weights[first_of]
        self.node_points = points[first_of]
        inverse = node_of[edge_of.ravel()]
        self.links = inverse.reshape(2, -1).T  # (segments, 2) node ids
        self.link_triangles = crossing
        # per node: (neighbouring node, segment) pairs
        self.neighbours: list[list[tuple[int, int]]] = [[] for _ in range(len(self.node_points))]
        for s, (p, q) in enumerate(self.links):
            if p == q:  # a segment shorter than SEAM_MM joins nothing
                continue
            self.neighbours[p].append((q, s))
            self.neighbours[q].append((p, s))
        self._bridge_open_ends()

    def _bridge_open_ends(self):
        """Join each open end to the nearest open end of another curve within BRIDGE_MM, by a
        segment of triangle -1 (closest pairs first, each end at most once)."""
        ends = np.array([k for k, n in enumerate(self.neighbours) if len(n) == 1], dtype=np.int64)
        if len(ends) < 2:
            return
        d = np.linalg.norm(self.node_points[ends][:, None] - self.node_points[ends][None], axis=2)
        d[np.arange(len(ends)), np.arange(len(ends))] = np.inf
        pairs = np.argwhere(np.triu(d <= BRIDGE_MM, 1))
        pairs = pairs[np.argsort(d[pairs[:, 0], pairs[:, 1]])]
        used: set[int] = set()
        links, triangles = [self.links], [self.link_triangles]
        for i, j in pairs:
            a, b = int(ends[i]), int(ends[j])
            if a in used or b in used or self.neighbours[a][0][0] == b:
                continue
            used.update((a, b))
            segment = sum(len(x) for x in links)
            links.append(np.array([[a, b]]))
            triangles.append(np.array([-1]))
            self.neighbours[a].append((b, segment))
            self.neighbours[b].append((a, segment))
        self.links = np.concatenate(links)
        self.link_triangles = np.concatenate(triangles)

    @property
    def empty(self) -> bool:
        return len(self.links) == 0

    def nearest_segment(self, point) -> int:
        """Index of the segment closest to ``point`` (3,)."""
        if self.empty:
            raise ValueError("the plane does not cut the mesh")
        a = self.node_points[self.links[:, 0]]
        b = self.node_points[self.links[:, 1]]
        ab = b - a
        t = np.clip(np.einsum("ij,ij->i", np.asarray(point) - a, ab)
                    / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0.0, 1.0)
        d = np.linalg.norm(a + t[:, None] * ab - point, axis=1)
        return int(np.argmin(d))

    def nearest_node(self, point) -> int:
        return int(np.argmin(np.linalg.norm(self.node_points - np.asarray(point), axis=1)))

    def _walk(self, start, came_by, stop_at):
        """Nodes and segments from ``start`` onward, leaving by any segment but ``came_by``,
        until the curve ends or reaches ``stop_at`` (then it is a loop: True is returned)."""
        nodes, segments = [start], list[int]()
        visited = {came_by}
        current = start
        while True:
            step = next(((q, s) for q, s in self.neighbours[current] if s not in visited), None)
            if step is None:
                return nodes, segments, False
            q, s = step
            visited.add(s)
            segments.append(s)
            if q == stop_at:
                return nodes, segments, True
            nodes.append(q)
            current = q

    def polyline_through(self, segment: int) -> Polyline:
        """The whole polyline that contains ``segment``, ordered from one end to the other (or
        once round, for a loop, starting at the segment's first node)."""
        p, q = self.links[segment]
        ahead, ahead_segments, closed = self._walk(q, segment, stop_at=p)
        if closed:
            nodes = [p] + ahead
            segments = [segment] + ahead_segments
        else:
            behind, behind_segments, _ = self._walk(p, segment, stop_at=q)
            nodes = behind[::-1] + ahead
            segments = behind_segments[::-1] + [segment] + ahead_segments
        nodes = np.array(nodes, dtype=np.int64)
        return Polyline(self.node_points[nodes], self.node_edges[nodes],
                        self.node_weights[nodes], self.link_triangles[np.array(segments)],
                        closed)


def point_at(polyline: Polyline, arc, s: float):
    """(point (3,), segment index) at arc length ``s`` along ``polyline`` (``arc`` from
    ``arc_lengths()``), clamped to its ends."""
    s = float(np.clip(s, arc[0], arc[-1]))
    k = int(np.clip(np.searchsorted(arc, s, side="right") - 1, 0, len(arc) - 2))
    span = arc[k + 1] - arc[k]
    w = 0.0 if span <= 0 else (s - arc[k]) / span
    return polyline.points[k] + w * (polyline.points[k + 1] - polyline.points[k]), k


def crossing_arc(arc, values, level, start=0, step=1):
    """Arc length where ``values`` (k,) first reaches ``level`` walking from index ``start`` by
    ``step`` (+1 or -1), linearly interpolated; None if it never does."""
    k = start
    while 0 <= k + step < len(values):
        a, b = values[k], values[k + step]
        if (a < level) != (b < level):
            w = (level - a) / (b - a)
            return float(arc[k] + w * (arc[k + step] - arc[k]))
        k += step
    return None
