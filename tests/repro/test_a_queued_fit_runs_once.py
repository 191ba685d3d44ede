"""A queued fit runs once, however many servers claim it at the same moment.

Every server (each uvicorn worker, each app replica) takes jobs from the one queue in the
database when one of its workers is free. A worker that read a job's state and then wrote
``running`` once let two servers both start it; a claim is now one transaction: on SQLite an
``UPDATE ... WHERE state = 'queued'``, on PostgreSQL ``SELECT ... FOR UPDATE SKIP LOCKED`` and
the ``UPDATE``, where servers claiming together each take a different job.
"""

import threading

import numpy as np
import pytest
from sqlalchemy.orm import Session

from glasshead.jobs import fit_queue
from glasshead.store.db import engine_for, upgrade_to_head
from glasshead.store.fit_jobs import FitJob

CLAIMANTS = 8


@pytest.fixture(params=["sqlite", "postgresql"])
def engine(request, tmp_path):
    if request.param == "sqlite":
        url = f"sqlite:///{tmp_path / 'jobs.sqlite3'}"
    else:
        server = request.getfixturevalue("postgres_server")
        url = server.url(server.create_database())
    engine = engine_for(url)
    upgrade_to_head(engine)
    yield engine
    engine.dispose()


def queue(engine, count: int) -> list[int]:
    with Session(engine) as session:
        jobs = [FitJob(name=f"job {k}", kind="contour", method="bobyqa", state="queued",
                       progress={}, source={"options": {}}) for k in range(count)]
        for job in jobs:
            job.set_observation(np.zeros((3, 2)))
        session.add_all(jobs)
        session.commit()
        return [job.id for job in jobs]


def claim_together(engine) -> list[int | None]:
    start = threading.Barrier(CLAIMANTS)
    results = []

    def claim():
        with Session(engine) as session:
            start.wait()
            results.append(fit_queue.claim_next(session))

    threads = [threading.Thread(target=claim) for _ in range(CLAIMANTS)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=30)
    return results


def test_of_eight_concurrent_claims_on_one_queued_job_exactly_one_succeeds(engine):
    (job_id,) = queue(engine, 1)
    results = claim_together(engine)
    assert sorted(results, key=lambda r: r is None) == [job_id] + [None] * (CLAIMANTS - 1)
    with Session(engine) as session:
        job = session.get(FitJob, job_id)
        assert job.state == "running" and job.started_at is not None
        assert job.progress == {"evaluations": 0, "best_error": None, "fraction": 0.0}
        assert fit_queue.claim_next(session) is None  # not taken again


def test_eight_concurrent_claims_on_three_queued_jobs_take_each_once(engine):
    ids = queue(engine, 3)
    results = claim_together(engine)
    taken = [r for r in results if r is not None]
    assert sorted(taken) == ids and results.count(None) == CLAIMANTS - 3
