"""Every public function, class and method of the package has a docstring with an example,
and every example runs (doctest), in the native module's docstrings and in the pure-Python
modules."""

from __future__ import annotations

import doctest
import inspect
import os
from pathlib import Path
from typing import Any, Iterator, Tuple

import facetlab
import facetlab.dask
import pytest

# Attributes (getters) document a value; functions, classes and methods show an example.
ATTRIBUTES = {
    "Cut": {"name", "family", "params", "facets"},
    "Scores": {"cut", "overhead_light_return", "brilliance", "brilliance_iso",
               "brilliance_cos", "fire", "scintillation", "aset"},
    "Render": {"linear", "srgb", "coverage", "stats"},
    "Grid": {"keys"},
}

# Private names with examples all the same: how a Cut pickles.
PICKLING = {"__reduce__", "_from_state"}


def documented() -> Iterator[Tuple[str, Any]]:
    for name in facetlab.__all__:
        obj = getattr(facetlab, name)
        if name in ("Error", "InternalError", "__version__"):
            continue
        yield name, obj
        if inspect.isclass(obj):
            for m, member in vars(obj).items():
                if (m.startswith("_") and m not in PICKLING) or m in ATTRIBUTES.get(name, set()):
                    continue
                yield f"{name}.{m}", member
    for name in facetlab.dask.__all__:
        yield f"dask.{name}", getattr(facetlab.dask, name)


@pytest.mark.parametrize("name, obj", list(documented()), ids=lambda x: x if isinstance(x, str) else "")
def test_the_example_in_the_docstring_runs(
    name: str, obj: Any, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    doc = inspect.getdoc(obj) or ""
    globs = dict(vars(facetlab.dask)) if name.startswith("dask.") else {}
    globs.update(facetlab=facetlab, os=os)
    test = doctest.DocTestParser().get_doctest(doc, globs, name, None, 0)
    assert test.examples, f"{name} has no example in its docstring"
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    runner.run(test)
    result = runner.summarize(verbose=False)
    assert result.failed == 0, f"{name}: {result.failed} example(s) failed"


def test_the_package_docstring_runs() -> None:
    for module in (facetlab, facetlab.dask):
        result = doctest.testmod(
            module, extraglobs={"facetlab": facetlab}, optionflags=doctest.ELLIPSIS
        )
        assert result.failed == 0 and result.attempted > 0, module.__name__
