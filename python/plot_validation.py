#!/usr/bin/env python3
"""Validation plots for Touchdown (NASA TN D-7045 lander touchdown dynamics).

Reads the data files that the `touchdown` CLI writes into a folder (default docs/validation/):

* validation.json        `touchdown validate --out DIR` (Table I rows, held-out errors, facts)
* fig-25-26-series.json  `touchdown validate --out DIR` (time histories of the figs. 25-26 landing)
* boundary-2-2.json      `touchdown boundary scenarios/fig-25-26.toml ... --format json`

and writes three PNGs into an output folder (default: the data folder):

* table-i.png      Table I maximum strokes per row: experiment, the report's analysis, ours;
* fig-25-26.png    vertical acceleration, pitch rate and primary strokes against time, with the
                   report's stated facts about figures 25-26 overlaid;
* boundary-2-2.png the 2-2 stability boundary (horizontal vs descent velocity).

Usage: python/plot_validation.py [--data DIR] [--out DIR]

Run it with the project's venv (`scripts/setup-python`, then `.venv/bin/python`); `scripts/plots`
regenerates the data and the plots together. The output is deterministic as far as matplotlib
allows: Agg backend, fixed figure sizes and DPI, no software/time stamps in the PNG metadata.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402  (after selecting the backend)
from matplotlib.patches import Patch  # noqa: E402

FT_PER_M = 1.0 / 0.3048
DPI = 110
PNG_METADATA = {"Software": None}

VALIDATION = "validation.json"
SERIES = "fig-25-26-series.json"
BOUNDARY = "boundary-2-2.json"

# Colours (colour-blind friendly, Okabe-Ito).
C_EXPERIMENT = "#000000"
C_ANALYSIS = "#E69F00"
C_OURS = "#0072B2"
C_REPORT = "#D55E00"
C_CALIBRATION = "#F0E442"
LEG_STYLES = [  # footpads 1-2 downhill, 3-4 uphill (scenarios/fig-25-26.toml)
    ("footpad 1 (downhill)", "#0072B2", "-"),
    ("footpad 2 (downhill)", "#56B4E9", "--"),
    ("footpad 3 (uphill)", "#D55E00", "-"),
    ("footpad 4 (uphill)", "#E69F00", "--"),
]

# The report's statements about figures 25-26 (TN D-7045 text; the figures themselves are not
# available), in the report's units.
REPORT_DOWNHILL_STRIKE_S = 0.06
REPORT_PITCH_RATE_BEFORE = -5.5  # rad/s, at the downhill strike
REPORT_PITCH_RATE_AFTER = -2.0  # rad/s, after the downhill impact
REPORT_MAX_STROKING_S = 0.12
REPORT_STAGE1_END_FT = 0.32
REPORT_FREE_FLIGHT_S = 0.02


class DataError(Exception):
    """A data file is missing or not in the expected shape."""


def load_json(data_dir: Path, name: str, how: str):
    path = data_dir / name
    if not path.is_file():
        raise DataError(f"missing data file {path} (written by `{how}`; `scripts/plots` regenerates all)")
    try:
        with path.open(encoding="utf-8") as f:
            return json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        raise DataError(f"cannot read {path}: {e}") from e


def field(obj, key, where):
    try:
        return obj[key]
    except (KeyError, IndexError, TypeError) as e:
        raise DataError(f"{where}: missing field {key!r}") from e


def save(fig, out: Path):
    fig.savefig(out, dpi=DPI, metadata=PNG_METADATA)
    plt.close(fig)


# --------------------------------------------------------------------------------------------
# Table I


def plot_table_i(validation, out: Path):
    rows = field(validation, "rows", VALIDATION)
    groups = [
        ("primary", "Primary strut stroke (1-2-1 landings)"),
        ("secondary", "Secondary strut stroke (2-2 landings)"),
    ]
    fig, axes = plt.subplots(1, 2, figsize=(12, 6), layout="constrained")
    width = 0.26
    for ax, (strut, title) in zip(axes, groups):
        sel = [r for r in rows if field(r, "strut", VALIDATION) == strut]
        sel.sort(key=lambda r: r["id"])
        xs = list(range(len(sel)))
        top = max([1.0] + [max(r["experiment_in"], r["analysis_in"], r["ours_in"]) for r in sel])
        for x, r in zip(xs, sel):
            if r.get("role") == "calibration":
                ax.axvspan(x - 0.5, x + 0.5, color=C_CALIBRATION, alpha=0.25, lw=0, zorder=0)
        ax.bar([x - width for x in xs], [r["experiment_in"] for r in sel], width,
               color=C_EXPERIMENT, label="experiment (Table I)", zorder=2)
        ax.bar(xs, [r["analysis_in"] for r in sel], width,
               color=C_ANALYSIS, label="report's analysis (Table I)", zorder=2)
        ours = ax.bar([x + width for x in xs], [r["ours_in"] for r in sel], width,
                      color=C_OURS, label="ours", zorder=2)
        for bar, r in zip(ours, sel):
            if r.get("role") == "calibration":
                bar.set_hatch("//")
                bar.set_edgecolor("white")
            err = r.get("error_vs_experiment_pct")
            if err is not None:
                ax.annotate(f"{err:+.0f}%", (bar.get_x() + bar.get_width() / 2, bar.get_height()),
                            xytext=(0, 3), textcoords="offset points", ha="center",
                            va="bottom", fontsize=8, color=C_OURS)
        labels = []
        for r in sel:
            role = "calibration" if r.get("role") == "calibration" else "held out"
            labels.append(
                f"row {r['id']} ({role})\n"
                f"Vv {abs(r['vv_ft_s']):g}, Vh {r['vh_ft_s']:g} ft/s"
            )
        ax.set_xticks(xs, labels, fontsize=8.5)
        ax.set_xlim(-0.6, len(sel) - 0.4)
        ax.set_ylim(0, top * 1.18)
        ax.set_ylabel("maximum stroke (in)")
        ax.set_title(title, fontsize=11)
        ax.grid(axis="y", alpha=0.3, zorder=0)
    handles, labels = axes[0].get_legend_handles_labels()
    handles.append(Patch(facecolor=C_CALIBRATION, alpha=0.4, label="calibration row (ours fitted here, hatched)"))
    axes[0].legend(handles=handles, loc="upper left", fontsize=8.5)

    title = "TN D-7045 Table I: maximum strut strokes (labels over our bars: error vs experiment)"
    ho, hr = validation.get("held_out_ours"), validation.get("held_out_report")
    if ho and hr:
        title += (
            f"\nheld-out rows mean |error| vs experiment: ours {ho['mean_abs_error_pct']:.1f}% "
            f"(max {ho['max_abs_error_pct']:.1f}%), report's analysis {hr['mean_abs_error_pct']:.1f}% "
            f"(max {hr['max_abs_error_pct']:.1f}%)"
        )
    fig.suptitle(title, fontsize=11.5)
    save(fig, out)


# --------------------------------------------------------------------------------------------
# Figures 25-26


def free_flight_intervals(t, contacts):
    """(start, end) of each run of samples with no footpad in contact, after the first contact."""
    out, start, touched = [], None, False
    for ti, c in zip(t, contacts):
        if c:
            touched = True
            if start is not None:
                out.append((start, ti))
                start = None
        elif touched and start is None:
            start = ti
    if start is not None:
        out.append((start, t[-1]))
    return out


def facts_by_name(validation):
    return {f.get("fact"): f for f in (validation.get("facts") or []) if isinstance(f, dict)}


def ours_of(facts, name):
    f = facts.get(name)
    return f" (ours {f['ours']})" if f and f.get("ours") else ""


def plot_fig_25_26(series, validation, out: Path):
    t = field(series, "t", SERIES)
    acc = field(series, "vertical_acceleration_g", SERIES)
    q = field(series, "pitch_rate", SERIES)
    strokes = field(series, "primary_stroke", SERIES)
    contacts = series.get("contacts") or [1] * len(t)
    for name, arr in (("vertical_acceleration_g", acc), ("pitch_rate", q), ("contacts", contacts)):
        if len(arr) != len(t):
            raise DataError(f"{SERIES}: {name} has {len(arr)} samples, t has {len(t)}")
    for i, leg in enumerate(strokes):
        if len(leg) != len(t):
            raise DataError(f"{SERIES}: primary_stroke[{i}] has {len(leg)} samples, t has {len(t)}")
    facts = facts_by_name(validation)

    fig, (a1, a2, a3) = plt.subplots(3, 1, figsize=(11, 11), sharex=True, layout="constrained")
    flights = free_flight_intervals(t, contacts)
    for ax in (a1, a2, a3):
        for i, (s, e) in enumerate(flights):
            ax.axvspan(s, e, color="0.85", lw=0, zorder=0,
                       label="no footpad in contact (ours)" if i == 0 else None)
        ax.axvline(REPORT_DOWNHILL_STRIKE_S, color=C_REPORT, ls="--", lw=1.2, zorder=1)
        ax.axvline(REPORT_MAX_STROKING_S, color=C_REPORT, ls=":", lw=1.5, zorder=1)
        ax.grid(alpha=0.3)

    # Vertical acceleration.
    a1.plot(t, acc, color=C_OURS, lw=1.2, label="ours")
    a1.set_ylabel("vertical acceleration (g)")
    a1.set_title("Figure 25: vertical acceleration", fontsize=11, loc="left")
    lo, hi = min(acc), max(acc)
    a1.text(REPORT_DOWNHILL_STRIKE_S, 1.02, " report: downhill footpads strike ≈ 0.06 s"
            + ours_of(facts, "downhill footpads strike"),
            transform=a1.get_xaxis_transform(), color=C_REPORT, fontsize=8.5, va="bottom", ha="left")
    a1.text(REPORT_MAX_STROKING_S, 0.97, " report: maximum stroking by 0.12 s"
            + ours_of(facts, "maximum stroking reached by"),
            transform=a1.get_xaxis_transform(), color=C_REPORT, fontsize=8.5, va="top", ha="left",
            bbox=dict(boxstyle="round", fc="white", ec="none", alpha=0.8))
    # Shifted right so it clears the downhill-strike label over the same axes.
    first_flight = flights[0] if flights else None
    note = f"report: free flight ≈ {REPORT_FREE_FLIGHT_S:g} s after the first pulse"
    if first_flight:
        note += f"\nours: {first_flight[1] - first_flight[0]:.3f} s ({first_flight[0]:.3f}–{first_flight[1]:.3f} s, shaded)"
    a1.text(0.99, 0.04, note, transform=a1.transAxes, ha="right", va="bottom", fontsize=8.5,
            bbox=dict(boxstyle="round", fc="white", ec="0.6"))
    a1.set_ylim(lo - 0.08 * (hi - lo), hi + 0.12 * (hi - lo))
    a1.legend(loc="center right", fontsize=8.5)

    # Pitch rate.
    a2.plot(t, q, color=C_OURS, lw=1.2, label="ours")
    a2.plot([REPORT_DOWNHILL_STRIKE_S], [REPORT_PITCH_RATE_BEFORE], "o", color=C_REPORT, ms=7,
            label="report: −5.5 rad/s at the downhill strike")
    a2.plot([REPORT_MAX_STROKING_S], [REPORT_PITCH_RATE_AFTER], "s", color=C_REPORT, ms=7,
            label="report: reduced to −2.0 rad/s (shown at 0.12 s)")
    a2.annotate("", xy=(REPORT_MAX_STROKING_S, REPORT_PITCH_RATE_AFTER),
                xytext=(REPORT_DOWNHILL_STRIKE_S, REPORT_PITCH_RATE_BEFORE),
                arrowprops=dict(arrowstyle="->", color=C_REPORT, lw=1.2, shrinkA=5, shrinkB=5))
    a2.axhline(0, color="0.4", lw=0.8)
    a2.set_ylabel("pitch rate (rad/s)")
    a2.set_title("Figure 26: pitch rate", fontsize=11, loc="left")
    a2.legend(loc="lower right", fontsize=8.5)

    # Primary strokes.
    for i, leg in enumerate(strokes):
        name, color, ls = LEG_STYLES[i] if i < len(LEG_STYLES) else (f"leg {i + 1}", None, "-")
        a3.plot(t, [v * FT_PER_M for v in leg], color=color, ls=ls, lw=1.4, label=name)
    a3.axhline(REPORT_STAGE1_END_FT, color=C_REPORT, ls="-.", lw=1.2,
               label=f"end of the primary first stage ({REPORT_STAGE1_END_FT:g} ft)")
    a3.set_ylabel("primary strut stroke (ft)")
    a3.set_xlabel("time (s)")
    a3.set_title("Primary strut strokes", fontsize=11, loc="left")
    a3.set_ylim(bottom=0, top=max(REPORT_STAGE1_END_FT, *(v * FT_PER_M for leg in strokes for v in leg)) * 1.25)
    a3.legend(loc="upper left", fontsize=8.5, ncols=2)
    a3.set_xlim(0, t[-1])

    fig.suptitle("TN D-7045 figures 25-26 landing (2-2, 5° slope, 4-in depressions under the "
                 "downhill footpads)\nours vs the report's stated facts (the figures' curves are "
                 "not available)", fontsize=11.5)
    save(fig, out)


# --------------------------------------------------------------------------------------------
# Stability boundary


def plot_boundary(boundary, out: Path):
    if not isinstance(boundary, list):
        raise DataError(f"{BOUNDARY}: expected an array of boundary points")
    pts = [(field(p, "vv", BOUNDARY), p) for p in boundary]
    pts.sort(key=lambda x: x[0])
    fig, ax = plt.subplots(figsize=(10, 6.5), layout="constrained")
    found = [(p["vh"], vv) for vv, p in pts if p.get("vh") is not None]
    xmax = 1.0
    if found:
        ax.plot([x for x, _ in found], [y for _, y in found], "o-", color=C_OURS, ms=7,
                label="ours: boundary (overturn above this Vh)")
        xmax = max(xmax, max(x for x, _ in found))
    first_arrow = True
    for vv, p in pts:
        # No boundary and nothing unstable (an unresolved boundary has both bracket ends).
        if p.get("vh") is None and p.get("stable_at") is not None and p.get("unstable_at") is None:
            s = p["stable_at"]
            ax.annotate("", xy=(s, vv), xytext=(0, vv),
                        arrowprops=dict(arrowstyle="-|>", color="#009E73", lw=2, mutation_scale=18))
            ax.plot([], [], color="#009E73", lw=2, marker=">",
                    label="ours: stable up to this Vh, no overturn found" if first_arrow else None)
            first_arrow = False
            ax.annotate(f"stable to {s:g} ft/s", (s, vv), xytext=(8, 0),
                        textcoords="offset points", va="center", fontsize=8.5, color="#009E73")
            xmax = max(xmax, s)
        if p.get("unstable_at") is not None:
            xmax = max(xmax, p["unstable_at"])
        extra = []
        if p.get("undecided"):
            extra.append(f"{p['undecided']} undecided")
        if p.get("landings") is not None:
            extra.append(f"{p['landings']} landings")
        if extra:
            ax.annotate(", ".join(extra), (0, vv), xytext=(4, 6), textcoords="offset points",
                        fontsize=7.5, color="0.35")
    unstable = [(p["unstable_at"], vv) for vv, p in pts if p.get("unstable_at") is not None]
    if unstable:
        ax.plot([x for x, _ in unstable], [y for _, y in unstable], "x", color=C_REPORT, ms=8,
                label="ours: first overturning landing found")

    ax.axhline(10, color=C_REPORT, ls="--", lw=1)
    ax.text(0.01, 0.98, "dashed: report, fig. 27: the analysis's boundary is within 1 ft/s of the "
            "experiment's at Vv = 10 ft/s (the figure's points are not available)",
            color=C_REPORT, fontsize=8.5, va="top", ha="left", transform=ax.transAxes)
    ax.set_xlim(0, xmax * 1.3)
    vvs = [vv for vv, _ in pts] or [10]
    ax.set_ylim(0, max(max(vvs), 10) + 2)
    ax.set_xlabel("horizontal velocity Vh (ft/s)")
    ax.set_ylabel("descent velocity Vv (ft/s)")
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=9)
    ax.set_title("2-2 landing stability boundary, reconstructed 1/6-scale model "
                 "(scenarios/fig-25-26.toml)", fontsize=11)
    save(fig, out)


# --------------------------------------------------------------------------------------------


def main(argv=None) -> int:
    root = Path(__file__).resolve().parent.parent
    default = root / "docs" / "validation"
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", type=Path, default=default,
                    help=f"folder with {VALIDATION}, {SERIES}, {BOUNDARY} (default: docs/validation)")
    ap.add_argument("--out", type=Path, default=None,
                    help="folder for the PNGs (default: the data folder)")
    args = ap.parse_args(argv)
    data_dir: Path = args.data
    out_dir: Path = args.out if args.out is not None else data_dir

    try:
        if not data_dir.is_dir():
            raise DataError(f"data folder {data_dir} does not exist")
        validation = load_json(data_dir, VALIDATION, "touchdown validate --out DIR")
        series = load_json(data_dir, SERIES, "touchdown validate --out DIR")
        boundary = load_json(data_dir, BOUNDARY, "touchdown boundary ... --format json")
        out_dir.mkdir(parents=True, exist_ok=True)
        plot_table_i(validation, out_dir / "table-i.png")
        plot_fig_25_26(series, validation, out_dir / "fig-25-26.png")
        plot_boundary(boundary, out_dir / "boundary-2-2.png")
    except DataError as e:
        print(f"plot_validation: error: {e}", file=sys.stderr)
        return 2
    for name in ("table-i.png", "fig-25-26.png", "boundary-2-2.png"):
        print(out_dir / name)
    return 0


if __name__ == "__main__":
    sys.exit(main())
