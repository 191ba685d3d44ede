"""A real `uvicorn glasshead.api.app:app` in its own process group on a free loopback port, on a
database the test chooses, with one or several worker processes; it can be killed with SIGKILL
(the whole group: uvicorn's supervisor and its workers) and started again on the same database.

Also ``write_concurrently``: bounded concurrent writes (poses and recording imports) that record
which were acknowledged, for the crash tests. Those routes need a signed-in user: the first
start makes an admin in the database and ``.headers`` carries their token.
"""

import os
import signal
import socket
import subprocess
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import httpx

from accounts_support import bearer
from glasshead.store.db import engine_for

REPO = Path(__file__).resolve().parents[1]
#: Seconds a server may take to start (migrations, assets, spawned workers).
START_TIMEOUT_S = 90.0
API = "/api/v1"
#: Writes sent in all by the crash tests (bounded), and after how many acknowledgements the
#: server is killed.
WRITES = 200
KILL_AFTER = 60


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


class ServerProcess:
    """``ServerProcess(tmp_path, database_url, workers=1).start()``; ``.base`` is its URL."""

    def __init__(self, tmp_path: Path, database_url: str, workers: int = 1):
        self.tmp_path, self.database_url, self.workers = tmp_path, database_url, workers
        self.process: subprocess.Popen | None = None
        self.base = ""
        self.starts = 0
        #: The Authorization header of an admin, made once the server has migrated the database.
        self.headers: dict = {}

    def start(self) -> "ServerProcess":
        port = free_port()
        env = {**os.environ, "GLASSHEAD_DATABASE_URL": self.database_url,
               "GLASSHEAD_WEB_DIST_DIR": str(self.tmp_path / "no-web"),
               "GLASSHEAD_ALLOWED_HOSTS": "127.0.0.1", "GLASSHEAD_COMPUTE_WORKERS": "1"}
        self.starts += 1
        self.log_path = self.tmp_path / f"server-{self.starts}.log"
        with self.log_path.open("wb") as log:
            self.process = subprocess.Popen(
                [sys.executable, "-m", "uvicorn", "glasshead.api.app:app", "--host", "127.0.0.1",
                 "--port", str(port), "--workers", str(self.workers), "--log-level", "warning"],
                cwd=REPO, env=env, stdout=log, stderr=subprocess.STDOUT,
                start_new_session=True)  # its own process group, so that a kill takes all
        self.base = f"http://127.0.0.1:{port}"
        deadline = time.monotonic() + START_TIMEOUT_S
        while True:
            if self.process.poll() is not None:
                raise RuntimeError(f"the server exited:\n{self.log_path.read_text()}")
            try:
                if httpx.get(f"{self.base}{API}/health", timeout=2).status_code == 200:
                    if not self.headers:
                        engine = engine_for(self.database_url)
                        self.headers = bearer("admin", engine=engine)
                        engine.dispose()
                    return self
            except httpx.HTTPError:
                pass
            if time.monotonic() > deadline:
                self.kill()
                raise RuntimeError(f"the server did not start in {START_TIMEOUT_S} s:\n"
                                   f"{self.log_path.read_text()}")
            time.sleep(0.2)

    def kill(self) -> None:
        """SIGKILL to every process of the server, as a crash or an OOM kill would."""
        if self.process is not None and self.process.poll() is None:
            os.killpg(self.process.pid, signal.SIGKILL)
            self.process.wait(timeout=10)

    def stop(self) -> None:
        """SIGTERM (a clean shutdown), then SIGKILL after 15 s."""
        if self.process is None or self.process.poll() is not None:
            return
        os.killpg(self.process.pid, signal.SIGTERM)
        try:
            self.process.wait(timeout=15)
        except subprocess.TimeoutExpired:
            self.kill()


def pose_body(k: int) -> dict:
    return {"name": f"write {k}", "description": f"written by request {k}",
            "params": {"tip_height": (k % 7) * 0.5}}


def recording_body(k: int) -> dict:
    rows = ["00000000", format(k % 256, "08b")] + ["00000000"] * 6  # row 1 has no corners
    return {"format": "emur-json", "name": f"write {k}",
            "content": {"frames": [{"t_ms": 0, "rows": rows}, {"t_ms": 10, "rows": rows}]}}


def write_concurrently(base: str, count: int, *, first: int = 0, threads: int = 8,
                       on_ack=None, headers: dict | None = None) -> dict:
    """Sends ``count`` writes (k from ``first`` on) from ``threads`` threads, even k a pose,
    odd k a recording import; returns {k: (kind, id)} for each write acknowledged (201).
    ``on_ack(acknowledged_so_far)`` is called after each acknowledgement. A write whose
    connection fails is not acknowledged. ``headers``: a signed-in user's (ServerProcess's)."""
    acknowledged: dict[int, tuple[str, int]] = {}
    lock = threading.Lock()

    def write(client: httpx.Client, k: int) -> None:
        try:
            if k % 2 == 0:
                response = client.post(f"{base}{API}/poses", json=pose_body(k))
                made = ("pose", response.json()["id"]) if response.status_code == 201 else None
            else:
                response = client.post(f"{base}{API}/epg/recordings", json=recording_body(k))
                made = (("recording", response.json()["recordings"][0]["id"])
                        if response.status_code == 201 else None)
        except httpx.HTTPError:
            return
        if made is None:
            raise AssertionError(f"write {k} answered {response.status_code}: {response.text}")
        with lock:
            acknowledged[k] = made
            so_far = len(acknowledged)
        if on_ack is not None:
            on_ack(so_far)

    with httpx.Client(timeout=20, headers=headers) as client, ThreadPoolExecutor(threads) as pool:
        list(pool.map(lambda k: write(client, k), range(first, first + count)))
    return acknowledged


def check_acknowledged_writes_are_there(base: str, acknowledged: dict,
                                        headers: dict | None = None) -> None:
    """Each acknowledged write reads back with what was written."""
    with httpx.Client(timeout=20, headers=headers) as client:
        for k, (kind, record_id) in sorted(acknowledged.items()):
            if kind == "pose":
                response = client.get(f"{base}{API}/poses/{record_id}")
                assert response.status_code == 200, (k, record_id, response.text)
                assert response.json()["name"] == pose_body(k)["name"]
                assert response.json()["params"]["tip_height"] == (k % 7) * 0.5
            else:
                response = client.get(f"{base}{API}/epg/recordings/{record_id}")
                assert response.status_code == 200, (k, record_id, response.text)
                body = recording_body(k)
                assert response.json()["name"] == body["name"]
                assert response.json()["frames"] == [
                    frame["rows"] for frame in body["content"]["frames"]], k


def kill_during_writes(server: ServerProcess) -> dict:
    """Concurrent writes to ``server``, killed with SIGKILL after KILL_AFTER acknowledgements;
    returns the acknowledged writes, at least KILL_AFTER and fewer than WRITES."""
    killed = threading.Event()

    def on_ack(so_far):
        if so_far >= KILL_AFTER and not killed.is_set():
            killed.set()
            server.kill()

    acknowledged = write_concurrently(server.base, WRITES, on_ack=on_ack, headers=server.headers)
    assert killed.is_set(), f"only {len(acknowledged)} writes were acknowledged"
    assert KILL_AFTER <= len(acknowledged) < WRITES, len(acknowledged)
    return acknowledged
