"""Issue 13, item 3: CPU-heavy routes run in a bounded pool of worker processes.

At 20 connections POST /tongue/surface ran in the server's own process, and /health took 1.7 s
at p50 meanwhile. Now the heavy routes answer from worker processes with the same documents as
the in-process code, a full queue is answered 503 with Retry-After at once, and /health is
answered while compute requests are still in flight (held there by the test, not by their
cost). Speeds are measured in bench/load.py."""

import asyncio
import json
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest
from fastapi import HTTPException

from accounts_support import signed_in
from assets_support import copy_built_assets
from glasshead.api.routes.collision import CorrectRequest, correct
from glasshead.api.routes.epg import ContactsRequest, contacts_json
from glasshead.api.routes.epg_compare import (
    CompareRequest,
    comparison_json,
    comparison_svg,
    recording_svg,
)
from glasshead.api.routes.epg_indices import IndicesRequest, indices_json
from glasshead.api.routes.tongue import SurfaceRequest, evaluate_surface
from glasshead.asset_store import RECHECK_S
from glasshead.constants import TONGUE_RIG_FILE
from glasshead.epg.plot import DEFAULT_PANELS
from glasshead.jobs.compute import ComputePool
from glasshead.store.db import database_url

API = "/api/v1"
#: Longest a test holds a worker, s: a wait for a state, never reached by a passing run.
HOLD_S = 60.0
ROWS = ["00111100", "01111110", "11000011", "10000001", "10000001", "10000001", "10000001",
        "11111111"]


def slow_task(store, seconds: float) -> bytes:
    """A task that holds its worker for ``seconds``."""
    time.sleep(seconds)
    return json.dumps({"slept": seconds}).encode()


def held_until(store, paths: tuple[str, str]) -> bytes:
    """A task that creates the file ``paths[0]`` once it runs, then holds its worker until the
    file ``paths[1]`` exists (at most HOLD_S)."""
    started, release = (Path(path) for path in paths)
    started.touch()
    deadline = time.monotonic() + HOLD_S
    while not release.exists() and time.monotonic() < deadline:
        time.sleep(0.01)
    return json.dumps({"released": release.exists()}).encode()


def _wait_until(condition) -> None:
    """Wait (at most HOLD_S) until ``condition()`` is true."""
    deadline = time.monotonic() + HOLD_S
    while not condition() and time.monotonic() < deadline:
        time.sleep(0.01)


def test_the_pool_gives_the_same_answers_as_the_in_process_code(start_app, built_assets):
    app, client = start_app()
    signed_in(client, "admin")
    surface = client.post(f"{API}/tongue/surface", json={"params": {"tip_height": 5.0}})
    assert surface.status_code == 200
    vertices = surface.json()["vertices"]
    cases = [
        ("/tongue/surface", evaluate_surface, SurfaceRequest,
         {"params": {"tip_height": 5.0, "jaw_opening": 10.0}}),
        ("/collision/correct", correct, CorrectRequest, {"vertices": vertices}),
        ("/collision/correct", correct, CorrectRequest,
         {"vertices": vertices, "velum_opening": 0.6}),
        ("/epg/contacts", contacts_json, ContactsRequest, {"params": {"tip_height": 6.0}}),
        ("/epg/contacts", contacts_json, ContactsRequest, {"vertices": vertices}),
        ("/epg/indices", indices_json, IndicesRequest, {"frames": [ROWS] * 5}),
    ]
    for path, task, model, body in cases:
        response = client.post(API + path, json=body)
        assert response.status_code == 200, (path, response.text)
        in_process = json.loads(task(app.state.assets, model(**body)))
        assert response.json() == in_process, path
    corrected = json.loads(correct(app.state.assets, CorrectRequest(vertices=vertices)))
    assert len(corrected["flags"]) == len(vertices) == corrected["counts"]["screened"]


def test_comparisons_and_plots_from_the_pool_match_the_in_process_code(start_app, data_dir):
    app, client = start_app()
    signed_in(client, "admin")
    emur = (data_dir / "epg" / "emur-engassim.json").read_bytes()
    created = client.post(f"{API}/epg/recordings",
                          files={"file": ("engassim.json", emur, "application/json")})
    assert created.status_code == 201
    first, second = (r["id"] for r in created.json()["recordings"][:2])
    url = database_url()
    for body in ({"reference": {"frames": [ROWS]}}, {"reference": {"recording_id": second}}):
        report = client.post(f"{API}/epg/recordings/{first}/compare", json=body)
        assert report.status_code == 200
        assert report.json() == json.loads(comparison_json(
            app.state.assets, (url, first, CompareRequest(**body))))
        plot = client.post(f"{API}/epg/recordings/{first}/compare/plot", json=body)
        assert plot.headers["content-type"].startswith("image/svg+xml")
        assert plot.content == comparison_svg(
            app.state.assets, (url, first, CompareRequest(**body), list(DEFAULT_PANELS)))
    alone = client.get(f"{API}/epg/recordings/{first}/plot")
    assert alone.content == recording_svg(app.state.assets, (url, first, list(DEFAULT_PANELS)))
    missing = client.get(f"{API}/epg/recordings/999/plot")
    assert missing.status_code == 404


def test_an_error_raised_in_a_worker_answers_as_it_would_in_process(start_app, built_assets):
    _, client = start_app()
    signed_in(client, "admin")
    response = client.post(f"{API}/epg/indices", json={"frames": [["2" * 8] * 8]})
    assert response.status_code == 422
    assert isinstance(response.json()["detail"], str) and response.json()["detail"]


def test_a_worker_follows_a_rebuilt_asset_by_its_content(start_app, built_assets, tmp_path):
    assets = tmp_path / "assets"
    copy_built_assets(built_assets, assets)
    _, client = start_app(assets)
    signed_in(client, "admin")
    body = {"params": {"tip_height": 4.0}}
    first = client.post(f"{API}/tongue/surface", json=body)
    assert first.status_code == 200
    rig = assets / TONGUE_RIG_FILE
    good = rig.read_bytes()
    rig.write_bytes(b"{ not json")
    time.sleep(RECHECK_S + 0.1)
    broken = client.post(f"{API}/tongue/surface", json=body)
    assert broken.status_code == 503
    assert broken.json()["asset"] == "tongue_rig" and broken.json()["problem"] == "corrupt"
    rig.write_bytes(good)
    time.sleep(RECHECK_S + 0.1)
    again = client.post(f"{API}/tongue/surface", json=body)
    assert again.status_code == 200 and again.json() == first.json()


def test_a_full_queue_is_answered_503_with_retry_after_at_once(built_assets):
    pool = ComputePool(built_assets, workers=1, queue_limit=1)

    async def scenario():
        running = [asyncio.ensure_future(pool.run(slow_task, 1.0)) for _ in range(2)]
        while pool.pending < 2:
            await asyncio.sleep(0)
        with pytest.raises(HTTPException) as refused:
            await pool.run(slow_task, 0.0)
        assert pool.pending == 2  # the refused request never queued
        answers = await asyncio.gather(*running)
        again = await pool.run(slow_task, 0.0)
        return refused.value, answers, again

    pool.start()
    try:
        refused, answers, again = asyncio.run(scenario())
    finally:
        pool.shutdown()
    assert refused.status_code == 503
    assert refused.headers == {"Retry-After": "1"}
    assert "1 computations run and 1 wait" in refused.detail
    assert [json.loads(a) for a in answers] == [{"slept": 1.0}] * 2
    assert json.loads(again) == {"slept": 0.0}
    assert pool.pending == 0


def test_a_compute_route_answers_503_when_its_queue_is_full(start_app, built_assets,
                                                            monkeypatch):
    monkeypatch.setenv("GLASSHEAD_COMPUTE_WORKERS", "1")
    monkeypatch.setenv("GLASSHEAD_COMPUTE_QUEUE_LIMIT", "0")
    app, client = start_app()
    signed_in(client, "admin")
    app.state.compute.pending = 1  # one request holds the only worker
    busy = client.post(f"{API}/tongue/surface", json={"params": {}})
    assert busy.status_code == 503
    assert busy.headers["Retry-After"] == "1"
    assert "busy" in busy.json()["detail"]
    assert client.get(f"{API}/health").status_code == 200
    app.state.compute.pending = 0
    assert client.post(f"{API}/tongue/surface", json={"params": {}}).status_code == 200


def test_health_and_a_read_route_are_answered_while_compute_requests_are_in_flight(
        start_app, built_assets, tmp_path, monkeypatch):
    """The pool's one worker is held by a task until the test lets it go, and four
    /collision/correct requests queue behind it: /health and a read route are answered while
    every one of them is still in flight, which holds however fast or slow the machine is."""
    monkeypatch.setenv("GLASSHEAD_COMPUTE_WORKERS", "1")
    monkeypatch.setenv("GLASSHEAD_COMPUTE_QUEUE_LIMIT", "8")
    app, client = start_app()
    signed_in(client, "admin")
    pool = app.state.compute
    vertices = client.post(f"{API}/tongue/surface", json={"params": {}}).json()["vertices"]
    started, release = tmp_path / "started", tmp_path / "release"
    in_flight = 4
    holder = client.portal.start_task_soon(pool.run, held_until, (str(started), str(release)))
    heavy = []
    with ThreadPoolExecutor(in_flight) as threads:
        try:
            _wait_until(started.exists)  # the worker is the held task's
            heavy = [threads.submit(client.post, f"{API}/collision/correct",
                                    json={"vertices": vertices, "velum_opening": 0.5})
                     for _ in range(in_flight)]
            _wait_until(lambda: pool.pending == 1 + in_flight)
            health = client.get(f"{API}/health")
            rig = client.get(f"{API}/tongue/rig")
            still = (pool.pending, holder.done(), [answer.done() for answer in heavy])
        finally:
            release.touch()
        statuses = [answer.result(timeout=300).status_code for answer in heavy]
    assert json.loads(holder.result(timeout=60)) == {"released": True}
    assert health.status_code == 200 and rig.status_code == 200
    assert still == (1 + in_flight, False, [False] * in_flight), (
        "pending, whether the held task and each compute request had finished")
    assert statuses == [200] * in_flight
