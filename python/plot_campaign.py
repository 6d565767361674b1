"""Draws a campaign's plots from its folder (written by `touchdown campaign --out DIR`):

* outcomes.png: every landing over the two dispersed inputs most correlated with a stable
  landing (statistics.json, "influence"), stable and unstable landings marked apart, the others
  (undecided, stopped, refused) in grey;
  with, when OUT/boundary.json is there (written by `touchdown campaign --plot` when those two
  inputs are the descent and horizontal speeds), the engine's stability boundary of the base
  configuration drawn over them;
* strokes.png: histograms of the maximum strokes as fractions of their strut's capacity, the
  primaries and the secondaries pooled over the legs, with the capacity (1.0) marked.

Usage: plot_campaign.py DIR OUT. The data behind both is DIR/landings.jsonl and
DIR/statistics.json. Run by `touchdown campaign --plot` (docs/campaigns.md).
"""

import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(folder, out):
    folder, out = Path(folder), Path(out)
    out.mkdir(parents=True, exist_ok=True)
    records = [json.loads(l) for l in (folder / "landings.jsonl").read_text().splitlines()]
    stats = json.loads((folder / "statistics.json").read_text())
    manifest = json.loads((folder / "manifest.json").read_text())
    title = f"{manifest['campaign_name']} ({manifest['engine']}, {stats['landings']} landings)"

    inputs = [i["column"] for i in stats["influence"]][:2]
    if len(inputs) == 2:
        x, y = inputs
        fig, ax = plt.subplots(figsize=(7.5, 5.5))
        groups = [
            ("stable", "tab:blue", "o"),
            ("unstable", "tab:red", "x"),
        ]
        for outcome, colour, marker in groups:
            pts = [(r[x], r[y]) for r in records if r["outcome"] == outcome]
            if pts:
                ax.scatter(*zip(*pts), s=10, c=colour, marker=marker, label=f"{outcome} ({len(pts)})")
        other = [(r[x], r[y]) for r in records if r["outcome"] not in ("stable", "unstable")]
        if other:
            ax.scatter(*zip(*other), s=14, c="grey", marker="s", label=f"undecided, stopped or refused ({len(other)})")
        boundary = out / "boundary.json"
        if boundary.exists():
            b = json.loads(boundary.read_text())
            pts = sorted(((p[x], p[y]) for p in b["points"] if x in p and y in p), key=lambda q: q[1])
            if pts:
                ax.plot(*zip(*pts), "k-", lw=1.8, label=f"{b['engine']} boundary of the base configuration")
        corr = {i["column"]: i["correlation_with_stable"] for i in stats["influence"]}
        ax.set_xlabel(f"{x.removeprefix('applied.')}  (correlation with stable {corr[x]:+.2f})")
        ax.set_ylabel(f"{y.removeprefix('applied.')}  (correlation with stable {corr[y]:+.2f})")
        ax.set_title(title, fontsize=10)
        ax.legend(loc="best", fontsize=8)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(out / "outcomes.png", dpi=120)
        plt.close(fig)

    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), sharey=False)
    for ax, kind in zip(axes, ("primary", "secondary")):
        values = [
            v
            for r in records
            for k, v in r.items()
            if k.endswith("stroke_of_capacity") and (".primary." in k) == (kind == "primary") and v > 0
        ]
        ax.hist(values, bins=40, color="tab:blue" if kind == "primary" else "tab:green")
        ax.axvline(1.0, color="k", linestyle="--", label="capacity (end of the last crush stage)")
        ax.set_xlabel(f"{kind} stroke / its capacity")
        ax.set_ylabel("strut-landings")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    fig.suptitle(f"{title}\nmaximum strokes of every strut of every leg that stroked", fontsize=10)
    fig.tight_layout()
    fig.savefig(out / "strokes.png", dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
