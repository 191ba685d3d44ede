"""The build's slow steps spread over forked processes that share one read-only context (the
rigs, meshes and tables a job reads), so that nothing is pickled but the items and results."""

import multiprocessing
from collections.abc import Callable, Sequence
from typing import Any

#: Worker processes of a step (each job is single-threaded numpy; the machines have two cores).
WORKERS = 2

_shared: Any = None


def _call(job_and_item):
    job, item = job_and_item
    return job(_shared, item)


def forked_map(job: Callable[[Any, Any], Any], items: Sequence, shared: Any,
               workers: int = WORKERS) -> list:
    """``[job(shared, item) for item in items]``, over ``workers`` forked processes that inherit
    ``shared`` (one process where fork is missing, or for one worker). ``job`` must be a
    module-level function. The jobs must be deterministic, so that the result does not depend
    on the number of workers."""
    global _shared
    if workers <= 1 or len(items) <= 1 or "fork" not in multiprocessing.get_all_start_methods():
        return [job(shared, item) for item in items]
    _shared = shared
    try:
        with multiprocessing.get_context("fork").Pool(workers) as pool:
            return pool.map(_call, [(job, item) for item in items], chunksize=1)
    finally:
        _shared = None
