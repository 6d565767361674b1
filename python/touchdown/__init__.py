"""Touchdown from Python: landings of the NASA TN D-7045 testbench on any engine, and the
shards of a campaign, computed by the project's Rust crates (the native module
`touchdown._native`, built by maturin from crates/python).

    import touchdown
    landing = touchdown.run("scenarios/table-i-2-2-vv8.toml", engine="core",
                            overrides={"touchdown.vertical_velocity": -10.0})
    landing["summary"]["max_primary_stroke_m"], landing["history"]["t_s"]

Errors are exceptions carrying what the command line prints: `ScenarioInvalid` (with `file`,
`field`, `message`), `LandingStopped` (with `time_s`, `law`, `leg`, `message`),
`EngineUnavailable`; all are `TouchdownError`. The calls release the interpreter's lock, so
threads land in parallel.
"""

import io
import json
from os import PathLike
from typing import Any, Mapping, Optional, Union

import numpy as np

from . import _native
from ._native import EngineUnavailable, LandingStopped, ScenarioInvalid, TouchdownError

__version__ = _native.__version__
__all__ = [
    "run",
    "TouchdownError",
    "ScenarioInvalid",
    "LandingStopped",
    "EngineUnavailable",
]


def _history(csv_text: str) -> dict:
    """The history's columns (units in their names) as NumPy arrays; an empty cell (an
    undefined stability distance) is NaN in its array."""
    data = np.genfromtxt(io.StringIO(csv_text), delimiter=",", names=True, dtype=float)
    return {name: np.asarray(data[name]) for name in data.dtype.names}


def run(
    scenario: Union[str, PathLike],
    engine: str = "core",
    overrides: Optional[Mapping[str, Any]] = None,
    history: bool = True,
) -> dict:
    """Lands `scenario` (a scenario file's path, or its TOML text without `extends`) on
    `engine` ("core", "rapier" or "mujoco"), with `overrides` (field path, e.g.
    "touchdown.attitude[2]", to value in the file's units). Returns {"summary": dict (as
    `touchdown run --format json`), "history": dict of NumPy arrays or None (MuJoCo, or
    history=False)}."""
    summary, csv_text = _native.run(str(scenario), engine, dict(overrides or {}), history)
    return {
        "summary": json.loads(summary),
        "history": _history(csv_text) if csv_text else None,
    }
