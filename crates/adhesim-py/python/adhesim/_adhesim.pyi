"""Type stubs of the compiled extension (see the docstrings of the objects for units and
signs: pressure > 0 compressive, depth > 0 into the body, displacement > 0 into the body,
fields float64 of shape (n, n) indexed [row = y, column = x])."""

from typing import Any, Callable, Dict, List, Literal, Mapping, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

# Fields come back as float64 arrays; as inputs any array_like of real numbers (float32,
# integers, nested lists) is taken as float64.
FloatField = npt.NDArray[np.float64]
BoolField = npt.NDArray[np.bool_]

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

class Grid:
    def __init__(self, n: int, size: float, boundary: Literal["free", "periodic"] = "free") -> None: ...
    @property
    def n(self) -> int: ...
    @property
    def size(self) -> float: ...
    @property
    def boundary(self) -> Literal["free", "periodic"]: ...
    @property
    def element_size(self) -> float: ...
    @property
    def element_area(self) -> float: ...
    def coordinates(self) -> FloatField: ...

class Material:
    def __init__(self, contact_modulus: float) -> None: ...
    @staticmethod
    def from_youngs_modulus(youngs_modulus: float, poisson_ratio: float) -> "Material": ...
    @staticmethod
    def from_two_bodies(first: Tuple[float, float], second: Tuple[float, float]) -> "Material": ...
    @property
    def contact_modulus(self) -> float: ...

class HalfSpace:
    def __init__(self, grid: Grid, material: Material) -> None: ...
    def apply(self, pressure: FloatField) -> FloatField: ...
    @property
    def grid(self) -> Grid: ...
    @property
    def material(self) -> Material: ...
    @property
    def self_compliance(self) -> float: ...
    @property
    def applications(self) -> int: ...

class ContactState:
    def __init__(self, grid: Grid) -> None: ...
    @property
    def pressure(self) -> FloatField: ...
    @property
    def displacement(self) -> FloatField: ...
    @property
    def contact(self) -> BoolField: ...
    @property
    def gap(self) -> FloatField: ...
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

class SolveReport:
    iterations: int
    residual: float
    contact_elements: int
    contact_area: float
    force: float
    depth: float
    operator_applications: int
    state: ContactState

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

class Ccg:
    def __init__(self, operator: HalfSpace, tolerance: float = 1e-10, max_iterations: int = 20000) -> None: ...
    def solve(
        self,
        heights: FloatField,
        depth: Optional[float] = None,
        load: Optional[float] = None,
        state: Optional[ContactState] = None,
    ) -> SolveReport: ...

class NestedActiveSet:
    def __init__(
        self,
        operator: HalfSpace,
        relative_tolerance: float = 1e-10,
        max_cg_iterations: int = 2000,
        max_rounds: int = 200,
        coarsest: int = 32,
    ) -> None: ...
    def solve(self, heights: FloatField, depth: float, state: Optional[ContactState] = None) -> SolveReport: ...
    @property
    def coarse_levels(self) -> int: ...

class AdhesiveSolver:
    def __init__(
        self,
        operator: HalfSpace,
        work_of_adhesion: Union[float, FloatField],
        relative_tolerance: float = 1e-6,
        front_tolerance: float = 1e-4,
        max_cg_iterations: int = 5000,
        max_rounds: int = 100000,
        attachment: Literal["trial", "penetration_only"] = "trial",
        worst_first_fraction: Optional[float] = None,
        preconditioned: bool = True,
        carry_bans_when_retracting: bool = True,
        retry_after_growth: bool = True,
    ) -> None: ...
    def step(self, heights: FloatField, depth: float, state: ContactState) -> StepReport: ...
    def steps(
        self,
        heights: FloatField,
        depths: npt.NDArray[np.float64],
        state: ContactState,
        progress: Optional[Callable[[int, StepReport], object]] = None,
    ) -> Dict[str, np.ndarray]: ...
    def reset(self) -> None: ...
    def energy(self, state: ContactState) -> float: ...
    @property
    def critical_stress(self) -> FloatField: ...

def sphere_heights(grid: Grid, radius: float) -> FloatField: ...
def flat_punch_heights(grid: Grid, radius: float) -> FloatField: ...
def wavy_sphere_heights(grid: Grid, radius: float, amplitude: float, wavelength: float, angle_degrees: float) -> FloatField: ...
def elliptic_punch_heights(grid: Grid, semi_axes: Tuple[float, float], angle_degrees: float) -> FloatField: ...
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
) -> Dict[str, Any]: ...
class _RunFields:
    def write_npz(self, path: str) -> None: ...

def _curve_column_kinds() -> Dict[str, str]: ...

class _SweepFolder:
    def cases(self) -> List[Dict[str, Any]]: ...
    def pending(self, retry_failed: bool) -> List[int]: ...
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
) -> _SweepFolder: ...
def _sweep_run_case(out: str, index: int) -> Tuple[bool, Optional[str]]: ...
def _toml_value(value: object) -> str: ...
def _toml_document(value: Mapping[str, object]) -> str: ...
def _self_affine(
    grid: Grid,
    hurst: float,
    seed: int,
    rms_height: Optional[float] = None,
    rms_slope: Optional[float] = None,
    rolloff_wavelength: Optional[float] = None,
    cutoff_wavelength: Optional[float] = None,
    mode: str = "random_phase",
) -> FloatField: ...
def _height_map_statistics(
    heights: FloatField, dx: float, dy: float, valid: Optional[BoolField] = None, periodic: bool = False
) -> Dict[str, Any]: ...
def _isotropic_psd(
    heights: FloatField, dx: float, dy: float, bins: int, valid: Optional[BoolField] = None, periodic: bool = False
) -> List[npt.NDArray[np.float64]]: ...
def _fill_invalid(heights: FloatField, valid: BoolField, periodic: bool = False) -> FloatField: ...
def _read_topography(
    path: str,
    channel: Optional[str] = None,
    spacing: Optional[Tuple[float, float]] = None,
    height_unit: Optional[str] = None,
    lateral_unit: Optional[str] = None,
) -> Dict[str, Any]: ...
