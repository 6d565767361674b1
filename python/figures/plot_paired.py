"""Draws a paired campaign's plots from its folder (written by `touchdown campaign --out DIR` for
a campaign that names several engines; docs/campaigns.md, "Paired campaigns"), for its first
pair of engines, A and B:

* disagreement.png: every landing over the two dispersed inputs most correlated with the
  engines disagreeing (statistics.json, the pair's "influence"), the landings where both are
  stable, where both overturn, and each kind of disagreement marked apart;
* differences.png: histograms of the paired differences B - A of each leg's maximum primary
  stroke, over the landings both engines measured.

Each PNG has the data it draws beside it under the same name: disagreement.csv (each landing's
two inputs and both outcomes) and differences.csv (each leg's difference, landing by landing).

Usage: plot_paired.py DIR OUT. Run by `touchdown campaign --plot` (docs/campaigns.md).

The inputs' field names are read in one function per input (read_landings, read_pair,
read_manifest): a renamed field is changed there and nowhere else.
"""

import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from plot_campaign import finish_scatter, write_csv  # noqa: E402  (beside this script)


def read_manifest(folder):
    """DIR/manifest.json: {"name" (the campaign's), "engines" (A, B: the first two)}."""
    manifest = json.loads((folder / "manifest.json").read_text())
    engines = manifest["engines"]
    if len(engines) < 2:
        raise SystemExit(f"{folder}: a campaign on one engine ({engines[0]}): plot_campaign.py draws it")
    return {"name": manifest["campaign_name"], "engines": engines[:2]}


def read_pair(folder):
    """DIR/statistics.json, its first pair: {"landings", "influence": [(input column,
    correlation with disagreement)], strongest first}."""
    stats = json.loads((folder / "statistics.json").read_text())
    pair = stats["pairs"][0]
    return {
        "landings": stats["landings"],
        "influence": [(i["column"], i.get("correlation_with_disagreement")) for i in pair["influence"]],
    }


def read_landings(folder, a, b, legs):
    """DIR/landings.jsonl: one dict per landing with "inputs" (every column, for the inputs named
    by the statistics), "outcomes" (A's, B's) and "primary" ([B - A of each leg's maximum primary
    stroke, m, or None where either engine did not measure it])."""
    landings = []
    for line in (folder / "landings.jsonl").read_text().splitlines():
        r = json.loads(line)
        diffs = []
        for leg in legs:
            x, y = r.get(f"{a}.leg{leg}.primary.stroke_m"), r.get(f"{b}.leg{leg}.primary.stroke_m")
            diffs.append(None if x is None or y is None else y - x)
        landings.append({"inputs": r, "outcomes": (r[f"{a}.outcome"], r[f"{b}.outcome"]), "primary": diffs})
    return landings


def legs_of(folder, a):
    """The legs numbered in the records' columns."""
    manifest = json.loads((folder / "manifest.json").read_text())
    names = [c["name"] for c in manifest["columns"]]
    return sorted({int(n.split(".")[1][3:]) for n in names if n.startswith(f"{a}.leg") and n.endswith(".primary.stroke_m")})


def kind(a, b, outcomes):
    """The class a landing's two outcomes put it in."""
    oa, ob = outcomes
    if oa == ob:
        return f"both {oa}"
    if oa == "stable":
        return f"stable on {a} only ({b}: other)"
    if ob == "stable":
        return f"stable on {b} only ({a}: other)"
    return "neither stable, outcomes differ"


def main(folder, out):
    folder, out = Path(folder), Path(out)
    out.mkdir(parents=True, exist_ok=True)
    manifest = read_manifest(folder)
    a, b = manifest["engines"]
    legs = legs_of(folder, a)
    pair = read_pair(folder)
    records = read_landings(folder, a, b, legs)
    title = f"{manifest['name']}\n({a} and {b}, {pair['landings']} landings)"

    inputs = [column for column, _ in pair["influence"]][:2]
    if len(inputs) == 2:
        x, y = inputs
        fig, ax = plt.subplots(figsize=(9.5, 5.5), layout="constrained")
        styles = {
            "both stable": ("tab:blue", "o", 6),
            "both unstable": ("tab:red", "x", 10),
            f"stable on {a} only ({b}: other)": ("tab:orange", "^", 22),
            f"stable on {b} only ({a}: other)": ("tab:purple", "v", 22),
            "neither stable, outcomes differ": ("tab:green", "D", 16),
        }
        classes = {}
        for r in records:
            classes.setdefault(kind(a, b, r["outcomes"]), []).append((r["inputs"][x], r["inputs"][y]))
        for name in sorted(classes, key=lambda k: (k not in styles, k)):
            colour, marker, size = styles.get(name, ("grey", "s", 14))
            ax.scatter(*zip(*classes[name]), s=size, c=colour, marker=marker, label=f"{name} ({len(classes[name])})")
        write_csv(
            out / "disagreement.csv",
            [x, y, f"{a}.outcome", f"{b}.outcome"],
            ([r["inputs"][x], r["inputs"][y], *r["outcomes"]] for r in records),
        )
        finish_scatter(fig, ax, (x, y), dict(pair["influence"]), "disagreement", title, out / "disagreement.png")

    fig, axes = plt.subplots(1, len(legs), figsize=(3.2 * len(legs), 3.8), sharey=True, squeeze=False)
    rows = []
    for ax, (i, leg) in zip(axes[0], enumerate(legs)):
        d = [1000.0 * r["primary"][i] for r in records if r["primary"][i] is not None]
        ax.hist(d, bins=40, color="tab:blue")
        ax.axvline(0.0, color="k", lw=0.8)
        ax.set_yscale("log")
        ax.set_xlabel(f"leg {leg}: {b} - {a}, mm")
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("landings")
    for r in records:
        rows.append([r["inputs"]["landing"], *("" if v is None else v for v in r["primary"])])
    write_csv(out / "differences.csv", ["landing", *(f"leg{leg}.primary.stroke_m difference" for leg in legs)], rows)
    fig.suptitle(f"{title}: paired differences of each leg's maximum primary stroke", fontsize=10)
    fig.tight_layout()
    fig.savefig(out / "differences.png", dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit("usage: plot_paired.py DIR OUT")
    main(sys.argv[1], sys.argv[2])
