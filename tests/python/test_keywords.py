"""The keyword arguments of score, score_many and render are listed once, in the native
module (``_keywords()``); the stubs spell the same signatures, checked here, and a keyword
that is not in the list is Python's own TypeError."""

from __future__ import annotations

import ast
from pathlib import Path
from typing import Dict

import facetlab
import facetlab._facetlab as native
import pytest

STUBS = Path(__file__).resolve().parents[2] / "src" / "python" / "facetlab" / "_facetlab.pyi"


def stub_keywords() -> Dict[str, Dict[str, str]]:
    """Each function's keyword arguments as the stubs type them: its ``**kwargs:
    Unpack[X]``'s ``TypedDict`` X with its bases' fields, ``{function: {name: annotation}}``."""
    tree = ast.parse(STUBS.read_text())
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}

    def fields(name: str) -> Dict[str, str]:
        c = classes[name]
        out: Dict[str, str] = {}
        for base in c.bases:
            if isinstance(base, ast.Name) and base.id in classes:
                out.update(fields(base.id))
        for a in c.body:
            if isinstance(a, ast.AnnAssign) and isinstance(a.target, ast.Name):
                assert a.target.id not in out, f"{name}.{a.target.id} twice"
                out[a.target.id] = ast.unparse(a.annotation)
        return out

    out: Dict[str, Dict[str, str]] = {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef) and node.args.kwarg is not None:
            ann = node.args.kwarg.annotation  # family(**params: float) is no list
            listed = node.name in ("score", "score_many", "render")  # plan's are its own
            if listed and isinstance(ann, ast.Subscript) and ast.unparse(ann.value) == "Unpack":
                out[node.name] = fields(ast.unparse(ann.slice))
    return out


def test_the_stubs_spell_the_keyword_lists() -> None:
    lists = native._keywords()
    stubs = stub_keywords()
    assert sorted(lists) == ["render", "score", "score_many"] == sorted(stubs)
    for function, keywords in lists.items():
        names = [k[0] for k in keywords]
        assert len(set(names)) == len(names), function
        want = {name: f"Optional[{kind}]" for name, kind, _ in keywords}
        assert stubs[function] == want, function
    assert ("polarization", "bool", "True") in [tuple(k) for k in lists["score"]]


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
