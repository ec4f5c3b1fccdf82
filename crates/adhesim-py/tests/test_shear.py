"""Friction at the interface through `adhesim.run` (docs/tangential.md): the same run
pipeline as the command line, so the shear columns and results arrive in Python."""

from pathlib import Path

import numpy as np

import adhesim

REPO = Path(__file__).resolve().parents[3]
SHEAR_TOML = REPO / "scenarios" / "shear.toml"


def test_a_shear_run_gives_stick_slip_columns_and_cattaneo_mindlin():
    # scenarios/shear.toml at a coarser grid (a = 20 elements): Cattaneo–Mindlin's
    # δ(Q) = δ*[1 − (1 − Q/μP)^(2/3)] within 3 % (the staircase edge at a/Δ = 20; the
    # command-line test holds 2 % at a = 40Δ), gross slip at the end of the stroke.
    result = adhesim.run(SHEAR_TOML, overrides={"grid.n": 64})
    curve = result.curve
    for name in ("n_stick", "n_slip", "area_front", "area_rear", "frictional_dissipation"):
        assert name in curve.columns, name
    shear = curve[curve["phase"] == "shear"]
    assert (shear["n_stick"] + shear["n_slip"] == shear["n_contact"]).all()
    mu, g, nu = 0.3, 1.0, 0.5
    p = float(shear["force_normal"].iloc[-1])
    a = float(np.sqrt(shear["area"].iloc[-1] / np.pi))
    full_slip = 3 * mu * p * (2 - nu) / (16 * g * a)
    partial = shear[shear["x"] < 0.9 * full_slip]
    ratio = partial["force_tangential"] / (mu * p)
    expected = full_slip * (1 - (1 - ratio) ** (2 / 3))
    assert np.all(np.abs(partial["x"] / expected - 1) < 0.03)
    results = result.summary["results"]
    assert int(shear["n_stick"].iloc[-1]) == 0
    assert results["sliding_friction_force"] is not None
    assert abs(results["mean_shear_stress"] * results["contact_area"] / results["sliding_friction_force"] - 1) < 1e-12


def test_a_glued_adhesive_contact_shrinks_under_shear_with_mode_mixity():
    # scenarios/friction/adhesive_shear.toml (a0 = 36 elements): glued, mode mixity 1.
    # The stuck contact's stiffness is Mindlin's 8G*a within 1 % (the command-line test's
    # bound), and the contact loses area at the end of the stroke as Savkoor & Briggs'
    # balance says, 1 − (a/a0)² = 0.0970, within 20 % (the local rule loses 1.13× the
    # balance's area at 36 elements, 1.055× at 144, docs/validation.md §17.1).
    result = adhesim.run(REPO / "scenarios" / "friction" / "adhesive_shear.toml")
    curve = result.curve
    shear = curve[curve["phase"] == "shear"]
    rest = float(curve[curve["phase"] == "approach"]["area"].iloc[-1])
    assert (shear["n_slip"] == 0).all()
    a = np.sqrt(shear["area"] / np.pi)
    stiffness = shear["force_tangential"] / (8 * (2 / 3) * a * shear["x"])
    assert np.all(np.abs(stiffness - 1) < 0.01)
    lost = 1 - float(shear["area"].iloc[-1]) / rest
    assert abs(lost / 0.0970 - 1) < 0.2, lost
    assert result.summary["results"]["contact_area_reduction"] < 1


def test_a_glued_adhesive_contact_at_constant_load_holds_its_force_and_shrinks_more():
    # The same run with protocol.normal_control = "force": the normal force of the end of
    # the approach is held at every shift step (1e-6 of it; the control's tolerance is
    # 1e-8), the indenter rises as the contact shrinks, and the contact loses more area
    # than at the held depth (19.2 % against 10.8 %, docs/tangential.md).
    scenario = REPO / "scenarios" / "friction" / "adhesive_shear.toml"
    result = adhesim.run(scenario, overrides={"protocol.normal_control": "force"})
    curve = result.curve
    shear = curve[curve["phase"] == "shear"]
    approach = curve[curve["phase"] == "approach"]
    load, rest = float(approach["force_normal"].iloc[-1]), float(approach["area"].iloc[-1])
    assert np.all(np.abs(shear["force_normal"] - load) <= 1e-6 * abs(load))
    assert np.all(np.diff(shear["d"]) <= 0)
    lost = 1 - float(shear["area"].iloc[-1]) / rest
    assert lost > 0.15, lost


def test_a_compliant_drive_saws_and_reads_back_with_its_kinds(tmp_path):
    # scenarios/friction/stick_slip.toml on 64² (a = 20 elements), the drive's stroke cut to
    # 0.036: the spring's balance F = k(X − δ) holds at every shift step (1e-9, the
    # solver's stretch against the tractions' sum), the force falls in slip events, and a
    # run read back by load() has the run's columns with the run's dtypes, bit for bit.
    stiffness = 0.5
    overrides = {"grid.n": 64, "protocol.distance": 0.036, "protocol.steps": 36}
    result = adhesim.run(REPO / "scenarios" / "friction" / "stick_slip.toml", out=tmp_path, overrides=overrides)
    arrays = result.curve_arrays
    shear = arrays["phase"] == "shear"
    force, stretch = arrays["force_tangential"][shear], (arrays["drive_x"] - arrays["x"])[shear]
    assert np.all(np.abs(force - stiffness * stretch) <= 1e-9 * np.abs(force).max())
    assert result.summary["results"]["slip_events"] >= 2
    assert np.any(np.diff(force) < 0)
    loaded = adhesim.load(tmp_path)
    for name, values in arrays.items():
        assert loaded.curve_arrays[name].dtype == values.dtype, name
        assert np.array_equal(loaded.curve_arrays[name], values), name


def test_a_slide_with_friction_adds_tau0_times_area_to_the_boundary_force():
    # scenarios/friction/slide_shear_strength.toml on 64² (a ≈ 10 elements), 20 steps of
    # 0.6Δ out: the same run pipeline as the command line gives the friction columns and
    # results of a translation with [friction]; once the whole contact slides, F_T/A is
    # τ0 up to the boundary force of the smooth sphere's lattice pinning (2 %: a per-step
    # boundary force of a JKR edge on a coarse grid).
    overrides = {"grid.n": 64, "protocol.steps": 20, "protocol.return_stroke": False}
    result = adhesim.run(REPO / "scenarios" / "friction" / "slide_shear_strength.toml", overrides=overrides)
    curve = result.curve
    moving = curve[curve["phase"] == "slide"]
    sliding = moving[moving["n_stick"] == 0]
    assert len(sliding) >= 10
    assert np.all(np.abs(sliding["force_tangential"] / sliding["area"] / 0.05 - 1) < 0.02)
    results = result.summary["results"]
    assert results["frictional_dissipation"] > 0 and results["measured_q"] is None
    assert abs(results["interface_friction_force"] / (0.05 * results["real_contact_area"]) - 1) < 0.01


def test_an_imposed_tangential_force_is_met_and_follows_cattaneo_mindlin():
    # scenarios/friction/fretting_force.toml on 64² (a = 20 elements), the forward stroke to
    # Q* = 0.75μP and one cycle: every shift step carries its imposed force to 1e-8 of μP
    # (the search's tolerance), and the loading shift follows Cattaneo–Mindlin within 3 %
    # (the staircase edge at a/Δ = 20, as the displacement-controlled test above).
    toml = REPO / "scenarios" / "friction" / "fretting_force.toml"
    result = adhesim.run(toml, overrides={"grid.n": 64, "protocol.cycles": 1, "protocol.steps": 6})
    shear = result.curve[result.curve["phase"] == "shear"]
    assert len(shear) == 6 * 5
    mu, g, nu = 0.3, 1.0, 0.5
    p = float(shear["force_normal"].iloc[-1])
    a = float(np.sqrt(shear["area"].iloc[-1] / np.pi))
    levels = [k / 6 for k in range(1, 7)] + [1 - k / 6 for k in range(1, 13)] + [-1 + k / 6 for k in range(1, 13)]
    imposed = 0.75 * mu * p * np.array(levels)
    assert np.all(np.abs(shear["force_tangential"].to_numpy() - imposed) <= 1e-8 * mu * p)
    loading = shear.iloc[:6]
    ratio = loading["force_tangential"] / (mu * p)
    full_slip = 3 * mu * p * (2 - nu) / (16 * g * a)
    expected = full_slip * (1 - (1 - ratio) ** (2 / 3))
    assert np.all(np.abs(loading["x"] / expected - 1) < 0.03)
