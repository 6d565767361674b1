#!/usr/bin/env python3
"""Engine-comparison plots for Touchdown (`touchdown compare --plot`, `touchdown boundary --plot`).

Two kinds, both drawn from data the `touchdown` CLI writes, so that a plot shows exactly the
series and boundaries the Rust side measured (nothing is recomputed here):

* traces      one landing on several engines, overlaid: the vertical acceleration over the
              comparison's 2 ms window, the pitch rate, and every leg's primary stroke against
              time. Input: `<stem>.<engine>.csv` per engine (touchdown_compare::plot).
* boundaries  the stability boundary of one configuration computed by each engine, overlaid:
              descent speed against the horizontal speed at which the landing turns unstable,
              with the bracket (last stable, first unstable) as a bar. Input: the JSON of
              `touchdown boundary --engines ... --format json` (one point per engine and
              descent speed, each naming its engine).

Usage:
  python/plot_compare.py traces --data DIR --stem STEM --engines core,rapier,mujoco \
      --title TITLE --out FILE.png
  python/plot_compare.py boundaries --data FILE.json --unit ft/s --title TITLE --out FILE.png

Run it with the project's venv (`scripts/setup-python`, then `.venv/bin/python`); the CLI does.
The output is deterministic as far as matplotlib allows: Agg backend, fixed sizes and DPI, no
software stamp in the PNG metadata.
"""

from __future__ import annotations

import argparse
import csv
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402  (after selecting the backend)

DPI = 110
PNG_METADATA = {"Software": None}
# One colour per engine, the same in every plot; one line style per leg.
COLOURS = {"core": "#1f3b73", "rapier": "#d95f02", "mujoco": "#1b9e77"}
LEG_STYLES = ["-", "--", ":", "-."]


def read_trace(path: Path) -> dict[str, list[float]]:
    """Columns of a trace CSV as float lists (empty cells dropped from their column)."""
    with path.open(newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit(f"plot_compare: {path} has no rows")
    columns: dict[str, list[float]] = {}
    for name in rows[0]:
        columns[name] = [float(r[name]) for r in rows if r[name] != ""]
    return columns


def traces(args: argparse.Namespace) -> None:
    data = Path(args.data)
    engines = [e for e in args.engines.split(",") if e]
    runs = {e: read_trace(data / f"{args.stem}.{e}.csv") for e in engines}
    fig, axes = plt.subplots(3, 1, figsize=(9, 10), sharex=True)
    acc, pitch, stroke = axes
    for engine, c in runs.items():
        colour = COLOURS.get(engine, "black")
        acc.plot(
            c["acceleration_t_s"],
            c["vertical_acceleration_m_s2"],
            color=colour,
            lw=1.2,
            label=engine,
        )
        pitch.plot(c["t_s"], c["pitch_rate_rad_s"], color=colour, lw=1.2, label=engine)
        legs = sorted(k for k in c if k.endswith("_primary_stroke_m"))
        for i, leg in enumerate(legs):
            stroke.plot(
                c["t_s"],
                [1000.0 * x for x in c[leg]],
                color=colour,
                ls=LEG_STYLES[i % len(LEG_STYLES)],
                lw=1.1,
                label=f"{engine} leg {leg[3:leg.index('_')]}",
            )
    acc.set_ylabel("vertical acceleration, m/s²\n(2 ms window, up +)")
    pitch.set_ylabel("pitch rate, rad/s")
    stroke.set_ylabel("primary stroke, mm")
    stroke.set_xlabel("time since first contact, s")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.axhline(0.0, color="grey", lw=0.6)
    acc.legend(loc="best", fontsize=8)
    stroke.legend(loc="best", fontsize=7, ncol=len(engines))
    fig.suptitle(args.title, fontsize=11)
    fig.tight_layout()
    fig.savefig(args.out, dpi=DPI, metadata=PNG_METADATA)


def boundaries(args: argparse.Namespace) -> None:
    points = json.loads(Path(args.data).read_text())
    by_engine: dict[str, list[dict]] = {}
    for p in points:
        by_engine.setdefault(p["engine"], []).append(p)
    fig, ax = plt.subplots(figsize=(7.5, 5.5))
    offsets = {e: 0.08 * (i - 1) for i, e in enumerate(COLOURS)}
    for engine, engine_points in by_engine.items():
        colour = COLOURS.get(engine, "black")
        found = [p for p in engine_points if p["vh"] is not None]
        ax.plot(
            [p["vh"] for p in found],
            [p["vv"] for p in found],
            "o-",
            color=colour,
            lw=1.6,
            label=f"{engine}",
        )
        for p in engine_points:
            y = p["vv"] + offsets.get(engine, 0.0)
            lo = p["stable_at"] if p["stable_at"] is not None else 0.0
            if p["unstable_at"] is None:
                # Stable up to the largest speed tried: an arrow past it.
                ax.annotate(
                    "",
                    xy=(lo + 1.0, y),
                    xytext=(lo, y),
                    arrowprops={"arrowstyle": "->", "color": colour},
                )
            else:
                ax.plot([lo, p["unstable_at"]], [y, y], color=colour, lw=4, alpha=0.35)
            if p["undecided"]:
                ax.annotate(
                    f"{p['undecided']} undecided",
                    (lo, y),
                    fontsize=7,
                    color=colour,
                    textcoords="offset points",
                    xytext=(3, 3),
                )
    ax.set_xlabel(f"horizontal touchdown speed Vh, {args.unit}")
    ax.set_ylabel(f"descent speed Vv, {args.unit}")
    ax.grid(True, alpha=0.3)
    ax.set_xlim(left=0.0)
    ax.legend(title="unstable to the right of", fontsize=9)
    ax.set_title(args.title, fontsize=10)
    fig.tight_layout()
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
    b = sub.add_parser("boundaries")
    b.add_argument("--data", required=True)
    b.add_argument("--title", default="")
    b.add_argument("--unit", default="ft/s")
    b.add_argument("--out", required=True)
    args = ap.parse_args()
    {"traces": traces, "boundaries": boundaries}[args.kind](args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
