"""The tongue: where its rig definition comes from, and the names the rest of the code uses.

- ``geometry.tongue_rig``: what the rig definition holds (and its parameter table);
- ``geometry.tongue_surface``: the reference evaluator (``TongueRig``);
- ``pipeline.tongue_rig``: the build step that fits the rest shape and writes the JSON.

``current_definition()`` reads ``<assets_dir>/tongue-rig.json`` (written by ``glasshead build``)
and, when it is absent, fits the rig in memory from the reference data (a few seconds, once per
process). Both are cached by path and modification time, so a rebuilt file is picked up.
"""

import json
from functools import lru_cache
from pathlib import Path

from glasshead.geometry.tongue_rig import validate_definition
from glasshead.geometry.tongue_surface import ParameterError, TongueRig, TongueSurface
from glasshead.settings import get_settings

RIG_FILE = "tongue-rig.json"

__all__ = ["RIG_FILE", "ParameterError", "TongueRig", "TongueSurface", "current_definition",
           "current_rig", "read_definition", "rig_path"]


def rig_path():
    """Where the build writes the rig definition."""
    return Path(get_settings().assets_dir) / RIG_FILE


def read_definition(path):
    """Read and validate a rig definition file; ValueError naming the file if it is not one."""
    path = Path(path)
    try:
        definition = json.loads(path.read_text())
        validate_definition(definition)
    except (json.JSONDecodeError, KeyError, TypeError, ValueError) as exc:
        raise ValueError(f"{path}: not a tongue rig definition ({exc})") from None
    return definition


@lru_cache(maxsize=4)
def _definition(path, modified, data_dir):
    if modified is not None:
        return read_definition(path)
    from glasshead.pipeline.tongue_rig import fit_definition

    return fit_definition(data_dir)


@lru_cache(maxsize=4)
def _rig(path, modified, data_dir):
    return TongueRig(_definition(path, modified, data_dir))


def _key():
    path = rig_path()
    modified = path.stat().st_mtime_ns if path.is_file() else None
    return str(path), modified, str(get_settings().data_dir)


def current_definition():
    """The rig definition the application serves (the built file, else fitted in memory)."""
    return _definition(*_key())


def current_rig():
    """A ``TongueRig`` for ``current_definition()`` (cached)."""
    return _rig(*_key())
