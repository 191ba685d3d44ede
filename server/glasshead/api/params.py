"""Articulation parameters as the routes take them: one check over every rig's parameter table.

A request's ``params`` map names to numbers across three rigs: the tongue rig (tongue and jaw),
the face rig (lips) and the velum rig (``velum_opening``). Each rig's table is read once per
version of its asset (``AssetStore.derived``), and only when a request names one of its
parameters, so a route that gets no lip or velum parameter never needs those assets.
``split_params`` checks the lip and velum values and returns the tongue's for the tongue rig
to check (its own messages) and each evaluator's share.
"""

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

from fastapi import HTTPException

from glasshead.asset_store import AssetStore
from glasshead.constants import FACE_RIG_LIP_PARAMETERS, VELUM_PARAMETER

#: The asset holding each parameter outside the tongue rig.
OTHER_RIGS = {**dict.fromkeys(FACE_RIG_LIP_PARAMETERS, "face_rig"), VELUM_PARAMETER: "velum_rig"}


def _table(assets: AssetStore, asset: str) -> dict:
    """name -> parameter spec of one rig's table, once per version of the asset."""
    def make(value) -> dict:
        # The tongue and velum rigs are loaded evaluators (``.definition``), the face rig a dict.
        definition = value if isinstance(value, Mapping) else value.definition
        return {p["name"]: p for p in definition["parameters"]}
    return assets.derived(asset, "parameter_table", make)


def _range_message(prefix: str, name: str, value: float, spec: Mapping) -> str | None:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        return f"{prefix}{name}: {value!r} is not a finite number"
    if not spec["min"] <= value <= spec["max"]:
        unit = "" if spec["unit"] == "ratio" else f" {spec['unit']}"
        return f"{prefix}{name}: {value:g} is outside [{spec['min']:g}, {spec['max']:g}]{unit}"
    return None


@dataclass
class SplitParams:
    """A request's parameters by evaluator: tongue (and jaw), lips, velum."""

    tongue: dict = field(default_factory=dict)
    lips: dict = field(default_factory=dict)
    velum: dict = field(default_factory=dict)


def split_params(assets: AssetStore, params: Mapping[str, float],
                 prefix: str = "params.") -> SplitParams:
    """Check the lip and velum parameters against their rigs' ranges (422 naming the parameter
    and its range, e.g. ``params.velum_opening: 1.5 is outside [0, 1]``) and split the set by
    evaluator. Names no other rig has go to ``tongue``, for the tongue rig to check."""
    split = SplitParams()
    for name, value in params.items():
        asset = OTHER_RIGS.get(name)
        if asset is None:
            split.tongue[name] = value
            continue
        spec = _table(assets, asset)[name]
        message = _range_message(prefix, name, value, spec)
        if message:
            raise HTTPException(status_code=422, detail=message)
        (split.velum if asset == "velum_rig" else split.lips)[name] = float(value)
    return split


def check_known_params(assets: AssetStore, params: Mapping[str, float],
                       prefix: str = "params.") -> None:
    """422 for a value out of range of any rig's parameter of that name (saved poses: names no
    rig has are kept as they are)."""
    split = split_params(assets, params, prefix)
    if not split.tongue:
        return
    table = _table(assets, "tongue_rig")
    for name, value in split.tongue.items():
        if name in table:
            message = _range_message(prefix, name, value, table[name])
            if message:
                raise HTTPException(status_code=422, detail=message)
