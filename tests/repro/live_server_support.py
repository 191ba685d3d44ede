"""A real uvicorn server on a free loopback port, for tests that need real sockets (a body that
streams in, requests that overlap), and a raw HTTP client that watches for the answer while it
still sends."""

import contextlib
import os
import select
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
#: Seconds a server may take to start (spawned workers, migrations, assets).
START_TIMEOUT_S = 60.0


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


@contextlib.contextmanager
def live_server(tmp_path: Path, **settings: str):
    """Yields (base URL, port) of `uvicorn glasshead.api.app:app` on 127.0.0.1 with a fresh
    SQLite database and the GLASSHEAD_* ``settings`` given (e.g. compute_workers="1"); the
    server is stopped (SIGTERM, then SIGKILL after 10 s) on leaving."""
    port = free_port()
    env = {**os.environ, "GLASSHEAD_DATABASE_URL": f"sqlite:///{tmp_path / 'live.sqlite3'}",
           "GLASSHEAD_WEB_DIST_DIR": str(tmp_path / "no-web")}
    env.update({f"GLASSHEAD_{key.upper()}": value for key, value in settings.items()})
    log = (tmp_path / "server.log").open("wb")
    server = subprocess.Popen(
        [sys.executable, "-m", "uvicorn", "glasshead.api.app:app", "--host", "127.0.0.1",
         "--port", str(port), "--log-level", "warning"],
        cwd=REPO, env=env, stdout=log, stderr=subprocess.STDOUT)
    base = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + START_TIMEOUT_S
        while True:
            if server.poll() is not None:
                raise RuntimeError(f"the server exited: {(tmp_path / 'server.log').read_text()}")
            try:
                with urllib.request.urlopen(f"{base}/api/v1/health", timeout=2):
                    break
            except OSError:
                if time.monotonic() > deadline:
                    raise RuntimeError("the server did not start in time") from None
                time.sleep(0.2)
        yield base, port
    finally:
        server.terminate()
        try:
            server.wait(timeout=10)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait(timeout=10)
        log.close()


def send_until_answered(port: int, head: bytes, chunks, timeout_s: float = 30.0):
    """Sends ``head`` then each of ``chunks`` to 127.0.0.1:``port``, looking for an answer
    before each chunk and stopping as soon as one arrives (or the server closes).

    Returns (status, response bytes, body bytes sent before the answer)."""
    sent = 0
    received = b""
    with socket.create_connection(("127.0.0.1", port), timeout=timeout_s) as sock:
        sock.sendall(head)
        for chunk in chunks:
            readable, _, _ = select.select([sock], [], [], 0)
            if readable:
                break
            try:
                sock.sendall(chunk)
            except (BrokenPipeError, ConnectionResetError, TimeoutError):
                break
            sent += len(chunk)
        with contextlib.suppress(ConnectionResetError, TimeoutError):
            while b"\r\n\r\n" not in received or not _complete(received):
                data = sock.recv(65536)
                if not data:
                    break
                received += data
    status = int(received.split(b" ", 2)[1]) if received.startswith(b"HTTP/") else None
    return status, received, sent


def _complete(response: bytes) -> bool:
    head, _, body = response.partition(b"\r\n\r\n")
    for line in head.split(b"\r\n")[1:]:
        name, _, value = line.partition(b":")
        if name.strip().lower() == b"content-length":
            return len(body) >= int(value.strip())
    return False
