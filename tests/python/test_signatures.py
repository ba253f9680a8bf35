"""Each public function and method of the native module spells its parameters in its PyO3
signature, so ``inspect.signature`` shows them; the stubs (``_facetlab.pyi``) must spell the
same: names, order, keyword-only markers, ``**kwargs`` and defaults, checked here by reading
the stubs with ``ast``. A keyword a function does not take is Python's own TypeError, and so is
a value of the wrong type; a value out of range is ``facetlab.Error`` with the command line's
line."""

from __future__ import annotations

import ast
import inspect
import sys
from pathlib import Path
from typing import Any, Callable, Dict, List, Tuple

import facetlab
import facetlab._facetlab as native
import pytest

STUBS = Path(__file__).resolve().parents[2] / "src" / "python" / "facetlab" / "_facetlab.pyi"

# A parameter as both sides spell it: (name, kind, default); `NO` for no default.
NO = "<no default>"
Param = Tuple[str, str, Any]


def stub_params(f: ast.FunctionDef, method: bool) -> List[Param]:
    """The stub's parameters of ``f`` (a method's ``self``/``cls`` left out)."""
    a = f.args
    out: List[Param] = []
    positional = a.posonlyargs + a.args
    firsts = [NO] * (len(positional) - len(a.defaults)) + [
        ast.literal_eval(d) for d in a.defaults
    ]
    for p, d in zip(positional, firsts):
        kind = "POSITIONAL_ONLY" if p in a.posonlyargs else "POSITIONAL_OR_KEYWORD"
        out.append((p.arg, kind, d))
    if a.vararg is not None:
        out.append((a.vararg.arg, "VAR_POSITIONAL", NO))
    for p, d in zip(a.kwonlyargs, a.kw_defaults):
        out.append((p.arg, "KEYWORD_ONLY", NO if d is None else ast.literal_eval(d)))
    if a.kwarg is not None:
        out.append((a.kwarg.arg, "VAR_KEYWORD", NO))
    return out[1:] if method else out


def runtime_params(obj: Any) -> List[Param]:
    """``inspect.signature(obj)``'s parameters (a method's ``self`` left out)."""
    out: List[Param] = []
    for p in inspect.signature(obj).parameters.values():
        d = NO if p.default is inspect.Parameter.empty else p.default
        out.append((p.name, p.kind.name, d))
    if out and out[0][0] in ("self", "cls"):
        out = out[1:]
    return out


def stub_functions() -> Dict[str, List[Tuple[List[Param], bool]]]:
    """Every public function and method the stubs spell, ``{"score": ..., "Cut.info":
    ...}``: each spelling's parameters, and whether it is an ``@overload``."""
    tree = ast.parse(STUBS.read_text())
    out: Dict[str, List[Tuple[List[Param], bool]]] = {}

    def add(name: str, f: ast.FunctionDef, method: bool) -> None:
        decorators = [ast.unparse(d) for d in f.decorator_list]
        if "property" in decorators:
            return
        if f.name.startswith("_") and f.name != "__init__":
            return
        out.setdefault(name, []).append((stub_params(f, method), "overload" in decorators))

    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            add(node.name, node, False)
        elif isinstance(node, ast.ClassDef):
            for f in node.body:
                if isinstance(f, ast.FunctionDef):
                    add(f"{node.name}.{f.name}", f, True)
    return out


def runtime_object(name: str) -> Any:
    cls, _, method = name.partition(".")
    obj = getattr(native, cls)
    if method == "__init__":
        return obj  # the class's signature is its constructor's
    return getattr(obj, method) if method else obj


def same(a: Any, b: Any) -> bool:
    return type(a) is type(b) and a == b


def test_every_signature_is_the_stubs() -> None:
    stubs = stub_functions()
    assert {"score", "score_many", "render", "trace", "plan", "Cut.info", "Recipe.__init__"} <= set(stubs)
    for name, spellings in stubs.items():
        got = runtime_params(runtime_object(name))
        for params, overload in spellings:
            where = f"{name}: stub {params} vs inspect.signature {got}"
            assert [(n, k) for n, k, _ in params] == [(n, k) for n, k, _ in got], where
            for (n, _, want), (_, _, have) in zip(params, got):
                # An @overload may drop a default to narrow its type (plan's `out`).
                if overload and want is NO:
                    continue
                assert same(want, have), f"{name}({n}=): stub {want!r}, signature {have!r}"


def test_every_public_callable_has_a_stub() -> None:
    stubs = stub_functions()
    for name in dir(native):
        obj = getattr(native, name)
        if name.startswith("_") or not callable(obj) or isinstance(obj, type) and issubclass(obj, Exception):
            continue
        if isinstance(obj, type):
            for m, v in vars(obj).items():
                if not m.startswith("_") and callable(v):
                    assert f"{name}.{m}" in stubs, f"{name}.{m} has no stub"
        else:
            assert name in stubs, f"{name} has no stub"


def timeless(x: Any) -> Any:
    """A document without its wall-clock times (`elapsed_s`)."""
    if isinstance(x, dict):
        return {k: timeless(v) for k, v in x.items() if k != "elapsed_s"}
    if isinstance(x, list):
        return [timeless(v) for v in x]
    return x


def test_the_signature_is_what_the_call_does() -> None:
    # The defaults shown are the ones used: the keywords left out or given as shown give
    # the same numbers.
    sig = inspect.signature(facetlab.score).parameters
    given = {k: p.default for k, p in sig.items() if k != "cut"}
    assert facetlab.score("tolkowsky", **given).to_dict() == facetlab.score("tolkowsky").to_dict()
    sig = inspect.signature(facetlab.render).parameters
    given = {k: p.default for k, p in sig.items() if k not in ("cut", "size")}
    a = facetlab.render("tolkowsky", size=16, **given)
    b = facetlab.render("tolkowsky", size=16)
    assert timeless(a.stats) == timeless(b.stats) and (a.srgb == b.srgb).all()
    assert facetlab.render("tolkowsky", size=16).stats["size"] == 16


def test_a_keyword_not_in_the_signature_is_a_type_error() -> None:
    with pytest.raises(TypeError, match=r"^score\(\) got an unexpected keyword argument 'colur'$"):
        facetlab.score("tolkowsky", colur="#7a3fa0")  # type: ignore[call-arg]
    with pytest.raises(TypeError, match=r"^render\(\) got an unexpected keyword argument"):
        facetlab.render("tolkowsky", photons=3)  # type: ignore[call-arg]
    # Positional after the cut: keyword-only, as the stubs' `*` says.
    with pytest.raises(TypeError):
        facetlab.score("tolkowsky", "diamond")  # type: ignore[call-arg]
    # A value of the wrong type is a TypeError saying what to give, the keyword in its note
    # (PyO3 adds it on Python 3.11 and later, shown under the traceback's last line).
    wrong: List[Tuple[Callable[[], object], str, str]] = [
        (lambda: facetlab.score("tolkowsky", ri="wide"), "ri", r"^`wide` is not allowed; give a number"),  # type: ignore[arg-type]
        (lambda: facetlab.render("tolkowsky", size=True), "size", r"^'bool' object cannot be interpreted as an integer"),
        (lambda: facetlab.render("tolkowsky", exposure=True), "exposure", r"^`True` is not allowed; give a number"),
        (lambda: facetlab.render("tolkowsky", tilt=[10]), "tilt", r"^`\[10\]` is not allowed; give a number or a str"),  # type: ignore[arg-type]
        (lambda: facetlab.score("tolkowsky", polarization=None), "polarization", r"is not an instance of 'bool'"),  # type: ignore[arg-type]
    ]
    for call, keyword, message in wrong:
        with pytest.raises(TypeError, match=message) as e:
            call()
        if sys.version_info >= (3, 11):
            assert f"while processing '{keyword}'" in getattr(e.value, "__notes__", [])
    assert facetlab.render("tolkowsky", size=16, tilt=None, material=None).stats["size"] == 16
    # Out of range: the command line's line, the keyword for its flag.
    with pytest.raises(facetlab.Error, match=r"^head_shadow: `61` is not allowed; give a half-angle"):
        facetlab.score("tolkowsky", head_shadow=61)
    with pytest.raises(facetlab.Error, match=r"^size: `4` is not allowed; give a whole number from 8"):
        facetlab.render("tolkowsky", size=4)
    with pytest.raises(facetlab.Error, match=r"^gear: `2` is not allowed"):
        facetlab.Recipe(gear=2)
