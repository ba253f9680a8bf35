"""Type stubs of facetlab's native module (src/python/*.rs, built by maturin)."""

import os
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union, overload

from typing_extensions import TypedDict, Unpack

import numpy as np
import numpy.typing as npt

__version__: str

PathLike = Union[str, "os.PathLike[str]"]
CutLike = Union["Cut", str, "os.PathLike[str]"]
ConfigLike = Union[str, "os.PathLike[str]", Dict[str, Any]]
Size = Union[float, str]

class Error(ValueError):
    """Bad input: the command line's one-line error naming the field and what is allowed."""

class InternalError(RuntimeError):
    """A bug in facetlab (a caught panic)."""

class Cut:
    @property
    def name(self) -> str: ...
    @property
    def family(self) -> Optional[str]: ...
    @property
    def params(self) -> Dict[str, float]: ...
    @property
    def facets(self) -> int: ...
    def with_set(
        self, changes: Optional[Dict[str, float]] = None, **kwargs: float
    ) -> "Cut": ...
    def write(self, path: PathLike, overwrite: bool = False) -> None: ...
    def __reduce__(self) -> Tuple[Callable[[bytes], "Cut"], Tuple[bytes]]: ...
    @classmethod
    def _from_state(cls, state: bytes) -> "Cut": ...
    def info(
        self,
        *,
        diameter_mm: float = 6.5,
        material: Optional[str] = None,
        instructions: bool = False,
        meets: bool = False,
        meet_tol: float = ...,
    ) -> Dict[str, Any]: ...

class Recipe:
    def __init__(
        self,
        name: str = "recipe",
        gear: int = 96,
        symmetry: int = 1,
        mirror: bool = False,
        index: float = 1.54,
        *,
        offset: float = 0.0,
        fractional: bool = False,
    ) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def tiers(self) -> List[str]: ...
    def add_tier(
        self,
        name: str,
        angle: Union[float, str],
        indices: Union[None, float, str, Sequence[Union[float, str]]] = None,
        *,
        meet: Union[None, str, Sequence[str]] = None,
        centre: bool = False,
        depth: Optional[float] = None,
        scale: Optional[float] = None,
        girdle: Optional[float] = None,
        table: Optional[float] = None,
        side: Optional[str] = None,
        note: Optional[str] = None,
    ) -> None: ...
    def build(self) -> Cut: ...
    def steps(self) -> List[Dict[str, Any]]: ...
    def findings(self) -> List[Dict[str, Any]]: ...
    def to_toml(self) -> str: ...
    @classmethod
    def from_toml(cls, text: str, name: str = "recipe") -> "Recipe": ...
    @classmethod
    def from_design(cls, design: CutLike) -> "Recipe": ...
    def __len__(self) -> int: ...
    def __eq__(self, other: object) -> bool: ...

class Scores:
    @property
    def cut(self) -> str: ...
    @property
    def overhead_light_return(self) -> float: ...
    @property
    def brilliance(self) -> float: ...
    @property
    def brilliance_iso(self) -> float: ...
    @property
    def brilliance_cos(self) -> float: ...
    @property
    def fire(self) -> float: ...
    @property
    def scintillation(self) -> float: ...
    @property
    def aset(self) -> Dict[str, float]: ...
    def to_dict(self) -> Dict[str, Any]: ...

class Render:
    @property
    def linear(self) -> npt.NDArray[np.floating[Any]]: ...
    @property
    def srgb(self) -> npt.NDArray[np.uint8]: ...
    @property
    def coverage(self) -> npt.NDArray[np.float64]: ...
    @property
    def stats(self) -> Dict[str, Any]: ...
    def write_png(self, path: PathLike, overwrite: bool = False) -> None: ...

class Grid:
    def __init__(self, config: ConfigLike, axes: Sequence[str]) -> None: ...
    def __len__(self) -> int: ...
    @property
    def keys(self) -> List[str]: ...
    def rows(self, indices: Optional[Sequence[int]] = None) -> List[Dict[str, Any]]: ...
    def csv(self, rows: Sequence[Dict[str, Any]]) -> str: ...

def cut(obj: CutLike) -> Cut: ...
def family(family: str, name: Optional[str] = None, **params: float) -> Cut: ...
def presets() -> List[str]: ...
def families() -> Dict[str, Dict[str, Any]]: ...
def materials() -> List[Dict[str, Any]]: ...
# The keyword arguments of score, score_many and render, as the native module lists them once
# (src/python/keywords.rs: STONE, SCORE, RENDER; tests/python/test_keywords.py checks these
# against that list). Every one may be left out or given as None (not given); the defaults
# are in the functions' docstrings.
class StoneKeywords(TypedDict, total=False):
    material: Optional[str]
    ri: Optional[float]
    colour: Optional[str]
    colour_density: Optional[float]
    size_mm: Optional[Size]
    diameter_mm: Optional[float]
    birefringence: Optional[bool]
    optic_axis: Optional[str]
    colour_e: Optional[str]

class ScoreKeywords(StoneKeywords, total=False):
    polarization: Optional[bool]
    head_shadow: Optional[float]

class RenderKeywords(StoneKeywords, total=False):
    light: Optional[str]
    size: Optional[int]
    tilt: Optional[Size]
    view: Optional[Size]
    distance: Optional[float]
    aperture: Optional[float]
    ground: Optional[str]
    ground_gap: Optional[float]
    light_rotation: Optional[float]
    tone: Optional[str]
    bands: Optional[int]
    head_shadow: Optional[float]
    exposure: Optional[float]
    polarization: Optional[bool]
    float64: Optional[bool]

def score(cut: CutLike, **kwargs: Unpack[ScoreKeywords]) -> Scores: ...
def score_many(cuts: Sequence[CutLike], **kwargs: Unpack[ScoreKeywords]) -> List[Scores]: ...
def render(cut: CutLike, **kwargs: Unpack[RenderKeywords]) -> Render: ...
def trace(
    cut: CutLike,
    *,
    light: str = "overhead",
    angle: Optional[float] = None,
    rotate: bool = False,
    photons: int = 1_000_000,
    depth: Optional[int] = 6,
    absorption: str = "thesis",
    polarization: bool = True,
    spectrum: str = "uniform",
    seed: int = 1,
    material: Optional[str] = None,
    ri: Optional[float] = None,
    birefringence: Optional[bool] = None,
    optic_axis: Optional[str] = None,
    colour_e: Optional[str] = None,
) -> Dict[str, Any]: ...
def optimize(
    config: ConfigLike,
    *,
    out: Optional[PathLike] = None,
    seed: Optional[int] = None,
    verify: bool = True,
    progress: Optional[Callable[[Dict[str, Any]], Any]] = None,
    overwrite: bool = False,
) -> Dict[str, Any]: ...
class PlanKeywords(TypedDict, total=False):
    config: Optional[PathLike]
    families: Optional[Sequence[str]]
    size_mm: Optional[float]
    material: Optional[str]
    top: Optional[int]
    stones: Optional[int]
    kerf: Optional[float]
    allowance: Optional[float]
    inclusions: Optional[Sequence[PathLike]]
    margin: Optional[float]

@overload
def plan(
    rough: PathLike, *, out: None = None, **kwargs: Unpack[PlanKeywords]
) -> List[Dict[str, Any]]: ...
@overload
def plan(rough: PathLike, *, out: PathLike, **kwargs: Unpack[PlanKeywords]) -> Dict[str, Any]: ...
def _keywords() -> Dict[str, List[Tuple[str, str, str]]]: ...
