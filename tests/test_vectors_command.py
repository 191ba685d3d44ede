"""`glasshead vectors`: one command for every vector file, with progress and a clear error when
the reference data is missing."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from glasshead.settings import REPO_ROOT
from glasshead.vectors import VECTOR_FILES
from vector_support import assert_same_document, read_vectors, tol

pytestmark = pytest.mark.vectors
#: The installed command, beside the interpreter.
COMMAND = Path(sys.executable).with_name("glasshead")


def run(*args, env=None):
    return subprocess.run([str(COMMAND), "vectors", *args], cwd=REPO_ROOT,
                          capture_output=True, text=True, env={**os.environ, **(env or {})})


def test_it_lists_every_vector_file():
    result = run("--list")
    assert result.returncode == 0
    assert result.stdout.split() == list(VECTOR_FILES)


def test_it_writes_the_files_named_with_progress_and_the_committed_content(tmp_path):
    result = run("constants.json", "epg-indices.json", "--out", str(tmp_path))
    assert result.returncode == 0, result.stderr
    assert "[1/2] constants.json" in result.stdout and "[2/2] epg-indices.json" in result.stdout
    assert sorted(p.name for p in tmp_path.iterdir()) == ["constants.json", "epg-indices.json"]
    for name in ("constants.json", "epg-indices.json"):
        stored = read_vectors(name)
        written = json.loads((tmp_path / name).read_text())
        relative = tol(stored, "value" if name == "constants.json" else "index")
        assert_same_document(written, stored, atol=relative, rtol=relative, path=name)


def test_missing_reference_data_stops_it_with_the_path_and_what_to_set(tmp_path):
    missing = tmp_path / "no-data"
    result = run("epg-indices.json", "--out", str(tmp_path / "out"),
                 env={"GLASSHEAD_DATA_DIR": str(missing)})
    assert result.returncode == 2
    assert f"reference data not found: expected the directory {missing}" in result.stderr
    assert "GLASSHEAD_DATA_DIR" in result.stderr and "Traceback" not in result.stderr
    assert not (tmp_path / "out").exists()


def test_an_unknown_file_is_refused_with_the_known_ones():
    result = run("tongue.json")
    assert result.returncode == 2
    assert "unknown vector file(s) tongue.json; known: constants.json" in result.stderr
