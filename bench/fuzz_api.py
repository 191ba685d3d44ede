"""Fuzzing benchmark: the suite's schemathesis run (tests/test_api_openapi_conformance.py) at a
larger scale, every phase (examples, coverage, fuzzing, stateful) as every caller (no token,
author, teacher, clinician, admin, a child), on the document as served (texts up to their full
500 characters).

Scale (BENCH there): 200 cases per operation and phase on the operations a caller may call, 5
on the others, invalid requests in every caller's coverage phase, 50 stateful sequences of at
most 12 requests per caller and group of operations. One app in this process, on the built
assets and a new SQLite database, one compute worker and no fit worker, as in the suite.

Prints, per caller: the operations called, the requests sent per phase, the answers per status,
how many of the operations that take an id were called with one from an earlier answer (and
answered 2xx), every failure found (with a curl command that repeats it), and the CPU seconds;
then the totals. Exits 1 when a request got a server error, an undocumented status, content type
or body, or no answer, or the engine failed.

    .venv/bin/python bench/fuzz_api.py [caller ...]
    GLASSHEAD_BENCH_QUICK=1: as admin only, one case per operation and phase, one stateful
    sequence per group, no coverage phase (the suite runs it).
"""

import os
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
QUICK = os.environ.get("GLASSHEAD_BENCH_QUICK") == "1"


def main() -> int:
    sys.path.insert(0, str(REPO / "tests"))
    import test_api_openapi_conformance as fuzzing
    from glasshead.settings import get_settings

    assets = get_settings().assets_dir
    if not (assets / "manifest.json").is_file():
        sys.exit(f"{assets}/manifest.json is missing: run `glasshead build` first")
    callers = sys.argv[1:] or (["admin"] if QUICK else list(fuzzing.CALLERS))
    scale = fuzzing.Scale(examples=1, other_examples=1, scenarios=1) if QUICK else fuzzing.BENCH
    phases = ("examples", "fuzzing", "stateful") if QUICK else fuzzing.PHASES
    print(f"schemathesis on {len(fuzzing.OPERATION_IDS)} operations, phases "
          f"{', '.join(phases)}; {scale.examples} cases per operation and phase "
          f"({scale.other_examples} on a caller's others), {scale.scenarios} stateful sequences "
          f"of at most {scale.steps} requests per caller and group, seed {fuzzing.SEED}")
    started = time.perf_counter()
    totals, problems, cpu = Counter(), [], 0.0
    with tempfile.TemporaryDirectory(prefix="glasshead-bench-fuzz-") as folder, \
            fuzzing.app_for_fuzzing(Path(folder), assets) as (app, engine):
        for caller in callers:
            begun = time.perf_counter()
            outcome = fuzzing.fuzz(app, engine, caller, scale, phases)
            ids = fuzzing.id_operations(caller)
            reached = outcome.reached() & ids
            sent = sum(outcome.cases.values())
            totals.update(outcome.cases)
            problems += outcome.problems()
            cpu += outcome.seconds
            print(f"\n{caller}: {len(outcome.operations)} operations, {sent} requests "
                  f"({', '.join(f'{p} {n}' for p, n in outcome.cases.items())}), "
                  f"{len(outcome.problems())} failures, {outcome.seconds:.0f} s CPU, "
                  f"{time.perf_counter() - begun:.0f} s")
            print("  answers: " + ", ".join(f"{status} x{count}" for status, count
                                           in sorted(outcome.statuses.items())))
            print(f"  operations with an id called with one from an earlier answer: "
                  f"{len(reached)} of {len(ids)}"
                  + (f"; not: {', '.join(sorted(ids - reached))}" if ids - reached else ""))
            for problem in outcome.problems():
                print("  FAILURE " + problem.replace("\n", "\n    "))
            sys.stdout.flush()
    print(f"\nall: {len(callers)} callers, {sum(totals.values())} requests "
          f"({', '.join(f'{p} {n}' for p, n in totals.items())}), {len(problems)} failures, "
          f"{cpu:.0f} s CPU in this process, {time.perf_counter() - started:.0f} s")
    print(f"check: no server error, undocumented answer or unanswered request: "
          f"{'ok' if not problems else 'FAILED'}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
