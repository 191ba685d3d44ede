"""The layers hold: kernels import no pipeline, API or settings; routes import no other route and
no pipeline; the API reads built files only through the asset store."""

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "server" / "glasshead"


def imported_modules(path):
    """Every module a Python file imports, at any depth (function-level imports included)."""
    tree = ast.parse(path.read_text(), filename=str(path))
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            yield from (alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module:
            yield node.module
            yield from (f"{node.module}.{alias.name}" for alias in node.names)


def offending_imports(folder, forbidden):
    found = []
    for path in sorted((PACKAGE / folder).rglob("*.py")):
        for module in imported_modules(path):
            if any(module == f or module.startswith(f + ".") for f in forbidden):
                found.append(f"{path.relative_to(PACKAGE)} imports {module}")
    return found


@pytest.mark.parametrize("folder", ["geometry", "epg"])
def test_kernels_import_no_pipeline_api_or_settings(folder):
    forbidden = ["glasshead.pipeline", "glasshead.api", "glasshead.settings",
                 "glasshead.asset_store"]
    assert offending_imports(folder, forbidden) == []


def test_routes_import_no_other_route_and_no_pipeline():
    found = []
    for path in sorted((PACKAGE / "api" / "routes").glob("*.py")):
        for module in imported_modules(path):
            if module.startswith("glasshead.pipeline") or (
                    module.startswith("glasshead.api.routes.")
                    and module.split(".")[3] != path.stem):
                found.append(f"{path.name} imports {module}")
    assert found == []


def test_the_api_reads_no_settings_or_files_of_the_build_itself():
    """Routes get built assets from the store (AssetsDep), never from a path of their own."""
    found = []
    for path in sorted((PACKAGE / "api" / "routes").glob("*.py")):
        text = path.read_text()
        for needle in ("get_settings", "assets_dir", "read_text(", "read_bytes(", "lru_cache"):
            if needle in text:
                found.append(f"{path.name} uses {needle}")
    assert found == []


def test_the_checker_sees_a_function_level_import(tmp_path):
    sample = tmp_path / "sample.py"
    sample.write_text("def f():\n    from glasshead.pipeline.build import run\n    return run\n")
    assert "glasshead.pipeline.build" in set(imported_modules(sample))
