"""Campaign shards from Python (docs/campaigns.md): only paths cross processes."""

from os import PathLike
from pathlib import Path
from typing import Iterable, Optional, Union

from . import _arguments as a
from . import _native


def run_shard(
    campaign: Union[str, PathLike], k: int, n: int, out_dir: Union[str, PathLike], resume: bool = False
) -> Path:
    """Runs shard `k` of `n` (k from 1) of the campaign file `campaign` into `out_dir`, exactly
    as `touchdown campaign CAMPAIGN --shard K/N --out OUT_DIR` does (the same bytes); with
    `resume`, as `--resume` does (a run of this shard stopped part-way goes on from the records
    it wrote in `<out_dir>.partial`). Returns `out_dir`."""
    campaign, k, n = a.path("campaign", campaign), a.count("k", k), a.count("n", n)
    out_dir, resume = a.path("out_dir", out_dir), a.flag("resume", resume)
    return Path(_native.run_shard(campaign, k, n, out_dir, resume))


def holds_shard(campaign: Union[str, PathLike], k: int, n: int, folder: Union[str, PathLike]) -> bool:
    """Whether `folder` holds shard `k` of `n` of the campaign file `campaign` as it is now,
    finished by this build: a folder of another campaign, or of this one before an edit, does
    not."""
    campaign, folder = a.path("campaign", campaign), a.path("folder", folder)
    return _native.holds_shard(campaign, a.count("k", k), a.count("n", n), folder)


def merge(parts: Iterable[Union[str, PathLike]], out_dir: Union[str, PathLike]) -> Path:
    """Merges the shards' folders `parts` into `out_dir`, exactly as `touchdown campaign merge`
    does (the same bytes as the whole campaign run at once); returns `out_dir`."""
    return Path(_native.merge(a.paths("parts", parts), a.path("out_dir", out_dir)))


def shard_dir(out_dir: Union[str, PathLike], k: int, n: int) -> Path:
    """The folder of shard `k` of `n` of the campaign merged into `out_dir`: beside it, under
    `<out_dir>.shards/`, since a campaign's folder holds the campaign's files only (the merge
    replaces it whole)."""
    out = Path(out_dir)
    return out.with_name(out.name + ".shards") / f"shard-{k}-of-{n}"


def run_shard_atomically(campaign: str, k: int, n: int, out_dir: str) -> str:
    """Runs shard `k` of `n` into `shard_dir(out_dir, k, n)`, unless that folder holds it: a
    shard's folder appears only complete (the run builds it beside, in `<folder>.partial`, and
    renames it), so one that holds this shard of this campaign is finished, what an interrupted
    campaign resumes from; one of the campaign before an edit is refused by the run. An attempt stopped part-way (its worker killed) leaves the records it finished there,
    and the next attempt resumes from them (`resume=True`); a second attempt while the first
    still runs is refused (the folder is locked) and retried. Returns the shard's folder."""
    final = shard_dir(out_dir, k, n)
    if not holds_shard(campaign, k, n, final):
        final.parent.mkdir(parents=True, exist_ok=True)
        run_shard(campaign, k, n, final, resume=True)
    return str(final)


def records(folder: Union[str, PathLike], engine: Optional[str] = None):
    """The records of the finished campaign folder `folder` as a pandas DataFrame, one row a
    landing (`landings.parquet`, read by pyarrow). A paired campaign's rows hold a block of
    columns per engine (`core.outcome`, `rapier.leg1.primary.stroke_m`, ...; docs/campaigns.md,
    "Paired campaigns"): with `engine`, the landing, the values applied and that engine's block
    under the names a campaign on one engine uses (`outcome`, `leg1.primary.stroke_m`), so
    that two engines' frames line up row by row. An engine the campaign did not land on is a
    ValueError naming those it did."""
    import json

    import pandas as pd

    folder = Path(folder)
    frame = pd.read_parquet(folder / "landings.parquet")
    if engine is None:
        return frame
    engines = json.loads((folder / "manifest.json").read_text())["engines"]
    if engine not in engines:
        raise ValueError(f"engine {engine!r}: the campaign in {folder} landed on {', '.join(engines)}")
    if len(engines) == 1:
        return frame
    prefix = f"{engine}."
    kept = [c for c in frame.columns if c == "landing" or c.startswith("applied.") or c.startswith(prefix)]
    return frame[kept].rename(columns=lambda c: c[len(prefix):] if c.startswith(prefix) else c)
