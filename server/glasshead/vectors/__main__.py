"""``python -m glasshead.vectors [FILE ...] [--list] [--out DIR]``: regenerate the vectors."""

import argparse
import importlib
import sys
import time
from pathlib import Path

from glasshead.vectors import GENERATORS, VECTOR_FILES
from glasshead.vectors.common import VECTORS_DIR, dumps
from glasshead.vectors.schema import VectorSchemaError, check


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


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m glasshead.vectors",
                                     description="Regenerate the shared test vectors.")
    parser.add_argument("names", nargs="*", metavar="FILE",
                        help="vector files to write (default: all)")
    parser.add_argument("--out", default=str(VECTORS_DIR), help="output directory")
    parser.add_argument("--list", action="store_true", help="list the files and stop")
    args = parser.parse_args(argv)
    if args.list:
        print("\n".join(VECTOR_FILES))
        return 0
    try:
        written = generate(args.names, args.out)
    except (ValueError, RuntimeError, VectorSchemaError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    print(f"wrote {len(written)} vector files")
    return 0


if __name__ == "__main__":
    sys.exit(main())
