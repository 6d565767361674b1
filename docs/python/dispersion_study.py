# %% [markdown]
# # A dispersion study and a stability boundary, from Python
#
# The worked example of docs/python.md, written as notebook cells (`# %%`): it runs as a
# script (`.venv/bin/python docs/python/dispersion_study.py`), which regenerates
# docs/python/dispersion-study.png and the data behind it, dispersion-study.json, or opens
# as a notebook in Jupyter (with jupytext) or VS Code.
#
# The 1/6-scale model lands in the 2-2 mode on the 5° slope of Table I (the scenario
# scenarios/table-i-2-2-vv8.toml, in feet). Its descent and horizontal speeds are dispersed
# uniformly; each landing runs on the core engine, in two threads at once (every call
# releases the interpreter's lock). The core's stability-boundary search then draws the line
# between stable and unstable landings at the base values of everything else.

# %%
import argparse
import json
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import touchdown

HERE = Path(__file__).resolve().parent
SCENARIO = HERE.parent.parent / "scenarios" / "table-i-2-2-vv8.toml"

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("--landings", type=int, default=400, help="landings in the study")
parser.add_argument("--out", type=Path, default=HERE, help="folder for the figure and its data")
args, _ = parser.parse_known_args()

# %% [markdown]
# ## The dispersion
# Descent speed 4 to 12 ft/s (downward, so the scenario's vertical velocity is negative),
# horizontal speed 0 to 24 ft/s along the scenario's downhill heading; a fixed seed, so the
# figure is the same each time.

# %%
rng = np.random.default_rng(20261125)
vv = rng.uniform(4.0, 12.0, args.landings)  # ft/s, positive down
vh = rng.uniform(0.0, 24.0, args.landings)  # ft/s, along the heading


def land(v):
    descent, horizontal = v
    summary = touchdown.run(
        SCENARIO,
        overrides={
            "touchdown.vertical_velocity": -descent,
            # The scenario heads along +Y (downhill): its horizontal velocity is [0, Vh].
            "touchdown.horizontal_velocity[1]": horizontal,
        },
        history=False,
    )["summary"]
    return summary["outcome"], max(summary["max_primary_stroke_m"])


with ThreadPoolExecutor(max_workers=2) as pool:
    landed = list(pool.map(land, zip(vv, vh)))
outcome = np.array([o for o, _ in landed])
stroke_m = np.array([s for _, s in landed])
for name in ("stable", "unstable", "undecided"):
    print(f"{name:>9}: {np.sum(outcome == name)} of {args.landings}")

# %% [markdown]
# ## The boundary
# The report's search at nine descent speeds: every change of outcome on a 0.5 ft/s grid of
# horizontal speed, bisected to 0.05 ft/s. The outcome is not monotonic in Vh here: near
# 8 ft/s an unstable band is followed by stable landings at higher Vh (the search finds every
# change between grid points, and a coarser grid can step over a narrow band), so the figure
# draws every transition, not only the reported boundary (the lowest stable → unstable one).

# %%
# Vertical velocities as the scenario files write them (negative down, ft/s); the points come
# back in SI (docs/schemas/boundary.schema.json) and are drawn in ft/s, descent positive down.
points = touchdown.boundary(SCENARIO, vv=-np.linspace(4.0, 12.0, 9), vh_step=0.5, vh_max=24.0, tol=0.05, scan_step=0.25)
FT = 0.3048  # m per ft
line = [(p["vh_m_s"] / FT, -p["vv_m_s"] / FT) for p in points if "vh_m_s" in p]
others = {
    direction: [
        (t["vh_m_s"] / FT, -p["vv_m_s"] / FT)
        for p in points
        for t in p["transitions"]
        if t["direction"] == direction and "vh_m_s" in t and t["vh_m_s"] != p.get("vh_m_s")
    ]
    for direction in ("stable_to_unstable", "unstable_to_stable")
}

# %% [markdown]
# ## The figure
# Left: each landing at its speeds, coloured by outcome, with the boundary. Right: the
# largest primary stroke of each landing against its horizontal speed.

# %%
fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 5.2), constrained_layout=True)
style = {"stable": ("tab:blue", "o"), "unstable": ("tab:red", "x"), "undecided": ("tab:gray", "s")}
for name, (colour, marker) in style.items():
    chosen = outcome == name
    if chosen.any():
        ax.scatter(vh[chosen], vv[chosen], s=14, c=colour, marker=marker, label=f"{name} ({chosen.sum()})")
        bx.scatter(vh[chosen], 1000 * stroke_m[chosen], s=14, c=colour, marker=marker, label=name)
if line:
    ax.plot(*zip(*line), "k-", lw=2, label="boundary: lowest stable → unstable")
for direction, marker, text in (
    ("stable_to_unstable", ">", "further stable → unstable"),
    ("unstable_to_stable", "<", "unstable → stable"),
):
    if others[direction]:
        ax.scatter(*zip(*others[direction]), s=60, c="k", marker=marker, label=text)
ax.set_xlabel("horizontal speed Vh, ft/s (downhill)")
ax.set_ylabel("descent speed Vv, ft/s (positive down)")
ax.set_title("Outcome of each landing, 2-2 mode, 5° slope")
ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=3, fontsize=8)
bx.set_xlabel("horizontal speed Vh, ft/s (downhill)")
bx.set_ylabel("largest primary stroke, mm")
bx.set_title("Largest primary stroke of each landing")
out = args.out
out.mkdir(parents=True, exist_ok=True)
fig.savefig(out / "dispersion-study.png", dpi=110)
# The points name the scenario as it was given (an absolute path here); within the project it
# is the same file wherever the project lies.
for p in points:
    p["scenario"]["path"] = "scenarios/table-i-2-2-vv8.toml"
(out / "dispersion-study.json").write_text(
    json.dumps(
        {
            "scenario": "scenarios/table-i-2-2-vv8.toml",
            "seed": 20261125,
            "landings": [
                {"vv_ft_s": float(a), "vh_ft_s": float(b), "outcome": str(o), "max_primary_stroke_m": float(s)}
                for a, b, o, s in zip(vv, vh, outcome, stroke_m)
            ],
            "boundary": points,
        },
        indent=1,
    )
    + "\n"
)
print(f"wrote {out / 'dispersion-study.png'} and {out / 'dispersion-study.json'}")
