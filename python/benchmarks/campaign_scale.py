"""A campaign at scale, on the command line and on a 2-worker Dask LocalCluster: wall time,
peak resident memory of every process, Dask's cost per shard, the merge of the shards, and
whether the two routes' folders are byte-identical (docs/performance.md, "Campaigns at scale").

    .venv/bin/python python/benchmarks/campaign_scale.py OUT [--landings 1000000]
        [--t-end 0.05] [--shards 100] [--routes cli,dask,merge]

The campaign is `scenarios/campaigns/lm-1-6-d3117.toml` with `landings` changed and each
landing's horizon set to `--t-end` seconds (a one-value list dispersion of `integrator.t_end`,
as `lm-1-6-d3117-paired.toml` sets its 1.5 s): it is written to OUT/campaign.toml. The horizon
sets the cost of a landing, not what is measured of the machinery (records streamed, memory,
shards, merge); the cost of a whole landing is measured beside it (docs/performance.md,
"Campaigns").

Routes: `cli` runs `touchdown campaign OUT/campaign.toml --threads 2 --out OUT/cli`; `dask`
runs `touchdown.dask.run_campaign` with `--shards` shards into OUT/dask (its shards under
OUT/dask.shards), timing the shards and the merge apart, and reads each worker's peak resident
memory; `merge` merges the Dask route's shards again with `touchdown campaign merge` into
OUT/merge. Every folder is compared with the first route's, file by file.
"""

import argparse
import filecmp
import re
import resource
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BASE = ROOT / "scenarios" / "campaigns" / "lm-1-6-d3117.toml"


def campaign_file(out: Path, landings: int, t_end: float) -> Path:
    text = BASE.read_text()
    text, n = re.subn(r"(?m)^landings = \d+$", f"landings = {landings}", text)
    if n != 1:
        sys.exit(f"{BASE}: expected one `landings = N` line")
    text = text.replace('scenario = "../', f'scenario = "{BASE.parent.parent}/')
    horizon = f"""
[[dispersion]]
field = "integrator.t_end"
unit = "s"
distribution = "list"
values = [{t_end!r}]
"""
    # The dispersions end where the first table after them begins.
    at = text.index("\n[[correlation]]") if "\n[[correlation]]" in text else len(text)
    text = text[:at] + horizon + text[at:]
    path = out / "campaign.toml"
    path.write_text(text)
    return path


def timed(command: list, out: Path) -> tuple:
    """Runs `command` under `/usr/bin/time`; returns its wall time (s) and peak resident memory
    (MB), that process's own (a child's peak read by this process would include Dask's workers)."""
    record = out / "time.txt"
    t = time.perf_counter()
    subprocess.run(["/usr/bin/time", "-f", "%M", "-o", str(record), *command], check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t, int(record.read_text().split()[-1]) / 1024


def touchdown() -> str:
    exe = shutil.which("touchdown")
    if exe is None:
        sys.exit("touchdown is not on PATH: cargo install --locked --path crates/cli --target-dir target")
    return exe


def cli(campaign: Path, out: Path) -> Path:
    folder = out / "cli"
    shutil.rmtree(folder, ignore_errors=True)
    wall, peak = timed([touchdown(), "campaign", str(campaign), "--threads", "2", "--quiet", "--out", str(folder)], out)
    print(f"cli: {wall:.1f} s wall, peak resident {peak:.1f} MB")
    return folder


def dask(campaign: Path, out: Path, shards: int) -> Path:
    from dask.distributed import Client, LocalCluster

    import touchdown.dask
    from touchdown import campaign as shards_of

    folder = out / "dask"
    shutil.rmtree(folder, ignore_errors=True)
    shutil.rmtree(folder.with_name("dask.shards"), ignore_errors=True)
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=":0") as cluster, Client(cluster) as client:
        t = time.perf_counter()
        futures = [
            client.submit(shards_of.run_shard_atomically, str(campaign), k, shards, str(folder), pure=False)
            for k in range(1, shards + 1)
        ]
        client.gather(futures)
        ran = time.perf_counter() - t
        workers = client.run(lambda: resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)
        t = time.perf_counter()
        touchdown.dask.run_campaign(client, campaign, shards=shards, out_dir=folder, progress=False)
        merged = time.perf_counter() - t
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"dask: {shards} shards {ran:.1f} s wall, merge {merged:.1f} s; client peak resident {peak:.1f} MB, "
          f"workers' {', '.join(f'{m:.1f}' for m in workers.values())} MB")
    return folder


def merge(out: Path, shards: int) -> Path:
    from touchdown import campaign as shards_of

    folder = out / "merge"
    shutil.rmtree(folder, ignore_errors=True)
    parts = [str(shards_of.shard_dir(out / "dask", k, shards)) for k in range(1, shards + 1)]
    missing = [p for p in parts if not Path(p).is_dir()]
    if missing:
        sys.exit(f"--routes merge: {missing[0]} is missing: the route merges the shards the dask route "
                 f"wrote with the same --shards ({len(missing)} of {shards} missing); run --routes dask first")
    wall, peak = timed([touchdown(), "campaign", "merge", "--quiet", "--out", str(folder), *parts], out)
    print(f"merge of {shards} shards: {wall:.1f} s wall, peak resident {peak:.1f} MB")
    return folder


def same(a: Path, b: Path) -> bool:
    files = sorted(p.relative_to(a) for p in a.rglob("*") if p.is_file())
    other = sorted(p.relative_to(b) for p in b.rglob("*") if p.is_file())
    if files != other:
        print(f"{a} and {b} hold different files")
        return False
    differ = [str(f) for f in files if not filecmp.cmp(a / f, b / f, shallow=False)]
    if differ:
        print(f"{a} and {b} differ in {', '.join(differ)}")
    return not differ


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", type=Path)
    parser.add_argument("--landings", type=int, default=1_000_000)
    parser.add_argument("--t-end", type=float, default=0.05)
    parser.add_argument("--shards", type=int, default=100)
    parser.add_argument("--routes", default="cli,dask,merge")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    campaign = campaign_file(args.out, args.landings, args.t_end)
    folders = []
    for route in args.routes.split(","):
        if route == "cli":
            folders.append(cli(campaign, args.out))
        elif route == "dask":
            folders.append(dask(campaign, args.out, args.shards))
        elif route == "merge":
            folders.append(merge(args.out, args.shards))
        else:
            sys.exit(f"--routes: expected cli, dask or merge, got {route!r}")
    if all(same(folders[0], f) for f in folders[1:]) and len(folders) > 1:
        print(f"byte-identical: {', '.join(f.name for f in folders)}")
    elif len(folders) > 1:
        sys.exit(1)


if __name__ == "__main__":
    main()
