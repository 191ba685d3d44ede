"""Benchmark: a learner's palate rebuilt from a scan (pipeline.learner_palate), start to finish,
against the rebuild of the head's own palate's tables and electrodes (the build's two steps on
its maxilla) in the same run.

The scan is the CBCT subject's maxilla (``artisynth-dynjaw``, 17,992 triangles, as an OBJ): read,
registered on the head (the 24 orientations, the whole-maxilla ICP, the mouth-facing refinement),
written, and its collision tables and electrode layout built. Printed: the median seconds of
each, the registration's share and the ratio. The issue's goal: under 60 s on 2 cores. Checked:
the registration's residual within 1.5 mm RMS, and the tables and layout written.

    .venv/bin/python bench/learner_palate.py [runs]        (GLASSHEAD_BENCH_QUICK=1: 1 run)
"""

import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

GOAL_S = 60.0
QUICK = os.environ.get("GLASSHEAD_BENCH_QUICK") == "1"


def main():
    from glasshead.constants import COLLISION_TABLES_FILE, EPG_LAYOUT_FILE
    from glasshead.pipeline.collision_tables import build_collision_tables, load_scene_maxilla
    from glasshead.pipeline.epg_layout import build_epg_layout
    from glasshead.pipeline.learner_palate import build_learner_palate
    from glasshead.settings import get_settings

    runs = 1 if QUICK else int(sys.argv[1]) if len(sys.argv) > 1 else 3
    settings = get_settings()
    scan = (settings.data_dir / "anatomy" / "artisynth-dynjaw" / "maxilla.obj").read_bytes()
    vertices, faces = load_scene_maxilla(settings.assets_dir)
    learner, registering, own, reports = [], [], [], []
    with tempfile.TemporaryDirectory() as scratch:
        for run in range(runs):
            marks: dict[str, float] = {}

            def mark(step, share, marks=marks):
                marks.setdefault(step, time.perf_counter())

            start = time.perf_counter()
            report = build_learner_palate(
                scan, "obj", settings.assets_dir, Path(scratch) / f"learner-{run}", progress=mark)
            learner.append(time.perf_counter() - start)
            registering.append(marks["building the collision tables"] - marks["reading the scan"])
            reports.append((report, Path(scratch) / f"learner-{run}"))
            start = time.perf_counter()
            build_collision_tables(vertices, faces, Path(scratch) / f"own-{run}")
            build_epg_layout(vertices, faces, Path(scratch) / f"own-{run}")
            own.append(time.perf_counter() - start)
        ours, baseline = statistics.median(learner), statistics.median(own)
        print(f"learner palate: the CBCT subject's maxilla as a scan, median of {runs} run(s)")
        print(f"  scan to tables and electrodes  {ours:6.2f} s  (registration "
              f"{statistics.median(registering):.2f} s)")
        print(f"  the head's own tables and electrodes  {baseline:6.2f} s")
        print(f"  ratio  {ours / baseline:.1f}x; goal < {GOAL_S:.0f} s: "
              f"{'met' if ours < GOAL_S else 'NOT met'}")
        ok = all(r["registration"]["mouth_facing_residual"]["rms_mm"] <= 1.5
                 and (out / COLLISION_TABLES_FILE).is_file() and (out / EPG_LAYOUT_FILE).is_file()
                 for r, out in reports)
    print(f"check: registered within 1.5 mm RMS, tables and layout written: "
          f"{'ok' if ok else 'FAILED'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
