"""The build report without the building machine's absolute paths.

Steps report the files they wrote or read as paths; ``portable`` rewrites each string that is an
absolute path under the assets directory, the data directory or the repository as a path relative
to it (``tongue-rig.json``, ``anatomy/artisynth-badin/tongue.obj``), so that a report copied from
one machine to another (or served) tells nothing about where it was built.
"""

from pathlib import Path, PurePosixPath

from glasshead.settings import REPO_ROOT


def portable(report, *, assets_dir, data_dir):
    """A copy of ``report`` (JSON-like: dicts, lists, strings, numbers) with every absolute
    path under ``assets_dir``, ``data_dir`` or the repository made relative to it."""
    roots = [Path(assets_dir).resolve(), Path(data_dir).resolve(), REPO_ROOT]

    def visit(value):
        if isinstance(value, dict):
            return {key: visit(item) for key, item in value.items()}
        if isinstance(value, list):
            return [visit(item) for item in value]
        if isinstance(value, str) and value.startswith("/"):
            return _relative(value, roots)
        return value

    return visit(report)


def _relative(text: str, roots: list[Path]) -> str:
    path = Path(text)
    for candidate in (path, path.resolve()):
        for root in roots:
            if candidate == root or root in candidate.parents:
                return str(PurePosixPath(*candidate.relative_to(root).parts)) or "."
    return text
