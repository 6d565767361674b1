"""Landings from Python in one thread and in several: the speed-up the released interpreter
lock gives (docs/performance.md, "Python threads").

    .venv/bin/python python/benchmarks/threads.py [--landings 200] [--threads 2] [--repeats 3]
"""

import argparse
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import touchdown

SCENARIO = Path(__file__).resolve().parents[2] / "scenarios" / "table-i-2-2-vv8.toml"

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("--landings", type=int, default=200)
parser.add_argument("--threads", type=int, default=2)
parser.add_argument("--repeats", type=int, default=3)
args = parser.parse_args()

# Descent speeds 4 to 12 ft/s: landings of different lengths, as a study has.
speeds = [-4.0 - 8.0 * i / max(args.landings - 1, 1) for i in range(args.landings)]


def land(v):
    return touchdown.run(SCENARIO, overrides={"touchdown.vertical_velocity": v}, history=False)["summary"]


best_one, best_many = float("inf"), float("inf")
for _ in range(args.repeats):
    start = time.perf_counter()
    one = [land(v) for v in speeds]
    best_one = min(best_one, time.perf_counter() - start)
    start = time.perf_counter()
    with ThreadPoolExecutor(max_workers=args.threads) as pool:
        many = list(pool.map(land, speeds))
    best_many = min(best_many, time.perf_counter() - start)
    assert many == one, "threads changed a result"
print(
    f"{args.landings} landings of {SCENARIO.name} (core, best of {args.repeats}): "
    f"1 thread {best_one:.3f} s ({1000 * best_one / args.landings:.2f} ms a landing), "
    f"{args.threads} threads {best_many:.3f} s: speed-up {best_one / best_many:.2f}"
)
