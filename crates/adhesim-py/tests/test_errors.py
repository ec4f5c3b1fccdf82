"""Bad input raises ValueError/TypeError naming the argument and the value, never a panic;
a solver that does not converge raises adhesim.SolveError."""

import numpy as np
import pytest

import adhesim


@pytest.fixture(scope="module")
def grid():
    return adhesim.Grid(32, 1.0)


@pytest.fixture(scope="module")
def operator(grid):
    return adhesim.HalfSpace(grid, adhesim.Material(1.0))


@pytest.mark.parametrize(
    "call, words",
    [
        (lambda: adhesim.reference.hertz(-1.0, 1.0, 0.1), ["radius", "-1"]),
        (lambda: adhesim.reference.jkr_scales(1.0, 1.0, -0.5), ["work_of_adhesion", "-0.5"]),
        (lambda: adhesim.reference.flat_punch(-2.0, 1.0), ["radius", "-2"]),
        (lambda: adhesim.reference.hertz(1.0, 0.0, 0.1), ["contact_modulus", "0"]),
        (lambda: adhesim.Material(-3.0), ["contact_modulus", "-3"]),
        (lambda: adhesim.Material.from_youngs_modulus(1.0, 0.7), ["Poisson", "0.7"]),
        (lambda: adhesim.Grid(1, 1.0), ["n", "1"]),
        (lambda: adhesim.Grid(-4, 1.0), ["n", "-4"]),
        (lambda: adhesim.Grid(8, float("nan")), ["size", "NaN"]),
        (lambda: adhesim.Grid(8, 1.0, "round"), ["boundary", "round"]),
        (lambda: adhesim.geometry.sphere(adhesim.Grid(8, 1.0), -1.0), ["radius", "-1"]),
        (lambda: adhesim.reference.johnson_parameter(1.0, -0.1, 1.0, 1.0), ["amplitude", "-0.1"]),
    ],
)
def test_bad_scalars_name_the_argument(call, words):
    with pytest.raises(ValueError) as error:
        call()
    for word in words:
        assert word in str(error.value)


def test_wrong_shape_heights(grid, operator):
    solver = adhesim.Ccg(operator)
    with pytest.raises(ValueError, match=r"heights must have shape \(32, 32\).*got shape \[16, 16\]"):
        solver.solve(np.zeros((16, 16)), 0.01)
    with pytest.raises(ValueError, match=r"heights must have shape \(32, 32\)"):
        adhesim.AdhesiveSolver(operator, 0.01).step(np.zeros(32 * 32), 0.01, adhesim.ContactState(grid))
    with pytest.raises(ValueError, match=r"pressure must have shape \(32, 32\)"):
        operator.apply(np.zeros((32, 31)))


def test_array_like_inputs_are_coerced_to_float64(grid, operator):
    """numpy's convention: float32, integers and nested lists are taken as float64 (the
    result equals the float64 solve of the same values, bit for bit); what numpy cannot
    make real floats of is a TypeError naming the argument."""
    heights = adhesim.geometry.sphere(grid, 1.0)
    depth = 0.2 * float(heights.max())
    as_float32 = heights.astype(np.float32)
    reference = adhesim.Ccg(operator).solve(as_float32.astype(np.float64), depth=depth)
    for value in (as_float32, as_float32.astype(np.float64).tolist()):
        result = adhesim.Ccg(operator).solve(value, depth=depth)
        pressure = result.state.pressure
        assert pressure.dtype == np.float64
        assert np.array_equal(pressure.view(np.int64), reference.state.pressure.view(np.int64))
        assert result.force == reference.force
    solver = adhesim.NestedActiveSet(operator)
    solver.solve(np.zeros((32, 32), dtype=np.int64), 0.01)
    with pytest.raises(TypeError, match=r"heights must be real numbers.*complex"):
        solver.solve(np.zeros((32, 32), dtype=np.complex128), 0.01)
    with pytest.raises(TypeError, match=r"heights must be array_like of floats.*str"):
        solver.solve("flat", 0.01)
    with pytest.raises(ValueError, match=r"heights must have shape \(32, 32\)"):
        solver.solve([[0.0] * 31] * 32, 0.01)


def test_non_finite_values(grid, operator):
    heights = adhesim.geometry.sphere(grid, 1.0)
    heights[3, 4] = np.nan
    with pytest.raises(ValueError, match=r"heights\[3, 4\] must be finite or \+inf.*NaN"):
        adhesim.Ccg(operator).solve(heights, 0.01)
    with pytest.raises(ValueError, match=r"depth must be finite, got inf"):
        adhesim.Ccg(operator).solve(adhesim.geometry.sphere(grid, 1.0), float("inf"))
    with pytest.raises(ValueError, match=r"work_of_adhesion must be finite and >= 0, got -1"):
        adhesim.AdhesiveSolver(operator, -1.0)
    with pytest.raises(ValueError, match=r"work_of_adhesion must have shape \(32, 32\)"):
        adhesim.AdhesiveSolver(operator, np.ones((4, 4)))


def test_control_and_grid_mismatch(grid, operator):
    heights = adhesim.geometry.sphere(grid, 1.0)
    with pytest.raises(ValueError, match=r"exactly one of depth and load"):
        adhesim.Ccg(operator).solve(heights, 0.01, load=1.0)
    with pytest.raises(ValueError, match=r"load must be finite and > 0, got -1"):
        adhesim.Ccg(operator).solve(heights, load=-1.0)
    other = adhesim.ContactState(adhesim.Grid(16, 1.0))
    with pytest.raises(ValueError, match=r"state is for Grid\(n=16"):
        adhesim.Ccg(operator).solve(heights, 0.01, state=other)
    periodic = adhesim.HalfSpace(adhesim.Grid(32, 1.0, "periodic"), adhesim.Material(1.0))
    with pytest.raises(ValueError, match=r"free grids only"):
        adhesim.NestedActiveSet(periodic)
    with pytest.raises(ValueError, match=r"max_iterations must be an integer >= 1, got 0"):
        adhesim.Ccg(operator, max_iterations=0)
    with pytest.raises(ValueError, match=r"attachment must be"):
        adhesim.AdhesiveSolver(operator, 0.01, attachment="glue")


def test_non_convergence_is_reported(grid, operator):
    heights = adhesim.geometry.sphere(grid, 1.0)
    with pytest.raises(adhesim.SolveError, match=r"did not converge in 2 iterations"):
        adhesim.Ccg(operator, max_iterations=2).solve(heights, 0.01)
    assert issubclass(adhesim.SolveError, RuntimeError)


def test_gap_needs_a_solve(grid):
    with pytest.raises(ValueError, match=r"not been solved"):
        adhesim.ContactState(grid).gap


# Second robustness audit (docs/reliability.md): sizes the library cannot index or hold
# raised a Rust panic, aborted the interpreter, or were accepted; each is now a Python
# exception naming what and why.
def test_audit_grids_beyond_the_index_range_or_floating_point_are_refused():
    with pytest.raises(ValueError, match=r"too large"):
        adhesim.Grid(2**32, 1.0)
    with pytest.raises(ValueError, match=r"too large"):
        adhesim.Grid(2**31, 1.0)
    with pytest.raises(ValueError, match=r"outside the floating-point range"):
        adhesim.Grid(32, 1e-310)


def test_audit_allocations_beyond_the_memory_available_raise_memory_error(monkeypatch):
    monkeypatch.setenv("ADHESIM_MEMORY_AVAILABLE", str(1 << 30))
    big = adhesim.Grid(2**31 - 1, 1.0)
    with pytest.raises(MemoryError, match=r"ContactState\(Grid\(n=2147483647.*of memory"):
        adhesim.ContactState(big)
    with pytest.raises(MemoryError, match=r"HalfSpace\(Grid\(n=100000.*ADHESIM_MEMORY_AVAILABLE"):
        adhesim.HalfSpace(adhesim.Grid(100000, 1.0), adhesim.Material(1.0))
    with pytest.raises(MemoryError, match=r"coordinates\(\)"):
        adhesim.Grid(2**31 - 1, 1.0).coordinates()
    # Small objects stay within the same limit.
    assert adhesim.ContactState(adhesim.Grid(64, 1.0)).force == 0.0
    assert len(adhesim.Grid(64, 1.0).coordinates()) == 64


def test_audit_arguments_are_checked_by_name(operator):
    scenario = {
        "grid": {"n": 16, "size": 0.5},
        "material": {"contact_modulus": 1.0},
        "adhesion": {"work_of_adhesion": 0.0},
        "indenter": {"shape": "sphere", "radius": 1.0},
        "protocol": {"kind": "indent_pulloff", "max_depth": 0.01, "depth_unit": "length", "steps": 2},
    }
    with pytest.raises(TypeError, match=r"overrides must be a mapping.*'grid.n=32'"):
        adhesim.run(scenario, overrides="grid.n=32")
    with pytest.raises(TypeError, match=r"vary must be a mapping.*\[1, 2\]"):
        adhesim.sweep(scenario, vary=[1, 2])
    with pytest.raises(TypeError, match=r"vary\['grid.n'\] must be a list of values"):
        adhesim.sweep(scenario, vary={"grid.n": "32"})
    with pytest.raises(ValueError, match=r"worst_first_fraction must be a fraction in \[0, 1\].*got 1.5"):
        adhesim.AdhesiveSolver(operator, 0.01, worst_first_fraction=1.5)
    radius = np.array([0.1, 0.2, np.nan])
    force = np.array([1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match=r"contact_radius must hold finite numbers, got NaN at index 2"):
        adhesim.fit.jkr_work_of_adhesion(radius, force, 1.0, 1.0)
    with pytest.raises(ValueError, match=r"y must hold finite numbers"):
        adhesim.fit.power_law(np.array([1.0, 2.0]), np.array([1.0, np.inf]))


def test_audit_hostile_object_sizes_raise_python_exceptions(monkeypatch):
    """A fixed-seed fuzz of the objects' sizes: every combination of hostile n and size
    either builds (and its arrays fit) or raises a Python exception; a panic or an abort
    would end the interpreter, not raise."""
    monkeypatch.setenv("ADHESIM_MEMORY_AVAILABLE", str(1 << 30))
    rng = np.random.default_rng(29)
    counts = [0, 1, 2, 3, 64, 100_000, 2**31 - 1, 2**31, 2**32, 2**62, -1]
    sizes = [1.0, 1e-310, 1e-300, 1e300, 0.0, -1.0, float("nan"), float("inf")]
    for _ in range(200):
        n = int(rng.choice(counts))
        size = float(rng.choice(sizes))
        boundary = "periodic" if rng.random() < 0.3 else "free"
        try:
            grid = adhesim.Grid(n, size, boundary)
        except (ValueError, OverflowError):
            continue
        for make in (
            lambda: grid.coordinates(),
            lambda: adhesim.ContactState(grid),
            lambda: adhesim.HalfSpace(grid, adhesim.Material(1.0)),
            lambda: adhesim.geometry.sphere(grid, 1.0),
        ):
            try:
                make()
            except (ValueError, MemoryError):
                pass


def test_scenario_errors_carry_the_key_value_and_requirement():
    """A bad scenario raises adhesim.ScenarioError, a ValueError whose fields name the key
    at fault, its value, the requirement and the kind (no message parsing needed)."""
    scenario = {
        "grid": {"n": 32, "size": 0.25},
        "material": {"contact_modulus": 1.0},
        "adhesion": {"work_of_adhesion": 0.0},
        "indenter": {"shape": "sphere", "radius": 1.0},
        "protocol": {"kind": "indent_pulloff", "max_depth": 0.01, "depth_unit": "length", "steps": 2},
    }
    with pytest.raises(adhesim.ScenarioError, match=r"grid.n must be >= 2, got -4") as info:
        adhesim.run(scenario, **{"grid.n": -4})
    assert isinstance(info.value, ValueError)
    error = info.value
    assert (error.key, error.value, error.requirement, error.kind) == ("grid.n", "-4", ">= 2", "invalid_value")
    with pytest.raises(adhesim.ScenarioError) as info:
        adhesim.run(scenario, **{"indenter.radius": -1.0})
    assert (info.value.key, info.value.value, info.value.requirement) == ("indenter.radius", "-1", "> 0")
    with pytest.raises(adhesim.ScenarioError, match="unknown key `grid.nn`") as info:
        adhesim.run(scenario, **{"grid.nn": 3})
    assert (info.value.key, info.value.kind) == ("grid.nn", "unknown_key")
    with pytest.raises(adhesim.ScenarioError, match="malformed TOML") as info:
        adhesim.run("[grid\nn = 3\n")
    assert (info.value.key, info.value.kind) == (None, "syntax")
    with pytest.raises(adhesim.ScenarioError, match=r"grid.n = \"many\"") as info:
        adhesim.run(scenario, **{"grid.n": "many"})
    assert (info.value.key, info.value.value, info.value.kind) == ("grid.n", '"many"', "invalid_value")
    # A sweep names the case and keeps the key.
    with pytest.raises(adhesim.ScenarioError, match=r"case 1 \(grid.n = -4\)") as info:
        adhesim.sweep(scenario, vary={"grid.n": [32, -4]})
    assert info.value.key == "grid.n"


BASE = {
    "grid": {"n": 16, "size": 0.25},
    "material": {"contact_modulus": 1.0},
    "adhesion": {"work_of_adhesion": 1e-5},
    "indenter": {"shape": "sphere", "radius": 1.0},
    "protocol": {"kind": "indent_pulloff", "max_depth": 2.0, "depth_unit": "jkr", "steps": 4},
}


@pytest.mark.parametrize(
    "overrides, kind, key, value, requirement",
    [
        ({"protocol.max_retract_steps": 0}, "invalid_value", "protocol.max_retract_steps", "0", ">= 1"),
        ({"protocol.steps": 0}, "invalid_value", "protocol.steps", "0", "in 1..=1000000"),
        ({"protocol.step": 0.5}, "invalid_value", "protocol.step", "0.5", "absent when protocol.steps is given"),
        ({"output.snapshot_steps": [2, -3]}, "invalid_value", "output.snapshot_steps", "-3", "steps >= 0"),
        ({"material.youngs_modulus": 2.0}, "invalid_value", "material.contact_modulus", "1",
         "absent when material.youngs_modulus or material.poisson_ratio is given"),
        ({"adhesion.law": "dugdale"}, "missing_key", "adhesion.cohesive_stress", None, 'with adhesion.law = "dugdale"'),
        ({"adhesion.range": 0.5}, "unknown_key", "adhesion.range", "0.5", 'absent with adhesion.law = "jkr"'),
        ({"analysis.tau0": 1.0}, "invalid_value", "protocol.kind", '"indent_pulloff"', '"roll" or "slide" with [analysis]'),
        ({"roughness.hurst": 0.8, "roughness.rms_height": 1e-4}, "missing_key", "roughness.seed", None,
         "for a random surface"),
        ({"roughness.hurst": 1.5, "roughness.rms_height": 1e-4, "roughness.seed": 1}, "invalid_value",
         "roughness.hurst", "1.5", "in (0, 1]"),
        ({"indenter.shape": "topography", "indenter.radius": None, "indenter.file": "no-such-map.npy",
          "indenter.spacing": 0.01}, "file", "indenter.file", "no-such-map.npy", "a height map file adhesim reads"),
    ],
)
def test_the_checks_of_each_key_reach_python_with_their_fields(overrides, kind, key, value, requirement):
    """Checks that reached Python as bare messages before (key None): each gives the key,
    the value as written, the requirement and the kind, and the message names the key."""
    scenario = {section: dict(keys) for section, keys in BASE.items()}
    for dotted, item in overrides.items():
        section, name = dotted.split(".")
        if item is None:
            del scenario[section][name]
        else:
            scenario.setdefault(section, {})[name] = item
    with pytest.raises(adhesim.ScenarioError) as info:
        adhesim.run(scenario)
    error = info.value
    assert (error.kind, error.key) == (kind, key), str(error)
    # A file's value is its path, joined to the folder relative paths resolve against.
    assert error.value == value or (value and error.value.endswith("/" + value)), (error.value, str(error))
    assert error.requirement is not None and error.requirement.startswith(requirement), (error.requirement, str(error))
    assert key.split(".")[-1] in str(error)


def test_a_sweep_pseudo_key_is_typed():
    with pytest.raises(adhesim.ScenarioError, match=r"alpha must be a finite number > 0, got -1") as info:
        adhesim.sweep(BASE, vary={"alpha": [-1.0]})
    assert (info.value.key, info.value.value, info.value.requirement) == ("alpha", "-1", "a finite number > 0")


def test_a_quantity_of_several_keys_gives_its_value_and_requirement_without_a_key():
    with pytest.raises(adhesim.ScenarioError, match=r"adhesion.work_of_adhesion = 1e-200") as info:
        adhesim.run(BASE, **{"adhesion.work_of_adhesion": 1e-200})
    assert info.value.key is None and info.value.value is not None and info.value.requirement is not None


@pytest.mark.parametrize(
    "tables, kind, key, value, requirement",
    [
        ({"random": {"seed": -1, "cases": 2, "grid.n": {"min": 8, "max": 16}}}, "invalid_value", "random.seed",
         "-1", "an integer >= 0"),
        ({"random": {"cases": 2, "grid.n": {"min": 8, "max": 16}}}, "missing_key", "random.seed", None,
         "with [random]"),
        ({"random": {"seed": 1, "cases": 0, "grid.n": {"min": 8, "max": 16}}}, "invalid_value", "random.cases",
         "0", "an integer >= 1"),
        ({"random": {"seed": 1, "cases": 2, "adhesion.work_of_adhesion": {"min": 0.2, "max": 0.1}}},
         "invalid_value", 'random."adhesion.work_of_adhesion".min', "0.2", "<= max (0.1)"),
        ({"random": {"seed": 1, "cases": 2, "grid.size": {"min": 0.0, "max": 1.0, "scale": "log"}}},
         "invalid_value", 'random."grid.size".min', "0", '> 0 with scale = "log"'),
        ({"random": {"seed": 1, "cases": 2, "grid.size": {"min": 0.1, "max": 1.0, "scale": "ln"}}},
         "invalid_value", 'random."grid.size".scale', '"ln"', '"log" or "linear"'),
        ({"vary": {"alpha": []}}, "invalid_value", "vary.alpha", "[]", "a non-empty list"),
        ({"zip": {"grid.n": [16, 32], "grid.size": [0.25]}}, "invalid_value", 'zip."grid.size"', "[0.25]",
         'a list of 2 values, as zip."grid.n"'),
        ({"vary": {"grid.n": [16]}, "zip": {"grid.n": [32]}}, "invalid_value", 'zip."grid.n"', "[32]",
         'given once in [set], [vary], [zip] and [random] (also vary."grid.n")'),
        ({"vary": {"alpha": [1.0]}, "derived": {"alpha": "indenter.radius"}}, "invalid_value", "derived.alpha",
         '"indenter.radius"', "one of indenter.amplitude"),
        ({"vary": {"alpha": [1.0]}, "derived": {"alpha": "indenter.wavelength"}}, "missing_key",
         "indenter.wavelength", None, "in the base scenario, for alpha"),
        ({"vary": {"alpah": [1.0]}}, "unknown_key", "alpah", None, "a dotted scenario key or one of"),
    ],
)
def test_the_checks_of_a_sweeps_own_tables_give_the_sweep_files_key(tables, kind, key, value, requirement, tmp_path):
    """The checks of the sweep's tables (seed, cases, ranges, lists, keys given twice, the
    [derived] alpha target) reached Python with key None before: each names the sweep
    file's key as a TOML dotted key, with the value and the requirement."""
    with pytest.raises(adhesim.ScenarioError) as info:
        adhesim.sweep(BASE, out=tmp_path / "out", **tables)
    error = info.value
    assert isinstance(error, ValueError)
    assert (error.kind, error.key, error.value) == (kind, key, value), str(error)
    assert error.requirement is not None and error.requirement.startswith(requirement), (error.requirement, str(error))
    assert not (tmp_path / "out").exists()


# Reliability, third pass (a probe of 2,923 hostile inputs; docs/reliability.md, "Third
# pass"): one test per cause of the Python entry points.


def test_a_checkpoint_interval_beyond_any_duration_names_the_argument(tmp_path):
    """checkpoint_every=1e300 panicked in Rust's Duration (any value from about 1.9e19 s)."""
    with pytest.raises(ValueError, match=r"checkpoint_every.*from 0 \(off\) to 1e9, got 1e300"):
        adhesim.sweep(BASE, vary={"grid.n": [16]}, out=tmp_path / "s", checkpoint_every=1e300)


def test_psd_bins_are_capped():
    """bins=4_000_000_000 asked for 96 GB and killed the interpreter."""
    heights = np.sin(np.arange(64.0)).reshape(8, 8)
    with pytest.raises(ValueError, match=r"bins must be an integer 1 … 1000000, got 4000000000"):
        adhesim.surface.psd(heights, 1.0, bins=4_000_000_000)
    assert len(adhesim.surface.psd(heights, 1.0, bins=10).q) > 0


def test_fifos_and_folders_are_refused_by_name(tmp_path):
    """read_topography and run on a FIFO blocked forever; the command line refused it. A
    missing scenario file is a FileNotFoundError (it was a ValueError)."""
    import os

    fifo = tmp_path / "map.npy"
    os.mkfifo(fifo)
    with pytest.raises(ValueError, match=r"path: .*map.npy is a FIFO \(named pipe\), not a regular file"):
        adhesim.read_topography(fifo, spacing=(1.0, 1.0), height_unit="m")
    scenario = tmp_path / "scenario.toml"
    os.mkfifo(scenario)
    with pytest.raises(ValueError, match=r"scenario: .*scenario.toml is a FIFO"):
        adhesim.run(scenario)
    with pytest.raises(ValueError, match=r"scenario: .* is a folder, not a regular file"):
        adhesim.run(tmp_path)
    with pytest.raises(FileNotFoundError, match=r"missing.toml does not exist"):
        adhesim.run(tmp_path / "missing.toml")
    with pytest.raises(FileNotFoundError, match=r"missing.npy does not exist"):
        adhesim.read_topography(tmp_path / "missing.npy", spacing=(1.0, 1.0), height_unit="m")


@pytest.mark.parametrize(
    "call, error, words",
    [
        (lambda: adhesim.Grid("32", 1.0), TypeError, ["n must be an integer, got str '32'"]),
        (lambda: adhesim.Grid(32, "1"), TypeError, ["size must be a number, got str '1'"]),
        (lambda: adhesim.Grid(2**64, 1.0), ValueError, ["n = 18446744073709551616 is out of range"]),
        (lambda: adhesim.Grid(8, 4, 1.0, "x"), TypeError, ["size_y must be a number, got str 'x'"]),
        (lambda: adhesim.Grid(n=8), TypeError, ["Grid needs size"]),
        (lambda: adhesim.Grid(8, 1.0, n=8), TypeError, ["Grid got n twice"]),
        (lambda: adhesim.Material("1"), TypeError, ["contact_modulus must be a number, got str '1'"]),
        (lambda: adhesim.Material(2**2000), ValueError, ["contact_modulus = ", "is out of range"]),
        (lambda: adhesim.Material.from_youngs_modulus(1.0, "x"), TypeError, ["poisson_ratio must be a number"]),
    ],
)
def test_grid_arguments_are_named(call, error, words):
    """Grid(*args) named no argument in its conversion errors ('str' object cannot be
    interpreted as an integer)."""
    with pytest.raises(error) as info:
        call()
    for word in words:
        assert word in str(info.value), str(info.value)


@pytest.mark.parametrize(
    "call, words",
    [
        (lambda: adhesim.geometry.sphere(adhesim.Grid(8, 1.0), "1"), ["radius must be a number, got str '1'"]),
        (lambda: adhesim.geometry.wavy_sphere(adhesim.Grid(8, 1.0), 1.0, "a", 0.1), ["amplitude must be a number"]),
        (lambda: adhesim.geometry.elliptic_punch(adhesim.Grid(8, 1.0), 0.5), ["semi_axes must be a pair of numbers"]),
        (lambda: adhesim.reference.jkr(1.0, 1.0, "x"), ["work_of_adhesion must be a number, got str 'x'"]),
        (lambda: adhesim.reference.jkr(1.0, 1.0, 1e-3, points="10"), ["points must be an integer, got str '10'"]),
        (lambda: adhesim.reference.hertz(1.0, 1.0, "x"), ["depth must be array_like of floats, got str 'x'"]),
        (lambda: adhesim.reference.flat_punch(True, 1.0), ["radius must be a number, got bool True"]),
        (lambda: adhesim.surface.self_affine(adhesim.Grid(8, 1.0), 0.8, seed="1", rms_height=1e-3), ["seed must be an integer"]),
        (lambda: adhesim.surface.psd(np.zeros((8, 8)), 1.0, "4"), ["bins must be an integer, got str '4'"]),
        (lambda: adhesim.surface.statistics(np.zeros((8, 8)), (1.0, "y")), ["spacing[1] must be a number, got str 'y'"]),
        (lambda: adhesim.surface.fill_invalid("x", np.ones((8, 8), bool)), ["heights must be array_like of floats"]),
        (lambda: adhesim.read_topography("missing.npy", spacing="x", height_unit="m"), ["spacing must be a number or a pair"]),
        (lambda: adhesim.sweep(BASE, vary={"grid.n": [16]}, out=None, checkpoint_every="x"), ["checkpoint_every must be a number"]),
    ],
)
def test_python_functions_name_the_argument_they_cannot_convert(call, words):
    """The pure-Python functions converted with float()/int(): 'could not convert string to
    float: 'x'' named no argument, and "1" was taken as 1.0."""
    with pytest.raises(TypeError) as info:
        call()
    for word in words:
        assert word in str(info.value), str(info.value)


@pytest.mark.parametrize(
    "call, error, words",
    [
        (lambda op, g: adhesim.HalfSpace("g", adhesim.Material(1.0)), TypeError, ["grid must be an adhesim.Grid, got str 'g'"]),
        (lambda op, g: adhesim.HalfSpace(g, 1.0), TypeError, ["material must be an adhesim.Material, got float 1.0"]),
        (lambda op, g: adhesim.ContactState(3), TypeError, ["grid must be an adhesim.Grid, got int 3"]),
        (lambda op, g: adhesim.Ccg(1.0), TypeError, ["operator must be an adhesim.HalfSpace, got float 1.0"]),
        (lambda op, g: adhesim.Ccg(op, tolerance="a"), TypeError, ["tolerance must be a number, got str 'a'"]),
        (lambda op, g: adhesim.Ccg(op, max_iterations=1.5), TypeError, ["max_iterations must be an integer, got float 1.5"]),
        (lambda op, g: adhesim.Ccg(op, max_iterations=2**70), ValueError, ["max_iterations = 1180591620717411303424 is out of range"]),
        (lambda op, g: adhesim.NestedActiveSet(op, relative_tolerance="x"), TypeError, ["relative_tolerance must be a number"]),
        (lambda op, g: adhesim.NestedActiveSet(op, coarsest="a"), TypeError, ["coarsest must be an integer, got str 'a'"]),
        (lambda op, g: adhesim.AdhesiveSolver(op, 1.0, attachment=3), TypeError, ["attachment must be a str, got int 3"]),
        (lambda op, g: adhesim.AdhesiveSolver(op, 1.0, preconditioned="yes"), TypeError, ["preconditioned must be True or False, got str 'yes'"]),
        (lambda op, g: adhesim.AdhesiveSolver(op, 1.0, worst_first_fraction="a"), TypeError, ["worst_first_fraction must be a number"]),
        (lambda op, g: adhesim.Ccg(op).solve(np.zeros((32, 32)), depth="a"), TypeError, ["depth must be a number, got str 'a'"]),
        (lambda op, g: adhesim.Ccg(op).solve(np.zeros((32, 32)), load="a"), TypeError, ["load must be a number, got str 'a'"]),
        (lambda op, g: adhesim.Ccg(op).solve(np.zeros((32, 32)), depth=0.1, state=3), TypeError, ["state must be an adhesim.ContactState or None, got int 3"]),
        (lambda op, g: adhesim.NestedActiveSet(op).solve(np.zeros((32, 32)), "a"), TypeError, ["depth must be a number, got str 'a'"]),
        (lambda op, g: adhesim.AdhesiveSolver(op, 1.0).step(np.zeros((32, 32)), "d", adhesim.ContactState(g)), TypeError, ["depth must be a number, got str 'd'"]),
        (lambda op, g: adhesim.AdhesiveSolver(op, 1.0).step(np.zeros((32, 32)), 0.1, None), TypeError, ["state must be an adhesim.ContactState, got NoneType None"]),
        (lambda op, g: adhesim.AdhesiveSolver(op, 1.0).energy(3), TypeError, ["state must be an adhesim.ContactState, got int 3"]),
        (lambda op, g: adhesim.Grid(8, 1.0, boundary=3), TypeError, ["boundary must be a str, got int 3"]),
        (lambda op, g: adhesim.ContactState(g).contact_radius(centre="ab"), TypeError, ["centre must be a pair of numbers, got str 'ab'"]),
        (lambda op, g: adhesim.ContactState(g).contact_radius(centre=(1.0,)), ValueError, ["centre must be a pair of numbers, got tuple (1.0,) of length 1"]),
        (lambda op, g: adhesim.ContactState(g).contact_radius(centre=(1.0, "b")), TypeError, ["centre[1] must be a number, got str 'b'"]),
        (lambda op, g: adhesim.Material.from_two_bodies((1.0, "a"), (1.0, 0.3)), TypeError, ["first[1] must be a number, got str 'a'"]),
        (lambda op, g: adhesim.reference.johnson_parameter("a", 1.0, 1.0, 1.0), TypeError, ["wavelength must be a number, got str 'a'"]),
    ],
)
def test_compiled_classes_name_the_argument_they_cannot_convert(operator, grid, call, error, words):
    """pyo3's own conversion errors said 'must be real number, not str' or ''str' object is
    not an instance of 'Grid'', naming neither the argument nor the value."""
    with pytest.raises(error) as info:
        call(operator, grid)
    for word in words:
        assert word in str(info.value), str(info.value)


def test_compiled_classes_still_take_what_they_took(operator, grid):
    """The named conversions accept numpy scalars and bools, None for optional arguments,
    keywords, and a numpy pair."""
    heights = np.zeros((32, 32))
    report = adhesim.Ccg(operator, tolerance=np.float32(1e-6), max_iterations=np.int64(500)).solve(
        heights, depth=np.float64(0.01), load=None, state=None
    )
    assert report.state.force > 0.0
    solver = adhesim.AdhesiveSolver(operator, 0.01, preconditioned=np.bool_(True), worst_first_fraction=None)
    solver.step(heights, 0.01, adhesim.ContactState(grid))
    assert adhesim.HalfSpace(grid=grid, material=adhesim.Material(1.0)).grid == grid
    assert adhesim.ContactState(grid).contact_radius(centre=np.array([0.0, 0.0])) == 0.0


def test_grid_takes_its_parameters_by_name():
    """Grid(n=, size=) and Grid(nx=, ny=, size_x=, size_y=), as the stubs say."""
    assert adhesim.Grid(n=8, size=1.0) == adhesim.Grid(8, 1.0)
    assert adhesim.Grid(nx=8, ny=4, size_x=1.0, size_y=0.5, boundary="periodic") == adhesim.Grid(
        8, 4, 1.0, 0.5, "periodic"
    )
    assert adhesim.Grid(8, size=1.0).n == 8


def test_sweep_progress_true_draws_a_bar_and_the_table_holds_numbers(tmp_path):
    """progress=True crashed after the first case ('bool' object is not callable), and
    .table held the cells' text where sweep_table gives floats."""
    pytest.importorskip("tqdm", reason="progress=True draws a tqdm bar")
    cases = adhesim.sweep(BASE, vary={"adhesion.work_of_adhesion": [1e-5, 2e-5]}, out=tmp_path / "s", progress=True)
    assert len(cases) == 2
    column = cases.table["max_adhesive_force"]
    assert column.dtype == np.float64
    assert list(column) == list(adhesim.sweep_table(list(cases), "results.max_adhesive_force")["results.max_adhesive_force"])
    with pytest.raises(TypeError, match=r"progress must be None, True or a callable"):
        adhesim.sweep(BASE, vary={"grid.n": [16]}, out=tmp_path / "t", progress="yes")


def test_closed_forms_refuse_what_they_cannot_compute(operator):
    """reference.jkr gave -inf or NaN for gamma = 1e300 and zeros for gamma = 0;
    AdhesiveSolver(op, 1e300) was accepted; contact_radius(centre=(nan, 0)) returned 0."""
    with pytest.raises(ValueError, match=r"leaves double precision.*work_of_adhesion = 1e300"):
        adhesim.reference.jkr(1.0, 1.0, 1e300)
    with pytest.raises(ValueError, match=r"work_of_adhesion = 0.0 gives no JKR contact radius"):
        adhesim.reference.jkr(1.0, 1.0, 0.0)
    # Given radii, gamma = 0 is Hertz's curve.
    assert adhesim.reference.jkr(1.0, 1.0, 0.0, contact_radius=[0.1])["force"][0] > 0.0
    with pytest.raises(ValueError, match=r"critical stress .* outside 1e-30..1e30"):
        adhesim.AdhesiveSolver(operator, 1e300)
    state = adhesim.ContactState(operator.grid)
    with pytest.raises(ValueError, match=r"centre must be a finite point \(x, y\), got \(NaN, 0"):
        state.contact_radius(centre=(float("nan"), 0.0))
    assert state.contact_radius() == 0.0


def test_fits_count_the_points_they_leave_out():
    """The fits dropped points (a <= 0; t, y <= 0) silently."""
    a = np.array([0.0, 0.1, 0.2, 0.3])
    force = 4 * a**3 / 3 - np.sqrt(8 * np.pi * 1e-3 * a**3)
    with pytest.warns(UserWarning, match=r"jkr_work_of_adhesion: 1 of 4 points left out \(contact_radius <= 0\)"):
        adhesim.fit.jkr_work_of_adhesion(a, force, 1.0, 1.0)
    with pytest.warns(UserWarning, match=r"power_law: 1 of 4 points left out"):
        adhesim.fit.power_law(np.array([0.0, 1.0, 2.0, 3.0]), np.array([1.0, 1.0, 2.0, 3.0]))


ADDRESS_SPACE_PROBE = """
import resource, sys
import adhesim
resource.setrlimit(resource.RLIMIT_AS, (2_000_000_000, 2_000_000_000))
scenario = {scenario!r}
for call in (
    lambda: adhesim.run(scenario, overrides={{"grid.n": 2500}}, allow_large=True),
    lambda: adhesim.sweep(scenario, vary={{"grid.n": [2500]}}, out=sys.argv[1], allow_large=True),
):
    try:
        call()
        print("ran")
    except ValueError as error:
        print("ValueError:", error)
"""


def test_allow_large_still_checks_the_address_space_limit(tmp_path):
    """allow_large=True lifted every memory check, so under an address-space limit
    (RLIMIT_AS, `ulimit -v`) a large run aborted the interpreter in an allocation. That
    limit is checked with it too, as `--allow-large` is on the command line."""
    import os
    import subprocess
    import sys

    env = {k: v for k, v in os.environ.items() if k != "ADHESIM_MEMORY_AVAILABLE"}
    probe = subprocess.run(
        [sys.executable, "-c", ADDRESS_SPACE_PROBE.format(scenario=BASE), str(tmp_path / "sweep")],
        capture_output=True, text=True, env=env, timeout=300,
    )
    assert probe.returncode == 0, probe.stderr
    lines = probe.stdout.splitlines()
    assert len(lines) == 2, probe.stdout
    for line in lines:
        assert line.startswith("ValueError:"), line
        assert "grid.n = 2500 needs about" in line and "RLIMIT_AS" in line, line
        assert "which allow_large=True does not lift" in line, line
