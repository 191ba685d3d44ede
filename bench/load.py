"""Load benchmark: a real uvicorn server on loopback, a compute route under 20 connections, and
/health and a cheap read route measured meanwhile, against the same routes on the unloaded
server in the same run (the baseline).

Phases, each ``seconds`` long (default 5), against one server started here on a free port
with a temporary database and the built assets:

1. unloaded: /health, the read route (GET /epg/layout) and the compute route (POST
   /tongue/surface), one connection each, one after another;
2. compute load: 20 connections of POST /tongue/surface (from a process of their own), while
   one connection each samples /health and the read route;
3. refused bodies: 3 connections each sending 50 MB bodies to /collision/correct, one after
   another, as fast as loopback takes them (answered 413; also from a process of their own),
   while one connection samples /health.

Prints requests/s, p50 and p99 per route and phase, the loaded p50 and p99 over the unloaded
ones, and how many compute requests were answered 503 (back-pressure). The client runs on the
same machine as the server and shares its CPUs.

Checked: every request to /health and to the read route is answered (none fails or is refused),
and every compute request is answered, 503 (back-pressure) allowed.

    .venv/bin/python bench/load.py [seconds] [connections]
    GLASSHEAD_BENCH_QUICK=1: 0.5 s per phase, 4 connections, one warm-up round.
"""

import asyncio
import multiprocessing
import os
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import httpx

REPO = Path(__file__).resolve().parents[1]
API = "/api/v1"
READ = ("GET", f"{API}/epg/layout", None)
HEALTH = ("GET", f"{API}/health", None)
COMPUTE = ("POST", f"{API}/tongue/surface", {"params": {"tip_height": 5.0, "jaw_opening": 8.0}})
GOAL_P99_MS = 100.0
QUICK = os.environ.get("GLASSHEAD_BENCH_QUICK") == "1"
BIG_BODY = 50_000_000


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def start_server(workdir: Path, port: int) -> subprocess.Popen:
    env = {**os.environ, "GLASSHEAD_DATABASE_URL": f"sqlite:///{workdir / 'load.sqlite3'}",
           "GLASSHEAD_WEB_DIST_DIR": str(workdir / "no-web")}
    return subprocess.Popen(
        [sys.executable, "-m", "uvicorn", "glasshead.api.app:app", "--host", "127.0.0.1",
         "--port", str(port), "--log-level", "warning"],
        cwd=REPO, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


async def wait_ready(client: httpx.AsyncClient, server: subprocess.Popen) -> None:
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        if server.poll() is not None:
            sys.exit("the server exited at start")
        try:
            if (await client.get(HEALTH[1])).status_code == 200:
                return
        except httpx.HTTPError:
            pass
        await asyncio.sleep(0.2)
    sys.exit("the server did not start in 60 s")


async def loop(client, request, until: float, times: list, statuses: list) -> None:
    method, path, body = request
    while time.monotonic() < until:
        start = time.perf_counter()
        response = await client.request(method, path, json=body)
        times.append((time.perf_counter() - start) * 1e3)
        statuses.append(response.status_code)


async def run(client, requests: dict, seconds: float) -> dict:
    """Runs each (request, connections) of ``requests`` for ``seconds`` at once."""
    until = time.monotonic() + seconds
    results, tasks = {}, []
    for name, (request, connections) in requests.items():
        results[name] = ([], [])
        tasks += [loop(client, request, until, *results[name]) for _ in range(connections)]
    started = time.perf_counter()
    await asyncio.gather(*tasks)
    elapsed = time.perf_counter() - started
    return {name: summary(times, statuses, elapsed) for name, (times, statuses)
            in results.items()}


def summary(times: list, statuses: list, elapsed: float) -> dict:
    ok = [t for t, s in zip(times, statuses, strict=True) if s < 500]
    ordered = sorted(ok) or [float("nan")]
    return {"rps": len(ok) / elapsed, "p50": statistics.median(ordered),
            "p99": ordered[min(len(ordered) - 1, int(0.99 * len(ordered)))],
            "n": len(ok), "busy": statuses.count(503),
            "failed": sum(s >= 300 and s != 503 for s in statuses)}


async def send_big_bodies(port: int, until: float, refused: list) -> None:
    """Sends 50 MB chunked bodies to /collision/correct until ``until``, one after another,
    stopping each as soon as the answer comes; appends whether it was a 413."""
    chunk = b"10000\r\n" + b" " * 65536 + b"\r\n"
    while time.monotonic() < until:
        reader, writer = await asyncio.open_connection("127.0.0.1", port)
        writer.write(f"POST {API}/collision/correct HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                     f"Content-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n"
                     .encode())
        answer = asyncio.ensure_future(reader.readline())
        try:
            for _ in range(BIG_BODY // 65536):
                if answer.done():
                    break
                writer.write(chunk)
                await writer.drain()
            status = (await asyncio.wait_for(answer, 10)).split(b" ")[1:2]
            refused.append(status == [b"413"])
        except (TimeoutError, ConnectionError):
            refused.append(answer.done() and not answer.exception()
                           and answer.result().split(b" ")[1:2] == [b"413"])
        finally:
            answer.cancel()
            writer.close()


def drive(port: int, request: tuple, connections: int, seconds: float) -> dict:
    """In a process of its own (so that its work does not delay the sampling client): a request
    over ``connections`` connections for ``seconds``; its summary."""
    async def go():
        async with httpx.AsyncClient(base_url=f"http://127.0.0.1:{port}", timeout=60,
                                     limits=httpx.Limits(max_connections=connections)) as client:
            return (await run(client, {"load": (request, connections)}, seconds))["load"]
    return asyncio.run(go())


def drive_bodies(port: int, connections: int, seconds: float) -> list:
    """In a process of its own: ``send_big_bodies`` over ``connections`` connections."""
    async def go():
        refused: list = []
        until = time.monotonic() + seconds
        await asyncio.gather(*(send_big_bodies(port, until, refused)
                               for _ in range(connections)))
        return refused
    return asyncio.run(go())


def peak_rss_mb(pid: int) -> float:
    """The peak resident memory of a process so far (Linux: VmHWM), MB."""
    for row in Path(f"/proc/{pid}/status").read_text().splitlines():
        if row.startswith("VmHWM:"):
            return int(row.split()[1]) / 1024
    return float("nan")


def line(label: str, result: dict, base: dict | None = None) -> str:
    text = (f"  {label:34s} {result['rps']:7.1f} req/s  p50 {result['p50']:7.1f} ms  "
            f"p99 {result['p99']:7.1f} ms  (n={result['n']}")
    text += f", 503: {result['busy']})" if result["busy"] else ")"
    if base:
        text += f"  x{result['p50'] / base['p50']:.1f} p50, x{result['p99'] / base['p99']:.1f} p99"
    return text


async def main() -> None:
    seconds = float(sys.argv[1]) if len(sys.argv) > 1 else (0.5 if QUICK else 5.0)
    connections = int(sys.argv[2]) if len(sys.argv) > 2 else (4 if QUICK else 20)
    if not (REPO / "assets" / "build" / "manifest.json").is_file():
        sys.exit("assets/build is missing: run `glasshead build` first")
    workdir = Path(tempfile.mkdtemp(prefix="glasshead-bench-load-"))
    port = free_port()
    server = start_server(workdir, port)
    limits = httpx.Limits(max_connections=connections + 4)
    try:
        async with httpx.AsyncClient(base_url=f"http://127.0.0.1:{port}", limits=limits,
                                     timeout=60) as client:
            await wait_ready(client, server)
            for _ in range(1 if QUICK else 2 * (os.cpu_count() or 1)):  # every worker loaded
                await asyncio.gather(*(client.post(COMPUTE[1], json=COMPUTE[2])
                                       for _ in range(os.cpu_count() or 1)))
            print(f"load: uvicorn on 127.0.0.1:{port}, {seconds:g} s per phase, "
                  f"{os.cpu_count()} CPUs (shared with this client)")
            base = {}
            for name, request in (("health", HEALTH), ("read", READ), ("compute", COMPUTE)):
                base[name] = (await run(client, {name: (request, 1)}, seconds))[name]
            rss_before = peak_rss_mb(server.pid)
            print("unloaded (baseline):")
            print(line("GET /health", base["health"]))
            print(line("GET /epg/layout", base["read"]))
            print(line("POST /tongue/surface", base["compute"]))
            with multiprocessing.get_context("spawn").Pool(1) as driver:
                load = driver.apply_async(drive, (port, COMPUTE, connections, seconds + 1.0))
                await asyncio.sleep(1.0)  # the driver's connections open
                loaded = await run(client, {"health": (HEALTH, 1), "read": (READ, 1)}, seconds)
                loaded["compute"] = load.get(timeout=seconds + 120)
            print(f"under compute load ({connections} connections of POST /tongue/surface):")
            print(line("POST /tongue/surface", loaded["compute"], base["compute"]))
            print(line("GET /health", loaded["health"], base["health"]))
            print(line("GET /epg/layout", loaded["read"], base["read"]))
            with multiprocessing.get_context("spawn").Pool(1) as driver:
                senders = driver.apply_async(drive_bodies, (port, 3, seconds + 1.0))
                await asyncio.sleep(1.0)
                bodies = [await run(client, {"health": (HEALTH, 1)}, seconds)]
                refused = senders.get(timeout=seconds + 60)
            print("while 3 connections send 50 MB bodies to POST /collision/correct:")
            print(line("GET /health", bodies[0]["health"], base["health"]))
            print(f"  50 MB bodies refused with 413: {sum(refused)} of {len(refused)} "
                  "(the others: the connection reset before the answer was read)")
            print(f"  the server's peak memory: {rss_before:.0f} MB before the bodies, "
                  f"{peak_rss_mb(server.pid):.0f} MB after")
            worst = max(loaded["health"]["p99"], loaded["read"]["p99"],
                        bodies[0]["health"]["p99"])
            verdict = "within" if worst < GOAL_P99_MS else "OVER"
            print(f"worst p99 of /health and the read route under load: {worst:.1f} ms "
                  f"({verdict} the {GOAL_P99_MS:.0f} ms goal)")
            reads = [base["health"], base["read"], loaded["health"], loaded["read"],
                     bodies[0]["health"]]
            reads_ok = all(r["n"] > 0 and r["failed"] == 0 and r["busy"] == 0 for r in reads)
            computes = [base["compute"], loaded["compute"]]
            computes_ok = all(r["n"] > 0 and r["failed"] == 0 for r in computes)
            print("check: /health and the read route answered every request: "
                  f"{'ok' if reads_ok else 'FAILED'}")
            print("check: every compute request was answered (200 or 503): "
                  f"{'ok' if computes_ok else 'FAILED'}")
            return 0 if reads_ok and computes_ok else 1
    finally:
        server.terminate()
        try:
            server.wait(timeout=15)
        except subprocess.TimeoutExpired:
            server.kill()


if __name__ == "__main__":
    sys.exit(asyncio.run(main()))
