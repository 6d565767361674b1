"""Campaign shards from Python (docs/campaigns.md): only paths cross processes."""

from os import PathLike
from pathlib import Path
from typing import Union

from . import _native


def run_shard(campaign: Union[str, PathLike], k: int, n: int, out_dir: Union[str, PathLike]) -> Path:
    """Runs shard `k` of `n` (k from 1) of the campaign file `campaign` into `out_dir`, exactly
    as `touchdown campaign CAMPAIGN --shard K/N --out OUT_DIR` does (the same bytes); returns
    `out_dir`."""
    return Path(_native.run_shard(str(campaign), int(k), int(n), str(out_dir)))
