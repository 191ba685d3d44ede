"""The bounded pool of worker processes that runs the CPU-heavy routes and every call into
native speech code, off the event loop and out of the server's process.

POST /tongue/surface, /collision/correct, /epg/contacts and /epg/indices take 40 to 110 ms of
numpy each (measured in-process with the built assets), and the comparisons and plots of an EPG
recording 2 to 4 s for one of 120,000 frames. Run in the server's own process, 20 clients of
the first starved everything else: /health waited 1.7 s. An utterance calls libespeak-ng and
VocalTractLab, native code that can fault on an input (60 digits once took the whole server
down). Here the route parses and checks the request as usual, then hands a plain function and
the request to ``ComputePool.run``; the function runs in a worker process and returns the
response already serialised as JSON, so the event loop only moves bytes.

- The workers are a ``jobs.pool.WorkerPool`` of up to ``settings.compute_workers`` spawned
  processes (default: the CPU count), each started only when every one started before is busy
  (requests one after another are served by one), at a lower priority
  (``WORKER_NICENESS``) so that the event loop never waits for a CPU behind them. One pool
  serves every app of a process with the same worker count, so tests that make many apps do
  not spawn many pools.
- Back-pressure: at most ``workers + settings.compute_queue_limit`` requests are running or
  waiting; the next one is answered 503 with ``Retry-After`` at once instead of an ever-growing
  wait. A client that goes away while its request waits takes it out of the queue.
- Each worker keeps one ``AssetStore`` per assets directory (the parent sends the directory with
  every task) and loads what a function asks of it once; the store reloads a file when its
  content hash changes, so a rebuild is picked up as in the server's own store.
- Errors a function raises on purpose (``HTTPException``, ``AssetUnavailableError``) are sent
  back as plain values and raised again in the server, so they answer as they would in-process.
- A worker that dies (a fault in native code, a signal, out of memory) costs only the request
  it served: that request is answered 502 with what the worker was doing and how it ended, the
  worker is replaced, and the next request is served. A task that runs past
  ``TASK_TIMEOUT_S`` is stopped with its worker and answered 504.
"""

import threading
from collections import OrderedDict
from collections.abc import Callable
from typing import Any

from fastapi import HTTPException, Response

from glasshead.asset_store import AssetStore, AssetUnavailableError
from glasshead.jobs.pool import WorkerDiedError, WorkerPool, WorkerTimeoutError

#: Seconds a client is told to wait (Retry-After) when the queue is full.
RETRY_AFTER_S = 1
#: Added to the workers' niceness: with as many workers as CPUs, the server's own process
#: still gets a CPU as soon as a request arrives.
WORKER_NICENESS = 10
#: Longest a task may run: the slowest, a plot of a 120,000-frame recording, takes seconds.
TASK_TIMEOUT_S = 120.0

#: A task: a module-level function of (store, payload) returning a JSON document as bytes.
Task = Callable[[AssetStore, Any], bytes]

_pools: dict[int, WorkerPool] = {}
_pools_lock = threading.Lock()
#: In a worker process: one asset store per assets directory, the most recently used kept (a
#: server has one directory; a process that makes apps on many keeps its workers' memory bounded).
_worker_stores: OrderedDict[str, AssetStore] = OrderedDict()
WORKER_STORES_KEPT = 4


def _pool(workers: int) -> WorkerPool:
    with _pools_lock:
        pool = _pools.get(workers)
        if pool is None:
            pool = _pools[workers] = WorkerPool(workers, name="compute",
                                                niceness=WORKER_NICENESS)
        return pool


def worker_store(assets_dir: str) -> AssetStore:
    """In a worker process (compute or fit): the process's one asset store of ``assets_dir``."""
    store = _worker_stores.get(assets_dir)
    if store is None:
        store = _worker_stores[assets_dir] = AssetStore(assets_dir)
        while len(_worker_stores) > WORKER_STORES_KEPT:
            _worker_stores.popitem(last=False)
    _worker_stores.move_to_end(assets_dir)
    return store


def run_task(assets_dir: str, task: Task, payload: Any) -> tuple:
    """In a worker: ``task(store, payload)`` as ("ok", bytes), or the error it raised on purpose
    as ("http", status, detail, headers) or ("asset", name, file, problem, reason)."""
    store = worker_store(assets_dir)
    try:
        return ("ok", task(store, payload))
    except HTTPException as exc:
        return ("http", exc.status_code, exc.detail, exc.headers)
    except AssetUnavailableError as exc:
        return ("asset", exc.name, exc.file, exc.problem, exc.reason)


class ComputePool:
    """Runs tasks in worker processes with a bounded queue (see the module docstring)."""

    def __init__(self, assets_dir, *, workers: int, queue_limit: int):
        if workers < 1 or queue_limit < 0:
            raise ValueError("a compute pool needs at least one worker and a queue of 0 or more")
        self.assets_dir = str(assets_dir)
        self.workers = workers
        self.queue_limit = queue_limit
        #: Requests running or waiting now (only touched on the event loop).
        self.pending = 0

    @property
    def pool(self) -> WorkerPool:
        """The worker processes behind this pool (shared by the apps with its worker count)."""
        return _pool(self.workers)

    def start(self) -> None:
        """Make the worker pool (its processes start with the first task)."""
        _pool(self.workers)

    def shutdown(self) -> None:
        """End the workers (a later task starts a new pool)."""
        shutdown_pool(self.workers)

    async def run(self, task: Task, payload: Any, *, doing: str | None = None) -> bytes:
        """``task(store, payload)`` in a worker; 503 with Retry-After when the queue is full;
        502 when the worker dies, naming ``doing`` (what the task was doing, e.g. "speaking
        the text '…'"); 504 past ``TASK_TIMEOUT_S``."""
        if self.pending >= self.workers + self.queue_limit:
            raise HTTPException(status_code=503, headers={"Retry-After": str(RETRY_AFTER_S)},
                                detail=f"the server is busy: {self.workers} computations run "
                                       f"and {self.queue_limit} wait; retry in "
                                       f"{RETRY_AFTER_S} s")
        self.pending += 1
        what = doing or f"running {getattr(task, '__name__', 'a computation')}"
        try:
            result = await self.pool.run(run_task, self.assets_dir, task, payload,
                                         timeout_s=TASK_TIMEOUT_S)
        except WorkerDiedError as exc:
            how = exc.signal_name or f"exit code {exc.exit_code}"
            raise HTTPException(status_code=502, detail=(
                f"the worker process {what} stopped ({how}) before it answered; nothing else "
                "was affected, and it has been replaced. Retry, or change the request if it "
                "stops again")) from None
        except WorkerTimeoutError as exc:
            raise HTTPException(status_code=504, detail=(
                f"{what} took more than {exc.seconds:g} s and was stopped")) from None
        finally:
            self.pending -= 1
        if result[0] == "http":
            raise HTTPException(status_code=result[1], detail=result[2], headers=result[3])
        if result[0] == "asset":
            raise AssetUnavailableError(*result[1:])
        return result[1]

    async def respond(self, task: Task, payload: Any, *, doing: str | None = None) -> Response:
        """``run`` answered as an application/json response."""
        return Response(await self.run(task, payload, doing=doing),
                        media_type="application/json")


def shutdown_pool(workers: int | None = None) -> None:
    """End the shared pool of ``workers`` workers, or every one when None."""
    with _pools_lock:
        ended = [_pools.pop(n) for n in list(_pools) if workers in (None, n)]
    for pool in ended:
        pool.shutdown()
