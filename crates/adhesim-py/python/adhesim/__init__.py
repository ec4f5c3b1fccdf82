"""adhesim: adhesive contacts of rough elastic bodies from Python.

FFT-accelerated boundary elements after Popov, Li, Lyashenko & Pohrt (2021), "Adhesion and
friction in hard and soft contacts: theory and experiment", Friction 9, 1688-1706.

Units and signs: any consistent unit system. A rigid indenter touches an elastic
half-space of contact modulus E* = E/(1 - nu^2).

- pressure p > 0 is compressive, p < 0 tensile (adhesion); normal force F = dx^2 * sum(p);
- indentation depth d > 0 pushes the indenter into the half-space;
- surface displacement u > 0 points into the body; gap g = z - d + u >= 0;
- the work of adhesion gamma is an energy per unit area.

Fields are float64 numpy arrays of shape (n, n) indexed [row = y, column = x].

Objects: Grid, Material, HalfSpace (u = K p), ContactState, the non-adhesive solvers
Ccg and NestedActiveSet, the AdhesiveSolver with its step API; closed forms in
adhesim.reference, fits in adhesim.fit, indenter heights in adhesim.geometry; random
self-affine surfaces, height-map statistics, PSD and filling in adhesim.surface;
read_topography(path, ...) reads instrument files (x3p, gwy, sur, ASCII, xyz, npy, npz).

One-call runs of a scenario file (the command line's TOML, a TOML string or a dict):
run(scenario, out=None, progress=None, **overrides) -> RunResult (.curve, .summary,
.snapshots); load(folder) reads a run folder back; sweep(scenario, vary={...}) runs cases.
"""

from . import fit, geometry, reference, surface
from .topography import Topography, read_topography
from . import _errors  # documents adhesim.ScenarioError's fields
from ._run import RunResult, Snapshot, load, run, sweep_table
from ._sweep import SweepResult, sweep
from ._adhesim import (
    RESULTS_REVISION,
    __version__,
    AdhesiveSolver,
    Ccg,
    ContactState,
    Grid,
    HalfSpace,
    Material,
    NestedActiveSet,
    ScenarioError,
    SolveError,
    SolveReport,
    StepReport,
)

__all__ = [
    "RESULTS_REVISION",
    "AdhesiveSolver",
    "Ccg",
    "ContactState",
    "Grid",
    "HalfSpace",
    "Material",
    "NestedActiveSet",
    "RunResult",
    "ScenarioError",
    "SolveError",
    "Snapshot",
    "SolveReport",
    "StepReport",
    "Topography",
    "fit",
    "geometry",
    "load",
    "reference",
    "read_topography",
    "run",
    "surface",
    "sweep",
    "SweepResult",
    "sweep_table",
]
