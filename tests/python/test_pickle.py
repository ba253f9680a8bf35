"""Cut objects pickle (Dask ships them to its workers): a cut made any way comes back with
every number bit for bit, so its scores are the same exactly, and no file is read again."""

from __future__ import annotations

import pickle
from pathlib import Path
from typing import List, Tuple

import facetlab
import pytest


def made_every_way(tmp_path: Path) -> List[Tuple[str, facetlab.Cut]]:
    """A preset, a family with parameters (and re-set), a GemCad design read from a file and
    re-angled with its meets kept, meshes read from .obj and .stl, and a planned cut."""
    facetlab.cut("tolkowsky").write(tmp_path / "t.asc")
    facetlab.cut("gia-reference").write(tmp_path / "g.obj")
    facetlab.cut("gia-reference").write(tmp_path / "g.stl")
    family = facetlab.family("round-brilliant", name="mine", table=0.56, crown_angle=34.5)
    planned = facetlab.plan("octahedron", size_mm=6, families=["oval"], top=1)[0]["cut"]
    return [
        ("preset", facetlab.cut("tolkowsky")),
        ("path", facetlab.cut(tmp_path / "t.asc")),
        ("family", family),
        ("family with_set", family.with_set(pavilion_angle=41.1)),
        ("design with_set", facetlab.cut(tmp_path / "t.asc").with_set({"pavilion-main": 41.2})),
        ("obj", facetlab.cut(tmp_path / "g.obj")),
        ("stl", facetlab.cut(str(tmp_path / "g.stl"))),
        ("plan", planned),
    ]


def test_a_cut_made_any_way_comes_back_with_the_same_numbers(tmp_path: Path) -> None:
    cuts = made_every_way(tmp_path)
    blobs = [(how, c, pickle.dumps(c)) for how, c in cuts]
    # The files are gone before unpickling: nothing is read again.
    for f in tmp_path.iterdir():
        f.unlink()
    for how, c, blob in blobs:
        back = pickle.loads(blob)
        assert isinstance(back, facetlab.Cut), how
        assert (back.name, back.family, back.params, back.facets) == (
            c.name, c.family, c.params, c.facets
        ), how
        assert back.info() == c.info(), how
        # The same bytes again, and the same scores exactly (==, not within a tolerance).
        assert pickle.dumps(back) == blob, how
        want = facetlab.score(c, polarization=False).to_dict()
        assert facetlab.score(back, polarization=False).to_dict() == want, how
    # Every protocol.
    c = cuts[3][1]
    for protocol in range(2, pickle.HIGHEST_PROTOCOL + 1):
        assert pickle.loads(pickle.dumps(c, protocol=protocol)).params == c.params


def test_broken_state_is_an_error_never_a_panic() -> None:
    state = facetlab.cut("tolkowsky").__reduce__()[1][0]
    for bad in (b"", b"nonsense", state[: len(state) // 2], state + b"\0"):
        with pytest.raises(facetlab.Error, match="^cut bytes: "):
            facetlab.Cut._from_state(bad)
