"""Copies of the built assets for tests that change or remove some of them.

The build directory also holds the speech cache (``utterances/``, written by any running server,
for example an end-to-end test's, while the Python tests run beside it): a copy leaves it out,
with any half-written file, so that a file that comes or goes during the copy cannot break it.
"""

import shutil
from pathlib import Path

#: What a copy of the built assets leaves out: the disposable speech cache and temporary files.
RUNTIME_FILES = ("utterances", "*.tmp")


def copy_built_assets(source: Path, target: Path, *also_leave_out: str) -> Path:
    """Copy the built assets at ``source`` to ``target`` without the runtime files (and
    ``also_leave_out``, glob patterns); returns ``target``."""
    shutil.copytree(source, target, ignore=shutil.ignore_patterns(*RUNTIME_FILES, *also_leave_out))
    return target
