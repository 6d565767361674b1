#!/usr/bin/env python3
"""Engine-comparison plots for Touchdown (`touchdown compare --plot`, `touchdown boundary --plot`,
`touchdown precision --plot`).

Three kinds, all drawn from data the `touchdown` CLI writes, so that a plot shows exactly the
series, verdicts and boundaries the Rust side measured (nothing is recomputed here):

* traces      one landing on several engines, overlaid: the vertical acceleration over the
              comparison's window, the pitch rate, and every leg's primary stroke against
              time. Legs of one engine whose stroke traces coincide (within LEG_TOLERANCE_M over
              the whole trace) are drawn as one line named "legs 1, 2 (identical)"; every other
              leg has its own line style. Beside each panel, the PASS/FAIL of every pair of
              engines on that panel's channels against their tolerances, when the comparison
              report is given (--report). Input: `<stem>.<engine>.csv` per engine
              (touchdown_compare::plot), and optionally the JSON of `touchdown compare
              --format json`.
* boundaries  the stability boundary of one configuration computed by each engine, overlaid:
              descent speed against the horizontal speed at which the landing turns unstable
              (the lowest stable -> unstable transition), every transition's bracket, the
              further transitions, the unresolved brackets, the undecided landings and the
              speeds stable on the whole grid, each kind of mark with a legend entry, and each
              engine's landing and undecided counts in its legend entry. Input: the JSON of
              `touchdown boundary --engines ... --format json` (one point per engine and
              descent speed, each naming its engine).
* precision   work-precision: log-log error against wall time, one line per engine and
              scheme over its ladder of steps or tolerances (strokes; pitch-rate history;
              final attitude), every rung labelled with its step or tolerance, failed rungs
              left out and listed, the 1 % stroke error marked. Input: the JSON of
              `touchdown precision --format json`.

Usage:
  python/figures/plot_compare.py traces --data DIR --stem STEM --engines core,rapier,mujoco \
      [--title TITLE] --out FILE.png [--report COMPARE.json]
  python/figures/plot_compare.py boundaries --data FILE.json --unit ft/s --title TITLE --out FILE.png
  python/figures/plot_compare.py precision --data FILE.json --title TITLE --out FILE.png

`touchdown boundary --plot` passes the title "<scenario name>\\nstability boundary per engine";
the plot is titled with the configuration (the scenario's name without its own touchdown
speeds, which the search replaces), the speeds varied, what is held, and the engines.

The input files' field names are read in one function per input (read_trace,
read_comparison_verdicts, read_boundary_points, read_precision_study): a renamed field is
changed there and nowhere else.

Run it with the project's venv (`scripts/setup-python`, then `.venv/bin/python`); the CLI does.
The output is deterministic as far as matplotlib allows: Agg backend, fixed sizes and DPI, no
software stamp in the PNG metadata.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import re
import sys
import textwrap
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402  (after selecting the backend)
from matplotlib.legend_handler import HandlerLine2D  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter  # noqa: E402

DPI = 110
PNG_METADATA = {"Software": None}
# One colour per engine, the same in every plot; one line style per leg.
COLOURS = {"core": "#1f3b73", "rapier": "#d95f02", "mujoco": "#1b9e77"}
ENGINE_NAMES = {"core": "core", "rapier": "rapier", "mujoco": "MuJoCo"}
LEG_STYLES = ["-", "--", ":", "-."]
# Two legs' stroke traces closer than this everywhere are drawn as one line (0.1 mm: under a
# pixel of the stroke panel for any stroke worth plotting).
LEG_TOLERANCE_M = 1.0e-4
# Colour of the marks that mean the same on every engine (boundary legend), and of the verdicts.
NEUTRAL = "0.3"
C_PASS = "#d9f0d3"
C_FAIL = "#f4c7c3"
C_NOT_DETERMINED = "#e6e6e6"
# A verdict as the figures write it and colour it.
VERDICT_WORDS = {"pass": "PASS", "fail": "FAIL", "not_determined": "NOT DETERMINED"}
VERDICT_COLOURS = {"pass": C_PASS, "fail": C_FAIL, "not_determined": C_NOT_DETERMINED}


def engine_name(engine: str) -> str:
    return ENGINE_NAMES.get(engine, engine)


# --------------------------------------------------------------------------------------------
# Inputs: every field name of the files the CLI writes is read here, one function per input.


def read_trace(path: Path) -> dict:
    """One engine's trace CSV (`<stem>.<engine>.csv`, touchdown_compare::plot) as
    {"t": [s], "pitch_rate": [rad/s], "strokes": {leg number: [m]}, "acc_t": [s],
    "acc": [m/s², up +]} (empty cells dropped from their column)."""
    with path.open(newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit(f"plot_compare: {path} has no rows")

    def column(name: str) -> list[float]:
        if name not in rows[0]:
            raise SystemExit(f"plot_compare: {path} has no column {name!r}")
        return [float(r[name]) for r in rows if r[name] != ""]

    legs = {}
    for name in rows[0]:
        m = re.fullmatch(r"leg(\d+)_primary_stroke_m", name)
        if m:
            legs[int(m.group(1))] = column(name)
    return {
        "t": column("t_s"),
        "pitch_rate": column("pitch_rate_rad_s"),
        "strokes": dict(sorted(legs.items())),
        # The window centred on t: empty within half a window of either end.
        "acc_t": [float(r["t_s"]) for r in rows if r["vertical_acceleration_m_s2"] != ""],
        "acc": column("vertical_acceleration_m_s2"),
    }


def channel_key(ch: dict) -> str:
    """A channel of the comparison's document as this script names it: its quantity, and for a
    stroke its leg and strut ("primary_stroke leg 1"), for an energy its account, for a
    pitch-rate extreme its sense ("peak_pitch_rate negative")."""
    key = ch["quantity"]
    if "leg" in ch:
        key += f" leg {ch['leg']}"
        if ch.get("strut", "primary") != "primary":
            key += f" {ch['strut']}"
    if "account" in ch:
        key += f" {ch['account']}"
    if "sense" in ch:
        key += f" {ch['sense']}"
    return key


def read_comparison_verdicts(path: Path) -> dict:
    """The verdicts of the comparison's document (`<stem>.json`, a line of `touchdown compare
    --format json`, docs/schemas/compare.schema.json) as {"scenario": its name, "pairs": [{"a",
    "b", "verdict", "outcome_agrees", "channels": {key (channel_key): {"difference", "tolerance",
    "verdict"}}}], "units": {key: the unit of its difference and tolerance},
    "acceleration_window_s": the window of the vertical acceleration}; a verdict is "pass",
    "fail" or "not_determined" (rounding decides it: docs/engines.md, "Rounding-decided
    channels")."""
    entry = json.loads(path.read_text())
    pairs, units = [], {}
    for p in entry["pairs"]:
        channels = {}
        for ch in p["channels"]:
            key = channel_key(ch)
            channels[key] = {"difference": ch["difference"], "tolerance": ch["tolerance"], "verdict": ch["verdict"]}
            units[key] = ch["difference_unit"]
        pairs.append(
            {
                "a": p["a"],
                "b": p["b"],
                "verdict": p["verdict"],
                "outcome_agrees": p["outcome_agrees"],
                "channels": channels,
            }
        )
    return {
        "scenario": entry["scenario_name"],
        "pairs": pairs,
        "units": units,
        "acceleration_window_s": entry["acceleration_window_s"],
    }


# Metres per second of the velocity units a scenario may state.
VELOCITY_UNITS = {"m/s": 1.0, "ft/s": 0.3048, "in/s": 0.0254}


def read_boundary_points(path: Path, unit: str) -> list[dict]:
    """The points of `touchdown boundary --format json` (JSON Lines, one per engine, end-stop
    restitution and vertical velocity, SI; docs/schemas/boundary.schema.json), as dicts with
    "engine" (with " e = E" appended when the search set the end stops' restitution), "vv"
    (descent speed, positive down), "vh" (the boundary, or None), "stable_at", "unstable_at" (or
    None), "transitions" ([{"up": stable -> unstable as Vh grows, "stable_at", "unstable_at",
    "vh", "resolved"}]), "capacity" (the first Vh past a strut's capacity, or None), "scanned"
    (whether the search scanned finer around the changes),
    "undecided_at" (list), "landings", "undecided"; velocities in `unit`."""
    per = VELOCITY_UNITS.get(unit)
    if per is None:
        raise SystemExit(f"plot_compare: unknown velocity unit {unit!r} (expected one of {sorted(VELOCITY_UNITS)})")

    def v(x):
        return None if x is None else x / per

    points = []
    for line in path.read_text().splitlines():
        if not line.strip():
            continue
        p = json.loads(line)
        capacity = p.get("capacity")
        e = p.get("stop_restitution")
        points.append(
            {
                "engine": p["engine"] if e is None else f"{p['engine']} e = {e:g}",
                "capacity": None if capacity is None else v(capacity.get("vh_m_s", capacity["past_at_vh_m_s"])),
                "scanned": any(k.startswith("scan_step") for k in p.get("settings", {})),
                "vv": -p["vv_m_s"] / per,
                "vh": v(p.get("vh_m_s")),
                "stable_at": v(p.get("stable_at_vh_m_s")),
                "unstable_at": v(p.get("unstable_at_vh_m_s")),
                "transitions": [
                    {
                        "up": t["direction"] == "stable_to_unstable",
                        "stable_at": v(t["stable_at_vh_m_s"]),
                        "unstable_at": v(t["unstable_at_vh_m_s"]),
                        "vh": v(t.get("vh_m_s")),
                        "resolved": t["resolved"],
                    }
                    for t in p["transitions"]
                ],
                "undecided_at": [v(x) for x in p["undecided_at_vh_m_s"]],
                "landings": p["landings"],
                "undecided": p["undecided"],
            }
        )
    return points


def read_precision_study(path: Path) -> dict:
    """The JSON of `touchdown precision --format json`, as {"scenario", "optimised_build",
    "fixed_error" (fraction of the largest primary stroke), "rungs": [{"method", "value" (its
    step, s, divisor or rtol), "wall_time" (s, median) or None, "errors": {"max_stroke",
    "pitch_rate_rms", "final_attitude"} or None, "failure" or None}]}."""
    study = json.loads(path.read_text())
    rungs = []
    for r in study["rungs"]:
        m = r.get("measured")
        rungs.append(
            {
                "method": r["method"],
                "value": r["value"],
                "wall_time": m["wall_time_s"] if m else None,
                "errors": {
                    "max_stroke": m["errors"]["max_stroke_fraction"],
                    "pitch_rate_rms": m["errors"]["pitch_rate_rms_fraction"],
                    "final_attitude": m["errors"]["final_attitude_rad"],
                }
                if m
                else None,
                "failure": r.get("failure"),
            }
        )
    return {
        "scenario": study["scenario_name"],
        "optimised_build": study["optimised_build"],
        "fixed_error": study["fixed_error_fraction"],
        "rungs": rungs,
    }


# --------------------------------------------------------------------------------------------
# Traces


def leg_groups(strokes: dict[int, list[float]]) -> list[list[int]]:
    """The legs in groups whose stroke traces stay within LEG_TOLERANCE_M of each other's first
    leg over the whole trace (each group ordered, groups by their first leg)."""
    groups: list[list[int]] = []
    for leg, s in strokes.items():
        for g in groups:
            first = strokes[g[0]]
            if len(first) == len(s) and all(abs(a - b) <= LEG_TOLERANCE_M for a, b in zip(first, s)):
                g.append(leg)
                break
        else:
            groups.append([leg])
    return groups


def legs_label(group: list[int]) -> str:
    if len(group) == 1:
        return f"leg {group[0]}"
    return "legs " + ", ".join(str(g) for g in group) + " (identical)"


def verdict_value(difference: float, unit: str) -> str:
    """A difference (or tolerance) in the way its channel measures it, short (to 3 significant
    figures, under 0.01 of the shown unit as "< 0.01")."""
    scales = {"footprint_radius": "% ℓ", "time_scale": "% τ", "velocity_scale": "% v"}
    if unit.startswith("fraction"):
        value, shown = 100.0 * difference, "%"
    elif unit in scales:
        # a fraction of one of the vehicle's scales (docs/engines.md, "Tolerances from the
        # vehicle's scales")
        value, shown = 100.0 * difference, scales[unit]
    elif unit == "s":
        value, shown = 1000.0 * difference, "ms"
    elif unit == "m":
        value, shown = 1000.0 * difference, "mm"
    else:
        value, shown = difference, unit
    if value == 0.0:
        return f"0 {shown}"
    if abs(value) < 0.01:
        return f"< 0.01 {shown}"
    return f"{value:.3g} {shown}"




def verdict_table(ax, verdicts: dict | None, channels: list[tuple[str, str]], legend_height: float):
    """PASS/FAIL of every pair of engines (rows) on `channels` ((name in the report, shown as);
    columns, headed with their tolerance) as a table in the lower part of `ax`, below a legend
    `legend_height` of the axes high."""
    ax.axis("off")
    if verdicts is None:
        ax.text(
            0.0,
            0.0,
            "PASS/FAIL: not shown (this plot was drawn without\n"
            "the comparison report; pass --report with the JSON of\n"
            "`touchdown compare --format json`, or read the report)",
            transform=ax.transAxes,
            fontsize=8,
            va="bottom",
            ha="left",
            color=NEUTRAL,
        )
        return
    pairs = verdicts["pairs"]
    if not pairs:
        ax.text(0.0, 0.0, "PASS/FAIL: one engine only, no pair to compare", transform=ax.transAxes,
                fontsize=8, va="bottom", ha="left", color=NEUTRAL)
        return
    header = ["pair"]
    for name, shown in channels:
        unit = verdicts["units"].get(name, "")
        tolerance = next((p["channels"][name]["tolerance"] for p in pairs if name in p["channels"]), None)
        header.append(shown + ("" if tolerance is None else f"\n≤ {verdict_value(tolerance, unit)}"))
    # More than four columns: each verdict over its value (NOT DETERMINED on two lines), so
    # that the cells stay readable.
    narrow = len(channels) > 4
    separator = "\n" if narrow else " "
    text, colours = [], []
    for p in pairs:
        row = [f"{engine_name(p['a'])}–{engine_name(p['b'])}"]
        row_colours = ["white"]
        for name, _ in channels:
            ch = p["channels"].get(name)
            if ch is None:
                row.append("—")
                row_colours.append("white")
            else:
                unit = verdicts["units"].get(name, "")
                word = VERDICT_WORDS[ch["verdict"]].replace(" ", separator)
                row.append(f"{word}{separator}{verdict_value(ch['difference'], unit)}")
                row_colours.append(VERDICT_COLOURS[ch["verdict"]])
        text.append(row)
        colours.append(row_colours)
    lines = max(h.count("\n") + 1 for h in header)
    cell_lines = max(cell.count("\n") + 1 for row in text for cell in row)
    height = min(1.0 - legend_height - 0.1, 0.11 * (len(text) * (0.5 + 0.5 * cell_lines) + 0.6 * lines + 0.3))
    width = min(1.0, 0.24 + max(0.3, 0.19 * len(channels)))
    table = ax.table(
        cellText=text,
        cellColours=colours,
        colLabels=header,
        colLoc="center",
        cellLoc="center",
        bbox=[0.0, 0.0, width, height],
    )
    table.auto_set_font_size(False)
    table.set_fontsize(7.5)
    first = 0.22 / width
    for (r, c), cell in table.get_celld().items():
        cell.set_width(first if c == 0 else (1.0 - first) / len(channels))
        cell.set_edgecolor("0.7")
        if r == 0:
            cell.set_text_props(weight="bold")
            cell.set_height(cell.get_height() * (0.6 * lines + 0.3))
    ax.text(0.0, height + 0.01, "PASS/FAIL of each pair: its difference (as touchdown compare\n"
            "measures it, docs/engines.md) against the tolerance under each channel",
            transform=ax.transAxes, fontsize=7.5, va="bottom", ha="left", color="0.2")


def traces(args: argparse.Namespace) -> None:
    data = Path(args.data)
    engines = [e for e in args.engines.split(",") if e]
    runs = {e: read_trace(data / f"{args.stem}.{e}.csv") for e in engines}
    verdicts = read_comparison_verdicts(Path(args.report)) if args.report else None
    title = args.title or (verdicts["scenario"] if verdicts else args.stem)
    fig = plt.figure(figsize=(15, 11.5), layout="constrained")
    grid = fig.add_gridspec(3, 2, width_ratios=[2.0, 1] if verdicts is not None else [2.8, 1])
    acc = fig.add_subplot(grid[0, 0])
    pitch = fig.add_subplot(grid[1, 0], sharex=acc)
    stroke = fig.add_subplot(grid[2, 0], sharex=acc)
    sides = [fig.add_subplot(grid[i, 1]) for i in range(3)]
    # Drawn widest first, so that coinciding engines show as nested lines.
    widths = {e: w for e, w in zip(engines, [2.4, 1.6, 1.0, 0.8])}
    engine_handles = []
    stroke_handles = []
    for engine, c in runs.items():
        colour = COLOURS.get(engine.split(" ")[0], "black")
        lw = widths.get(engine, 1.0)
        acc.plot(c["acc_t"], c["acc"], color=colour, lw=lw)
        pitch.plot(c["t"], c["pitch_rate"], color=colour, lw=lw)
        engine_handles.append(Line2D([], [], color=colour, lw=lw, label=engine_name(engine)))
        for group in leg_groups(c["strokes"]):
            style = LEG_STYLES[(group[0] - 1) % len(LEG_STYLES)]
            (line,) = stroke.plot(
                c["t"],
                [1000.0 * x for x in c["strokes"][group[0]]],
                color=colour,
                ls=style,
                lw=lw,
                label=f"{engine_name(engine)} {legs_label(group)}",
            )
            stroke_handles.append(line)
    window = f"{1000.0 * verdicts['acceleration_window_s']:.3g} ms window, " if verdicts else ""
    acc.set_ylabel(f"vertical acceleration, m/s²\n({window}up +)")
    pitch.set_ylabel("pitch rate, rad/s")
    stroke.set_ylabel("primary stroke, mm")
    stroke.set_xlabel("time since first contact, s")
    for ax in (acc, pitch, stroke):
        ax.grid(True, alpha=0.3)
        ax.axhline(0.0, color="grey", lw=0.6)
    plt.setp(acc.get_xticklabels(), visible=False)
    plt.setp(pitch.get_xticklabels(), visible=False)

    legs = sorted({leg for c in runs.values() for leg in c["strokes"]})
    panels = [
        (
            sides[0],
            engine_handles,
            "engines (line width: drawn in this order,\nso coinciding engines stay visible)",
            [("peak_vertical_acceleration", "peak")],
        ),
        (
            sides[1],
            None,
            None,
            [
                ("peak_pitch_rate positive", "peak +"),
                ("peak_pitch_rate_time positive", "time of\npeak +"),
                ("peak_pitch_rate negative", "peak −"),
                ("peak_pitch_rate_time negative", "time of\npeak −"),
                ("pitch_rate_history_rms_difference", "history\nRMS"),
                ("pitch_rate_history_largest_difference", "history\nmax."),
            ],
        ),
        (
            sides[2],
            stroke_handles,
            f"primary strokes: colour engine, style leg;\n'identical': within {1000 * LEG_TOLERANCE_M:g} mm "
            "over the whole trace",
            [(f"primary_stroke leg {leg}", f"max. stroke\nleg {leg}") for leg in legs],
        ),
    ]
    for index, (side, handles, legend_title, channels) in enumerate(panels):
        legend_height = 0.0
        if handles:
            ncol = 2 if len(handles) > 6 else 1
            side.legend(handles=handles, loc="upper left", fontsize=7.5, title=legend_title,
                        title_fontsize=7.5, ncol=ncol, frameon=False, alignment="left", handlelength=4.5)
            rows = math.ceil(len(handles) / ncol) + legend_title.count("\n") + 1
            legend_height = min(0.65, 0.075 * rows + 0.05)
        if verdicts is None and index > 0:
            side.axis("off")
            continue
        verdict_table(side, verdicts, channels, legend_height)

    subtitle = "the engines overlaid"
    if verdicts is not None and verdicts["pairs"]:

        drawn = {name for _, _, _, channels in panels for name, _ in channels}

        def verdict(p) -> str:
            """PASS, or FAIL or NOT DETERMINED naming the channels that fail or that rounding
            decides (those not drawn marked so): what the panels do not show is named where the
            reader looks first."""
            if p["verdict"] == "pass":
                return "PASS"
            word = VERDICT_WORDS[p["verdict"]]
            failed = [name for name, ch in p["channels"].items() if ch["verdict"] != "pass"]
            named = [name.replace("_", " ") + ("" if name in drawn else " (not drawn)") for name in failed[:3]]
            if len(failed) > 3:
                named.append(f"{len(failed) - 3} more")
            if not p["outcome_agrees"]:
                named.insert(0, "outcomes differ")
            return f"{word} on {', '.join(named)}" if named else word

        overall = "\n".join(f"{engine_name(p['a'])}–{engine_name(p['b'])} {verdict(p)}" for p in verdicts["pairs"])
        subtitle = f"every channel of the comparison (touchdown compare's text has them all):\n{overall}"
    fig.suptitle(f"{title}\n{subtitle}", fontsize=11)
    fig.savefig(args.out, dpi=DPI, metadata=PNG_METADATA)


# --------------------------------------------------------------------------------------------
# Boundaries

# A scenario's own touchdown speeds in its name ("Vv = -8.0 ft/s", ", Vh = 6 ft/s uphill"): the
# boundary search replaces them, so a boundary's title leaves them out.
_SPEED = re.compile(
    r",?\s*\bV[vh]\s*=\s*[-+]?\d+(?:\.\d+)?\s*(?:ft|m|in|cm|mm)/s(?:\s+(?:uphill|downhill|sideways))?"
)


def configuration_of(scenario_name: str) -> tuple[str, bool]:
    """The scenario's name without its own touchdown speeds; whether any were found."""
    stripped = _SPEED.sub("", scenario_name).strip().rstrip(",:;").strip()
    return (stripped or scenario_name), stripped != scenario_name.strip()


def speeds_text(values: list[float]) -> str:
    """Sorted distinct speeds as "4 to 12 in steps of 2" when evenly spaced, else a list."""
    vs = sorted(set(values))
    if len(vs) >= 3:
        steps = [b - a for a, b in zip(vs, vs[1:])]
        if max(steps) - min(steps) <= 1e-9 * max(1.0, abs(vs[-1])):
            return f"{vs[0]:g} to {vs[-1]:g} in steps of {steps[0]:g}"
    return ", ".join(f"{v:g}" for v in vs)


def boundary_title(first_line: str, points: list[dict], unit: str) -> str:
    """`first_line` (which configuration), then what the search varies, what it holds and on
    which engines."""
    engines = list(dict.fromkeys(p["engine"] for p in points))
    names = ", ".join(engine_name(e) for e in engines) or "none"
    title = (
        f"{first_line}\n"
        f"varied: descent speed Vv = {speeds_text([p['vv'] for p in points])} {unit}, and at each the "
        f"horizontal speed Vh (grid, {'a finer scan around its changes, ' if any(p['scanned'] for p in points) else ''}"
        f"then bisection)\n"
        f"held: attitude, surface, vehicle and every other input of the scenario · "
        f"engine{'s' if len(engines) != 1 else ''}: {names}"
    )
    return "\n".join(textwrap.fill(line, 150) for line in title.split("\n"))


def draw_boundary(ax, points: list[dict], unit: str) -> tuple[list, list]:
    """Draws the boundary points of every engine into `ax`; returns the legend handles of the
    engines (with their landing counts) and of the kinds of mark drawn."""
    by_engine: dict[str, list[dict]] = {}
    for p in points:
        by_engine.setdefault(p["engine"], []).append(p)
    kinds: dict[str, Line2D] = {}

    def kind(key: str, handle: Line2D) -> None:
        kinds.setdefault(key, handle)

    xmax = 1.0
    engine_handles = []
    # Drawn largest first, so that engines with the same boundary show as nested marks.
    sizes = [(7.5, 2.4), (5.5, 1.6), (3.5, 1.0)]
    for index, (engine, pts) in enumerate(by_engine.items()):
        ms, lw = sizes[min(index, len(sizes) - 1)]
        pts = sorted(pts, key=lambda p: p["vv"])
        colour = COLOURS.get(engine.split(" ")[0], "black")
        found = [p for p in pts if p["vh"] is not None]
        landings = sum(p["landings"] or 0 for p in pts)
        undecided = sum(p["undecided"] or 0 for p in pts)
        (line,) = ax.plot(
            [p["vh"] for p in found],
            [p["vv"] for p in found],
            "o-",
            color=colour,
            ms=ms,
            lw=lw,
            zorder=4,
        )
        engine_handles.append(
            Line2D([], [], color=colour, marker="o", ms=ms, lw=lw,
                   label=f"{engine_name(engine)}: boundary ({landings} landings, {undecided} undecided)")
        )
        for p in pts:
            y = p["vv"]
            for x in (p["stable_at"], p["unstable_at"], p["vh"]):
                if x is not None:
                    xmax = max(xmax, x)
            if not p["transitions"] and p["unstable_at"] is None and p["stable_at"] is not None:
                # Stable on the whole grid: a dotted run to the largest speed tried.
                s = p["stable_at"]
                ax.plot([0.0, s], [y, y], ls=":", color=colour, lw=1.6, zorder=2)
                ax.plot([s], [y], ">", color=colour, ms=8, zorder=3)
                kind("stable", Line2D([], [], ls=":", color=NEUTRAL, marker=">", ms=7, lw=1.6,
                                      label="stable at every Vh tried, up to ▶ (no unstable landing)"))
            if not p["transitions"] and p["unstable_at"] is not None:
                ax.plot([p["unstable_at"]], [y], "s", color=colour, ms=7, zorder=3)
                kind("unstable", Line2D([], [], ls="none", color=NEUTRAL, marker="s", ms=7,
                                        label="unstable from the smallest Vh tried (nothing stable below)"))
            for t in p["transitions"]:
                lo, hi = sorted((t["stable_at"], t["unstable_at"]))
                ls = "-" if t["resolved"] else ":"
                ax.plot([lo, hi], [y, y], ls=ls, color=colour, lw=1.2, zorder=3)
                ax.plot([lo, hi], [y, y], "|", color=colour, ms=13, mew=1.4, zorder=3)
                if t["resolved"]:
                    kind("bracket", Line2D([], [], color=NEUTRAL, lw=1.2, marker="|", ms=11, mew=1.4,
                                           label="bracket of a transition: the Vh found stable and the\n"
                                                 "Vh found unstable beside it (bisected to the tolerance)"))
                else:
                    kind("unresolved", Line2D([], [], color=NEUTRAL, lw=1.2, ls=":", marker="|", ms=11,
                                              mew=1.4, label="unresolved bracket (an undecided landing inside)"))
                if t["resolved"] and t["vh"] is not None and t["vh"] != p["vh"]:
                    marker = ">" if t["up"] else "<"
                    ax.plot([t["vh"]], [y], marker, color=colour, mfc="white", mew=1.4, ms=8, zorder=5)
                    kind(
                        "up" if t["up"] else "down",
                        Line2D([], [], ls="none", color=NEUTRAL, marker=marker, mfc="white", mew=1.4, ms=8,
                               label="further transition, stable → unstable (above the boundary)"
                               if t["up"]
                               else "transition unstable → stable (stable again above it)"),
                    )
            if p["capacity"] is not None:
                ax.plot([p["capacity"]], [y], "D", color=colour, mfc="none", mew=1.4, ms=8, zorder=5)
                xmax = max(xmax, p["capacity"])
                kind("capacity", Line2D([], [], ls="none", color=NEUTRAL, marker="D", mfc="none", mew=1.4,
                                        ms=8, label="first Vh at which a strut goes past its capacity\n"
                                                    "(onto its end stop, an estimated law)"))
            if p["undecided_at"]:
                ax.plot(p["undecided_at"], [y] * len(p["undecided_at"]), "x", color=colour, ms=7,
                        mew=1.5, ls="none", zorder=5)
                kind("undecided", Line2D([], [], ls="none", color=NEUTRAL, marker="x", ms=7, mew=1.5,
                                         label="undecided landing (neither stable nor unstable)"))
    ax.set_xlabel(f"horizontal touchdown speed Vh, {unit}")
    ax.set_ylabel(f"descent speed Vv, {unit}")
    ax.grid(True, alpha=0.3)
    ax.set_xlim(-0.015 * xmax, 1.06 * xmax)
    vvs = [p["vv"] for p in points]
    if vvs:
        pad = max(0.5, 0.1 * (max(vvs) - min(vvs)))
        ax.set_ylim(min(vvs) - pad, max(vvs) + pad)
    order = ["bracket", "unresolved", "up", "down", "capacity", "stable", "unstable", "undecided"]
    kind_handles = [kinds[k] for k in order if k in kinds]
    return engine_handles, kind_handles


def boundary_legends(ax, engine_handles: list, kind_handles: list, extra: list | None = None) -> None:
    """The engines' and the marks' legends beside the axes (right), one above the other."""
    first = ax.legend(
        handles=engine_handles + (extra or []),
        title="boundary: the lowest stable → unstable transition\n(engines drawn largest first: "
              "coinciding ones nest)" if len(engine_handles) > 1 else
              "boundary: the lowest stable → unstable transition",
        loc="upper left",
        bbox_to_anchor=(1.02, 1.0),
        fontsize=8,
        title_fontsize=8,
        alignment="left",
    )
    if kind_handles:
        ax.add_artist(first)
        # A bracket's proxy shows both its ends.
        two_ends = {h: HandlerLine2D(numpoints=2) for h in kind_handles if h.get_marker() == "|"}
        ax.legend(
            handles=kind_handles,
            handler_map=two_ends,
            title="marks (in each engine's colour)",
            loc="lower left",
            bbox_to_anchor=(1.02, 0.0),
            fontsize=8,
            title_fontsize=8,
            alignment="left",
        )


def boundaries(args: argparse.Namespace) -> None:
    points = read_boundary_points(Path(args.data), args.unit)
    scenario = args.title.split("\n")[0].strip()
    configuration, stripped = configuration_of(scenario)
    if not scenario:
        first_line = "Stability boundary of the scenario's configuration"
    elif stripped:
        first_line = f"Stability boundary of the configuration “{configuration}”"
    else:
        first_line = f"Stability boundary of the configuration of “{configuration}” (its touchdown speeds replaced)"
    fig, ax = plt.subplots(figsize=(11.5, 6.2), layout="constrained")
    engine_handles, kind_handles = draw_boundary(ax, points, args.unit)
    boundary_legends(ax, engine_handles, kind_handles)
    fig.suptitle(boundary_title(first_line, points, args.unit), fontsize=10)
    fig.savefig(args.out, dpi=DPI, metadata=PNG_METADATA)


# --------------------------------------------------------------------------------------------
# Precision

# One colour and marker per integration method of the work-precision plot, and what its ladder
# varies.
METHODS = {
    "report": ("core report", COLOURS["core"], "o", "DIST and dt_max divided by"),
    "strides": ("core strides", "#66a61e", "P", "DIST, dt_max and mode_step divided by"),
    "rk4": ("core rk4", "#7570b3", "s", "fixed step"),
    "dopri5": ("core dopri5", "#e7298a", "^", "relative tolerance"),
    "rapier": ("rapier", COLOURS["rapier"], "D", "timestep"),
    "mujoco": ("MuJoCo", COLOURS["mujoco"], "v", "timestep"),
}


def rung_label(method: str, value: float) -> str:
    """A rung's setting as `touchdown precision` prints it (precision::setting_label)."""
    if method in ("report", "strides"):
        return f"÷{value:g}"
    if method == "dopri5":
        mantissa, exponent = f"{value:.0e}".split("e")
        return f"{mantissa}e{int(exponent)}"
    return f"{value * 1e6:g} µs"


def seconds(t: float, _pos=None) -> str:
    """A time tick: 1 µs, 10 ms, 1 s."""
    for scale, unit in ((1.0, "s"), (1e-3, "ms"), (1e-6, "µs")):
        if t >= scale * 0.999:
            return f"{t / scale:g} {unit}"
    return f"{t:g} s"


def mantissa(v: float) -> int | None:
    """The leading digit of `v` when `v` is that digit times a power of ten, else None."""
    m = v / 10.0 ** math.floor(math.log10(v) + 1e-9)
    return round(m) if abs(m - round(m)) < 1e-6 else None


def power_of_ten(v: float, _pos=None) -> str:
    """An error tick: 10⁻³, 2×10⁻³."""
    e = math.floor(math.log10(v) + 1e-9)
    m = mantissa(v)
    if m == 1:
        return f"$10^{{{e}}}$"
    if m is not None:
        return f"${m}\\times10^{{{e}}}$"
    return f"{v:g}"


def decades(lo: float, hi: float, margin: float = 0.15) -> tuple[float, float]:
    """Log-axis limits padded by `margin` decades and spanning at least one decade boundary."""
    a, b = math.log10(lo) - margin, math.log10(hi) + margin
    if math.floor(b) < math.ceil(a):
        # No decade inside: widen to the nearest ones.
        a = min(a, math.floor(a))
        b = max(b, math.ceil(b))
    return 10.0**a, 10.0**b


def place_labels(fig, ax, items, obstacles, fontsize=7):
    """Labels each (x, y, text, colour) of `items` near its point in `ax` without overlapping the
    other labels, the `obstacles` (display-space boxes: markers and lines) or the axes' edges;
    a label set away from its point gets a leader line."""
    renderer = fig.canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    taken = list(obstacles)
    directions = [(1, 0), (1, 1), (1, -1), (0, 1), (0, -1), (-1, 0), (-1, 1), (-1, -1)]

    def label(x, y, text, colour, ox, oy, ha, va, leader):
        arrow = None
        if leader:
            arrow = {"arrowstyle": "-", "color": colour, "lw": 0.5, "alpha": 0.8, "shrinkA": 1, "shrinkB": 4}
        return ax.annotate(text, (x, y), xytext=(ox, oy), textcoords="offset points", fontsize=fontsize,
                           color=colour, ha=ha, va=va, zorder=6, arrowprops=arrow)

    for x, y, text, colour in items:
        chosen = None
        fallback = None
        for radius in (6, 11, 17, 24, 32, 42, 54, 68, 85):
            for dx, dy in directions:
                norm = math.hypot(dx, dy)
                spot = (radius * dx / norm, radius * dy / norm,
                        "left" if dx > 0 else "right" if dx < 0 else "center",
                        "bottom" if dy > 0 else "top" if dy < 0 else "center")
                t = label(x, y, text, colour, *spot, False)
                box = t.get_window_extent(renderer).padded(3.0)
                t.remove()
                inside = (box.x0 >= frame.x0 + 2 and box.x1 <= frame.x1 - 2
                          and box.y0 >= frame.y0 + 2 and box.y1 <= frame.y1 - 2)
                if inside and fallback is None:
                    fallback = (spot, box, radius)
                if inside and not any(box.overlaps(o) for o in taken):
                    chosen = (spot, box, radius)
                    break
            if chosen:
                break
        # Nowhere clear: the nearest spot inside the axes, whatever it overlaps.
        spot, box, radius = chosen or fallback or ((6, 0, "left", "center"), None, 6)
        t = label(x, y, text, colour, *spot, radius > 6)
        taken.append(box if box is not None else t.get_window_extent(renderer))


def line_obstacles(line, marker_px=10.0):
    """Display-space boxes over a drawn line's markers and along its segments."""
    from matplotlib.transforms import Bbox

    pts = line.get_transform().transform(line.get_xydata())
    boxes = []
    if line.get_marker() not in (None, "None", ""):
        boxes += [Bbox.from_extents(px - marker_px / 2, py - marker_px / 2, px + marker_px / 2, py + marker_px / 2)
                  for px, py in pts]
    if line.get_linestyle() not in ("None", "none", ""):
        for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
            n = max(1, int(math.hypot(x1 - x0, y1 - y0) / 4))
            for i in range(0, n + 1):
                cx, cy = x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * i / n
                boxes.append(Bbox.from_extents(cx - 1.5, cy - 1.5, cx + 1.5, cy + 1.5))
    return boxes


def precision(args: argparse.Namespace) -> None:
    study = read_precision_study(Path(args.data))
    panels = [
        ("max_stroke", "maximum-stroke error\n(fraction of the largest primary stroke)"),
        ("pitch_rate_rms", "pitch-rate history RMS error\n(fraction of its peak)"),
        ("final_attitude", "final-attitude error, rad"),
    ]
    fig, grid = plt.subplots(2, 2, figsize=(15, 11.5), layout="constrained")
    axes = [grid[0, 0], grid[0, 1], grid[1, 0]]
    key_ax = grid[1, 1]
    measured = [r for r in study["rungs"] if r["errors"] is not None and r["wall_time"] is not None]
    times = [r["wall_time"] for r in measured] or [1e-3, 1e-2]
    xlim = decades(min(times), max(times))
    drawn: dict[str, list] = {}
    for ax, (key, label) in zip(axes, panels):
        values = [r["errors"][key] for r in measured if r["errors"][key] > 0]
        floor = min(values) / 3 if values else 1e-6
        series = []
        for method, (name, colour, marker, _) in METHODS.items():
            rungs = [r for r in measured if r["method"] == method]
            # A log axis cannot show an exact zero: such a rung sits at the floor of the data.
            pts = [(r["wall_time"], max(r["errors"][key], floor), rung_label(method, r["value"])) for r in rungs]
            if pts:
                xs, ys, _ = zip(*pts)
                (line,) = ax.loglog(xs, ys, marker=marker, color=colour, lw=1.4, ms=6, label=name)
                drawn.setdefault(method, line)
                series.append((pts, colour))
        ylo, yhi = min(values + [floor]), max(values + [floor])
        if key == "max_stroke":
            ylo, yhi = min(ylo, study["fixed_error"]), max(yhi, study["fixed_error"])
            ax.axhline(study["fixed_error"], color="grey", ls="--", lw=1)
        ax.set_xlim(*xlim)
        ax.set_ylim(*decades(ylo, yhi, margin=0.35))
        ax.set_xlabel("wall time per landing (median)")
        ax.set_ylabel(label)
        ax.grid(True, which="major", alpha=0.35)
        ax.grid(True, which="minor", alpha=0.12)
        # Decades are labelled, and on an axis shorter than 1.5 decades also 2 and 5 times them
        # (matplotlib's own choice labels every minor tick of a short axis, and they overlap).
        for axis, limits, fmt in ((ax.xaxis, ax.get_xlim(), seconds), (ax.yaxis, ax.get_ylim(), power_of_ten)):
            axis.set_major_locator(LogLocator(base=10, numticks=12))
            axis.set_minor_locator(LogLocator(base=10, subs=range(2, 10), numticks=12))
            axis.set_major_formatter(FuncFormatter(fmt))
            short = math.log10(limits[1] / limits[0]) < 1.5
            if short:
                axis.set_minor_formatter(FuncFormatter(lambda v, _pos, fmt=fmt: fmt(v) if mantissa(v) in (2, 5) else ""))
            else:
                axis.set_minor_formatter(NullFormatter())
        ax.set_title(label.split("\n")[0], fontsize=10)
    fig.canvas.draw()
    for ax, (key, _) in zip(axes, panels):
        obstacles = []
        items = []
        for line in ax.get_lines():
            obstacles += line_obstacles(line)
        values = [q["errors"][key] for q in measured if q["errors"][key] > 0]
        floor = min(values) / 3 if values else 1e-6
        for method, (_, colour, _, _) in METHODS.items():
            # Rungs of one method that land on the same spot (within a marker) share a label.
            clusters: list[list] = []
            for r in measured:
                if r["method"] != method:
                    continue
                xy = (r["wall_time"], max(r["errors"][key], floor))
                px = ax.transData.transform(xy)
                for c in clusters:
                    if math.hypot(*(px - c[0])) <= 7.0:
                        c[2].append(rung_label(method, r["value"]))
                        break
                else:
                    clusters.append([px, xy, [rung_label(method, r["value"])]])
            for _, (x, y), names in clusters:
                items.append((x, y, ", ".join(names), colour))
        place_labels(fig, ax, items, obstacles)

    # The key: methods, what each ladder varies, the failed rungs, the 1 % line.
    key_ax.axis("off")
    handles = []
    for method, (name, colour, marker, varies) in METHODS.items():
        rungs = [r for r in study["rungs"] if r["method"] == method]
        if not rungs:
            continue
        ok = [rung_label(method, r["value"]) for r in rungs if r["errors"] is not None]
        text = f"{name}: {varies} {', '.join(ok)}" if ok else f"{name}: no rung measured"
        handles.append(Line2D([], [], color=colour, marker=marker, lw=1.4, label=text))
    handles.append(Line2D([], [], color="grey", ls="--", lw=1,
                          label=f"{100 * study['fixed_error']:g} % of the largest primary stroke (stroke panel)"))
    key_ax.legend(handles=handles, loc="upper left", fontsize=9, frameon=False, alignment="left",
                  title="methods and their rungs (each point labelled with its rung)", title_fontsize=9)
    failed = [r for r in study["rungs"] if r["errors"] is None or r["wall_time"] is None]
    if failed:
        lines = ["rungs that failed (left out):"]
        for r in failed:
            reason = (r["failure"] or "no measurement").split(": ")[-1]
            lines.append(f"• {METHODS.get(r['method'], (r['method'],))[0]} {rung_label(r['method'], r['value'])}: {reason}")
        wrapped = []
        for line in lines:
            wrapped += textwrap.wrap(line, 78, subsequent_indent="   ") or [""]
        key_ax.text(0.0, 0.0, "\n".join(wrapped), transform=key_ax.transAxes, fontsize=8.5,
                    va="bottom", ha="left", color="0.2")
    build = "" if study["optimised_build"] else " (debug build: times not representative)"
    title = args.title or study["scenario"]
    fig.suptitle(f"{title}: work-precision against the converged reference{build}", fontsize=11)
    fig.savefig(args.out, dpi=DPI, metadata=PNG_METADATA)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="kind", required=True)
    t = sub.add_parser("traces")
    t.add_argument("--data", required=True)
    t.add_argument("--stem", required=True)
    t.add_argument("--engines", required=True)
    t.add_argument("--title", default="")
    t.add_argument("--out", required=True)
    t.add_argument("--report", default=None,
                   help="the JSON of `touchdown compare --format json` (PASS/FAIL beside each panel; "
                        "its scenario name is the title if --title is not given)")
    b = sub.add_parser("boundaries")
    b.add_argument("--data", required=True)
    b.add_argument("--title", default="")
    b.add_argument("--unit", default="ft/s")
    b.add_argument("--out", required=True)
    p = sub.add_parser("precision")
    p.add_argument("--data", required=True)
    p.add_argument("--title", default="")
    p.add_argument("--out", required=True)
    args = ap.parse_args()
    {"traces": traces, "boundaries": boundaries, "precision": precision}[args.kind](args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
