#!/usr/bin/env python3
"""Regenerates the two engine comparison tables of docs/engines.md as Markdown.

    python3 python/figures/engine_tables.py [--touchdown BIN] [--jobs N] [--out FILE]

(normally through `scripts/engine-tables`, which builds the release binary first). Runs
`touchdown run SCENARIO --engine core|rapier|mujoco --format json` on every landing of the
tables (the eight scenarios/table-i-*.toml, fig-25-26.toml and flat-drop.toml) from the
workspace root and prints, or writes to FILE (e.g. docs/engines/tables.md), two tables:

- core / rapier, the table under "Where the rebuild parts from the core";
- core / mujoco with the rapier cross-check, the table under "Where MuJoCo parts from the core,
  and where it agrees with rapier".

Definitions (as docs/engines.md states them):
- max primary stroke: the largest of the four legs' maximum primary strokes;
- a "worst" column names the leg (primary, strokes above 10 mm in either engine) or the leg's
  secondary strut (3-1 or 4-1, strokes above 5 mm in either engine) with the largest relative
  difference, |second - first| / first, written `leg 3: 0.0185 / 0.0195 (+4.9 %)` (first
  engine / second engine, and the second's relative difference against the first); a
  secondary strut's stroke is the larger of its compression and tension maxima;
- "primary vs rapier": the largest difference of a leg's maximum primary stroke between rapier
  and MuJoCo, as a fraction of the landing's largest primary stroke on those two engines;
- peak pitch rate: the summary's signed `peak_pitch_rate_rad_s`;
- balance residual: `energy.residual_j` as a percentage of the energy put in,
  `kinetic_initial_j + max(0, -potential_change_j) + driving_input_j` (the energy guard's
  scale).

BIN defaults to $TOUCHDOWN, else target/release/touchdown (the MuJoCo engine finds
libtouchdown_mujoco.so next to it, and the project's .venv, made by scripts/setup-python). N
defaults to the number of CPUs. Thirty runs, about 20 s on two cores. Standard library only.
"""

import argparse
import json
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
ENGINES = ("core", "rapier", "mujoco")
PRIMARY_MIN_M = 0.010
SECONDARY_MIN_M = 0.005
STRUTS = ("3-1", "4-1")


def landings():
    table_i = sorted(p.name for p in (ROOT / "scenarios").glob("table-i-*.toml"))
    return table_i + ["fig-25-26.toml", "flat-drop.toml"]


def run(touchdown, landing, engine):
    cmd = [touchdown, "run", f"scenarios/{landing}", "--engine", engine, "--format", "json"]
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(
            f"`{' '.join(cmd)}` exited with {p.returncode}:\n{p.stderr.strip()}"
        )
    return json.loads(p.stdout)


def primary(s):
    return list(s["max_primary_stroke_m"])


def secondary(s):
    """{(leg, strut): stroke}: the larger of each secondary's compression and tension maxima."""
    out = {}
    for leg, (comp, tens) in enumerate(
        zip(s["max_secondary_compression_m"], s["max_secondary_tension_m"]), start=1
    ):
        for k, strut in enumerate(STRUTS):
            out[(leg, strut)] = max(comp[k], tens[k])
    return out


def rel(a, b):
    return (b - a) / a if a > 0 else float("inf")


def worst(first, second, minimum, label):
    """The key with the largest relative difference among strokes above `minimum`."""
    best = None
    for key in first:
        a, b = first[key], second[key]
        if max(a, b) <= minimum:
            continue
        r = rel(a, b)
        if best is None or abs(r) > abs(best[1]):
            best = (key, r)
    if best is None:
        return f"none above {minimum * 1000:.0f} mm"
    key, r = best
    pct = "new" if r == float("inf") else f"{100 * r:+.1f} %"
    return f"{label(key)}: {first[key]:.4f} / {second[key]:.4f} ({pct})"


def worst_primary(s1, s2):
    p1 = dict(enumerate(primary(s1), start=1))
    p2 = dict(enumerate(primary(s2), start=1))
    return worst(p1, p2, PRIMARY_MIN_M, lambda leg: f"leg {leg}")


def worst_secondary(s1, s2):
    return worst(
        secondary(s1), secondary(s2), SECONDARY_MIN_M, lambda k: f"leg {k[0]} {k[1]}"
    )


def residual_pct(s):
    e = s["energy"]
    put_in = e["kinetic_initial_j"] + max(0.0, -e["potential_change_j"]) + e["driving_input_j"]
    return f"{100 * e['residual_j'] / put_in:+.2f} %"


def primary_vs(s1, s2):
    p1, p2 = primary(s1), primary(s2)
    largest = max(p1 + p2)
    return f"{100 * max(abs(a - b) for a, b in zip(p1, p2)) / largest:.1f} %"


def pair(s1, s2, fmt):
    return f"{fmt(s1)} / {fmt(s2)}"


def outcome(s):
    return s["outcome"]


def max_primary(s):
    return f"{max(primary(s)):.4f}"


def pitch(s):
    return f"{s['peak_pitch_rate_rad_s']:+.2f}"


def table(title, header, rows):
    lines = [title, "", "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def tables(results):
    rapier_rows, mujoco_rows = [], []
    for landing, s in results.items():
        core, rapier, mj = s["core"], s["rapier"], s["mujoco"]
        rapier_rows.append([
            f"`{landing}`",
            pair(core, rapier, outcome),
            pair(core, rapier, max_primary),
            worst_primary(core, rapier),
            worst_secondary(core, rapier),
            pair(core, rapier, pitch),
            residual_pct(rapier),
        ])
        mujoco_rows.append([
            f"`{landing}`",
            pair(core, mj, outcome),
            pair(core, mj, max_primary),
            worst_primary(core, mj),
            worst_secondary(core, mj),
            primary_vs(rapier, mj),
            worst_secondary(rapier, mj),
            pair(core, mj, pitch),
            residual_pct(mj),
        ])
    first = table(
        "#### core / rapier",
        ["landing", "outcome core / rapier", "max primary stroke core / rapier, m",
         "worst primary leg", "worst secondary stroke", "peak pitch rate core / rapier, rad/s",
         "rapier balance residual, % of energy put in"],
        rapier_rows,
    )
    second = table(
        "#### core / mujoco, with rapier",
        ["landing", "outcome core / mujoco", "max primary stroke core / mujoco, m",
         "worst primary leg", "worst secondary stroke", "primary vs rapier",
         "worst secondary rapier / mujoco", "peak pitch rate core / mujoco, rad/s",
         "mujoco balance residual, % of energy put in"],
        mujoco_rows,
    )
    return first + "\n" + second


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--touchdown", default=os.environ.get("TOUCHDOWN"),
                    help="touchdown binary (default $TOUCHDOWN, else target/release/touchdown)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                    help="runs in parallel (default: the number of CPUs)")
    ap.add_argument("--out", help="write the Markdown to this file instead of standard output")
    args = ap.parse_args()
    touchdown = str(Path(args.touchdown or ROOT / "target/release/touchdown").resolve())
    if not os.access(touchdown, os.X_OK):
        sys.exit(f"engine-tables: {touchdown} is not an executable; build it with "
                 "`cargo build --release -p touchdown-cli -p touchdown-mujoco`")

    start = time.monotonic()
    names = landings()
    # MuJoCo's runs are the longest: start them first.
    jobs = [(n, e) for e in reversed(ENGINES) for n in names]
    with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        futures = {job: pool.submit(run, touchdown, *job) for job in jobs}
        try:
            results = {n: {e: futures[(n, e)].result() for e in ENGINES} for n in names}
        except RuntimeError as err:
            for f in futures.values():
                f.cancel()
            sys.exit(f"engine-tables: {err}")

    text = tables(results)
    if args.out:
        out = Path(args.out)
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(text)
    else:
        sys.stdout.write(text)
    print(f"engine-tables: {len(jobs)} runs in {time.monotonic() - start:.0f} s"
          + (f", written to {args.out}" if args.out else ""), file=sys.stderr)


if __name__ == "__main__":
    main()
