#!/usr/bin/env python3
"""The cross-validation plot (docs/validation.md, "Cross-validation").

Reads cross-validation.json (`touchdown validate --protocol cv --out DIR`) from the data folder
and writes cross-validation.png into the output folder (both default docs/validation/):

* left:   each Table I row's stroke: the experiment with its ±10 % band, the report's
          analysis, and ours predicted out of fold with the 95 % interval of the calibration's
          uncertainty;
* middle: the profile of the objective along each parameter over its bounds, the others fitted
          again to every row (a flat profile is a parameter the rows do not fix);
* right:  each parameter's spread at that fit against its bounds' (sd / bounds' sd), with the
          protocol's line between determined and not.

Usage: python/figures/plot_cross_validation.py [--data DIR] [--out DIR]   (the project's .venv)
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402  (after selecting the backend)

DPI = 110
PNG_METADATA = {"Software": None}
C_EXPERIMENT = "#000000"
C_REPORT = "#E69F00"
C_OURS = "#0072B2"
C_BAD = "#D55E00"


# Metres per inch.
M_PER_IN = 0.0254


def main(argv=None) -> int:
    default = Path(__file__).resolve().parents[2] / "docs" / "validation"
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", type=Path, default=default, help="folder holding cross-validation.json")
    ap.add_argument("--out", type=Path, default=None, help="folder for cross-validation.png (default: --data)")
    args = ap.parse_args(argv)
    path = args.data / "cross-validation.json"
    if not path.is_file():
        print(f"error: missing {path} (written by `touchdown validate --protocol cv --out DIR`; `scripts/plots` regenerates it)", file=sys.stderr)
        return 1
    cv = json.loads(path.read_text(encoding="utf-8"))
    out = args.out or args.data
    out.mkdir(parents=True, exist_ok=True)

    fig, (a, b, c) = plt.subplots(1, 3, figsize=(16, 5.4), gridspec_kw={"width_ratios": [1.5, 1.2, 1.0]},
                                  constrained_layout=True)
    # The document is SI; Table I's strokes are drawn in the report's inches.
    folds = [
        {
            **f,
            "experiment_in": f["experiment_m"] / M_PER_IN,
            "report_in": f["report_m"] / M_PER_IN,
            "predicted_in": f["predicted_m"] / M_PER_IN,
            "interval_in": [v / M_PER_IN for v in f["interval_m"]],
        }
        for f in cv["folds"]
    ]
    x = list(range(len(folds)))
    exp = [f["experiment_in"] for f in folds]
    a.bar(x, [0.2 * e for e in exp], bottom=[0.9 * e for e in exp], width=0.6, color="0.88",
          label="experiment ±10 %")
    a.plot(x, exp, "_", color=C_EXPERIMENT, ms=22, mew=2.5, label="experiment (Table I)")
    a.plot([i - 0.15 for i in x], [f["report_in"] for f in folds], "s", color=C_REPORT, ms=6,
           label="report's analysis")
    ours = [f["predicted_in"] for f in folds]
    low = [f["predicted_in"] - f["interval_in"][0] for f in folds]
    high = [f["interval_in"][1] - f["predicted_in"] for f in folds]
    a.errorbar([i + 0.15 for i in x], ours, yerr=[low, high], fmt="o", color=C_OURS, capsize=4,
               label="ours, out of fold, 95 % interval")
    for i, f in enumerate(folds):
        a.annotate(f"{f['error_pct']:+.0f} %", (i + 0.15, f["interval_in"][1]), textcoords="offset points",
                   xytext=(0, 4), ha="center", fontsize=8, color=C_OURS if f["within_10_pct"] else C_BAD)
    a.set_xticks(x, [f"row {f['held_out']}" for f in folds])
    a.set_ylabel("maximum compression stroke, in")
    e = cv["two_row_held_out"]
    a.set_title(f"Table I, leave-one-out: mean |error| {cv['all_rows']['mean_pct']:.1f} % "
                f"(report {cv['all_rows']['report_mean_pct']:.1f} %)\n"
                f"on rows {', '.join(map(str, e['rows']))}: {e['mean_pct']:.1f} % (report {e['report_mean_pct']:.1f} %)",
                fontsize=10)
    a.legend(fontsize=8, loc="upper right")
    a.text(1.5, 0.2, "1-2-1 rows: primary strut", ha="center", fontsize=8, color="0.3")
    a.text(5.5, 0.2, "2-2 rows: secondary strut", ha="center", fontsize=8, color="0.3")
    a.axvline(3.5, color="0.6", lw=0.8)
    a.set_ylim(bottom=0)

    fit = cv["full_fit"]["objective"]
    for k, p in enumerate(cv["profiles"]):
        lo, hi = p["value"][0], p["value"][-1]
        pos = [(v - lo) / (hi - lo) for v in p["value"]]
        b.plot(pos, p["objective"], "-o", ms=3, label=p["name"])
        at = (cv["full_fit"]["value"][k] - lo) / (hi - lo)
        b.plot([at], [fit], "k*", ms=8)
    b.set_yscale("log")
    b.set_xlabel("parameter position within its bounds (0 = lower, 1 = upper)")
    b.set_ylabel("objective: Σ (relative stroke error)² over the 8 rows")
    b.set_title("Profile of the objective: each parameter held at a value, the others fitted again\n"
                "to every row (★ the fit); a flat profile is a parameter the rows do not fix",
                fontsize=9.5)
    b.legend(fontsize=7.5, loc="upper center")

    params = cv["identifiability"]["parameters"]
    ratio = [d["ratio"] for d in params]
    colours = [C_OURS if d["determined"] else C_BAD for d in params]
    names = [d["name"].replace(" (tension = compression)", "") for d in params]
    c.barh(range(len(params)), ratio, color=colours)
    limit = cv["protocol"]["determined_ratio"]
    c.axvline(limit, color="k", ls="--", lw=1)
    c.text(limit, len(params) - 0.4, f" determined below {limit:g}", fontsize=8, va="bottom")
    c.set_yticks(range(len(params)), names, fontsize=8)
    c.invert_yaxis()
    c.set_xlim(0, 1.05)
    c.set_xlabel("sd at the fit / sd of the bounds\n(1: the rows say nothing)")
    c.set_title("What Table I determines", fontsize=10)

    fig.suptitle("Cross-validation of the reconstructed 1/6-scale model over TN D-7045 Table I "
                 "(reference/cross-validation-protocol.toml)", fontsize=11.5)
    fig.savefig(out / "cross-validation.png", dpi=DPI, metadata=PNG_METADATA)
    return 0


if __name__ == "__main__":
    sys.exit(main())
