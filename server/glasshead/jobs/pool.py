"""Worker processes whose death costs one task: the pool under the compute routes, speech and
the fit jobs.

Each worker is a spawned process (a fork would copy the server's event loop and threads) with a
pipe of its own, serving one task at a time. A task is a module-level function and its
arguments; the worker sends back what it returned or the exception it raised. When a worker
dies while it serves a task (a fault in native code, a signal, the kernel's out-of-memory
killer), only that task fails, with ``WorkerDiedError`` naming the signal or exit code; the
worker is replaced before the next task, and every other task goes on. (A
``ProcessPoolExecutor`` breaks whole when one of its workers dies: every task it holds fails.)

A task may be given a time limit: a worker that runs past it is killed and replaced, and its
task fails with ``WorkerTimeoutError``.

``submit`` returns a ``concurrent.futures.Future``; ``run`` awaits one. Tasks wait in the
order they came for a free worker; a task cancelled while it waits never starts. One parent
thread per worker sends a task and waits for its answer, so the event loop never blocks on a
pipe.
"""

import logging
import multiprocessing
import os
import signal
import threading
from collections.abc import Callable
from concurrent.futures import CancelledError, Future, ThreadPoolExecutor
from multiprocessing.connection import Connection
from queue import LifoQueue
from typing import Any

log = logging.getLogger("glasshead.jobs")

#: Seconds a worker is given to leave after it was asked to, before it is killed.
STOP_GRACE_S = 5.0


class WorkerDiedError(RuntimeError):
    """The worker serving a task died before it answered. ``signal_name`` is the signal that
    ended it (e.g. "SIGSEGV", "SIGKILL"), or None when it exited with ``exit_code``."""

    def __init__(self, signal_name: str | None, exit_code: int | None):
        self.signal_name = signal_name
        self.exit_code = exit_code
        how = f"was ended by {signal_name}" if signal_name else f"exited with code {exit_code}"
        super().__init__(f"the worker process {how}")


class WorkerTimeoutError(RuntimeError):
    """A task ran past its time limit; its worker was killed."""

    def __init__(self, seconds: float):
        self.seconds = seconds
        super().__init__(f"the task ran for more than {seconds:g} s and was stopped")


def _serve(connection: Connection, niceness: int, initializer, initargs) -> None:
    """A worker's loop: receive (function, args), answer ("ok", value) or ("raised", exc)."""
    if niceness:
        os.nice(niceness)
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C in a terminal stops the parent
    if initializer is not None:
        initializer(*initargs)
    while True:
        try:
            message = connection.recv()
        except (EOFError, OSError):
            return
        if message is None:
            return
        function, args = message
        try:
            answer: tuple = ("ok", function(*args))
        except BaseException as exc:  # sent back to the caller, who raises it
            answer = ("raised", exc)
        try:
            connection.send(answer)
        except Exception as exc:  # an unpicklable value or exception
            connection.send(("raised", RuntimeError(f"{exc.__class__.__name__}: {exc}")))


class _Worker:
    """One process and the parent's end of its pipe."""

    def __init__(self, context, niceness: int, initializer, initargs, name: str):
        self.connection, child = context.Pipe(duplex=True)
        self.process = context.Process(target=_serve, name=name, daemon=True,
                                       args=(child, niceness, initializer, initargs))
        self.process.start()
        child.close()

    def death(self) -> WorkerDiedError:
        """What ended the process (waits briefly for it to be reaped)."""
        self.process.join(timeout=STOP_GRACE_S)
        code = self.process.exitcode
        if code is not None and code < 0:
            try:
                return WorkerDiedError(signal.Signals(-code).name, None)
            except ValueError:
                return WorkerDiedError(f"signal {-code}", None)
        return WorkerDiedError(None, code)

    def kill(self) -> None:
        if self.process.is_alive():
            self.process.kill()
        self.process.join(timeout=STOP_GRACE_S)
        self.connection.close()

    def stop(self) -> None:
        """Ask the worker to leave; kill it if it does not."""
        try:
            self.connection.send(None)
        except (OSError, ValueError):
            pass
        self.process.join(timeout=STOP_GRACE_S)
        self.kill()


class WorkerPool:
    """``workers`` processes, each serving one task at a time (see the module docstring).

    ``niceness`` is added to each worker's niceness; ``initializer(*initargs)`` runs once in
    each new worker. Workers start at the first task that needs one."""

    def __init__(self, workers: int, *, name: str = "worker", niceness: int = 0,
                 initializer: Callable[..., None] | None = None, initargs: tuple = ()):
        if workers < 1:
            raise ValueError("a worker pool needs at least one worker")
        self.workers = workers
        self.name = name
        self._niceness = niceness
        self._initializer = initializer
        self._initargs = initargs
        self._context = multiprocessing.get_context("spawn")
        # Last in, first out: a task takes the worker that finished last, so a slot's process
        # starts only when every started worker is busy (one at a time, one process).
        self._idle: LifoQueue[_Worker | None] = LifoQueue()
        for _ in range(workers):
            self._idle.put(None)  # a slot whose process starts when first needed
        self._busy: dict[int, _Worker] = {}
        self._lock = threading.Lock()
        self._closed = False
        self._started = 0
        #: Tasks handed to a worker so far.
        self.tasks = 0
        self._threads = ThreadPoolExecutor(max_workers=workers, thread_name_prefix=name)

    @property
    def started(self) -> int:
        """How many worker processes this pool has started (replacements included)."""
        return self._started

    def pids(self) -> list[int]:
        """The process ids of the workers serving a task now."""
        with self._lock:
            return [w.process.pid for w in self._busy.values() if w.process.pid is not None]

    def submit(self, function: Callable[..., Any], *args: Any,
               timeout_s: float | None = None) -> Future:
        """``function(*args)`` in a worker; the future holds its value or its exception, or
        ``WorkerDiedError`` / ``WorkerTimeoutError``."""
        if self._closed:
            raise RuntimeError(f"the {self.name} pool is shut down")
        return self._threads.submit(self._call, function, args, timeout_s)

    async def run(self, function: Callable[..., Any], *args: Any,
                  timeout_s: float | None = None) -> Any:
        """``submit`` awaited; cancelling the await takes a task that waits out of the queue."""
        import asyncio

        return await asyncio.wrap_future(self.submit(function, *args, timeout_s=timeout_s))

    def _take(self) -> _Worker:
        worker = self._idle.get()
        if worker is not None and worker.process.is_alive():
            return worker
        if worker is not None:  # died while idle (killed from outside)
            worker.kill()
        with self._lock:
            self._started += 1
            number = self._started
        return _Worker(self._context, self._niceness, self._initializer, self._initargs,
                       f"glasshead-{self.name}-{number}")

    def _call(self, function, args, timeout_s):
        if self._closed:
            raise CancelledError()
        worker = self._take()
        key = id(worker)
        with self._lock:
            self._busy[key] = worker
            self.tasks += 1
        keep: _Worker | None = worker
        try:
            try:
                worker.connection.send((function, args))
            except (OSError, ValueError):
                keep = None
                raise worker.death() from None
            if not worker.connection.poll(timeout_s):
                keep = None
                worker.kill()
                raise WorkerTimeoutError(timeout_s or 0.0)
            try:
                status, value = worker.connection.recv()
            except (EOFError, OSError):
                keep = None
                error = worker.death()
                worker.kill()
                if not self._closed:
                    log.warning("%s worker %s died serving %s: %s", self.name,
                                worker.process.pid, getattr(function, "__name__", function),
                                error)
                raise error from None
            if status == "raised":
                raise value
            return value
        finally:
            with self._lock:
                self._busy.pop(key, None)
            self._idle.put(keep)

    def shutdown(self, *, kill_running: bool = False) -> None:
        """End the pool: tasks that wait are cancelled; tasks that run are waited for, or with
        ``kill_running`` their workers are killed (those tasks fail with WorkerDiedError)."""
        self._closed = True
        if kill_running:
            with self._lock:
                running = list(self._busy.values())
            for worker in running:
                if worker.process.is_alive():
                    worker.process.kill()
        self._threads.shutdown(wait=True, cancel_futures=True)
        while not self._idle.empty():
            worker = self._idle.get()
            if worker is not None:
                worker.stop()
