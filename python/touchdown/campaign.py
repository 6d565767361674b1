"""Campaign shards from Python (docs/campaigns.md): only paths cross processes."""

import os
import shutil
import uuid
from os import PathLike
from pathlib import Path
from typing import Iterable, Union

from . import _native


def run_shard(campaign: Union[str, PathLike], k: int, n: int, out_dir: Union[str, PathLike]) -> Path:
    """Runs shard `k` of `n` (k from 1) of the campaign file `campaign` into `out_dir`, exactly
    as `touchdown campaign CAMPAIGN --shard K/N --out OUT_DIR` does (the same bytes); returns
    `out_dir`."""
    return Path(_native.run_shard(str(campaign), int(k), int(n), str(out_dir)))


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
    """Runs shard `k` of `n` into `shard_dir(out_dir, k, n)`, writing it under a temporary
    name and renaming it when complete, so that a folder that exists is a finished shard (what
    an interrupted campaign resumes from). Returns the shard's folder."""
    final = shard_dir(out_dir, k, n)
    if final.exists():
        return str(final)
    final.parent.mkdir(parents=True, exist_ok=True)
    partial = final.with_name(f".{final.name}.{uuid.uuid4().hex}")
    try:
        run_shard(campaign, k, n, partial)
        if not final.exists():  # a second attempt of the same shard may have finished first
            os.replace(partial, final)
    finally:
        if partial.exists():
            shutil.rmtree(partial, ignore_errors=True)
    return str(final)
