"""Reads a campaign folder's landings.parquet with pandas (pyarrow), polars and DuckDB, and
checks each against landings.jsonl, record by record: the same landings, the same columns, the
same values (floats bit for bit, text exactly, a key missing from a JSON line is a null).

Usage: campaign_read.py DIR. Prints one JSON object (rows, columns, readers) and exits 0 when
every reader agrees with the JSON Lines; otherwise prints what differs and exits 1. Run by
crates/campaign/tests/campaign.rs (docs/campaigns.md, "Reading the records").
"""

import json
import math
import sys
from pathlib import Path

import duckdb
import pandas as pd
import polars as pl


def same(a, b):
    """Whether a Parquet value equals a JSON value (None for a missing key)."""
    if a is None or (isinstance(a, float) and math.isnan(a)):
        return b is None
    if isinstance(b, bool) or isinstance(a, bool):
        return bool(a) == b and isinstance(b, bool)
    if isinstance(b, (int, float)):
        return float(a) == float(b)
    return a == b


def main(folder):
    folder = Path(folder)
    lines = [json.loads(l) for l in (folder / "landings.jsonl").read_text().splitlines()]
    manifest = json.loads((folder / "manifest.json").read_text())
    columns = [c["name"] for c in manifest["columns"]]
    parquet = str(folder / "landings.parquet")
    readers = {
        "pandas": pd.read_parquet(parquet).to_dict("records"),
        "polars": pl.read_parquet(parquet).to_dicts(),
        "duckdb": [
            dict(zip(columns, row))
            for row in duckdb.sql(f"SELECT * FROM read_parquet('{parquet}') ORDER BY landing").fetchall()
        ],
    }
    problems = []
    for name, records in readers.items():
        if len(records) != len(lines):
            problems.append(f"{name}: {len(records)} rows, landings.jsonl has {len(lines)}")
            continue
        for record, line in zip(records, lines):
            if list(record.keys()) != columns:
                problems.append(f"{name}: columns {list(record.keys())[:3]}... differ from the manifest's")
                break
            bad = [c for c in columns if not same(record[c], line.get(c))]
            if bad:
                problems.append(f"{name}: landing {line['landing']}: {bad[:3]} differ")
                break
    print(json.dumps({"rows": len(lines), "columns": len(columns), "readers": sorted(readers), "problems": problems}))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
