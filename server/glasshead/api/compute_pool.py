"""The bounded pool of worker processes that runs the CPU-heavy routes, off the event loop.

POST /tongue/surface, /collision/correct, /epg/contacts and /epg/indices take 40 to 110 ms of
numpy each (measured in-process with the built assets), and the comparisons and plots of an EPG
recording 2 to 4 s for one of 120,000 frames. Run in the server's own process, 20 clients of
the first starved everything else: /health waited 1.7 s. Here the route parses and checks
the request as usual, then hands a plain function and the request to ``ComputePool.run``; the
function runs in a worker process and returns the response already serialised as JSON, so the
event loop only moves bytes.

- The pool is a ``ProcessPoolExecutor`` over spawned processes (a fork would copy the event
  loop and its threads), ``settings.compute_workers`` of them (default: the CPU count). The
  lifespan starts it; the processes start at the first request. They run at a lower priority
  (``WORKER_NICENESS``), so that the event loop never waits for a CPU behind them. One
  executor serves every app of a process with the same worker count, so tests that make many
  apps do not spawn many pools.
- Back-pressure: at most ``workers + settings.compute_queue_limit`` requests are running or
  waiting; the next one is answered 503 with ``Retry-After`` at once instead of an ever-growing
  wait. A client that goes away while its request waits takes it out of the queue.
- Each worker keeps one ``AssetStore`` per assets directory (the parent sends the directory with
  every task) and loads what a function asks of it once; the store reloads a file when its
  content hash changes, so a rebuild is picked up as in the server's own store.
- Errors a function raises on purpose (``HTTPException``, ``AssetUnavailableError``) are sent
  back as plain values and raised again in the server, so they answer as they would in-process.
  A worker that dies (killed, out of memory) breaks its executor; the request answers 503 and
  the next one starts a new executor.
"""

import asyncio
import multiprocessing
import os
import threading
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from typing import Annotated, Any

from fastapi import Depends, HTTPException, Request, Response

from glasshead.asset_store import AssetStore, AssetUnavailableError

#: Seconds a client is told to wait (Retry-After) when the queue is full.
RETRY_AFTER_S = 1
#: Added to the workers' niceness: with as many workers as CPUs, the server's own process
#: still gets a CPU as soon as a request arrives.
WORKER_NICENESS = 10

#: A task: a module-level function of (store, payload) returning a JSON document as bytes.
Task = Callable[[AssetStore, Any], bytes]

_executors: dict[int, ProcessPoolExecutor] = {}
_executors_lock = threading.Lock()
#: In a worker process: one asset store per assets directory.
_worker_stores: dict[str, AssetStore] = {}


def _executor(workers: int) -> ProcessPoolExecutor:
    with _executors_lock:
        executor = _executors.get(workers)
        if executor is None:
            executor = _executors[workers] = ProcessPoolExecutor(
                max_workers=workers, mp_context=multiprocessing.get_context("spawn"),
                initializer=os.nice, initargs=(WORKER_NICENESS,))
        return executor


def _drop_executor(workers: int, executor: ProcessPoolExecutor) -> None:
    with _executors_lock:
        if _executors.get(workers) is executor:
            del _executors[workers]
    executor.shutdown(wait=False, cancel_futures=True)


def run_task(assets_dir: str, task: Task, payload: Any) -> tuple:
    """In a worker: ``task(store, payload)`` as ("ok", bytes), or the error it raised on purpose
    as ("http", status, detail, headers) or ("asset", name, file, problem, reason)."""
    store = _worker_stores.get(assets_dir)
    if store is None:
        store = _worker_stores[assets_dir] = AssetStore(assets_dir)
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

    def start(self) -> None:
        """Make the executor (its processes start with the first task)."""
        _executor(self.workers)

    def shutdown(self) -> None:
        """End the executor's processes (a later task starts a new executor)."""
        with _executors_lock:
            executor = _executors.pop(self.workers, None)
        if executor is not None:
            executor.shutdown(wait=True, cancel_futures=True)

    async def run(self, task: Task, payload: Any) -> bytes:
        """``task(store, payload)`` in a worker; 503 with Retry-After when the queue is full."""
        if self.pending >= self.workers + self.queue_limit:
            raise HTTPException(status_code=503, headers={"Retry-After": str(RETRY_AFTER_S)},
                                detail=f"the server is busy: {self.workers} computations run "
                                       f"and {self.queue_limit} wait; retry in "
                                       f"{RETRY_AFTER_S} s")
        self.pending += 1
        executor = _executor(self.workers)
        try:
            result = await asyncio.wrap_future(
                executor.submit(run_task, self.assets_dir, task, payload))
        except BrokenProcessPool:
            _drop_executor(self.workers, executor)
            raise HTTPException(status_code=503, headers={"Retry-After": str(RETRY_AFTER_S)},
                                detail="a compute worker stopped; retry") from None
        finally:
            self.pending -= 1
        if result[0] == "http":
            raise HTTPException(status_code=result[1], detail=result[2], headers=result[3])
        if result[0] == "asset":
            raise AssetUnavailableError(*result[1:])
        return result[1]

    async def respond(self, task: Task, payload: Any) -> Response:
        """``run`` answered as an application/json response."""
        return Response(await self.run(task, payload), media_type="application/json")


def get_compute_pool(request: Request) -> ComputePool:
    """The application's compute pool, made in ``create_app``."""
    return request.app.state.compute


ComputeDep = Annotated[ComputePool, Depends(get_compute_pool)]
