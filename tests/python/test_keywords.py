"""The keyword arguments of score, score_many and render are listed once, in the native
module (``_keywords()``); the stubs spell the same signatures, checked here, and a keyword
that is not in the list is Python's own TypeError."""

from __future__ import annotations

import ast
from pathlib import Path
from typing import Dict, List, Tuple

import facetlab
import facetlab._facetlab as native
import pytest

STUBS = Path(__file__).resolve().parents[2] / "src" / "python" / "facetlab" / "_facetlab.pyi"


def stub_keywords() -> Dict[str, List[Tuple[str, str, str]]]:
    tree = ast.parse(STUBS.read_text())
    out: Dict[str, List[Tuple[str, str, str]]] = {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            a = node.args
            out[node.name] = [
                (arg.arg, ast.unparse(arg.annotation) if arg.annotation else "",
                 ast.unparse(d) if d is not None else "")
                for arg, d in zip(a.kwonlyargs, a.kw_defaults)
            ]
    return out


def test_the_stubs_spell_the_keyword_lists() -> None:
    lists = native._keywords()
    stubs = stub_keywords()
    assert sorted(lists) == ["render", "score", "score_many"]
    for function, keywords in lists.items():
        assert stubs[function] == [tuple(k) for k in keywords], function
    assert ("ri", "Optional[float]", "None") in [tuple(k) for k in lists["score"]]


def test_a_keyword_not_in_the_list_is_a_type_error() -> None:
    with pytest.raises(TypeError, match=r"^score\(\) got an unexpected keyword argument 'colur'$"):
        facetlab.score("tolkowsky", colur="#7a3fa0")  # type: ignore[call-arg]
    with pytest.raises(TypeError, match=r"^render\(\) got an unexpected keyword argument"):
        facetlab.render("tolkowsky", photons=3)  # type: ignore[call-arg]
    # A value of the wrong type names the keyword; None is "not given".
    with pytest.raises(facetlab.Error, match=r"^ri: `wide` is not allowed; give a number"):
        facetlab.score("tolkowsky", ri="wide")  # type: ignore[arg-type]
    with pytest.raises(facetlab.Error, match=r"^size: `True` is not allowed"):
        facetlab.render("tolkowsky", size=True)
    assert facetlab.render("tolkowsky", size=16, tilt=None, material=None).stats["size"] == 16
