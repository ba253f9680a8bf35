"""Every public function, class and method of the package has a docstring with an example,
and every example runs (doctest), in the native module's docstrings and in the pure-Python
modules."""

from __future__ import annotations

import doctest
import importlib.util
import inspect
import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any, Iterator, List, Tuple

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
    "Recipe": {"name", "tiers"},
}

# Private names with examples all the same: how a Cut pickles.
PICKLING = {"__reduce__", "_from_state"}

ROOT = Path(__file__).resolve().parents[2]


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


# The ```python blocks of the README and of the pages under docs/, run as written.
DOC_PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def python_blocks() -> Iterator[Tuple[str, str]]:
    for page in DOC_PAGES:
        lines = page.read_text(encoding="utf-8").splitlines()
        i = 0
        while i < len(lines):
            if lines[i].startswith("```"):
                lang, start = lines[i].strip("`").strip(), i + 1
                body: List[str] = []
                i += 1
                while i < len(lines) and not lines[i].startswith("```"):
                    body.append(lines[i])
                    i += 1
                if lang == "python":
                    yield f"{page.relative_to(ROOT)}:{start}", "\n".join(body) + "\n"
            i += 1


def test_the_pages_have_python_blocks() -> None:
    where = [w for w, _ in python_blocks()]
    assert any(w.startswith("README.md") for w in where), where
    assert any(w.startswith("docs/python.md") for w in where), where


@pytest.mark.parametrize("where, code", list(python_blocks()), ids=lambda x: x if ":" in x else "")
def test_the_python_blocks_of_the_docs_run_as_written(where: str, code: str, tmp_path: Path) -> None:
    # As a reader runs them: a script (so a main guard works, for Dask's worker processes) in a
    # folder holding the repository's bundled files and an empty results/.
    if "distributed" in code and importlib.util.find_spec("distributed") is None and not os.environ.get("CI"):
        pytest.skip("dask[distributed] is not installed (CI installs it)")
    for folder in ("cuts", "optim"):
        shutil.copytree(ROOT / folder, tmp_path / folder)
    (tmp_path / "results").mkdir()
    script = tmp_path / "block.py"
    script.write_text(code, encoding="utf-8")
    done = subprocess.run(
        [sys.executable, str(script)], cwd=tmp_path, capture_output=True, text=True, timeout=600
    )
    assert done.returncode == 0, f"{where} failed:\n{code}\n{done.stderr}"
    written = [p.name for p in (tmp_path / "results").iterdir()]
    # (Dask's scratch folder aside, its own.)
    stray = [
        p.name
        for p in tmp_path.iterdir()
        if p.name not in ("cuts", "optim", "results", "block.py") and not p.name.startswith("dask-")
    ]
    assert not stray, f"{where} wrote {stray} outside results/"
    assert written or "write" not in code, f"{where} says it writes but wrote nothing under results/"
