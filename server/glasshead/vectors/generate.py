"""Writing the vector files, for ``glasshead vectors [FILE ...] [--list] [--out DIR]``."""

import importlib
import time
from pathlib import Path

from glasshead.vectors import GENERATORS, VECTOR_FILES
from glasshead.vectors.common import VECTORS_DIR, dumps
from glasshead.vectors.schema import check


def _produce(generator):
    module_name, function_name = generator.producer.split(":")
    return getattr(importlib.import_module(module_name), function_name)()


def generate(names=None, out_dir=VECTORS_DIR, log=print):
    """Write the named vector files (all when None or empty); returns the paths written.

    Each JSON document is checked against the schema before anything is written."""
    names = list(names or VECTOR_FILES)
    unknown = [n for n in names if n not in VECTOR_FILES]
    if unknown:
        raise ValueError(f"unknown vector file(s) {', '.join(unknown)}; known: "
                         f"{', '.join(VECTOR_FILES)}")
    chosen = [g for g in GENERATORS if set(g.files) & set(names)]
    written = []
    for step, generator in enumerate(chosen, 1):
        wanted = [name for name in generator.files if name in names]
        log(f"[{step}/{len(chosen)}] {', '.join(wanted)}")
        started = time.perf_counter()
        produced = _produce(generator)
        for name in wanted:
            content = produced[name]
            if isinstance(content, dict):
                content = dumps(check(content, name)).encode("utf-8")
            path = Path(out_dir) / name
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_bytes(content)
            written.append(path)
            log(f"    wrote {path} ({len(content):,} bytes)")
        log(f"    done in {time.perf_counter() - started:.1f} s")
    return written

