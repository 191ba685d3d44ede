"""Fit jobs without the API: uploads read into observations, fits of each kind, the worker's job
(its row's states and progress) run in this process, and the runner's pool of workers stopped
and started again, and losing a worker mid-fit."""

import io
import json
import os
import signal
import time

import numpy as np
import pytest
from sqlalchemy.orm import Session

from glasshead import uploads
from glasshead.asset_store import AssetStore
from glasshead.fitting import authored, fit3d
from glasshead.jobs import fit_job, fit_queue
from glasshead.jobs.fit_runner import FitRunner
from glasshead.store.db import engine_for, upgrade_to_head
from glasshead.store.fit_jobs import FitJob


@pytest.fixture(scope="module")
def inputs(built_assets):
    return fit_job.fit_inputs(AssetStore(built_assets))


@pytest.fixture(scope="module")
def shape_a(built_assets):
    shapes = json.loads((built_assets / "vtl-observations.json").read_text())["shapes"]
    return next(s for s in shapes if s["name"] == "a")


@pytest.fixture
def engine(tmp_path):
    url = f"sqlite:///{tmp_path / 'jobs.sqlite3'}"
    engine = engine_for(url)
    upgrade_to_head(engine)
    yield url, engine
    engine.dispose()


def test_a_contour_csv_reads_with_header_comments_and_any_separator():
    text = b"# JD3 /a/\nx_mm,y_mm\n-40,-31\n-30 -10\n-20;0\n0,\t8\n\n10,5\n20,-2\n"
    points = uploads.read_contour(text)
    np.testing.assert_allclose(points, [[-40, -31], [-30, -10], [-20, 0], [0, 8], [10, 5],
                                        [20, -2]], atol=0)


def test_a_contour_in_metres_is_refused_by_its_length_and_one_off_frame_by_its_line():
    with pytest.raises(uploads.ObservationError, match="mm long"):
        uploads.read_contour(b"-0.04,-0.03\n-0.03,-0.01\n-0.02,0\n0,0.008\n0.01,0.005\n")
    with pytest.raises(uploads.ObservationError, match="line 3: a coordinate beyond 150 mm"):
        uploads.read_contour(b"0,0\n5,1\n400,2\n15,3\n20,4\n")


def test_an_obj_surface_and_the_same_surface_as_binary_ply_give_the_same_vertices(shape_a):
    import trimesh

    vertices = np.asarray(shape_a["tongue_surface_vertices"])
    obj = "".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in vertices.tolist()).encode()
    from_obj, fmt = uploads.read_surface(obj + b"f 1 2 3\n", "a.obj")
    assert fmt == "obj"
    ply = io.BytesIO()
    trimesh.PointCloud(vertices).export(ply, file_type="ply", encoding="binary")
    from_ply, fmt = uploads.read_surface(ply.getvalue(), None)
    assert fmt == "ply"
    np.testing.assert_array_equal(from_obj, vertices)
    np.testing.assert_allclose(from_ply, vertices, rtol=1e-6, atol=1e-4)  # PLY stores float32


def test_a_surface_with_a_nan_vertex_is_refused_naming_its_line():
    lines = [f"v {k} {k % 7} {k % 3}" for k in range(60)]
    lines[9] = "v 1 nan 2"
    with pytest.raises(uploads.ObservationError, match="line 10: a vertex is not finite"):
        uploads.read_surface("\n".join(lines).encode(), "s.obj")


def test_an_epg_frame_index_chooses_that_frame_and_one_past_the_end_is_refused(data_dir):
    content = (data_dir / "epg" / "emur-engassim.json").read_bytes()
    document = json.loads(content)
    document["segments"] = document["segments"][:1]
    small = json.dumps(document).encode()
    observation = uploads.read_observation("epg", small, "one.json", frame=20)
    rows = document["segments"][0]["frames"][20]["rows"]
    wanted = np.array([[int(c) for c in row] for row in rows]) & uploads.ELECTRODES
    np.testing.assert_array_equal(observation.points[0], wanted)
    assert observation.source["goal"] == "frame 20"
    count = len(document["segments"][0]["frames"])
    with pytest.raises(uploads.ObservationError, match=f"0 to {count - 1}"):
        uploads.read_observation("epg", small, "one.json", frame=count)


def test_a_surface_fit_is_fit3ds_fit_and_its_target_holds_every_parameter(inputs, shape_a):
    vertices = np.asarray(shape_a["tongue_surface_vertices"])
    seen = []
    result = authored.fit_observation(inputs, "surface", vertices, max_evals=200,
                                      progress=lambda *step: seen.append(step))
    direct = fit3d.fit_surface(inputs.rig, vertices, max_evals=200, section=inputs.section)
    assert result["report"]["rms_mm"] == pytest.approx(direct.rms_mm, abs=1e-9)
    assert len(seen) == result["report"]["evaluations"] == 200
    assert seen[-1][2] == pytest.approx(1.0) and seen[0][2] == pytest.approx(1 / 200)
    assert set(result["params"]) == set(inputs.rig.parameter_names) | set(inputs.others)
    assert result["params"]["velum_opening"] == inputs.others["velum_opening"]


def test_the_rest_outline_runs_root_to_tip_over_the_dorsum(inputs):
    outline = authored.rest_outline(inputs.section, inputs.rig)
    assert outline[0, 0] < -40 and outline[-1, 0] > 15  # root behind, tip in front
    assert outline[:, 1].max() > 10 and np.all(np.isfinite(outline))


def _queue(engine, points, kind="contour", **source) -> int:
    with Session(engine) as session:
        job = FitJob(name="job", kind=kind, method="bobyqa", state="queued", progress={},
                     source={"options": source})
        job.set_observation(points)
        session.add(job)
        session.commit()
        return job.id


def _claim(engine) -> int | None:
    with Session(engine) as session:
        return fit_queue.claim_next(session)


def test_the_worker_runs_a_claimed_job_to_done_with_its_target_and_report(
        engine, shape_a, built_assets):
    url, eng = engine
    job_id = _queue(eng, np.asarray(shape_a["tongue_outline"]), max_evals=150)
    assert fit_job.run_job(url, str(built_assets), job_id) == "queued"  # not claimed: not run
    assert _claim(eng) == job_id and _claim(eng) is None
    assert fit_job.run_job(url, str(built_assets), job_id) == "done"
    with Session(eng) as session:
        job = session.get(FitJob, job_id)
        assert job.state == "done" and job.message is None
        assert job.report["evaluations"] == 150 and job.progress["fraction"] == 1.0
        assert job.started_at <= job.finished_at and len(job.params) > 32
    assert fit_job.run_job(url, str(built_assets), job_id) == "done"  # not run twice


def test_a_fit_that_cannot_run_fails_its_job_with_the_reason(engine, built_assets):
    url, eng = engine
    short = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0], [4.0, 0.0]])  # 5 rays
    job_id = _queue(eng, short)
    assert _claim(eng) == job_id
    assert fit_job.run_job(url, str(built_assets), job_id) == "failed"
    with Session(eng) as session:
        job = session.get(FitJob, job_id)
        assert job.state == "failed" and "ValueError" in job.message and job.params is None


def test_progress_is_written_a_few_times_a_second_and_a_deleted_row_stops_the_fit(engine):
    url, eng = engine
    job_id = _queue(eng, np.zeros((5, 2)))
    with Session(eng) as session:
        session.get(FitJob, job_id).state = "running"
        session.commit()
        writer = fit_job.ProgressWriter(session, job_id, interval_s=0.25)
        commits = []
        real_commit = session.commit
        session.commit = lambda: (commits.append(1), real_commit())
        for k in range(2000):
            writer(k, 1.0 / (k + 1), k / 2000)
        assert len(commits) <= 2  # the loop takes well under half a second
        writer.last = 0.0
        writer(2000, 0.5, 1.0)
        assert session.get(FitJob, job_id).progress["evaluations"] == 2000
        session.execute(FitJob.__table__.delete().where(FitJob.id == job_id))
        real_commit()
        writer.last = 0.0
        with pytest.raises(fit_job.JobDeletedError):
            writer(2001, 0.5, 1.0)


def _state(engine, job_id):
    with Session(engine) as session:
        job = session.get(FitJob, job_id)
        return None if job is None else (job.state, job.progress, job.message)


def _wait_running(engine, job_id, timeout_s=60.0):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        state = _state(engine, job_id)
        if state[0] == "running" and state[1].get("evaluations", 0) > 0:
            return
        time.sleep(0.1)
    pytest.fail(f"job {job_id} did not start within {timeout_s} s: {_state(engine, job_id)}")


def test_a_stop_fails_the_running_fit_keeps_the_queued_one_and_a_restart_runs_it(
        engine, built_assets):
    url, eng = engine
    goal = np.stack([np.eye(8), np.ones((8, 8))])  # a diagonal: never met, the fit runs on
    first, second = (_queue(eng, goal, kind="epg", max_evals=20000) for _ in range(2))
    runner = FitRunner(url, built_assets)
    runner.start()
    try:
        _wait_running(eng, first)
    finally:
        runner.shutdown()
    # Stopped, not waited for: a fit of 20,000 evaluations toward a goal it never meets would
    # have ended "done".
    assert _state(eng, first)[0] == "failed" and "stopped" in _state(eng, first)[2]
    assert _state(eng, second)[0] == "queued"
    again = FitRunner(url, built_assets)
    again.start()
    try:
        _wait_running(eng, second)
        with Session(eng) as session:  # deleted while it runs: the fit stops
            session.delete(session.get(FitJob, second))
            session.commit()
        deadline = time.monotonic() + 60.0
        while again.running and time.monotonic() < deadline:
            time.sleep(0.1)
        assert not again.running, "the deleted job's fit did not stop"
    finally:
        again.shutdown()


def test_a_worker_killed_mid_fit_fails_only_its_job_and_the_next_job_runs(
        engine, built_assets, shape_a):
    url, eng = engine
    goal = np.stack([np.eye(8), np.ones((8, 8))])
    doomed = _queue(eng, goal, kind="epg", max_evals=20000)
    runner = FitRunner(url, built_assets)
    runner.start()
    try:
        _wait_running(eng, doomed)
        after = _queue(eng, np.asarray(shape_a["tongue_outline"]), max_evals=100)
        runner.wake()
        (pid,) = runner._pool.pids()
        os.kill(pid, signal.SIGKILL)  # as the out-of-memory killer would
        deadline = time.monotonic() + 60.0
        while _state(eng, after)[0] != "done" and time.monotonic() < deadline:
            time.sleep(0.1)
        state, _, message = _state(eng, doomed)
        assert state == "failed" and "SIGKILL" in message, message
        assert _state(eng, after)[0] == "done"
        assert runner._pool.started == 2  # the dead worker was replaced
    finally:
        runner.shutdown()
