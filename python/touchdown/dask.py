"""Campaigns past one machine: the shards of `touchdown campaign --shard K/N` as tasks of a
`dask.distributed` cluster (docs/campaigns.md, "Past one machine").

    from dask.distributed import Client, LocalCluster
    import touchdown.dask
    with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
        touchdown.dask.run_campaign(client, "scenarios/campaigns/lm-1-6-d3117.toml",
                                    shards=16, out_dir="out/d3117")

Each task runs one shard in its worker's process with the Rust landing code and writes the
shard's folder (only paths and numbers cross processes); a shard whose folder holds it is done
(a folder of the campaign before an edit is not: its run refuses the folder, naming it),
so a campaign interrupted and resumed recomputes only the missing shards, and a task lost with
its worker is run again, going on from the records its shard had written. The shards are merged with the campaign's own merge: the result is
byte for byte that of `touchdown campaign FILE --out DIR` on one machine.
"""

from os import PathLike
from pathlib import Path
from typing import Union

from . import _arguments
from . import campaign as _campaign

#: Retries of a shard whose task failed (its worker died, or it raised).
RETRIES = 2


def run_campaign(
    client,
    campaign: Union[str, PathLike],
    shards: int,
    out_dir: Union[str, PathLike],
    progress: bool = True,
) -> Path:
    """Runs the campaign file `campaign` as `shards` shards on the cluster of `client` and
    merges them into `out_dir` (the shards' folders beside it, under `<out_dir>.shards/`). Size the shards
    so that each task lasts seconds (Dask's overhead is about a millisecond a task). Returns
    `out_dir`."""
    shards = _arguments.count("shards", shards)
    campaign, out = _arguments.path("campaign", campaign), Path(_arguments.path("out_dir", out_dir))
    progress = _arguments.flag("progress", progress)
    todo = [
        k for k in range(1, shards + 1) if not _campaign.holds_shard(campaign, k, shards, _campaign.shard_dir(out, k, shards))
    ]
    futures = [
        client.submit(
            _campaign.run_shard_atomically,
            campaign,
            k,
            shards,
            str(out),
            key=f"touchdown-shard-{k}-of-{shards}-{out.resolve()}",
            retries=RETRIES,
            pure=False,
        )
        for k in todo
    ]
    if progress and futures:
        from dask.distributed import progress as show

        show(futures)
    client.gather(futures)
    parts = [_campaign.shard_dir(out, k, shards) for k in range(1, shards + 1)]
    return _campaign.merge(parts, out)
