"""Type stubs of the compiled extension (see the docstrings of the objects for units and
signs: pressure > 0 compressive, depth > 0 into the body, displacement > 0 into the body,
fields float64 of shape (ny, nx) indexed [row = y, column = x]). The solvers' default
parameters are the Rust library's (`Ccg.defaults()`, ...), not repeated here."""

from typing import Any, Callable, Dict, List, Literal, Mapping, Optional, Tuple, Union, final, overload

import numpy as np
import numpy.typing as npt

# Fields come back as float64 arrays; as inputs any array_like of real numbers (float32,
# integers, nested lists) is taken as float64.
_FloatField = npt.NDArray[np.float64]
_BoolField = npt.NDArray[np.bool_]

# The extension module's __all__ (PyO3 lists every name it adds).
__all__ = [
    "RESULTS_REVISION", "__version__", "cli_main", "SolveError", "ScenarioError",
    "Grid", "Material", "HalfSpace", "ContactState", "SolveReport", "StepReport", "Ccg",
    "NestedActiveSet", "AdhesiveSolver", "sphere_heights", "flat_punch_heights",
    "wavy_sphere_heights", "elliptic_punch_heights", "_hertz", "_jkr_curve",
    "_jkr_at_depth", "jkr_scales", "_flat_punch", "johnson_parameter", "_fit_jkr_force",
    "_fit_jkr_depth", "_fit_power_law", "_RunFields", "_run_scenario", "_scenario_heights",
    "_curve_column_kinds", "_toml_value", "_toml_document", "_read_input_text", "_SweepFolder",
    "_sweep_open", "_sweep_run_case", "_self_affine", "_height_map_statistics",
    "_isotropic_psd", "_fill_invalid", "_read_topography",
]

RESULTS_REVISION: int
__version__: str

def cli_main(argv: List[str]) -> int: ...

class ScenarioError(ValueError):
    key: Optional[str]
    value: Optional[str]
    requirement: Optional[str]
    kind: str

class SolveError(RuntimeError):
    """A solver did not converge (iteration or round limit, or a non-finite value)."""

@final
class Grid:
    """Grid(n, size) or Grid(nx, ny, size_x, size_y), then the boundary; fields are (ny, nx)."""
    @overload
    def __new__(cls, n: int, size: float, boundary: Literal["free", "periodic"] = "free") -> "Grid": ...
    @overload
    def __new__(
        cls, nx: int, ny: int, size_x: float, size_y: float, boundary: Literal["free", "periodic"] = "free"
    ) -> "Grid": ...
    @property
    def n(self) -> int: ...
    @property
    def nx(self) -> int: ...
    @property
    def ny(self) -> int: ...
    @property
    def shape(self) -> Tuple[int, int]: ...
    @property
    def size(self) -> float: ...
    @property
    def size_x(self) -> float: ...
    @property
    def size_y(self) -> float: ...
    @property
    def boundary(self) -> Literal["free", "periodic"]: ...
    @property
    def element_size(self) -> float: ...
    @property
    def dx(self) -> float: ...
    @property
    def dy(self) -> float: ...
    @property
    def element_area(self) -> float: ...
    def coordinates(self) -> _FloatField: ...
    def x(self) -> _FloatField: ...
    def y(self) -> _FloatField: ...

@final
class Material:
    def __new__(cls, contact_modulus: float) -> "Material": ...
    @staticmethod
    def from_youngs_modulus(youngs_modulus: float, poisson_ratio: float) -> "Material": ...
    @staticmethod
    def from_two_bodies(first: Tuple[float, float], second: Tuple[float, float]) -> "Material": ...
    @property
    def contact_modulus(self) -> float: ...

@final
class HalfSpace:
    def __new__(cls, grid: Grid, material: Material) -> "HalfSpace": ...
    def apply(self, pressure: _FloatField) -> _FloatField: ...
    @property
    def grid(self) -> Grid: ...
    @property
    def material(self) -> Material: ...
    @property
    def self_compliance(self) -> float: ...
    @property
    def applications(self) -> int: ...

@final
class ContactState:
    def __new__(cls, grid: Grid) -> "ContactState": ...
    @property
    def pressure(self) -> _FloatField: ...
    @property
    def displacement(self) -> _FloatField: ...
    @property
    def contact(self) -> _BoolField: ...
    @property
    def gap(self) -> _FloatField: ...
    @property
    def depth(self) -> Optional[float]: ...
    @property
    def force(self) -> float: ...
    @property
    def contact_elements(self) -> int: ...
    @property
    def contact_area(self) -> float: ...
    def contact_radius(self, centre: Tuple[float, float] = (0.0, 0.0)) -> float: ...
    @property
    def grid(self) -> Grid: ...
    def copy(self) -> "ContactState": ...

@final
class SolveReport:
    iterations: int
    residual: float
    contact_elements: int
    contact_area: float
    force: float
    depth: float
    operator_applications: int
    state: ContactState

@final
class StepReport:
    depth: float
    force: float
    force_before_change: float
    contact_elements: int
    attached: int
    detached: int
    energy: float
    energy_before_change: float
    dissipated_energy: float
    solves: int
    cg_iterations: int
    operator_applications: int

@final
class Ccg:
    def __new__(cls, operator: HalfSpace, tolerance: float = ..., max_iterations: int = ...) -> "Ccg": ...
    @staticmethod
    def defaults() -> Dict[str, Any]: ...
    def solve(
        self,
        heights: _FloatField,
        depth: Optional[float] = None,
        load: Optional[float] = None,
        state: Optional[ContactState] = None,
    ) -> SolveReport: ...

@final
class NestedActiveSet:
    def __new__(
        cls,
        operator: HalfSpace,
        relative_tolerance: float = ...,
        max_cg_iterations: int = ...,
        max_rounds: int = ...,
        coarsest: int = ...,
    ) -> "NestedActiveSet": ...
    @staticmethod
    def defaults() -> Dict[str, Any]: ...
    def solve(self, heights: _FloatField, depth: float, state: Optional[ContactState] = None) -> SolveReport: ...
    @property
    def coarse_levels(self) -> int: ...

@final
class AdhesiveSolver:
    def __new__(
        cls,
        operator: HalfSpace,
        work_of_adhesion: Union[float, _FloatField],
        relative_tolerance: float = ...,
        front_tolerance: float = ...,
        max_cg_iterations: int = ...,
        max_rounds: int = ...,
        attachment: Literal["trial", "penetration_only"] = ...,
        worst_first_fraction: Optional[float] = ...,
        preconditioned: bool = ...,
        carry_bans_when_retracting: bool = ...,
        retry_after_growth: bool = ...,
    ) -> "AdhesiveSolver": ...
    @staticmethod
    def defaults() -> Dict[str, Any]: ...
    def step(self, heights: _FloatField, depth: float, state: ContactState) -> StepReport: ...
    def steps(
        self,
        heights: _FloatField,
        depths: npt.NDArray[np.float64],
        state: ContactState,
        progress: Optional[Callable[[int, StepReport], object]] = None,
    ) -> Dict[str, np.ndarray]: ...
    def reset(self) -> None: ...
    def energy(self, state: ContactState) -> float: ...
    @property
    def critical_stress(self) -> _FloatField: ...

def sphere_heights(grid: Grid, radius: float) -> _FloatField: ...
def flat_punch_heights(grid: Grid, radius: float) -> _FloatField: ...
def wavy_sphere_heights(grid: Grid, radius: float, amplitude: float, wavelength: float, angle_degrees: float) -> _FloatField: ...
def elliptic_punch_heights(grid: Grid, semi_axes: Tuple[float, float], angle_degrees: float) -> _FloatField: ...
def jkr_scales(radius: float, contact_modulus: float, work_of_adhesion: float) -> Dict[str, float]: ...
def johnson_parameter(wavelength: float, amplitude: float, work_of_adhesion: float, contact_modulus: float) -> float: ...
def _hertz(
    radius: float, contact_modulus: float, depth: npt.NDArray[np.float64]
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
def _jkr_curve(
    radius: float, contact_modulus: float, work_of_adhesion: float, contact_radius: npt.NDArray[np.float64]
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
def _jkr_at_depth(
    radius: float, contact_modulus: float, work_of_adhesion: float, depth: npt.NDArray[np.float64]
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.bool_]]: ...
def _flat_punch(radius: float, contact_modulus: float, work_of_adhesion: float) -> Tuple[float, float, float]: ...
def _fit_jkr_force(
    contact_radius: npt.NDArray[np.float64], force: npt.NDArray[np.float64], radius: float, contact_modulus: float
) -> Dict[str, float]: ...
def _fit_jkr_depth(
    contact_radius: npt.NDArray[np.float64], depth: npt.NDArray[np.float64], radius: float, contact_modulus: float
) -> Dict[str, float]: ...
def _fit_power_law(t: npt.NDArray[np.float64], y: npt.NDArray[np.float64]) -> Tuple[float, float]: ...
def _run_scenario(
    text: str,
    origin: str,
    base: str,
    overrides: List[str],
    progress: Optional[Callable[[int, int], object]] = None,
    check_memory: bool = False,
    out: Optional[str] = None,
    force: bool = False,
    threads: Optional[int] = None,
) -> Dict[str, Any]: ...
def _scenario_heights(text: str, origin: str, base: str, overrides: List[str]) -> Tuple[Grid, _FloatField]: ...
@final
class _RunFields:
    def write_npz(self, path: str) -> None: ...

def _curve_column_kinds() -> Dict[str, str]: ...

@final
class _SweepFolder:
    def cases(self) -> List[Dict[str, Any]]: ...
    def pending(self, retry_failed: bool) -> List[Tuple[int, Optional[str]]]: ...
    def finish(self) -> Tuple[str, List[str]]: ...
    def close(self) -> None: ...

def _sweep_open(
    out: str,
    sweep_text: str,
    scenario_text: str,
    origin: str,
    base: str,
    series: str,
    check_memory: bool,
    jobs: int,
    checkpoint_seconds: float = 0.0,
) -> _SweepFolder: ...
def _sweep_run_case(
    out: str,
    index: int,
    checkpoint_seconds: float = 0.0,
    resume: Optional[str] = None,
    threads: Optional[int] = None,
) -> Tuple[bool, Optional[str]]: ...
def _toml_value(value: object) -> str: ...
def _toml_document(value: Mapping[str, object]) -> str: ...
def _read_input_text(path: str, what: str) -> str: ...
def _self_affine(
    grid: Grid,
    hurst: float,
    seed: int,
    rms_height: Optional[float] = None,
    rms_slope: Optional[float] = None,
    rolloff_wavelength: Optional[float] = None,
    cutoff_wavelength: Optional[float] = None,
    mode: str = "random_phase",
) -> _FloatField: ...
def _height_map_statistics(
    heights: _FloatField, dx: float, dy: float, valid: Optional[_BoolField] = None, periodic: bool = False
) -> Dict[str, Any]: ...
def _isotropic_psd(
    heights: _FloatField, dx: float, dy: float, bins: int, valid: Optional[_BoolField] = None, periodic: bool = False
) -> List[npt.NDArray[np.float64]]: ...
def _fill_invalid(heights: _FloatField, valid: _BoolField, periodic: bool = False) -> _FloatField: ...
def _read_topography(
    path: str,
    channel: Optional[str] = None,
    spacing: Optional[Tuple[float, float]] = None,
    height_unit: Optional[str] = None,
    lateral_unit: Optional[str] = None,
) -> Dict[str, Any]: ...
