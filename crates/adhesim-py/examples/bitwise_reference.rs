//! The pytest set-ups computed through the Rust API directly, printed at full precision
//! (shortest round-trip floats and FNV-1a hashes of the fields' bits), so that
//! `tests/test_bitwise.py` can check that the Python objects give the same bits.
//!
//! `cargo run --release -p adhesim-py --example bitwise_reference`
use adhesim::analysis::reference::Jkr;
use adhesim::{
    AdhesiveParams, AdhesiveSolver, Boundary, Ccg, CcgParams, ContactState, Control, ElasticMaterial, Grid, HalfSpace,
    NestedActiveSet, NestedParams, Profile, Sphere,
};

/// FNV-1a over the bit patterns of the values, row-major.
fn field_hash(values: &[f64]) -> u64 {
    values.iter().fold(0xcbf2_9ce4_8422_2325, |hash, value| {
        (hash ^ value.to_bits()).wrapping_mul(0x0100_0000_01b3)
    })
}

fn main() {
    // Hertz, free grid n = 128, a = 32 elements (tests/test_hertz.py)
    let grid = Grid::new(128, 1.0, Boundary::Free).expect("grid");
    let material = ElasticMaterial::new(1.0).expect("modulus");
    let mut operator = HalfSpace::new(grid, material);
    let heights = Sphere::new(1.0).expect("radius").heights(&grid);
    let a = 32.0 * grid.dx();
    let depth = a * a;
    let mut state = ContactState::new(&grid);
    let report = NestedActiveSet::new(grid, material, NestedParams::default())
        .solve(&mut operator, &heights, depth, &mut state)
        .expect("nested solve");
    println!("nested_force {:?}", report.force);
    println!("nested_pressure {:016x}", field_hash(&state.pressure));
    let mut state = ContactState::new(&grid);
    let report = Ccg::new(CcgParams::default())
        .solve(&mut operator, &heights, Control::Displacement(depth), &mut state)
        .expect("ccg solve");
    println!("ccg_force {:?}", report.force);
    println!("ccg_pressure {:016x}", field_hash(&state.pressure));

    // JKR cycle at a_JKR/Δ = 8 as IndentPulloff steps it (tests/test_jkr.py)
    let a_jkr: f64 = 0.05;
    let gamma = a_jkr.powi(3) * 8.0 / (9.0 * std::f64::consts::PI);
    let jkr = Jkr {
        radius: 1.0,
        contact_modulus: 1.0,
        work_of_adhesion: gamma,
    };
    let delta = a_jkr / 8.0;
    let d_jkr = jkr.critical_depth().abs();
    let reach = jkr.radius_at_depth(2.0 * d_jkr).expect("in contact");
    let n = ((2.3 * reach / delta).ceil() as usize).max(16);
    let n = n + n % 2;
    let grid = Grid::new(n, n as f64 * delta, Boundary::Free).expect("grid");
    let mut operator = HalfSpace::new(grid, material);
    let heights = Sphere::new(1.0).expect("radius").heights(&grid);
    let mut solver = AdhesiveSolver::new(grid, 1.0, vec![gamma; grid.len()], AdhesiveParams::default());
    let mut state = ContactState::new(&grid);
    let (step, max_depth) = (d_jkr / 40.0, 2.0 * d_jkr);
    let mut forces = Vec::new();
    for i in 1..=(max_depth / step).ceil() as usize {
        let depth = (i as f64 * step).min(max_depth);
        forces.push(
            solver
                .step(&mut operator, &heights, depth, &mut state)
                .expect("step")
                .force,
        );
    }
    let mut depth = max_depth;
    loop {
        depth -= step;
        forces.push(
            solver
                .step(&mut operator, &heights, depth, &mut state)
                .expect("step")
                .force,
        );
        if state.contact_elements() == 0 {
            break;
        }
    }
    println!("jkr_n {n}");
    println!("jkr_forces {:016x}", field_hash(&forces));
    println!("jkr_last_depth {depth:?}");
}
