#!/usr/bin/env python3
"""Validation plots for Touchdown (NASA TN D-7045 lander touchdown dynamics).

Reads the data files that the `touchdown` CLI writes into a folder (default docs/validation/):

* validation.json        `touchdown validate --out DIR` (Table I rows, held-out errors, facts)
* fig-25-26-series.json  `touchdown validate --out DIR` (time histories of the figs. 25-26 landing)
* boundary-2-2.jsonl     `touchdown boundary scenarios/fig-25-26.toml ... --format json` (JSON Lines)

and writes three PNGs into an output folder (default: the data folder), each with the data it
draws beside it under the same name:

* table-i.png      Table I maximum strokes per row: experiment, the report's analysis, ours
                   (table-i.csv: the bars);
* fig-25-26.png    vertical acceleration, pitch rate and primary strokes against time, with the
                   report's stated facts about figures 25-26 overlaid (fig-25-26.csv: the curves);
* boundary-2-2.png the stability boundary of the figure 25-26 configuration (horizontal vs
                   descent velocity), drawn as `touchdown boundary --plot` draws one
                   (python/figures/plot_compare.py) (boundary-2-2.jsonl, copied when --out is another
                   folder).

Usage: python/figures/plot_validation.py [--data DIR] [--out DIR]

Run it with the project's venv (`scripts/setup-python`, then `.venv/bin/python`); `scripts/plots`
regenerates the data and the plots together. The output is deterministic as far as matplotlib
allows: Agg backend, fixed figure sizes and DPI, no software/time stamps in the PNG metadata.
"""

from __future__ import annotations

import argparse
import csv
import json
import shutil
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402  (after selecting the backend)
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

# The boundary is drawn, and its JSON read, as `touchdown boundary --plot` draws and reads one.
from plot_compare import boundary_legends, boundary_title, draw_boundary, read_boundary_points  # noqa: E402

FT_PER_M = 1.0 / 0.3048
DPI = 110
PNG_METADATA = {"Software": None}

VALIDATION = "validation.json"
SERIES = "fig-25-26-series.json"
BOUNDARY = "boundary-2-2.jsonl"
# Metres per foot and per inch: the documents are SI, the report's Table I and figures are not.
M_PER_FT = 0.3048
M_PER_IN = 0.0254

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


# The inputs' field names are read in one function per input (read_validation, read_series,
# load_boundary): a renamed field is changed there and nowhere else.


def read_validation(data_dir: Path) -> dict:
    """VALIDATION as {"rows": [{"id", "strut" ("primary" or "secondary"), "calibration" (bool),
    "vv", "vh" (ft/s), "experiment", "analysis", "ours" (maximum stroke, in), "error_pct" (ours
    against the experiment, or None)}], "held_out_ours" and "held_out_report" ({"mean_pct",
    "max_pct"} of the held-out rows' |error|, or None), "facts" ({fact: ours, as text})}."""
    v = load_json(data_dir, VALIDATION, "touchdown validate --out DIR")
    try:
        rows = [
            {
                "id": r["id"],
                "strut": r["strut"],
                "calibration": r.get("role") == "calibration",
                # The document is SI; Table I is drawn in the report's units.
                "vv": r["vv_m_s"] / M_PER_FT,
                "vh": r["vh_m_s"] / M_PER_FT,
                "experiment": r["experiment_m"] / M_PER_IN,
                "analysis": r["analysis_m"] / M_PER_IN,
                "ours": r["ours_m"] / M_PER_IN,
                "error_pct": r.get("error_vs_experiment_pct"),
            }
            for r in v["rows"]
        ]

        def held_out(key):
            h = v.get(key)
            return {"mean_pct": h["mean_abs_error_pct"], "max_pct": h["max_abs_error_pct"]} if h else None

        facts = {f.get("fact"): f.get("ours") for f in (v.get("facts") or []) if isinstance(f, dict)}
        return {"rows": rows, "held_out_ours": held_out("held_out_ours"),
                "held_out_report": held_out("held_out_report"), "facts": facts}
    except (KeyError, TypeError) as e:
        raise DataError(f"{VALIDATION}: missing field {e}") from e


def read_series(data_dir: Path) -> dict:
    """SERIES as {"t" (s), "acc_g" (vertical acceleration, g), "pitch_rate" (rad/s), "strokes"
    (primary stroke per footpad, m), "contacts" (footpads in contact per sample, bit i set:
    footpad i + 1)}, every series as long as "t"."""
    s = load_json(data_dir, SERIES, "touchdown validate --out DIR")
    try:
        t = s["t_s"]
        series = {
            "t": t,
            "acc_g": s["vertical_acceleration_g"],
            "pitch_rate": s["pitch_rate_rad_s"],
            "strokes": s["primary_stroke_m"],
            "contacts": s.get("contacts") or [1] * len(t),
        }
    except (KeyError, TypeError) as e:
        raise DataError(f"{SERIES}: missing field {e}") from e
    for name in ("acc_g", "pitch_rate", "contacts"):
        if len(series[name]) != len(t):
            raise DataError(f"{SERIES}: {name} has {len(series[name])} samples, t has {len(t)}")
    for i, leg in enumerate(series["strokes"]):
        if len(leg) != len(t):
            raise DataError(f"{SERIES}: primary stroke {i + 1} has {len(leg)} samples, t has {len(t)}")
    return series


def save(fig, out: Path):
    fig.savefig(out, dpi=DPI, metadata=PNG_METADATA)
    plt.close(fig)


# --------------------------------------------------------------------------------------------
# Table I


def plot_table_i(validation, out: Path):
    rows = validation["rows"]
    groups = [
        ("primary", "Primary strut stroke (1-2-1 landings)"),
        ("secondary", "Secondary strut stroke (2-2 landings)"),
    ]
    fig, axes = plt.subplots(1, 2, figsize=(12, 6), layout="constrained")
    width = 0.26
    for ax, (strut, title) in zip(axes, groups):
        sel = [r for r in rows if r["strut"] == strut]
        sel.sort(key=lambda r: r["id"])
        xs = list(range(len(sel)))
        top = max([1.0] + [max(r["experiment"], r["analysis"], r["ours"]) for r in sel])
        for x, r in zip(xs, sel):
            if r["calibration"]:
                ax.axvspan(x - 0.5, x + 0.5, color=C_CALIBRATION, alpha=0.25, lw=0, zorder=0)
        ax.bar([x - width for x in xs], [r["experiment"] for r in sel], width,
               color=C_EXPERIMENT, label="experiment (Table I)", zorder=2)
        ax.bar(xs, [r["analysis"] for r in sel], width,
               color=C_ANALYSIS, label="report's analysis (Table I)", zorder=2)
        ours = ax.bar([x + width for x in xs], [r["ours"] for r in sel], width,
                      color=C_OURS, label="ours", zorder=2)
        for bar, r in zip(ours, sel):
            if r["calibration"]:
                bar.set_hatch("//")
                bar.set_edgecolor("white")
            err = r["error_pct"]
            if err is not None:
                ax.annotate(f"{err:+.0f}%", (bar.get_x() + bar.get_width() / 2, bar.get_height()),
                            xytext=(0, 3), textcoords="offset points", ha="center",
                            va="bottom", fontsize=8, color=C_OURS)
        labels = []
        for r in sel:
            role = "calibration" if r["calibration"] else "held out"
            labels.append(
                f"row {r['id']} ({role})\n"
                f"Vv {abs(r['vv']):g}, Vh {r['vh']:g} ft/s"
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
            f"\nheld-out rows mean |error| vs experiment: ours {ho['mean_pct']:.1f}% "
            f"(max {ho['max_pct']:.1f}%), report's analysis {hr['mean_pct']:.1f}% "
            f"(max {hr['max_pct']:.1f}%)"
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


def ours_of(facts, name):
    ours = facts.get(name)
    return f" (ours {ours})" if ours else ""


def plot_fig_25_26(series, validation, out: Path):
    t, acc, q = series["t"], series["acc_g"], series["pitch_rate"]
    strokes, contacts = series["strokes"], series["contacts"]
    facts = validation["facts"]

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
    # Out to the report's 0.12 s marks even where our landing is decided sooner.
    a3.set_xlim(0, max(t[-1], REPORT_MAX_STROKING_S + 0.01))

    fig.suptitle("TN D-7045 figures 25-26 landing (2-2, 5° slope, 4-in depressions under the "
                 "downhill footpads)\nours vs the report's stated facts (the figures' curves are "
                 "not available)", fontsize=11.5)
    save(fig, out)


# --------------------------------------------------------------------------------------------
# Stability boundary


def load_boundary(data_dir: Path):
    """The boundary points of BOUNDARY (read by plot_compare.read_boundary_points, which names
    the JSON's fields for both boundary plots)."""
    path = data_dir / BOUNDARY
    if not path.is_file():
        raise DataError(f"missing data file {path} (written by `touchdown boundary ... --format json`; "
                        "`scripts/plots` regenerates all)")
    try:
        return read_boundary_points(path, "ft/s")
    except (OSError, ValueError, KeyError, TypeError) as e:
        raise DataError(f"cannot read {path}: {e}") from e


def plot_boundary(points, out: Path):
    """The stability boundary of the figure 25-26 configuration, drawn as `touchdown boundary
    --plot` draws one (python/figures/plot_compare.py), with the report's statement about fig. 27 in the
    legend (its points are not available, so nothing of it is drawn)."""
    fig, ax = plt.subplots(figsize=(12, 6.5), layout="constrained")
    engine_handles, kind_handles = draw_boundary(ax, points, "ft/s")
    vvs = [p["vv"] for p in points] or [10.0]
    ax.set_ylim(0, max(max(vvs), 10) + 2)
    report = Line2D([], [], ls="none", label="report, fig. 27: its analysis's boundary is within\n"
                                             "1 ft/s of the experiment's at Vv = 10 ft/s (the\n"
                                             "figure's points are not available: not drawn)")
    boundary_legends(ax, engine_handles, kind_handles, extra=[report])
    first_line = ("Stability boundary of the figures 25-26 configuration (scenarios/fig-25-26.toml):\n"
                  "reconstructed 1/6-scale model, 2-2, 5° slope, 4-in depressions under the downhill footpads")
    fig.suptitle(boundary_title(first_line, points, "ft/s"), fontsize=10.5)
    save(fig, out)


# --------------------------------------------------------------------------------------------
# The data beside each plot: what it draws, as CSV with the plot's basename.


def write_csv(path: Path, header: list[str], rows) -> None:
    with path.open("w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        w.writerows(rows)


def table_i_data(validation, path: Path) -> None:
    """table-i.csv: the bars of table-i.png, one row per Table I row."""
    rows = sorted(validation["rows"], key=lambda r: (r["strut"], r["id"]))
    write_csv(
        path,
        ["row", "strut", "role", "vv_m_s", "vh_m_s", "experiment_m", "analysis_m", "ours_m",
         "ours_error_vs_experiment_pct"],
        ([r["id"], r["strut"], "calibration" if r["calibration"] else "held out",
          f"{r['vv'] * M_PER_FT:.6g}", f"{r['vh'] * M_PER_FT:.6g}", f"{r['experiment'] * M_PER_IN:.6g}",
          f"{r['analysis'] * M_PER_IN:.6g}", f"{r['ours'] * M_PER_IN:.6g}",
          "" if r["error_pct"] is None else r["error_pct"]]
         for r in rows),
    )


def fig_25_26_data(series, path: Path) -> None:
    """fig-25-26.csv: the curves of fig-25-26.png, one row per sample."""
    t, strokes, contacts = series["t"], series["strokes"], series["contacts"]
    header = ["t_s", "vertical_acceleration_g", "pitch_rate_rad_s"]
    header += [f"footpad{i + 1}_primary_stroke_m" for i in range(len(strokes))]
    header += [f"footpad{i + 1}_in_contact" for i in range(len(strokes))]
    write_csv(
        path,
        header,
        ([t[k], series["acc_g"][k], series["pitch_rate"][k]]
         + [f"{leg[k]:.6g}" for leg in strokes]
         + [(int(contacts[k]) >> i) & 1 for i in range(len(strokes))] for k in range(len(t))),
    )


# --------------------------------------------------------------------------------------------


def main(argv=None) -> int:
    root = Path(__file__).resolve().parents[2]
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
        validation = read_validation(data_dir)
        series = read_series(data_dir)
        boundary = load_boundary(data_dir)
        out_dir.mkdir(parents=True, exist_ok=True)
        plot_table_i(validation, out_dir / "table-i.png")
        table_i_data(validation, out_dir / "table-i.csv")
        plot_fig_25_26(series, validation, out_dir / "fig-25-26.png")
        fig_25_26_data(series, out_dir / "fig-25-26.csv")
        plot_boundary(boundary, out_dir / "boundary-2-2.png")
        if out_dir.resolve() != data_dir.resolve():
            shutil.copyfile(data_dir / BOUNDARY, out_dir / BOUNDARY)
    except DataError as e:
        print(f"plot_validation: error: {e}", file=sys.stderr)
        return 2
    for name in ("table-i.png", "fig-25-26.png", "boundary-2-2.png"):
        print(out_dir / name)
    return 0


if __name__ == "__main__":
    sys.exit(main())
