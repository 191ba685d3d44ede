"""gzip siblings of the built files, written once at build time and served by api/static.py.

A file ``name`` of a compressible kind gets ``name.gz`` beside it (gzip level 9, mtime 0, so the
same bytes always give the same sibling). The server serves the sibling, with
``Content-Encoding: gzip``, to a request whose ``Accept-Encoding`` allows it; a sibling older than
its file is stale and never served (``fresh_sibling``), so a rebuilt file that has not been
compressed again is served plain rather than out of date. Files that gzip cannot shrink by
``MIN_SAVING`` keep no sibling. Measured: the built assets 12.6 MB -> 5.1 MB (the collision
tables 2.92 -> 1.25 MB), the web bundle 0.93 -> 0.26 MB (three.js's chunk 760 -> 198 kB).

Run at the end of every ``glasshead build`` (even one that finds the assets up to date) and after
``vite build`` (web/vite.config.js does the same for the bundle). A module of its own, not of the
pipeline, since the server reads its rules too (``fresh_sibling``).
"""

import gzip
import os
from pathlib import Path

#: Suffixes of the files worth compressing: meshes, tables, JSON, the web app's text.
SUFFIXES = frozenset({".glb", ".bin", ".json", ".html", ".js", ".css", ".svg", ".txt", ".csv"})
#: Files smaller than this are served as they are.
MIN_SIZE = 1024
#: A sibling is written only when it saves at least this share of the file.
MIN_SAVING = 0.05
LEVEL = 9


def sibling(path: Path) -> Path:
    return path.with_name(path.name + ".gz")


def fresh_sibling(path: Path) -> Path | None:
    """The ``.gz`` sibling of ``path`` when it exists and is not older than the file, else None."""
    gz = sibling(path)
    try:
        return gz if gz.stat().st_mtime_ns >= path.stat().st_mtime_ns else None
    except FileNotFoundError:
        return None


def precompress(directory, recursive: bool = True) -> dict:
    """Write the missing or stale ``.gz`` siblings under ``directory``; remove those whose file
    is gone. Returns ``{"files": n, "written": n, "bytes": plain, "gzip_bytes": compressed}``
    over the files that have a sibling."""
    directory = Path(directory)
    summary = {"files": 0, "written": 0, "bytes": 0, "gzip_bytes": 0}
    if not directory.is_dir():
        return summary
    paths = sorted(directory.rglob("*") if recursive else directory.iterdir())
    for path in paths:
        if path.name.startswith(".") or not path.is_file():
            continue
        if path.suffix == ".gz":
            if not path.with_suffix("").exists():
                path.unlink()
            continue
        if path.suffix not in SUFFIXES or path.stat().st_size < MIN_SIZE:
            continue
        gz = fresh_sibling(path)
        if gz is None:
            data = path.read_bytes()
            packed = gzip.compress(data, compresslevel=LEVEL, mtime=0)
            if len(packed) > (1 - MIN_SAVING) * len(data):
                sibling(path).unlink(missing_ok=True)
                continue
            temporary = path.with_name(f".{path.name}.gz.tmp")
            temporary.write_bytes(packed)
            os.replace(temporary, sibling(path))
            summary["written"] += 1
            gz = sibling(path)
        summary["files"] += 1
        summary["bytes"] += path.stat().st_size
        summary["gzip_bytes"] += gz.stat().st_size
    return summary

