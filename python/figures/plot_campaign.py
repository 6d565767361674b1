"""Draws a campaign's plots from its folder (written by `touchdown campaign --out DIR`):

* outcomes.png: every landing over the two dispersed inputs most correlated with a stable
  landing (statistics.json, "influence"), stable and unstable landings marked apart, the others
  (undecided, stopped, refused) in grey;
  with, when OUT/boundary.json is there (written by `touchdown campaign --plot` when those two
  inputs are the descent and horizontal speeds), the engine's stability boundary of the base
  configuration drawn over them;
* strokes.png: histograms of the maximum strokes as fractions of their strut's capacity, the
  primaries and the secondaries pooled over the legs, with the capacity (1.0) marked.

Each PNG has the data it draws beside it under the same name: outcomes.csv (each landing's two
inputs and its outcome; the boundary is boundary.json) and strokes.csv (each histogram's bins
and counts).

Usage: plot_campaign.py DIR OUT. The data behind both is DIR/landings.jsonl and
DIR/statistics.json. Run by `touchdown campaign --plot` (docs/campaigns.md).

The inputs' field names are read in one function per input (read_landings, read_statistics,
read_manifest, read_boundary): a renamed field is changed there and nowhere else.
"""

import csv
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# Records' columns: a stroke as a fraction of its strut's capacity ends with this; a primary's
# contains ".primary.".
STROKE_OF_CAPACITY = "stroke_of_capacity"


def read_landings(folder):
    """DIR/landings.jsonl: one dict per landing with "outcome" (stable, unstable, undecided,
    stopped, refused), "inputs" (every column, for the inputs named by the statistics) and
    "strokes" ([(kind "primary" or "secondary", stroke / capacity)] of every strut)."""
    landings = []
    for line in (folder / "landings.jsonl").read_text().splitlines():
        r = json.loads(line)
        strokes = [
            ("primary" if ".primary." in k else "secondary", v)
            for k, v in r.items()
            if k.endswith(STROKE_OF_CAPACITY)
        ]
        landings.append({"outcome": r["outcome"], "inputs": r, "strokes": strokes})
    return landings


def read_statistics(folder):
    """DIR/statistics.json: {"landings", "influence": [(input column, correlation with a stable
    landing, None where not defined)], strongest first}."""
    stats = json.loads((folder / "statistics.json").read_text())
    return {
        "landings": stats["landings"],
        "influence": [(i["column"], i.get("correlation_with_stable")) for i in stats["influence"]],
    }


def read_manifest(folder):
    """DIR/manifest.json: {"name" (the campaign's), "engine" (its one engine: the plots draw a
    campaign on one engine)}."""
    manifest = json.loads((folder / "manifest.json").read_text())
    engines = manifest["engines"]
    if len(engines) != 1:
        raise SystemExit(f"{folder}: a paired campaign ({', '.join(engines)}): these plots draw a campaign on one engine")
    return {"name": manifest["campaign_name"], "engine": engines[0]}


def read_boundary(path, x, y):
    """OUT/boundary.json: {"engine", "points": [(x, y)]} of the points with both inputs, by y."""
    b = json.loads(path.read_text())
    pts = sorted(((p[x], p[y]) for p in b["points"] if x in p and y in p), key=lambda q: q[1])
    return {"engine": b["engine"], "points": pts}


def write_csv(path, header, rows):
    with path.open("w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        w.writerows(rows)


def finish_scatter(fig, ax, inputs, correlation, what, title, path):
    """Labels the scatter of landings over the two `inputs` (columns) with each one's
    `correlation` with `what`, titles it and writes it to `path`."""
    for axis, column in zip((ax.set_xlabel, ax.set_ylabel), inputs):
        r = correlation[column]
        r = "not defined" if r is None else f"{r:+.2f}"
        axis(f"{column.removeprefix('applied.')}  (correlation with {what} {r})")
    ax.set_title(title, fontsize=10)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, title="landings", title_fontsize=8)
    ax.grid(alpha=0.3)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(folder, out):
    folder, out = Path(folder), Path(out)
    out.mkdir(parents=True, exist_ok=True)
    records = read_landings(folder)
    stats = read_statistics(folder)
    manifest = read_manifest(folder)
    title = f"{manifest['name']} ({manifest['engine']}, {stats['landings']} landings)"

    inputs = [column for column, _ in stats["influence"]][:2]
    if len(inputs) == 2:
        x, y = inputs
        fig, ax = plt.subplots(figsize=(9.5, 5.5), layout="constrained")
        groups = [
            ("stable", "tab:blue", "o"),
            ("unstable", "tab:red", "x"),
        ]
        for outcome, colour, marker in groups:
            pts = [(r["inputs"][x], r["inputs"][y]) for r in records if r["outcome"] == outcome]
            if pts:
                ax.scatter(*zip(*pts), s=10, c=colour, marker=marker, label=f"{outcome} ({len(pts)})")
        other = [(r["inputs"][x], r["inputs"][y]) for r in records if r["outcome"] not in ("stable", "unstable")]
        if other:
            ax.scatter(*zip(*other), s=14, c="grey", marker="s", label=f"undecided, stopped or refused ({len(other)})")
        write_csv(
            out / "outcomes.csv",
            [x, y, "outcome"],
            ([r["inputs"][x], r["inputs"][y], r["outcome"]] for r in records),
        )
        boundary = out / "boundary.json"
        if boundary.exists():
            b = read_boundary(boundary, x, y)
            if b["points"]:
                ax.plot(*zip(*b["points"]), "k-", lw=1.8, label=f"{b['engine']} boundary of the base\nconfiguration (boundary.json)")
        finish_scatter(fig, ax, (x, y), dict(stats["influence"]), "stable", title, out / "outcomes.png")

    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), sharey=False)
    bins = []
    for ax, kind in zip(axes, ("primary", "secondary")):
        values = [v for r in records for k, v in r["strokes"] if k == kind and v > 0]
        counts, edges, _ = ax.hist(values, bins=40, color="tab:blue" if kind == "primary" else "tab:green")
        bins += [(kind, edges[i], edges[i + 1], int(counts[i])) for i in range(len(counts))]
        ax.axvline(1.0, color="k", linestyle="--", label="capacity (end of the last crush stage)")
        ax.set_xlabel(f"{kind} stroke / its capacity")
        ax.set_ylabel("strut-landings")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    write_csv(out / "strokes.csv", ["strut", "stroke_of_capacity_from", "stroke_of_capacity_to", "strut_landings"], bins)
    fig.suptitle(f"{title}\nmaximum strokes of every strut of every leg that stroked", fontsize=10)
    fig.tight_layout()
    fig.savefig(out / "strokes.png", dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
