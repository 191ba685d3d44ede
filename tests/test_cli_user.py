"""`glasshead user create`: the first admin from the command line, with clear errors."""

import io

import pytest
from sqlalchemy import select
from sqlalchemy.orm import Session

from glasshead import accounts
from glasshead.cli import main
from glasshead.settings import get_settings
from glasshead.store.db import engine_for
from glasshead.store.users import User

PASSWORD = "correct horse battery"


@pytest.fixture
def database(tmp_path, monkeypatch):
    url = f"sqlite:///{tmp_path / 'cli.sqlite3'}"
    monkeypatch.setenv("GLASSHEAD_DATABASE_URL", url)
    get_settings.cache_clear()
    yield engine_for(url)
    get_settings.cache_clear()


def users(engine) -> list[User]:
    with Session(engine) as session:
        return list(session.scalars(select(User)))


def test_an_admin_is_created_with_the_password_from_stdin(database, monkeypatch, capsys):
    monkeypatch.setattr("sys.stdin", io.StringIO(PASSWORD + "\n"))
    code = main(["user", "create", "--role", "admin", "--display-name", "Head Office",
                 "--password-stdin", "Admin@School.example"])
    assert code == 0
    assert "created admin admin@school.example (user 1)" in capsys.readouterr().err
    [user] = users(database)
    assert (user.username, user.display_name, user.role) == ("admin@school.example",
                                                             "Head Office", "admin")
    assert accounts.verify_password(user.password_hash, PASSWORD)


def test_the_prompted_password_is_asked_twice_and_must_match(database, monkeypatch, capsys):
    answers = iter([PASSWORD, PASSWORD + "?"])
    monkeypatch.setattr("getpass.getpass", lambda prompt: next(answers))
    assert main(["user", "create", "--role", "admin", "root"]) == 1
    assert "the two passwords differ; nothing was stored" in capsys.readouterr().err
    answers = iter([PASSWORD, PASSWORD])
    assert main(["user", "create", "--role", "admin", "root"]) == 0
    assert [u.username for u in users(database)] == ["root"]


def test_a_taken_username_or_a_short_password_is_an_error_that_stores_nothing(
        database, monkeypatch, capsys):
    monkeypatch.setattr("sys.stdin", io.StringIO(PASSWORD + "\n"))
    assert main(["user", "create", "--role", "teacher", "--password-stdin", "ann"]) == 0
    monkeypatch.setattr("sys.stdin", io.StringIO(PASSWORD + "\n"))
    assert main(["user", "create", "--role", "admin", "--password-stdin", "ANN"]) == 1
    assert "error: username 'ann' is taken; nothing was stored" in capsys.readouterr().err
    monkeypatch.setattr("sys.stdin", io.StringIO("short\n"))
    assert main(["user", "create", "--role", "admin", "--password-stdin", "bob"]) == 1
    assert "8 to 1024 characters; this one has 5" in capsys.readouterr().err
    assert [u.role for u in users(database)] == ["teacher"]


def test_an_unknown_role_is_refused_by_the_parser(database, capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["user", "create", "--role", "pupil", "--password-stdin", "bob"])
    assert exit_.value.code == 2 and "invalid choice: 'pupil'" in capsys.readouterr().err
