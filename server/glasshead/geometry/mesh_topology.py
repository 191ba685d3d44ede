"""The topology of a triangle mesh: which triangle lies across each edge, whether the surface is
closed and consistently oriented, and which triangles meet at each vertex."""

import numpy as np
import numpy.typing as npt

Ints = npt.NDArray[np.int64]


def triangle_adjacency(triangles: Ints) -> Ints:
    """(m, 3) int64: the triangle across the edge opposite corner k of each triangle, -1 where the
    edge is a boundary or shared by more than two triangles."""
    m = len(triangles)
    lo = np.minimum(triangles[:, [1, 2, 0]], triangles[:, [2, 0, 1]]).ravel()
    hi = np.maximum(triangles[:, [1, 2, 0]], triangles[:, [2, 0, 1]]).ravel()
    key = lo * (int(triangles.max()) + 1) + hi
    order = np.argsort(key, kind="stable")
    k = key[order]
    adjacency = np.full(3 * m, -1, dtype=np.int64)
    same = k[1:] == k[:-1]
    # a pair is two equal keys not part of a longer run
    before = np.r_[False, same[:-1]]
    after = np.r_[same[1:], False]
    pair = np.flatnonzero(same & ~before & ~after)
    first, second = order[pair], order[pair + 1]
    adjacency[first] = second // 3
    adjacency[second] = first // 3
    return adjacency.reshape(m, 3)


def closed_and_oriented(triangles: Ints) -> bool:
    """True when every edge is used by exactly two triangles, once in each direction: a closed,
    consistently oriented surface, around which crossings can be counted."""
    n = int(triangles.max()) + 1
    start, end = triangles.ravel(), triangles[:, [1, 2, 0]].ravel()
    key = np.sort(start * n + end)
    if np.any(key[1:] == key[:-1]) or np.any(start == end):
        return False
    return bool(np.array_equal(key, np.sort(end * n + start)))


def vertex_stars(triangles: Ints, vertex_count: int) -> tuple[Ints, Ints]:
    """The triangles round each vertex, compressed: (star (3 m,) int64, start (n + 1,) int64),
    vertex v's triangles being ``star[start[v]:start[v + 1]]``, in increasing order."""
    by_vertex = np.argsort(triangles.ravel(), kind="stable")
    return by_vertex // 3, np.searchsorted(triangles.ravel()[by_vertex],
                                           np.arange(vertex_count + 1))
