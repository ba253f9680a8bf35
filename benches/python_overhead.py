"""The Python package's binding overhead (issue 42): ``facetlab.score(cut)`` against the
library call it wraps, ``metrics::score`` timed inside Rust on the same cut and settings
(``facetlab._facetlab._library_score_seconds``), alternated in the same minutes, medians of
each; and ``score_many`` on 200 cuts against one ``score`` at a time (parallel speed-up).

Run after building the package into a virtual environment (docs/python.md):

    .venv/bin/python benches/python_overhead.py [ROUNDS]

Target: the Python call costs at most 1.05× the library call.
"""

from __future__ import annotations

import statistics
import sys
import time

import facetlab
from facetlab import _facetlab


def main() -> None:
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 15
    cut = facetlab.cut("tolkowsky")
    facetlab.score(cut)  # warm caches
    lib, py = [], []
    for _ in range(rounds):
        lib.extend(_facetlab._library_score_seconds(cut, 1))
        t0 = time.perf_counter()
        facetlab.score(cut)
        py.append(time.perf_counter() - t0)
    ml, mp = statistics.median(lib), statistics.median(py)
    print(f"score tolkowsky: library {ml * 1e3:.2f} ms, Python {mp * 1e3:.2f} ms, "
          f"ratio {mp / ml:.3f} (median of {rounds}, alternated)")
    # By name: the preset's loading and the document too.
    byname = []
    for _ in range(rounds):
        t0 = time.perf_counter()
        facetlab.score("tolkowsky")
        byname.append(time.perf_counter() - t0)
    print(f"score 'tolkowsky' (loaded by name): {statistics.median(byname) * 1e3:.2f} ms, "
          f"ratio {statistics.median(byname) / ml:.3f}")

    cuts = [
        facetlab.family("round-brilliant", table=0.52 + 0.0005 * i, name=f"t{i}")
        for i in range(200)
    ]
    t0 = time.perf_counter()
    for c in cuts:
        facetlab.score(c, polarization=False)
    one = time.perf_counter() - t0
    t0 = time.perf_counter()
    facetlab.score_many(cuts, polarization=False)
    many = time.perf_counter() - t0
    print(f"200 cuts: one at a time {one:.2f} s, score_many {many:.2f} s, "
          f"speed-up {one / many:.2f}×")


if __name__ == "__main__":
    main()
