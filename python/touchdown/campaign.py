"""Campaign shards from Python (docs/campaigns.md): only paths cross processes."""

from os import PathLike
from pathlib import Path
from typing import Iterable, Union

from . import _native


def run_shard(
    campaign: Union[str, PathLike], k: int, n: int, out_dir: Union[str, PathLike], resume: bool = False
) -> Path:
    """Runs shard `k` of `n` (k from 1) of the campaign file `campaign` into `out_dir`, exactly
    as `touchdown campaign CAMPAIGN --shard K/N --out OUT_DIR` does (the same bytes); with
    `resume`, as `--resume` does (a run of this shard stopped part-way goes on from the records
    it wrote in `<out_dir>.partial`). Returns `out_dir`."""
    return Path(_native.run_shard(str(campaign), int(k), int(n), str(out_dir), bool(resume)))


def merge(parts: Iterable[Union[str, PathLike]], out_dir: Union[str, PathLike]) -> Path:
    """Merges the shards' folders `parts` into `out_dir`, exactly as `touchdown campaign merge`
    does (the same bytes as the whole campaign run at once); returns `out_dir`."""
    return Path(_native.merge([str(p) for p in parts], str(out_dir)))


def shard_dir(out_dir: Union[str, PathLike], k: int, n: int) -> Path:
    """The folder of shard `k` of `n` of the campaign merged into `out_dir`: beside it, under
    `<out_dir>.shards/`, since a campaign's folder holds the campaign's files only (the merge
    replaces it whole)."""
    out = Path(out_dir)
    return out.with_name(out.name + ".shards") / f"shard-{k}-of-{n}"


def run_shard_atomically(campaign: str, k: int, n: int, out_dir: str) -> str:
    """Runs shard `k` of `n` into `shard_dir(out_dir, k, n)`, unless that folder exists: a
    shard's folder appears only complete (the run builds it beside, in `<folder>.partial`, and
    renames it), so one that exists is a finished shard, what an interrupted campaign resumes
    from. An attempt stopped part-way (its worker killed) leaves the records it finished there,
    and the next attempt resumes from them (`resume=True`); a second attempt while the first
    still runs is refused (the folder is locked) and retried. Returns the shard's folder."""
    final = shard_dir(out_dir, k, n)
    if not final.exists():
        final.parent.mkdir(parents=True, exist_ok=True)
        run_shard(campaign, k, n, final, resume=True)
    return str(final)
