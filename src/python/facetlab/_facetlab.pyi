"""Type stubs of facetlab's native module (src/python/*.rs, built by maturin)."""

import os
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union, overload

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
        meet_tol: float = 1e-4,
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
# score, score_many and render spell their keyword arguments in their signatures, as
# inspect.signature shows them (tests/python/test_signatures.py checks each function and
# method here against it); the stone's keywords come in the same order in all three.
def score(
    cut: CutLike,
    *,
    material: Optional[str] = None,
    ri: Optional[float] = None,
    colour: Optional[str] = None,
    colour_density: Optional[float] = None,
    size_mm: Optional[Size] = None,
    diameter_mm: Optional[float] = None,
    birefringence: Optional[bool] = None,
    optic_axis: Optional[str] = None,
    colour_e: Optional[str] = None,
    polarization: bool = True,
    head_shadow: float = 15.0,
) -> Scores: ...
def score_many(
    cuts: Sequence[CutLike],
    *,
    material: Optional[str] = None,
    ri: Optional[float] = None,
    colour: Optional[str] = None,
    colour_density: Optional[float] = None,
    size_mm: Optional[Size] = None,
    diameter_mm: Optional[float] = None,
    birefringence: Optional[bool] = None,
    optic_axis: Optional[str] = None,
    colour_e: Optional[str] = None,
    polarization: bool = True,
    head_shadow: float = 15.0,
) -> List[Scores]: ...
def render(
    cut: CutLike,
    *,
    light: str = "iso",
    size: int = 256,
    tilt: Optional[Size] = None,
    view: Optional[Size] = None,
    distance: Optional[float] = None,
    aperture: Optional[float] = None,
    ground: Optional[str] = None,
    ground_gap: Optional[float] = None,
    light_rotation: Optional[float] = None,
    tone: Optional[str] = None,
    bands: Optional[int] = None,
    head_shadow: Optional[float] = None,
    exposure: float = 1.0,
    polarization: bool = True,
    material: Optional[str] = None,
    ri: Optional[float] = None,
    colour: Optional[str] = None,
    colour_density: Optional[float] = None,
    size_mm: Optional[Size] = None,
    diameter_mm: Optional[float] = None,
    birefringence: Optional[bool] = None,
    optic_axis: Optional[str] = None,
    colour_e: Optional[str] = None,
    float64: bool = False,
) -> Render: ...
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
# Without out: the plans; with out: {"plans", "folder"} (and "layout").
@overload
def plan(
    rough: PathLike,
    *,
    config: Optional[PathLike] = None,
    families: Optional[Sequence[str]] = None,
    size_mm: Optional[float] = None,
    material: Optional[str] = None,
    top: Optional[int] = None,
    stones: Optional[int] = None,
    kerf: Optional[float] = None,
    allowance: Optional[float] = None,
    inclusions: Optional[Sequence[PathLike]] = None,
    margin: Optional[float] = None,
    cutter: Optional[str] = None,
    out: None = None,
) -> List[Dict[str, Any]]: ...
@overload
def plan(
    rough: PathLike,
    *,
    config: Optional[PathLike] = None,
    families: Optional[Sequence[str]] = None,
    size_mm: Optional[float] = None,
    material: Optional[str] = None,
    top: Optional[int] = None,
    stones: Optional[int] = None,
    kerf: Optional[float] = None,
    allowance: Optional[float] = None,
    inclusions: Optional[Sequence[PathLike]] = None,
    margin: Optional[float] = None,
    cutter: Optional[str] = None,
    out: PathLike,
) -> Dict[str, Any]: ...
