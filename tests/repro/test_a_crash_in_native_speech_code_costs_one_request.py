"""Issue 27, item 1: native code cannot take the server down.

``POST /utterances`` with 60 zeros as its text killed the whole server: libespeak-ng faulted
(a general protection fault) on a word of about 240 phones, in the server's own process. Now
every utterance that is not cached is made in a compute worker (``jobs.compute``), a worker that
dies costs only the request it served (a JSON 502 naming the input), and long numbers and long
words are spoken in pieces espeak-ng survives.
"""

import ctypes
import json
import os
import signal
import threading
import time
import unicodedata

import pytest

from glasshead.jobs.pool import WorkerDiedError, WorkerPool, WorkerTimeoutError
from glasshead.speech import espeak
from glasshead.speech.pronounce import MAX_NUMBER_DIGITS, tokenize

API = "/api/v1"


def fault(_):
    """A real fault inside native code: libc reads address 0."""
    return ctypes.string_at(0)


def pause(seconds):
    time.sleep(seconds)
    return seconds


def own_pid(_):
    return os.getpid()


def wait_until_dead(pid: int, seconds: float = 30.0) -> None:
    """Until the child can be reaped (left unreaped, for the pool to reap). The state "Z" in
    /proc is not enough: the leader of a process with threads shows "Z" while its other
    threads still exit, and until they have, the process reads as alive."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        try:
            if os.waitid(os.P_PID, pid, os.WEXITED | os.WNOHANG | os.WNOWAIT) is not None:
                return
        except ChildProcessError:  # already reaped
            return
        time.sleep(0.005)
    raise AssertionError(f"process {pid} still runs {seconds} s after SIGKILL")


@pytest.fixture
def pool():
    pool = WorkerPool(2, name="test")
    yield pool
    pool.shutdown(kill_running=True)


def test_a_worker_that_faults_costs_its_own_task_and_is_replaced(pool):
    slow = pool.submit(pause, 1.0)
    with pytest.raises(WorkerDiedError) as died:
        pool.submit(fault, None).result(timeout=60)
    assert died.value.signal_name == "SIGSEGV"
    assert "SIGSEGV" in str(died.value)
    assert slow.result(timeout=60) == 1.0  # the other worker's task went on
    together = [pool.submit(pause, 0.5) for _ in range(2)]  # both slots busy at once
    assert [task.result(timeout=60) for task in together] == [0.5, 0.5]
    assert pool.started == 3  # two workers and the one that replaced the dead one
    assert os.getpid() not in {pool.submit(own_pid, None).result(timeout=60) for _ in range(2)}


def test_tasks_one_after_another_are_served_by_one_worker_process(pool):
    """A slot's process starts only when every started worker is busy: one process, not one
    per slot, serves tasks that never overlap."""
    pids = {pool.submit(own_pid, None).result(timeout=60) for _ in range(4)}
    assert len(pids) == 1 and pool.started == 1


def test_a_worker_killed_from_outside_while_idle_is_replaced_before_the_next_task(pool):
    first = pool.submit(own_pid, None).result(timeout=60)
    os.kill(first, signal.SIGKILL)
    wait_until_dead(first)  # the kill lands (a task sent in the instant before costs itself)
    answers = [pool.submit(own_pid, None).result(timeout=60) for _ in range(3)]
    assert first not in answers


def test_a_task_past_its_time_limit_is_stopped_with_its_worker(pool):
    with pytest.raises(WorkerTimeoutError):
        pool.submit(pause, 30.0, timeout_s=0.5).result(timeout=60)
    assert pool.submit(pause, 0.0).result(timeout=60) == 0.0


def test_an_exception_a_task_raises_comes_back_as_itself(pool):
    with pytest.raises(ZeroDivisionError):
        pool.submit(divmod, 1, 0).result(timeout=60)


def test_sixty_zeros_are_read_digit_by_digit():
    assert tokenize("0" * 60) == ["0"] * 60
    assert tokenize("call 4155550123456") == ["call", *"4155550123456"]
    assert tokenize("1,000,000,000") == ["1,000,000,000"]  # a number espeak-ng reads out
    assert len("4155550123456") > MAX_NUMBER_DIGITS >= len("1000000000")


def test_a_word_of_hundreds_of_phones_is_handed_to_espeak_ng_in_pieces(monkeypatch):
    """400 phones in one word faulted espeak-ng's synthesis; in pieces it speaks them."""
    engine = espeak.get_engine()
    word = [("Z", None), ("IY", 1), ("R", None), ("OW", 0)] * 100
    synthesis = engine.synthesize([word])
    spoken = [p for p in synthesis.phones if p["index"] is not None]
    assert len(spoken) == 400
    assert synthesis.duration_s > 10


@pytest.fixture
def client(built_assets, start_app, tmp_path, monkeypatch):
    monkeypatch.setenv("GLASSHEAD_SPEECH_CACHE_DIR", str(tmp_path / "utterances"))
    return start_app(built_assets)[1]


def test_the_sixty_digit_text_that_killed_the_server_is_spoken(client):
    response = client.post(f"{API}/utterances", json={"text": "0" * 60})
    assert response.status_code == 200, response.text
    words = response.json()["words"]
    assert [w["text"] for w in words] == ["0"] * 60
    assert client.get(f"{API}/health").status_code == 200


def test_a_synthesis_worker_killed_mid_request_costs_that_request_only(client):
    """SIGSEGV to the worker while it speaks: that request gets a JSON 502 naming its text,
    /health answers throughout, and the next utterance is served."""
    pool = client.app.state.compute.pool
    answers = {}

    def speak():
        answers["killed"] = client.post(f"{API}/utterances",
                                        json={"text": "the worker that speaks this is killed"})

    speaking = threading.Thread(target=speak)
    speaking.start()
    deadline = time.monotonic() + 60
    while not pool.pids() and time.monotonic() < deadline:
        time.sleep(0.005)
    busy = pool.pids()
    assert busy, "no worker took the request"
    os.kill(busy[0], signal.SIGSEGV)
    health = []
    while speaking.is_alive():
        health.append(client.get(f"{API}/health").status_code)
    speaking.join()
    killed = answers["killed"]
    assert killed.status_code == 502
    assert killed.headers["content-type"] == "application/json"
    detail = killed.json()["detail"]
    assert "SIGSEGV" in detail and "the worker that speaks this is killed" in detail
    assert health and set(health) == {200}
    after = client.post(f"{API}/utterances", json={"text": "and the next one is spoken"})
    assert after.status_code == 200
    assert json.loads(after.content)["phones"]
    assert busy[0] not in pool.pids()


def one_of_each_unicode_category() -> str:
    """A text with the first character of every Unicode general category (surrogates, which
    JSON cannot carry alone, left out), words and marks side by side."""
    seen: dict[str, str] = {}
    for code in range(0x110000):
        category = unicodedata.category(chr(code))
        if category not in seen and category != "Cs":
            seen[category] = chr(code)
    return " ".join(f"a{c}b" for c in seen.values())


@pytest.mark.parametrize("body, status", [
    ({"text": "x" * 10_000}, 422),
    ({"text": "7" * 10_000}, 422),
    ({"text": "1" * 500}, 200),
    ({"text": "nul\x00 and \x07 bell \x1b escape"}, 200),
    ({"text": one_of_each_unicode_category()}, 200),
    ({"text": "\u0301\u200b\ue000\U0001f600 \u2028 \U000e0001 \ufeff"}, 422),
    ({"phonemes": "Q X ʘ ǃ ǂ"}, 422),
    ({"phonemes": ["s", "\x00"]}, 422),
])
def test_bad_text_and_phonemes_get_an_answer_and_the_server_stays_up(client, body, status):
    response = client.post(f"{API}/utterances", json=body)
    assert response.status_code == status, response.text[:300]
    if status != 200:
        assert response.json()["detail"]
    assert client.get(f"{API}/health").status_code == 200
