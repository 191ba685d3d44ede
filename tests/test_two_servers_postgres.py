"""Beyond one machine: two servers (real processes) on one PostgreSQL share the fit queue and the
utterance cache, and neither keeps anything on its own disk that the other needs.

Server A runs no fit workers (``GLASSHEAD_FIT_WORKERS=0``), so a fit queued on A can only be
run by B, which hears of it by ``NOTIFY`` (not by its 30 s safety sweep). An utterance made by A
is served by B from the shared cache: its audio URL from B, and the same request answered by B
without a synthesis, with B's cache directory empty throughout.
"""

import json
import os
import time
from datetime import datetime
from pathlib import Path

import httpx
import numpy as np
import pytest

from glasshead.jobs.fit_runner import SAFETY_SWEEP_S
from server_process import API, ServerProcess

#: Seconds the fit may take from upload to done, B's worker start included.
FIT_TIMEOUT_S = 120.0
UTTERANCE = {"text": "Ted sips tea.", "audio": {"kind": "natural"}}


@pytest.fixture
def postgres_url(postgres_server) -> str:
    return postgres_server.url(postgres_server.create_database())


def children(pid: int) -> set[int]:
    """The process ids whose parent is ``pid`` (spawned workers, the resource tracker)."""
    found = set()
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue
        if int(fields[1]) == pid:
            found.add(int(stat.parent.name))
    return found


def start(tmp_path: Path, name: str, url: str, fit_workers: int, monkeypatch,
          headers: dict | None = None) -> ServerProcess:
    folder = tmp_path / name
    folder.mkdir()
    monkeypatch.setenv("GLASSHEAD_FIT_WORKERS", str(fit_workers))
    monkeypatch.setenv("GLASSHEAD_SPEECH_CACHE_DIR", str(folder / "utterances"))
    server = ServerProcess(folder, url)
    server.headers = dict(headers or {})
    return server.start()


def test_a_fit_queued_on_one_server_is_run_by_the_other_and_an_utterance_is_served_by_both(
        tmp_path, postgres_url, built_assets, monkeypatch):
    a = start(tmp_path, "a", postgres_url, 0, monkeypatch)
    b = None
    try:
        b = start(tmp_path, "b", postgres_url, 1, monkeypatch, headers=a.headers)
        shapes = json.loads((built_assets / "vtl-observations.json").read_text())["shapes"]
        outline = np.array(next(s for s in shapes if s["name"] == "a")["tongue_outline"])
        csv = "x_mm,y_mm\n" + "".join(f"{x:.4f},{y:.4f}\n" for x, y in outline)
        with httpx.Client(timeout=60, headers=a.headers) as client:
            # A fit queued on A, which has no fit workers: B must take it.
            created = client.post(f"{a.base}{API}/fits", data={"kind": "contour",
                                                               "max_evals": "200"},
                                  files={"file": ("a.csv", csv.encode())})
            assert created.status_code == 202, created.text
            fit_id = created.json()["id"]
            deadline = time.monotonic() + FIT_TIMEOUT_S
            while (job := client.get(f"{a.base}{API}/fits/{fit_id}").json())["state"] in (
                    "queued", "running") and time.monotonic() < deadline:
                time.sleep(0.2)
            assert job["state"] == "done", job
            assert job["report"]["evaluations"] == 200
            waited_s = (datetime.fromisoformat(job["started_at"])
                        - datetime.fromisoformat(job["created_at"])).total_seconds()
            assert waited_s < SAFETY_SWEEP_S / 3, waited_s  # woken by NOTIFY, not the sweep
            print(f"fit {fit_id}: queued on A, claimed by B after {waited_s:.3f} s")
            # An utterance made by A ...
            made = client.post(f"{a.base}{API}/utterances", json=UTTERANCE)
            assert made.status_code == 200, made.text
            audio_url = made.json()["audio_url"]
            from_a = client.get(f"{a.base}{audio_url}")
            assert from_a.status_code == 200 and from_a.content[:4] == b"RIFF"
            # ... is served by B, which never made it and starts no worker to answer it.
            before = children(b.process.pid)
            assert before, "B's fit worker is not among its children"
            from_b = client.get(f"{b.base}{audio_url}")
            assert from_b.status_code == 200, from_b.text
            assert from_b.headers["content-type"] == "audio/wav"
            assert from_b.content == from_a.content
            part = client.get(f"{b.base}{audio_url}", headers={"Range": "bytes=0-43"})
            assert part.status_code == 206 and part.content == from_a.content[:44]
            assert part.headers["content-range"] == f"bytes 0-43/{len(from_a.content)}"
            again = client.post(f"{b.base}{API}/utterances", json=UTTERANCE)
            assert again.status_code == 200 and again.content == made.content
            assert children(b.process.pid) == before, "B started a worker to answer it"
        for server in ("a", "b"):  # the cache is the database, not either server's disk
            cache = tmp_path / server / "utterances"
            assert not cache.exists() or not os.listdir(cache)
    finally:
        if b is not None:
            b.stop()
        a.stop()
