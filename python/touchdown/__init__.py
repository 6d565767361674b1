"""Touchdown from Python: landings of the NASA TN D-7045 testbench on any engine, and the
shards of a campaign, computed by the project's Rust crates (the native module
`touchdown._native`, built by maturin from crates/python).

    import touchdown
    landing = touchdown.run("scenarios/table-i-2-2-vv8.toml", engine="core",
                            overrides={"touchdown.vertical_velocity": -10.0})
    landing["summary"]["max_primary_stroke_m"], landing["history"]["t_s"]
    touchdown.run(path, frame="pandas")["history"]      # a pandas (or "polars") frame
    touchdown.compare(path, engines=("core", "rapier"))  # as `touchdown compare --format json`
    touchdown.boundary(path, vv=[6.0, 8.0])              # as `touchdown boundary --format json`

Errors are exceptions carrying what the command line prints: `ScenarioInvalid` (with `file`,
`field`, `message`), `LandingStopped` (with `time_s`, `law`, `leg`, `message`),
`EngineUnavailable`; all are `TouchdownError`. The calls release the interpreter's lock, so
threads land in parallel.
"""

import io
import json
from numbers import Real
from os import PathLike
from typing import Any, Mapping, Optional, Sequence, Union

import numpy as np

from . import _arguments as a
from . import _native
from ._native import EngineUnavailable, LandingStopped, ScenarioInvalid, TouchdownError

__version__ = _native.__version__
__all__ = [
    "run",
    "check",
    "compare",
    "view",
    "boundary",
    "TouchdownError",
    "ScenarioInvalid",
    "LandingStopped",
    "EngineUnavailable",
]


def _history(csv_text: str, frame: Optional[str]) -> Any:
    """The history's columns (units in their names): a dict of NumPy arrays, or a pandas or
    polars frame; an empty cell (an undefined stability distance) is NaN."""
    data = np.genfromtxt(io.StringIO(csv_text), delimiter=",", names=True, dtype=float)
    columns = {name: np.asarray(data[name]) for name in data.dtype.names}
    if frame is None:
        return columns
    if frame == "pandas":
        import pandas

        return pandas.DataFrame(columns)
    if frame == "polars":
        import polars

        return polars.DataFrame(columns)
    raise ValueError(f'frame: expected None, "pandas" or "polars", got {frame!r}')


def run(
    scenario: Union[str, PathLike],
    engine: str = "core",
    overrides: Optional[Mapping[str, Any]] = None,
    history: bool = True,
    frame: Optional[str] = None,
    rounding: bool = False,
) -> dict:
    """Lands `scenario` (a scenario file's path, or its TOML text without `extends`: text spans
    lines, and a one-line string naming no file raises FileNotFoundError) on
    `engine` ("core", "rapier" or "mujoco"), with `overrides` (field path, e.g.
    "touchdown.attitude[2]", to value in the file's units). Returns {"summary": dict (as
    `touchdown run --format json`, docs/schemas/run.schema.json), "history": the history (a dict of NumPy arrays, or with
    `frame="pandas"` or `"polars"` a frame of that package), or None (MuJoCo, or
    history=False)}. With `rounding=True` the summary also has `rounding`, as `touchdown run
    --rounding` gives it: the maxima that a unit in the last place of the touchdown velocity
    moves by more than their compare tolerance (three more landings; docs/engines.md,
    "Rounding-decided channels")."""
    if frame not in (None, "pandas", "polars"):
        raise ValueError(f'frame: expected None, "pandas" or "polars", got {frame!r}')
    summary, csv_text = _native.run(
        a.path("scenario", scenario),
        a.text("engine", engine),
        a.mapping("overrides", overrides),
        a.flag("history", history),
        a.flag("rounding", rounding),
    )
    return {
        "summary": json.loads(summary),
        "history": _history(csv_text, frame) if csv_text else None,
    }


def check(scenario: Union[str, PathLike], overrides: Optional[Mapping[str, Any]] = None) -> dict:
    """Reviews `scenario` (a path, or TOML text) with `overrides` before it lands: the gear's
    crush load against the weight, its stroke energy against the touchdown energy, the static
    tip-over angle against the slope, the principal moments, and every finding with the file
    that set the value; the document `touchdown check --format json` prints
    (docs/schemas/check.schema.json). Nothing is landed."""
    return json.loads(_native.check(a.path("scenario", scenario), a.mapping("overrides", overrides)))


def compare(
    scenario: Union[str, PathLike],
    engines: Sequence[str] = ("core", "rapier", "mujoco"),
    overrides: Optional[Mapping[str, Any]] = None,
) -> dict:
    """Lands `scenario` (a path, or TOML text) with `overrides` on each of `engines` that its
    `engines.applicable` lists and compares every pair channel by channel against the written
    tolerances (docs/engines.md, "Comparing the engines"): the document `touchdown compare
    --format json` prints for the scenario (docs/schemas/compare.schema.json)."""
    return json.loads(
        _native.compare(a.path("scenario", scenario), a.texts("engines", engines), a.mapping("overrides", overrides))
    )


def view(
    scenario: Union[str, PathLike],
    engines: Sequence[str] = ("core", "rapier", "mujoco"),
    overrides: Optional[Mapping[str, Any]] = None,
    frame_interval: float = 1.0e-3,
) -> dict:
    """A landing to watch, as `touchdown view` writes it: `scenario` (a path, or TOML text) with
    `overrides` on each of `engines` that its `engines.applicable` lists, a frame kept every
    `frame_interval` s of landing (every contact event besides). Returns `{"trajectory": ...,
    "html": ...}`: the trajectory document (docs/schemas/trajectory.schema.json) and the
    self-contained page that plays it (write it to a file and open it in a browser, or show it
    in a notebook: `IPython.display.IFrame` of the file, docs/python.md)."""
    data, html = _native.view(
        a.path("scenario", scenario),
        a.texts("engines", engines),
        a.number("frame_interval", frame_interval),
        a.mapping("overrides", overrides),
    )
    return {"trajectory": json.loads(data), "html": html}


def boundary(
    scenario: Union[str, PathLike],
    vv: Union[float, Sequence[float]],
    vh_start: Optional[float] = None,
    vh_step: Optional[float] = None,
    vh_max: Optional[float] = None,
    tol: Optional[float] = None,
    engines: Sequence[str] = ("core",),
    overrides: Optional[Mapping[str, Any]] = None,
    scan_step: Optional[float] = None,
    stop_restitution: Sequence[float] = (),
) -> list:
    """The report's stability-boundary search of `scenario` (a path, or TOML text) with
    `overrides`, as `touchdown boundary --format json` does: at each vertical velocity of `vv`
    (negative down, as the scenario files write `touchdown.vertical_velocity`; one number or a
    list), the horizontal
    speeds on the grid `vh_start`, `vh_start + vh_step`, ... up to `vh_max`, scanned every
    `scan_step` around the changes the grid finds (0: the grid only), every change of outcome
    and the first speed past a strut's capacity bisected to `tol`, once per end-stop
    restitution of `stop_restitution` (empty: the scenario's own); the settings in the
    scenario's length unit per second, the horizontal direction the scenario's. A setting left
    None takes the command's default, a ratio of the vehicle's velocity scale
    √(g·footprint radius): `vh_start` 0, `vh_step` 0.25, `vh_max` 3.5, `tol` 0.006 (2.11, 29.6
    and 0.051 ft/s on the 1/6-scale model), `scan_step` an eighth of `vh_step`.
    One dict per engine, restitution and vertical velocity, the command's JSON Lines document
    (docs/schemas/boundary.schema.json): in SI, `vv_m_s`, `vh_m_s` (the boundary, absent if
    none), `stable_at_vh_m_s`, `unstable_at_vh_m_s`, `transitions` (each end with its
    `stable_stops` / `unstable_stops`), `band`, `capacity`, `safe`, `undecided_at_vh_m_s`,
    `landings`, `undecided`, with the scenario and the settings."""
    if isinstance(vv, Real) and not isinstance(vv, bool):
        vv = [vv]  # one vertical velocity, as a list of one
    lines = _native.boundary(
        a.path("scenario", scenario),
        a.numbers("vv", vv),
        a.optional_number("vh_start", vh_start),
        a.optional_number("vh_step", vh_step),
        a.optional_number("vh_max", vh_max),
        a.optional_number("tol", tol),
        a.texts("engines", engines),
        a.mapping("overrides", overrides),
        a.optional_number("scan_step", scan_step),
        a.numbers("stop_restitution", stop_restitution),
    )
    return [json.loads(line) for line in lines]
