"""facetlab: design, score and optimize cut gemstones with real optics.

The same library as the ``facetlab`` command line, called directly (never the binary), so
the numbers are the command line's. A cut is anything the command line's CUT takes (a
preset name such as ``"tolkowsky"``, a ``.toml .asc .gem .obj .stl`` path) or a
:class:`Cut`:

>>> import facetlab
>>> s = facetlab.score("tolkowsky")
>>> round(s.brilliance, 2) > 0.6
True
>>> sorted(s.aset)
['blue', 'green', 'leak', 'port', 'red']

Bad input raises :class:`facetlab.Error` (a ``ValueError``) with the command line's one-line
message; ``facetlab.dask`` spreads sweeps and batches of scores over a Dask cluster.
"""

from ._facetlab import (
    Cut,
    Error,
    Grid,
    InternalError,
    Recipe,
    Render,
    Scores,
    __version__,
    cut,
    families,
    family,
    materials,
    optimize,
    plan,
    presets,
    render,
    score,
    score_many,
    trace,
)

from typing import Any, Dict, List, Optional, Sequence


def sweep(
    config: Any, axes: Sequence[str], indices: Optional[Sequence[int]] = None
) -> List[Dict[str, Any]]:
    """The rows of ``facetlab sweep CONFIG`` over ``axes`` ("KEY:MIN:MAX:STEP" each): one
    dict per point in grid order (or in the order of ``indices``), with the axes' values,
    ``brilliance``, ``fire``, ``scintillation``, ``objective``, ``ok`` and the extra scores.
    ``Grid(config, axes).csv(rows)`` makes ``sweep.csv`` of them; ``facetlab.dask.sweep``
    spreads them over a cluster.

    >>> config = {"cut": {"family": "round-brilliant"}, "free": {"table": [0.5, 0.6]},
    ...           "score": {"ri": 1.54, "polarization": False}}
    >>> [r["table"] for r in facetlab.sweep(config, ["table:0.55:0.57:0.01"])]
    [0.55, 0.56, 0.57]
    """
    return Grid(config, list(axes)).rows(None if indices is None else list(indices))


__all__ = [
    "Cut",
    "Error",
    "Grid",
    "InternalError",
    "Recipe",
    "Render",
    "Scores",
    "__version__",
    "cut",
    "families",
    "family",
    "materials",
    "optimize",
    "plan",
    "presets",
    "render",
    "score",
    "score_many",
    "sweep",
    "trace",
]
