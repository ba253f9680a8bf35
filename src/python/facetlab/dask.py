"""Sweeps and batches of scores spread over a Dask cluster (``dask.distributed``).

Each task is a chunk of a sweep's grid points or of a list of cuts, evaluated by the library
on a worker (``facetlab.Grid.rows`` / ``facetlab.score_many``); the results are gathered and
merged in the single-process order, so they equal ``facetlab sweep``'s CSV and
``facetlab.score_many``'s list to the last digit, on any number of workers. A task whose
worker dies is run again by the scheduler (and ``retries`` more times if it fails), and,
being deterministic, gives the same rows.

Any ``distributed.Client`` works: a ``LocalCluster`` on one machine, ``dask_jobqueue``'s
``SLURMCluster`` on a Slurm cluster, or ``dask_kubernetes``' ``KubeCluster`` on
Kubernetes. A config given as a path must be readable at that path on the workers (a shared
file system); a dict config travels with the task, and so do cuts (pickled ``Cut`` objects,
their exact bytes: :func:`score_many` reads names and paths on the client).

>>> from distributed import Client, LocalCluster               # doctest: +SKIP
>>> client = Client(LocalCluster(n_workers=2, processes=True)) # doctest: +SKIP
>>> csv = facetlab.dask.sweep_csv(client, "optim/round-brilliance.toml",
...                               ["crown_angle:30:36:0.5", "pavilion_angle:40:42:0.25"])  # doctest: +SKIP
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Sequence, Union

import facetlab

if TYPE_CHECKING:  # pragma: no cover
    from distributed import Client

Config = Union[str, "os.PathLike[str]", Dict[str, Any]]
Row = Dict[str, Any]

__all__ = ["sweep", "sweep_csv", "score_many", "chunks"]


def chunks(n: int, size: int) -> List[List[int]]:
    """The indices ``0..n`` cut into consecutive chunks of at most ``size``.

    >>> chunks(5, 2)
    [[0, 1], [2, 3], [4]]
    """
    if size < 1:
        raise facetlab.Error(f"chunk: {size} is not allowed; give a chunk of 1 or more")
    return [list(range(i, min(i + size, n))) for i in range(0, n, size)]


def _rows(config: Config, axes: Sequence[str], indices: List[int]) -> List[Row]:
    return facetlab.Grid(config, list(axes)).rows(indices)


def _scores(cuts: List[Any], kwargs: Dict[str, Any]) -> List[Dict[str, Any]]:
    return [s.to_dict() for s in facetlab.score_many(cuts, **kwargs)]


def sweep(
    client: "Client",
    config: Config,
    axes: Sequence[str],
    *,
    chunk: Optional[int] = None,
    retries: int = 2,
) -> List[Row]:
    """The rows of a sweep (``facetlab.Grid(config, axes).rows()``) computed on ``client``'s
    workers, ``chunk`` points per task (default: about four tasks per worker), in grid order.

    >>> from distributed import Client
    >>> client = Client(processes=False, n_workers=1, dashboard_address=None)
    >>> config = {"cut": {"family": "round-brilliant"}, "free": {"table": [0.5, 0.6]},
    ...           "score": {"ri": 1.54, "polarization": False}}
    >>> rows = sweep(client, config, ["table:0.55:0.58:0.01"], chunk=1)
    >>> rows == facetlab.Grid(config, ["table:0.55:0.58:0.01"]).rows()
    True
    >>> client.close()
    """
    grid = facetlab.Grid(config, list(axes))  # checks the config and axes here, at once
    n = len(grid)
    if chunk is None:
        workers = max(1, len(client.scheduler_info().get("workers", {})))
        chunk = max(1, -(-n // (4 * workers)))
    parts = chunks(n, chunk)
    futures = client.map(
        _rows,
        [config] * len(parts),
        [list(axes)] * len(parts),
        parts,
        pure=False,
        retries=retries,
    )
    out: List[Row] = []
    for rows in client.gather(futures):
        out.extend(rows)
    return out


def sweep_csv(
    client: "Client",
    config: Config,
    axes: Sequence[str],
    *,
    chunk: Optional[int] = None,
    retries: int = 2,
) -> str:
    """The sweep's CSV, byte for byte ``facetlab sweep``'s ``sweep.csv``, computed on
    ``client``'s workers (see :func:`sweep`).

    >>> from distributed import Client
    >>> client = Client(processes=False, n_workers=1, dashboard_address=None)
    >>> config = {"cut": {"family": "round-brilliant"}, "free": {"table": [0.5, 0.6]},
    ...           "score": {"ri": 1.54, "polarization": False}}
    >>> sweep_csv(client, config, ["table:0.55:0.56:0.01"]).splitlines()[1].split(",")[0]
    '0.55'
    >>> client.close()
    """
    rows = sweep(client, config, axes, chunk=chunk, retries=retries)
    return facetlab.Grid(config, list(axes)).csv(rows)


def score_many(
    client: "Client",
    cuts: Sequence[Union["facetlab.Cut", str, "os.PathLike[str]"]],
    *,
    chunk: int = 8,
    retries: int = 2,
    **kwargs: Any,
) -> List[Dict[str, Any]]:
    """``facetlab.score_many(cuts, **kwargs)``'s documents (``Scores.to_dict()``), ``chunk``
    cuts per task on ``client``'s workers, in the order given. A cut is a :class:`Cut` or
    anything :func:`facetlab.cut` takes; names and paths are read here, on the client, and
    every cut travels to the workers as a pickled ``Cut`` (its exact bytes), so the workers
    need no files and score the very solids given.

    >>> from distributed import Client
    >>> client = Client(processes=False, n_workers=1, dashboard_address=None)
    >>> cuts = ["tolkowsky", facetlab.family("round-brilliant", table=0.6)]
    >>> [d["cut"] for d in score_many(client, cuts, chunk=1)]
    ['Tolkowsky', 'round-brilliant']
    >>> client.close()
    """
    loaded = [c if isinstance(c, facetlab.Cut) else facetlab.cut(c) for c in cuts]
    parts = [[loaded[i] for i in idx] for idx in chunks(len(loaded), chunk)]
    futures = client.map(
        _scores, parts, [kwargs] * len(parts), pure=False, retries=retries
    )
    out: List[Dict[str, Any]] = []
    for docs in client.gather(futures):
        out.extend(docs)
    return out
