//! Paper Sect. 5.1 / Fig. 12: which end-to-middle ratio of a quadratic work of adhesion
//! along the major axis of a flat elliptic punch (a = 2b) moves the start of detachment
//! from the ends of the major axis to the ends of the minor axis (the paper: "at least
//! 13"), and which one splits the contact into two patches before it is lost ("at least
//! 20"). The punch of `scenarios/fig12_*.toml` (a = 1, b = 0.5, L = 2.4, E* = 1,
//! γ0 = 1e-4 in the middle) is pressed in by 0.005 and pulled off in steps of 2e-4, at
//! n = 64, 128 and 256 (b = 13, 27 and 53 elements).
//!
//! `cargo run --release -p adhesim --example fig12_thresholds`
//!
//! Prints one row per (n, ratio): where the first released elements lie (`minor`: all
//! within |x| < 0.5a, `major`: all within |x| > 0.75a, `mixed` otherwise) and the largest
//! number of separate contact patches during the pull-off.

use adhesim::analysis::contact::DetachmentWatch;
use adhesim::{
    AdhesiveParams, AdhesiveSolver, Axis, Boundary, ElasticMaterial, EllipticPunch, FreeOperator, Grid, IndentPulloff,
    NormalSolver, Problem, Profile, WorkOfAdhesion,
};

const SEMI_AXES: (f64, f64) = (1.0, 0.5);

fn run(n: usize, ratio: f64) -> Result<DetachmentWatch, String> {
    let grid = Grid::new(n, 2.4, Boundary::Free).map_err(|e| e.to_string())?;
    let operator = FreeOperator::new(grid, ElasticMaterial::new(1.0).map_err(|e| e.to_string())?);
    let heights = EllipticPunch::new(SEMI_AXES, 0.0)
        .map_err(|e| e.to_string())?
        .heights(&grid);
    let field = WorkOfAdhesion::Quadratic {
        middle: 1e-4,
        ratio_end_to_middle: ratio,
        half_length: SEMI_AXES.0,
        axis: Axis::X,
    };
    let gamma = field.on_grid(&grid).map_err(|e| e.to_string())?;
    let mut solver = NormalSolver::Adhesive(Box::new(AdhesiveSolver::new(
        grid,
        1.0,
        gamma,
        AdhesiveParams::default(),
    )));
    let protocol = IndentPulloff {
        start_depth: 0.0,
        max_depth: 0.005,
        depth_step: 2e-4,
        max_retract_steps: 100_000,
        jump_force_threshold: 0.0,
    };
    let mut watch = DetachmentWatch::new(grid);
    let mut problem = Problem::new(Box::new(operator), heights).expect("a valid problem");
    protocol
        .run(&mut problem, &mut solver, &mut watch)
        .map_err(|e| e.to_string())?;
    Ok(watch)
}

fn main() -> Result<(), String> {
    println!("n,ratio,first_detachment,first_detached_elements,most_patches");
    for n in [64, 128, 256] {
        for ratio in [
            1.0, 1.5, 1.8, 2.2, 2.5, 3.0, 4.0, 8.0, 13.0, 16.0, 18.0, 19.0, 20.0, 21.0, 22.0, 24.0,
        ] {
            let watch = run(n, ratio)?;
            let first = watch.first_detached.unwrap_or_default();
            let a = SEMI_AXES.0;
            let place = if first.is_empty() {
                "none"
            } else if first.iter().all(|&(x, _)| x.abs() < 0.5 * a) {
                "minor"
            } else if first.iter().all(|&(x, _)| x.abs() > 0.75 * a) {
                "major"
            } else {
                "mixed"
            };
            println!("{n},{ratio},{place},{},{}", first.len(), watch.most_patches);
        }
    }
    Ok(())
}
