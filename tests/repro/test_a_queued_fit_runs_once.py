"""A queued fit runs once, however many servers hand it to their pools.

Every server (each uvicorn worker, each app replica) hands the jobs it finds queued at start-up
to its own pool; the worker that ran a job first read its state and then wrote ``running``, so two
of them could both start it. The claim is now one conditional UPDATE.
"""

import threading

import numpy as np
from sqlalchemy.orm import Session

from glasshead.fitting import jobs
from glasshead.store.db import engine_for, upgrade_to_head
from glasshead.store.fit_jobs import FitJob

CLAIMANTS = 8


def test_of_eight_concurrent_claims_on_one_queued_job_exactly_one_succeeds(tmp_path):
    engine = engine_for(f"sqlite:///{tmp_path / 'jobs.sqlite3'}")
    upgrade_to_head(engine)
    with Session(engine) as session:
        job = FitJob(name="job", kind="contour", method="bobyqa", state="queued", progress={},
                     source={"options": {}})
        job.set_observation(np.zeros((3, 2)))
        session.add(job)
        session.commit()
        job_id = job.id
    start = threading.Barrier(CLAIMANTS)
    results = []

    def claim():
        with Session(engine) as session:
            start.wait()
            results.append(jobs.claim_job(session, job_id))

    threads = [threading.Thread(target=claim) for _ in range(CLAIMANTS)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=30)
    assert sorted(results) == [False] * (CLAIMANTS - 1) + [True]
    with Session(engine) as session:
        job = session.get(FitJob, job_id)
        assert job.state == "running" and job.started_at is not None
        assert job.progress == {"evaluations": 0, "best_error": None, "fraction": 0.0}
    assert jobs.run_job(str(engine.url), str(tmp_path), job_id) == "running"  # not run again
    engine.dispose()
