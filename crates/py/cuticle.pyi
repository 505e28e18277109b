"""Type stubs of `cuticle` (the Rust extension of crates/py). Units and ranges are in each
docstring; the ranges themselves are `cuticle.RANGES`, read from the Rust crates."""

from os import PathLike
from typing import Optional, Sequence, Tuple, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str
MODELS: list[str]
RANGES: dict[str, str]

ArrayLike = npt.ArrayLike
F64 = npt.NDArray[np.float64]
F32 = npt.NDArray[np.float32]
Rgb = Union[float, Sequence[float]]

class Fiber:
    """A hair fiber's scattering function S (sr^-1) under one model of cuticle's registry
    (cuticle.MODELS). Units, defaults and ranges: help(cuticle.Fiber), cuticle.RANGES.
    Directions: (N, 3) or (3,) unit vectors in the fiber frame (x along the fiber)."""

    def __init__(
        self,
        model: str = ...,
        *,
        beta: float = ...,
        alpha_deg: float = ...,
        eta: float = ...,
        mu_a: Optional[Rgb] = None,
        eumelanin: Optional[float] = None,
        pheomelanin: Optional[float] = None,
        iterations: int = ...,
        tabulated: bool = ...,
    ) -> None: ...
    @property
    def model(self) -> str: ...
    @property
    def beta(self) -> float: ...
    @property
    def alpha_deg(self) -> float: ...
    @property
    def eta(self) -> float: ...
    @property
    def mu_a(self) -> Tuple[float, float, float]: ...
    def eval(self, wi: ArrayLike, wo: ArrayLike) -> F64:
        """S(wi, wo), RGB, sr^-1: shape (N, 3)."""
    def lobes(self, wi: ArrayLike, wo: ArrayLike) -> dict[str, F64]:
        """S per lobe ("R", "TT", "TRT", "TRRT", "rest"), each (N, 3)."""
    def pdf(self, wi: ArrayLike, wo: ArrayLike) -> F64:
        """The sampling density per steradian: shape (N,)."""
    def sample(self, wi: ArrayLike, u: ArrayLike) -> Tuple[F64, F64, F64]:
        """(wo (N, 3), weight S/pdf (N, 3), pdf (N,)) from u of shape (N, 4) in [0, 1)."""
    def latlong(self, theta_i: float, width: int = ..., height: int | None = ...) -> dict:
        """`cuticle lobes`' images ((width/4, width, 3) per lobe and "total") and "energy"."""

class SimResult(TypedDict):
    R: F64
    TT: F64
    TRT: F64
    TRRT: F64
    rest: F64
    total: F64
    energy: dict[str, F64]
    lost: dict[str, F64]
    absorbed: F64
    rays: int
    seconds: float

def simulate(
    *,
    theta_i: float = ...,
    alpha_deg: float = ...,
    beta: float = ...,
    eta: float = ...,
    mu_a: Optional[Rgb] = None,
    rays: int = ...,
    seed: int = ...,
) -> SimResult:
    """`cuticle sim` (defaults and ranges its own, cuticle.RANGES): images (100, 400, 3)."""

def read_exr(path: Union[str, PathLike]) -> F32:
    """An RGB OpenEXR file as float32 (height, width, 3)."""

def render(
    *,
    groom: Optional[str] = None,
    env: Optional[str] = None,
    method: Optional[str] = None,
    width: Optional[int] = None,
    height: Optional[int] = None,
    supersampling: Optional[int] = None,
    strands: Optional[int] = None,
    lights: Optional[int] = None,
    quadrature: Optional[int] = None,
    multiple: Optional[bool] = None,
    brute_grid: Optional[int] = None,
    spp: Optional[int] = None,
    seed: Optional[int] = None,
    max_depth: Optional[int] = None,
    eta: Optional[float] = None,
    alpha_r_deg: Optional[float] = None,
    beta_r_deg: Optional[float] = None,
    mu_a: Optional[Rgb] = None,
    eccentricity: Optional[float] = None,
    caustic_width_deg: Optional[float] = None,
    scene: Optional[Union[str, PathLike]] = None,
) -> F32:
    """`cuticle render --device cpu` (methods srbf, brute, path): linear radiance (H, W, 3)."""

def load_groom(groom: str, strands: Optional[int] = None) -> dict:
    """A preset or .hair file: "strands", "points" (P, 3), "offsets" (strands + 1,), "thickness"."""

def fit_env(env: str, lights: int = ...) -> dict:
    """SRBF lights: "directions" (J, 3), "bandwidths" (J,), "coefficients" (J, 3), "relative_l2"."""
