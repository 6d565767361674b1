#!/usr/bin/env python3
"""Engine-comparison plots for Touchdown (`touchdown compare --plot`, `touchdown boundary --plot`,
`touchdown precision --plot`).

Three kinds, both drawn from data the `touchdown` CLI writes, so that a plot shows exactly the
series and boundaries the Rust side measured (nothing is recomputed here):

* traces      one landing on several engines, overlaid: the vertical acceleration over the
              comparison's 2 ms window, the pitch rate, and every leg's primary stroke against
              time. Input: `<stem>.<engine>.csv` per engine (touchdown_compare::plot).
* boundaries  the stability boundary of one configuration computed by each engine, overlaid:
              descent speed against the horizontal speed at which the landing turns unstable
              (the lowest stable -> unstable transition), every transition's bracket as a bar
              (dotted if unresolved), the further transitions marked > (stable -> unstable) or
              < (unstable -> stable), and every undecided landing as x. Input: the JSON of
              `touchdown boundary --engines ... --format json` (one point per engine and
              descent speed, each naming its engine).
* precision   work-precision: log-log error against wall time, one line per engine and
              scheme over its ladder of steps or tolerances (strokes; pitch-rate history;
              final attitude), failed rungs left out, the 1 % stroke error marked. Input: the
              JSON of `touchdown precision --format json`.

Usage:
  python/plot_compare.py traces --data DIR --stem STEM --engines core,rapier,mujoco \
      --title TITLE --out FILE.png
  python/plot_compare.py boundaries --data FILE.json --unit ft/s --title TITLE --out FILE.png
  python/plot_compare.py precision --data FILE.json --title TITLE --out FILE.png

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
    # The arrows drawn by annotate do not widen the axes: the right end is set from them.
    xmax = 1.0
    # One legend entry per kind of mark, whichever engine drew it first.
    labelled: set[str] = set()

    def once(kind: str, label: str) -> str | None:
        if kind in labelled:
            return None
        labelled.add(kind)
        return label

    for engine, engine_points in by_engine.items():
        colour = COLOURS.get(engine, "black")
        # The reported boundary: the lowest stable -> unstable transition at each Vv.
        found = [p for p in engine_points if p.get("vh") is not None]
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
            transitions = p.get("transitions", [])
            if not transitions and p.get("unstable_at") is None and p.get("stable_at") is not None:
                # Stable up to the largest speed found stable: an arrow past it.
                lo = p["stable_at"]
                xmax = max(xmax, lo + 1.0)
                ax.annotate(
                    "",
                    xy=(lo + 1.0, y),
                    xytext=(lo, y),
                    arrowprops={"arrowstyle": "->", "color": colour},
                )
            if not transitions and p.get("unstable_at") is not None:
                # Unstable from the smallest speed found unstable, nothing stable below it.
                ax.plot(
                    p["unstable_at"],
                    y,
                    "|",
                    color=colour,
                    ms=10,
                    ls="none",
                    label=once("unstable", "unstable from here, nothing stable below"),
                )
            for t in transitions:
                lo, hi = sorted((t["stable_at"], t["unstable_at"]))
                if t["resolved"]:
                    # Every transition's bracket as a bar; the ones beyond the reported
                    # boundary also get a marker: > stable to unstable, < unstable to stable.
                    ax.plot([lo, hi], [y, y], color=colour, lw=4, alpha=0.35)
                    if t.get("vh") != p.get("vh"):
                        up = t["direction"] == "stable_to_unstable"
                        ax.plot(
                            t["vh"],
                            y,
                            ">" if up else "<",
                            color=colour,
                            ms=6,
                            ls="none",
                            label=once(
                                "up" if up else "down",
                                "further transition, stable → unstable"
                                if up
                                else "transition unstable → stable",
                            ),
                        )
                else:
                    # Unresolved: an undecided landing inside the bracket.
                    ax.plot(
                        [lo, hi],
                        [y, y],
                        color=colour,
                        lw=4,
                        alpha=0.35,
                        ls=":",
                        label=once("unresolved", "unresolved bracket (undecided inside)"),
                    )
            undecided = p.get("undecided_at", [])
            if undecided:
                ax.plot(
                    undecided,
                    [y] * len(undecided),
                    "x",
                    color=colour,
                    ms=6,
                    ls="none",
                    label=once("undecided", "undecided landing"),
                )
    ax.set_xlabel(f"horizontal touchdown speed Vh, {args.unit}")
    ax.set_ylabel(f"descent speed Vv, {args.unit}")
    ax.grid(True, alpha=0.3)
    left, right = ax.get_xlim()
    ax.set_xlim(left=min(left, 0.0), right=max(right, 1.05 * xmax))
    vvs = [p["vv"] for p in points]
    if vvs:
        pad = max(0.5, 0.1 * (max(vvs) - min(vvs)))
        ax.set_ylim(min(vvs) - pad, max(vvs) + pad)
    ax.legend(title="boundary: lowest stable → unstable", fontsize=8, loc="best")
    ax.set_title(args.title, fontsize=10)
    fig.tight_layout()
    fig.savefig(args.out, dpi=DPI, metadata=PNG_METADATA)


# One colour and marker per integration method of the work-precision plot.
METHODS = {
    "report": ("core report", COLOURS["core"], "o"),
    "rk4": ("core rk4", "#7570b3", "s"),
    "dopri5": ("core dopri5", "#e7298a", "^"),
    "rapier": ("rapier", COLOURS["rapier"], "D"),
    "mujoco": ("mujoco", COLOURS["mujoco"], "v"),
}


def precision(args: argparse.Namespace) -> None:
    study = json.loads(Path(args.data).read_text())
    panels = [
        ("max_stroke", "maximum-stroke error\n(fraction of the largest primary stroke)"),
        ("pitch_rate_rms", "pitch-rate history RMS error\n(fraction of its peak)"),
        ("final_attitude_rad", "final-attitude error, rad"),
    ]
    fig, axes = plt.subplots(1, 3, figsize=(15, 5))
    for ax, (key, label) in zip(axes, panels):
        for method, (name, colour, marker) in METHODS.items():
            rungs = [r for r in study["rungs"] if r["method"] == method and r.get("measured")]
            # A log axis cannot show an exact zero: such a rung sits at the axis floor.
            points = [
                (r["measured"]["wall_time_s"], max(r["measured"]["errors"][key], 1e-12))
                for r in rungs
            ]
            if points:
                ax.loglog(*zip(*points), marker=marker, color=colour, lw=1.4, label=name)
        if key == "max_stroke":
            ax.axhline(study["fixed_error"], color="grey", ls="--", lw=1, label="1 % of stroke")
        ax.set_xlabel("wall time per landing, s (median)")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    build = "" if study["optimised_build"] else " (debug build: times not representative)"
    fig.suptitle(f"{args.title}: work-precision against the converged reference{build}", fontsize=10)
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
    p = sub.add_parser("precision")
    p.add_argument("--data", required=True)
    p.add_argument("--title", default="")
    p.add_argument("--out", required=True)
    args = ap.parse_args()
    {"traces": traces, "boundaries": boundaries, "precision": precision}[args.kind](args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
