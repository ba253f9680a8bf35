"""facetlab: design, score and optimize cut gemstones with real optics.

The same library as the ``facetlab`` command line, called directly (never the binary), so
the numbers are the command line's. A cut is anything the command line's CUT takes (a
preset name such as ``"tolkowsky"``, a ``.toml .asc .gem .obj .stl`` path) or a
:class:`Cut`:

>>> import facetlab
>>> s = facetlab.score("tolkowsky")
>>> round(s.brilliance, 2) > 0.7
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

__all__ = [
    "Cut",
    "Error",
    "Grid",
    "InternalError",
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
    "trace",
]
