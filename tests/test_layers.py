"""The layers hold: the import contracts of pyproject.toml ([tool.importlinter], which
`lint-imports` checks with indirect imports too) on every module's direct imports, function-level
ones included; routes import no other route and no pipeline; the API reads built files only
through the asset store."""

import ast
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "server" / "glasshead"
CONTRACTS = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["importlinter"][
    "contracts"]
FORBIDDEN = [c for c in CONTRACTS if c["type"] == "forbidden"]
LAYERS = [[name.strip() for name in layer.split("|")]
          for layer in next(c for c in CONTRACTS if c["type"] == "layers")["layers"]]


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


def folder_of(module):
    return module.removeprefix("glasshead.").replace(".", "/")


@pytest.mark.parametrize("contract", FORBIDDEN, ids=[c["name"] for c in FORBIDDEN])
def test_no_module_imports_what_its_contract_forbids(contract):
    found = []
    for source in contract["source_modules"]:
        found += offending_imports(folder_of(source), contract["forbidden_modules"])
    assert found == []


def test_the_layers_name_every_package_once():
    named = [name for layer in LAYERS for name in layer]
    packages = sorted(f"glasshead.{path.parent.name}" for path in PACKAGE.glob("*/__init__.py"))
    assert sorted(named) == packages


@pytest.mark.parametrize("depth", range(len(LAYERS)))
def test_a_package_imports_no_package_above_it_nor_one_beside_it(depth):
    above = [name for layer in LAYERS[:depth] for name in layer]
    found = []
    for package in LAYERS[depth]:
        beside = [name for name in LAYERS[depth] if name != package]
        found += offending_imports(folder_of(package), above + beside)
    assert found == []


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
