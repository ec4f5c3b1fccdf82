//! Parameters, options and per-step report of the adhesive solver, and the local
//! detachment criterion σ_c (docs/physics.md §2.2).

use std::num::NonZeroUsize;

/// c_U = [2 ln(1+√2) − (2/3)(√2 − 1)]/π: elastic energy U = c_U σ²Δ³/E* stored by one
/// square element under uniform tension σ (mean displacement; docs/physics.md §2.2).
pub const ELEMENT_ENERGY_FACTOR: f64 = 0.473_201_004_409_338_54;

/// Critical tensile stress of the local mesh-dependent detachment criterion,
/// σ_c = √(E*γ/(c_U Δ)) (Pohrt & Popov 2015, *FU Mech. Eng.* 13(1), 3–10): an element is
/// released once the elastic energy it stores pays for its new free surface γΔ².
///
/// # Example
/// ```
/// use adhesim::solver::critical_stress;
///
/// // σ_c = √(E*γ/(c_U Δ)) ≈ 1.4537·√(E*γ/Δ) (docs/physics.md §2.2).
/// let sigma = critical_stress(4.0, 1e-3, 0.01);
/// assert!((sigma / (4.0f64 * 1e-3 / 0.01).sqrt() - 1.453708).abs() < 1e-6);
/// ```
pub fn critical_stress(contact_modulus: f64, work_of_adhesion: f64, element_size: f64) -> f64 {
    (contact_modulus * work_of_adhesion / (ELEMENT_ENERGY_FACTOR * element_size)).sqrt()
}

/// The element size Δ that [`critical_stress`] takes for a grid of Δx × Δy elements: Δx
/// itself on square elements, and on rectangles the side Δ_e of the square element that
/// stores the same elastic energy per area under uniform tension σ. Love's element of
/// sides A × B stores U = I σ²/(2πE*) with the double area integral of 1/|r − r′|
///
/// I = 2[A²B·asinh(B/A) + AB²·asinh(A/B)] + (2/3)[A³ + B³ − (A² + B²)^{3/2}],
///
/// which is 2π c_U Δ³ for A = B = Δ; U = γAB then gives σ_c = √(E*γ/(c_U Δ_e)) with
/// Δ_e = I/(2π c_U AB) (docs/physics.md §2.2).
pub fn detachment_element_size(element_x: f64, element_y: f64) -> f64 {
    if element_x == element_y {
        return element_x;
    }
    let (a, b) = (element_x, element_y);
    let integral = 2.0 * (a * a * b * (b / a).asinh() + a * b * b * (a / b).asinh())
        + 2.0 / 3.0 * (a.powi(3) + b.powi(3) - (a * a + b * b).powf(1.5));
    integral / (std::f64::consts::TAU * ELEMENT_ENERGY_FACTOR * a * b)
}

/// Over-stress ratio −p/σ_c of an element in contact: > 1 exactly when it violates
/// p < −σ_c. An element without adhesion (σ_c = 0, γ = 0) detaches under any tension, so
/// its ratio is +∞ for p < 0 and 0 otherwise (never NaN): such elements are violators
/// ahead of every finite ratio (docs/physics.md §2.2).
pub fn over_stress_ratio(pressure: f64, critical_stress: f64) -> f64 {
    if critical_stress > 0.0 {
        -pressure / critical_stress
    } else if pressure < 0.0 {
        f64::INFINITY
    } else {
        0.0
    }
}

/// How new contact is formed (docs/physics.md §2.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Attachment {
    /// Penetrating elements attach, and every free edge-neighbour of the contact (every
    /// free element within [`AdhesiveParams::trial_ring_layers`] steps of it) is
    /// tentatively attached; those that cannot hold (p < −σ_c) are released and banned for
    /// the rest of the step: the discrete Griffith closure test with the same σ_c.
    #[default]
    Trial,
    /// Only penetrating elements (g < 0) attach: a non-adhesive approach (strong
    /// artificial hysteresis), kept for comparison.
    PenetrationOnly,
}

/// Which over-stressed elements are released per round.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Detachment {
    /// All elements with p < −σ_c at once (the standard choice).
    #[default]
    AllViolators,
    /// Only those within `fraction` of the largest over-stress ratio −p/σ_c (path studies).
    WorstFirst {
        /// Relative band below the largest ratio, e.g. 0.01.
        fraction: f64,
    },
    /// A random half of the violators (at least the worst one) per round, drawn from
    /// `seed`: a deliberately different release order, the independent oracle of the
    /// order-independence argument (docs/fast-step.md). Solves are fully converged.
    RandomHalf {
        /// Seed of the xorshift generator.
        seed: u64,
    },
}

/// Grids with at least this many elements use predicted-subset growth under
/// [`PredictedGrowth::Auto`] (512²).
pub const PREDICTION_MIN_ELEMENTS: usize = 512 * 512;

/// When the adhesive step grows trial rings through predicted subsets (docs/fast-step.md §3).
/// Default `Auto`: with the tie guard of docs/fast-step.md §3 (a predicted subset is accepted
/// only if certainly stable) the contact sets equal the exact peel's on every equivalence
/// case (n ≤ 128, prediction forced on) and in the Fig. 1 cycle at n = 256 (75 and 150
/// steps) and N = 512. The one difference seen since (N = 512 with the replay window capped
/// at 64) is a tie of docs/fast-step.md §2 met on a set the exact peel also visits: exact
/// up to ties, as the certified fast rule itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PredictedGrowth {
    /// Never: every ring is peeled exactly.
    Off,
    /// Always (where it applies).
    On,
    /// On grids of at least [`PREDICTION_MIN_ELEMENTS`] elements, where it pays in wall
    /// time on 2 cores (Fig. 1 cycle, docs/history.md §2026-11-23: threads, and predicted
    /// growth on by default from 512² (commit 66838ca)): at 512², 153.6 s instead of 171.8 s;
    /// at 256², 22 % fewer FFT pairs but the same CPU time and 8–12 % more wall time (the
    /// replays run on one thread); at 128², 15–25 % more CPU (the patchy Fig. 2 contact at
    /// h = 0.006: about 3× the wall time).
    #[default]
    Auto,
}

/// Parameters of [`AdhesiveSolver`](super::AdhesiveSolver).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdhesiveParams {
    /// CG stops when ‖r‖_C ≤ this·‖d − z‖_C (default 1e-6; the front criterion below is
    /// the one the contact set depends on: 1e-9 gives the same contact sets at every step
    /// with 35 % more CG iterations, see docs/history.md §2026-11-23: the adhesive step,
    /// first round (tolerances, single precision)) ...
    pub relative_tolerance: f64,
    /// ... and max|r_i| ≤ this·K(0,0)·σ_c,min (default 1e-4): the stress error at the front
    /// must be far below σ_c or the contact set flickers.
    pub front_tolerance: f64,
    /// CG iteration limit per solve (default 5 000).
    pub max_cg_iterations: usize,
    /// Limit on solve/attach/detach rounds per displacement step (default 100 000).
    pub max_rounds: usize,
    /// Attachment rule.
    pub attachment: Attachment,
    /// Detachment rule.
    pub detachment: Detachment,
    /// Precondition the fixed-set CG with the |q| spectral preconditioner (default true).
    pub preconditioned: bool,
    /// Keep the bans of the previous step while the depth keeps decreasing (default true).
    /// On a fixed set p(d) = p₀ + d·p₁ with p₁ ≥ 0 (the positive equilibrium pressure of
    /// a flat punch of that shape), so at a smaller depth every trial element would be
    /// more tensile than when it failed: re-testing it is futile. This removes the trial
    /// cascade from quiet retraction steps; the tests check it leaves curves unchanged.
    pub carry_bans_when_retracting: bool,
    /// Once the contact has grown within a step, every element banned so far in the step
    /// is tried again (default true). Under continuous loading an element that failed its
    /// closure test is re-tested as soon as the contact around it changes; keeping it
    /// banned for the rest of a finite step makes the contact lag behind by a step-size
    /// dependent amount (γ1 on Fig. 1 at N = 128: 1.115, 1.167, 1.192, 1.206 for 75, 150,
    /// 300, 600 approach steps without retries, 1.219, 1.218, 1.217 with them). Bans are
    /// lifted only when the contact is larger than at every earlier retry of the step, so
    /// the step still ends.
    pub retry_after_growth: bool,
    /// The rule before certified early stops (default false): every fixed-set solve converges
    /// fully before its release decisions. Otherwise a solve whose release decisions are
    /// certified (docs/fast-step.md) stops early; contact sets are the same, the reference mode
    /// is kept to show it.
    pub reference_rule: bool,
    /// Predicted-subset growth on the approach (docs/fast-step.md §3): after the solve with
    /// a full trial ring, attach only the members a local replay of the peel predicts to
    /// hold. Same contact sets, fewer solves; never in the reference rule, the other
    /// release orders, or on periodic grids. Default [`PredictedGrowth::Auto`]: the product
    /// (`adhesim run`, sweeps, studies, Python) and the benchmarks use the same rule.
    pub predicted_growth: PredictedGrowth,
    /// How many layers of free elements around the contact one trial ring holds (default 1,
    /// the paper's rule and the reference for every result). Trial elements are the free,
    /// unbanned, adhesive elements whose grid distance to the contact is at most this many
    /// edge-neighbour steps ([`Grid::for_each_neighbour`](crate::Grid::for_each_neighbour),
    /// wrapping on periodic grids; the path may cross any element). 2 attaches the whole
    /// two-element neighbourhood per ring: a growing front needs fewer rings (17–36 % fewer
    /// on the Fig. 1 cycle) but more solves per ring. It is a different closure rule: the
    /// inner layer is tested with the outer one attached (F2 of docs/fast-step.md raises
    /// its pressures), so the approach branch changes (γ1 up by 3–5 % on the Fig. 1 cycle;
    /// BENCHMARKS.md §What did not pay, two layers per trial ring). Kept for that measurement;
    /// predicted-subset growth is used with 1 only. `NonZeroUsize`: a ring of 0 layers
    /// would attach nothing.
    pub trial_ring_layers: NonZeroUsize,
    /// Test aid (default false): after every certified early stop, converge the solve
    /// fully on a copy and panic if a pressure moved by more than the certified bound or a
    /// release decision changed. Costs a full solve per early stop.
    pub check_certificates: bool,
    /// Run each fixed-set CG on the contact's bounding box on a free half-space (default
    /// true; the module `window` of the adhesive solver): the same matrix K_CC, transforms
    /// of twice the box's side instead of twice the grid's while the box is at most 0.8 of
    /// the grid's side, and one application of the solve's pressure change on the whole
    /// grid for the displacement outside it. False runs every CG on the whole grid.
    pub contact_window: bool,
}

impl Default for AdhesiveParams {
    fn default() -> Self {
        Self {
            relative_tolerance: 1e-6,
            front_tolerance: 1e-4,
            max_cg_iterations: 5_000,
            max_rounds: 100_000,
            attachment: Attachment::Trial,
            detachment: Detachment::AllViolators,
            preconditioned: true,
            carry_bans_when_retracting: true,
            retry_after_growth: true,
            reference_rule: false,
            predicted_growth: PredictedGrowth::Auto,
            trial_ring_layers: NonZeroUsize::MIN,
            check_certificates: false,
            contact_window: true,
        }
    }
}

/// What one quasi-static step did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct StepReport {
    /// Fixed-set solves (rounds of the step loop).
    pub solves: usize,
    /// CG iterations over all solves.
    pub cg_iterations: usize,
    /// Elastic operator applications (FFT pairs).
    pub operator_applications: u64,
    /// Of those, the applications on contact windows (`AdhesiveParams::contact_window`:
    /// DC-FFT pairs of twice a window's side).
    #[cfg_attr(feature = "serde", serde(default))]
    pub window_applications: u64,
    /// Applications of the CG's spectral preconditioner: FFT pairs of the solved grid's own
    /// size (the whole grid, a window or a nested level), not counted in
    /// `operator_applications`.
    #[cfg_attr(feature = "serde", serde(default))]
    pub preconditioner_applications: u64,
    /// Attachment rounds: how often the step attached candidates (a trial ring, penetrating
    /// elements, or both) and went on to solve; a growing front needs one per ring.
    pub attachment_rounds: usize,
    /// Elements in C at the end that were not at the start.
    pub attached: usize,
    /// Elements in C at the start that are not at the end.
    pub detached: usize,
    /// Normal force Δ²Σp after the first solve with the previous contact set.
    pub force_before_change: f64,
    /// Normal force at the end of the step.
    pub force: f64,
    /// Energy Π = ½Δ²Σp·u − Δ²Σ_C γ after the first solve with the previous set.
    pub energy_before_change: f64,
    /// Π at the end of the step.
    pub energy: f64,
    /// Energy released by the configuration change of this step, Π_before − Π_end. Real
    /// instabilities make it positive; on a lattice a closure that passes the σ_c test can
    /// raise Π slightly (lattice trapping), so it is not clamped: the sum over a cycle then
    /// equals ∮F dd exactly.
    pub dissipated_energy: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn element_energy_factor_is_the_closed_form() {
        let sqrt2 = 2f64.sqrt();
        let expected = (2.0 * (1.0 + sqrt2).ln() - 2.0 / 3.0 * (sqrt2 - 1.0)) / std::f64::consts::PI;
        assert!((ELEMENT_ENERGY_FACTOR - expected).abs() < 1e-15, "{expected}");
        // σ_c = 1.453708·√(E*γ/Δ) (docs/physics.md §2.2)
        assert!((critical_stress(1.0, 1.0, 1.0) - 1.453_708).abs() < 1e-6);
    }

    /// The [likely] constant c_U checked independently: U = ½σΔ²·w̄ with w̄ the mean of
    /// Love's coefficient over the element itself, by 2-D Gauss–Legendre quadrature of the
    /// (continuous, log-kinked) coefficient; 1e-5 covers the quadrature error at the kink.
    #[test]
    fn element_energy_factor_from_love_coefficient() {
        use crate::elastic::influence::{love_coefficient, square_quadrature};
        let mean = square_quadrature(1.0, 32, |x, y| love_coefficient(x, y, 1.0, 1.0));
        assert!(
            (0.5 * mean / ELEMENT_ENERGY_FACTOR - 1.0).abs() < 1e-5,
            "{}",
            0.5 * mean
        );
    }

    #[test]
    fn rectangular_elements_store_the_energy_of_their_quadrature() {
        use crate::elastic::influence::{love_rectangle, rectangle_quadrature};
        // U/σ² = (1/2)∫∫K over the element; with Δ_e: c_U Δ_e³·(AB/Δ_e²)/E* = c_U Δ_e AB/E*.
        // Composite Gauss on the log-singular integrand converges to ~1e-6 at 32² cells.
        for (a, b) in [(1.0, 2.0), (0.3, 0.1), (1.0, 1.0 + 1e-9)] {
            let energy = 0.5 * rectangle_quadrature(a, b, 32, |x, y| love_rectangle(x, y, a, b, 1.0));
            let size = detachment_element_size(a, b);
            let expected = ELEMENT_ENERGY_FACTOR * size * a * b;
            assert!(
                (energy / expected - 1.0).abs() < 1e-5,
                "{a}×{b}: {energy} vs {expected}"
            );
        }
        // Continuous at the square and exact there.
        assert!((detachment_element_size(1.0, 1.0 + 1e-9) - 1.0).abs() < 1e-8);
        assert_eq!(detachment_element_size(0.25, 0.25), 0.25);
    }
}
