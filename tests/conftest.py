"""Shared fixtures: the reference data (required, never skipped) and the built assets."""

import json
from pathlib import Path

import pytest

from glasshead.settings import get_settings


@pytest.fixture(scope="session")
def data_dir() -> Path:
    """The reference data directory; a missing one fails the test with the path expected."""
    path = get_settings().data_dir
    if not (path / "anatomy" / "artisynth-badin").is_dir():
        pytest.fail(f"reference data missing: expected {path} (set GLASSHEAD_DATA_DIR)")
    return path


@pytest.fixture(scope="session")
def built_assets(data_dir) -> Path:
    """The assets directory after `glasshead build` (instant when already up to date)."""
    from glasshead.pipeline.build import run

    assets = get_settings().assets_dir
    run(data_dir, assets, log=lambda message: None)
    return assets


@pytest.fixture(scope="session")
def manifest(built_assets) -> dict:
    return json.loads((built_assets / "manifest.json").read_text())


@pytest.fixture(scope="session")
def build_report(built_assets) -> dict:
    return json.loads((built_assets / "build-report.json").read_text())
