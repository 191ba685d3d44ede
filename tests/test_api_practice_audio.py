"""The recording of a child's attempts: off unless a clinician switches it on, each change kept
with who and when; while on, an attempt's WAV is kept with its practice record, read back as it
was sent, and deleted with the record; bad files are refused and store nothing."""

from dataclasses import dataclass

import pytest
from sqlalchemy import text

from accounts_support import add_user, bearer, child_bearer, header, token_for
from glasshead.api.routes.practice_audio import MAX_AUDIO_BYTES
from glasshead.store.db import get_engine
from wav_support import tone_wav

API = "/api/v1"
WAV = {"Content-Type": "audio/wav"}


@dataclass
class Setting:
    client: object
    clinician: dict
    teacher: dict
    child: dict
    other_child: dict
    child_id: int
    record_id: int
    other_record_id: int


def _post(client, path, body, headers):
    answer = client.post(f"{API}/{path}", json=body, headers=headers)
    assert answer.status_code == 201, answer.text
    return answer.json()


@pytest.fixture
def setting(start_app) -> Setting:
    """A clinician's caseload shared with a teacher: two children, each with a practice record
    of a lesson assigned to the class."""
    client = start_app()[1]
    clinician_id = add_user("clinician", "dr.ames@test.example")
    clinician = header(token_for(clinician_id))
    teacher_id = add_user("teacher", "tess@test.example")
    caseload = _post(client, "classes", {"name": "Tuesday"}, clinician)
    _post(client, f"classes/{caseload['id']}/staff", {"username": "tess@test.example"},
          clinician)
    children = [_post(client, "children", {"class_id": caseload["id"], "display_name": name,
                                           "avatar": "owl"}, clinician) for name in ("Ada", "Bo")]
    lesson = _post(client, "lessons", {"title": "heed", "items": [
        {"target": {"kind": "word", "text": "heed"}}]}, bearer("author"))
    _post(client, "assignments", {"lesson_id": lesson["id"], "class_id": caseload["id"]},
          clinician)
    records = [_post(client, "practice", {"child_id": c["id"], "lesson_id": lesson["id"],
                                          "item_index": 0}, clinician) for c in children]
    return Setting(client, clinician, header(token_for(teacher_id)),
                   child_bearer(children[0]["id"]), child_bearer(children[1]["id"]),
                   children[0]["id"], records[0]["id"], records[1]["id"])


def _switch(s: Setting, enabled: bool, who=None):
    return s.client.put(f"{API}/children/{s.child_id}/audio-recording",
                        json={"enabled": enabled}, headers=s.clinician if who is None else who)


def _kept_rows() -> int:
    with get_engine().connect() as connection:
        return connection.execute(text("SELECT count(*) FROM practice_audio")).scalar_one()


def test_recording_is_off_until_switched_on_and_an_upload_before_stores_nothing(setting):
    s = setting
    state = s.client.get(f"{API}/children/{s.child_id}/audio-recording", headers=s.child)
    assert state.status_code == 200
    assert state.json() | {"history": None} == {
        "child_id": s.child_id, "enabled": False, "set_by": None, "set_by_name": None,
        "set_at": None, "history": None}
    refused = s.client.put(f"{API}/practice/{s.record_id}/audio", content=tone_wav(16_000, 1),
                           headers={**s.child, **WAV})
    assert refused.status_code == 409
    assert refused.json()["detail"].startswith(f"recording is off for child {s.child_id}")
    assert _kept_rows() == 0
    record = s.client.get(f"{API}/practice/{s.record_id}", headers=s.child).json()
    assert record["has_audio"] is False


def test_only_a_clinician_of_the_class_or_an_admin_sets_the_switch_and_each_change_is_kept(
        setting):
    s = setting
    assert _switch(s, True, {}).status_code == 401
    for who in (s.teacher, s.child, bearer("author")):
        assert _switch(s, True, who).status_code == 403
    assert _switch(s, True, bearer("clinician")).status_code == 404  # not their caseload
    assert _switch(s, True).status_code == 200
    state = _switch(s, False, bearer("admin")).json()
    assert state["enabled"] is False and state["set_by_name"].startswith("admin-")
    assert [(c["enabled"], c["set_by_name"]) for c in state["history"]] == [
        (False, state["set_by_name"]), (True, "dr.ames")]
    assert state["history"][0]["set_at"] >= state["history"][1]["set_at"]
    # The teacher who shares the class reads it, as does the child.
    for who in (s.teacher, s.child):
        read = s.client.get(f"{API}/children/{s.child_id}/audio-recording", headers=who)
        assert read.status_code == 200 and read.json() == state


def test_while_on_the_attempt_is_kept_read_back_as_sent_replaced_and_deleted(setting):
    s = setting
    _switch(s, True)
    first, second = tone_wav(16_000, 1.25), tone_wav(22_050, 0.5, hz=330)
    kept = s.client.put(f"{API}/practice/{s.record_id}/audio", content=first,
                        headers={**s.child, **WAV})
    assert kept.status_code == 201, kept.text
    assert kept.json() | {"created_at": None} == {
        "practice_id": s.record_id, "child_id": s.child_id, "sample_rate": 16_000,
        "duration_s": 1.25, "bytes": len(first), "created_at": None}
    for who in (s.clinician, s.teacher, s.child):
        heard = s.client.get(f"{API}/practice/{s.record_id}/audio", headers=who)
        assert heard.status_code == 200 and heard.content == first
        assert heard.headers["content-type"] == "audio/wav"
    listed = s.client.get(f"{API}/practice", headers=s.clinician).json()["records"]
    assert {r["id"]: r["has_audio"] for r in listed} == {s.record_id: True,
                                                         s.other_record_id: False}
    assert s.client.put(f"{API}/practice/{s.record_id}/audio", content=second,
                        headers={**s.clinician, **WAV}).json()["sample_rate"] == 22_050
    assert s.client.get(f"{API}/practice/{s.record_id}/audio",
                        headers=s.child).content == second
    assert _kept_rows() == 1
    assert s.client.delete(f"{API}/practice/{s.record_id}/audio",
                           headers=s.child).status_code == 403
    assert s.client.delete(f"{API}/practice/{s.record_id}/audio",
                           headers=s.teacher).status_code == 204
    assert s.client.get(f"{API}/practice/{s.record_id}/audio",
                        headers=s.clinician).status_code == 404
    assert s.client.get(f"{API}/practice/{s.record_id}",
                        headers=s.clinician).json()["has_audio"] is False


def test_switching_off_keeps_what_was_kept_and_refuses_the_next(setting):
    s = setting
    _switch(s, True)
    assert s.client.put(f"{API}/practice/{s.record_id}/audio", content=tone_wav(8_000, 1),
                        headers={**s.child, **WAV}).status_code == 201
    _switch(s, False)
    assert s.client.get(f"{API}/practice/{s.record_id}/audio",
                        headers=s.clinician).status_code == 200
    assert s.client.put(f"{API}/practice/{s.record_id}/audio", content=tone_wav(8_000, 2),
                        headers={**s.child, **WAV}).status_code == 409
    assert s.client.get(f"{API}/practice/{s.record_id}/audio",
                        headers=s.clinician).content == tone_wav(8_000, 1)


def test_a_child_keeps_audio_only_for_their_own_record(setting):
    s = setting
    _switch(s, True)
    theirs = s.client.put(f"{API}/practice/{s.other_record_id}/audio",
                          content=tone_wav(16_000, 1), headers={**s.child, **WAV})
    assert theirs.status_code == 404 and _kept_rows() == 0
    assert s.client.get(f"{API}/practice/{s.record_id}/audio",
                        headers=s.other_child).status_code == 404


def test_deleting_the_practice_record_deletes_its_audio(setting):
    s = setting
    _switch(s, True)
    s.client.put(f"{API}/practice/{s.record_id}/audio", content=tone_wav(16_000, 1),
                 headers={**s.child, **WAV})
    assert _kept_rows() == 1
    assert s.client.delete(f"{API}/practice/{s.record_id}",
                           headers=s.clinician).status_code == 204
    assert _kept_rows() == 0


@pytest.mark.parametrize(("content", "status", "says"), [
    (b"", 422, "not a PCM WAV file"),
    (b"RIFF....WAVEfmt nonsense", 422, "not a PCM WAV file"),
    (tone_wav(16_000, 1, channels=2), 422, "2 channels, not 1 (mono)"),
    (tone_wav(16_000, 1, width=1), 422, "8-bit samples, not 16-bit"),
    (tone_wav(4_000, 1), 422, "4000 Hz, not 8000 to 48000 Hz"),
    (tone_wav(8_000, 31), 422, "lasts 31.0 s, more than 30 s"),
    (tone_wav(16_000, 1)[:20_000], 422, "cut short"),
])
def test_a_file_that_is_not_a_short_mono_16_bit_wav_is_refused_and_nothing_kept(
        setting, content, status, says):
    s = setting
    _switch(s, True)
    answer = s.client.put(f"{API}/practice/{s.record_id}/audio", content=content,
                          headers={**s.child, **WAV})
    assert answer.status_code == status and says in answer.json()["detail"]
    assert _kept_rows() == 0


def test_a_body_sent_as_another_type_or_past_the_limit_is_refused(setting):
    s = setting
    _switch(s, True)
    wrong_type = s.client.put(f"{API}/practice/{s.record_id}/audio", content=tone_wav(16_000, 1),
                              headers={**s.child, "Content-Type": "application/octet-stream"})
    assert wrong_type.status_code == 415 and "audio/wav" in wrong_type.json()["detail"]
    too_large = s.client.put(f"{API}/practice/{s.record_id}/audio",
                             content=b"\0" * (MAX_AUDIO_BYTES + 1), headers={**s.child, **WAV})
    assert too_large.status_code == 413
    assert _kept_rows() == 0
