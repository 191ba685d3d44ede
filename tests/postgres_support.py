"""A throwaway PostgreSQL server for tests: initdb in a temporary directory, listening only on a
Unix socket in that directory, stopped and removed afterwards.

PostgreSQL refuses to run as root, so as root the server runs as the ``postgres`` user (Debian's
``postgresql`` package makes it) through ``runuser``, in a directory that user owns. Missing
binaries fail the test with what to install; nothing is skipped.
"""

import contextlib
import glob
import os
import pwd
import shutil
import subprocess
import tempfile
import uuid
from pathlib import Path

import pytest

#: Debian installs each major version's server binaries here.
BIN_GLOB = "/usr/lib/postgresql/*/bin"
PORT = 5432  # only names the socket file; nothing listens on TCP
INSTALL_HINT = ("PostgreSQL server binaries are missing (looked for initdb in "
                f"{BIN_GLOB}): install Debian's postgresql package "
                "(apt-get install postgresql), or run `node scripts/setup.mjs test`")


def server_binaries() -> Path:
    """The newest installed major version's bin directory; fails the test when there is none."""
    found = sorted((Path(p) for p in glob.glob(BIN_GLOB) if (Path(p) / "initdb").is_file()),
                   key=lambda p: int(p.parent.name) if p.parent.name.isdigit() else 0)
    if not found:
        pytest.fail(INSTALL_HINT)
    return found[-1]


class PostgresServer:
    """``start()`` makes and starts a cluster; ``url(database)`` is a SQLAlchemy URL over its
    socket; ``create_database()`` makes a fresh database; ``stop()`` stops and removes it all."""

    def __init__(self):
        self.bin = server_binaries()
        self.root = Path(tempfile.mkdtemp(prefix="glasshead-pg-"))
        self.data = self.root / "data"
        self.as_root = os.geteuid() == 0
        if self.as_root:
            try:
                user = pwd.getpwnam("postgres")
            except KeyError:
                pytest.fail("running as root, PostgreSQL needs the postgres user: "
                            + INSTALL_HINT)
            os.chown(self.root, user.pw_uid, user.pw_gid)

    def _run(self, *command: str, timeout: float = 60) -> str:
        prefix = ["runuser", "-u", "postgres", "--"] if self.as_root else []
        result = subprocess.run(prefix + list(command), capture_output=True, text=True,
                                timeout=timeout, cwd=self.root)
        if result.returncode != 0:
            raise RuntimeError(f"{' '.join(command)} failed:\n{result.stdout}{result.stderr}")
        return result.stdout

    def start(self) -> "PostgresServer":
        self._run(str(self.bin / "initdb"), "-D", str(self.data), "-U", "postgres",
                  "--auth=trust", "-E", "UTF8", "--no-sync", "--no-instructions")
        # Unix socket only, in our own directory; small, since the tests are small.
        options = (f"-k {self.root} -c listen_addresses='' -p {PORT} -c max_connections=60 "
                   "-c shared_buffers=16MB")
        self._run(str(self.bin / "pg_ctl"), "-D", str(self.data), "-o", options, "-w",
                  "-t", "60", "-l", str(self.root / "server.log"), "start")
        return self

    def url(self, database: str = "postgres") -> str:
        return f"postgresql+psycopg://postgres@/{database}?host={self.root}&port={PORT}"

    def psql(self, database: str, sql: str) -> str:
        return self._run(str(self.bin / "psql"), "-h", str(self.root), "-p", str(PORT),
                         "-U", "postgres", "-d", database, "-v", "ON_ERROR_STOP=1", "-At",
                         "-c", sql)

    def create_database(self) -> str:
        """A new empty database's name (one per test)."""
        name = f"test_{uuid.uuid4().hex[:12]}"
        self.psql("postgres", f"CREATE DATABASE {name}")
        return name

    def amcheck(self, database: str) -> str:
        """pg_amcheck over every table and index of ``database`` (installs the amcheck
        extension); raises when it finds corruption. Returns its output."""
        return self._run(str(self.bin / "pg_amcheck"), "-h", str(self.root), "-p", str(PORT),
                         "-U", "postgres", "--install-missing", "--heapallindexed", database)

    def stop(self) -> None:
        with contextlib.suppress(RuntimeError, subprocess.TimeoutExpired):
            self._run(str(self.bin / "pg_ctl"), "-D", str(self.data), "-m", "fast", "-w",
                      "stop", timeout=30)
        shutil.rmtree(self.root, ignore_errors=True)


@contextlib.contextmanager
def throwaway_postgres():
    """A started ``PostgresServer``, stopped and removed on leaving (a session fixture's body:
    ``with throwaway_postgres() as server: yield server``)."""
    server = PostgresServer()
    try:
        server.start()
        yield server
    finally:
        server.stop()
