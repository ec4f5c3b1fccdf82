//! The axisymmetric contact of a frictionless rigid indenter with an elastic layer on a rigid
//! base, solved as a Fredholm integral equation of the second kind: a reference that shares
//! nothing with the boundary elements but the layer's Fourier factor f(kt).
//!
//! The surface pressure is written through its Hankel transform,
//! p̃(k) = ∫₀^∞ p(r) J₀(kr) r dr = ∫₀^a φ(s) cos(ks) ds, so that the load is
//! P = 2π p̃(0) = 2π ∫₀^a φ ds and, on the half-space, w(r) = (2/E*) ∫₀^r φ(s)/√(r² − s²) ds
//! inside the contact (Sneddon's Abel representation). On the layer the surface
//! displacement is (2/E*) ∫₀^∞ f(kt) p̃(k) J₀(kr) dk; writing f = 1 − (1 − f) and inverting
//! the Abel operator turns w = δ − r²/(2R) on r < a into
//!
//!     φ(x) − (1/π) ∫₀^a φ(y) [M(x − y) + M(x + y)] dy = (E*/π)(δ − x²/R),
//!     M(u) = ∫₀^∞ (1 − f(kt)) cos(ku) dk,
//!
//! (the layer equations of Johnson & Sridhar 1994 and of Hayes, Keer, Herrmann & Mockros
//! 1972 in this notation). The pressure near the edge is φ(a)/√(2a(a − r)), so the stress
//! intensity is K = φ(a)√(π/a) and the energy release rate G = πφ(a)²/(2aE*) (the near field
//! is the half-space's at distances ≪ t). M is smooth (1 − f decays as e^{−2kt}), so φ is
//! smooth and Nyström's method on Gauss–Legendre nodes converges exponentially.

use adhesim::elastic::layer_compliance_factor;
use adhesim::LayerBase;
use std::f64::consts::PI;

/// n Gauss–Legendre nodes and weights on [lo, hi] (Newton on P_n from Chebyshev guesses).
pub(super) fn gauss_legendre(n: usize, lo: f64, hi: f64) -> Vec<(f64, f64)> {
    let (mid, half) = (0.5 * (hi + lo), 0.5 * (hi - lo));
    (0..n)
        .map(|i| {
            let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut derivative = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    (p0, p1) = (p1, p2);
                }
                derivative = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let step = p1 / derivative;
                x -= step;
                if step.abs() < 1e-16 {
                    break;
                }
            }
            (mid - half * x, half * 2.0 / ((1.0 - x * x) * derivative * derivative))
        })
        .collect()
}

/// A layer of thickness t (or the half-space, t = ∞) of contact modulus E*.
pub(super) struct AxisymmetricLayer {
    thickness: f64,
    contact_modulus: f64,
    /// (s, weight·(1 − f(s))) on s = kt ∈ [0, 20]: 1 − f < 1e-14 beyond for both bases and
    /// every ν (it decays as 2(2s² + (1 + κ²)/2)e^{−2s}/κ on a bonded base, κ = 3 − 4ν,
    /// largest at ν = 1/2: 7.1e-15 at s = 20; as 2(2s + 1)e^{−2s} on a frictionless one).
    excess: Vec<(f64, f64)>,
}

/// The two unit solutions at one contact radius a: per unit depth (the flat punch) and for
/// the sphere's shape at δ = 0.
#[derive(Clone, Copy, Debug)]
pub(super) struct Solution {
    pub radius: f64,
    pub contact_modulus: f64,
    /// Load of the flat punch per unit depth: the stiffness 1/C(a).
    pub punch_load: f64,
    /// φ(a) of the flat punch per unit depth.
    pub punch_edge: f64,
    /// Load and φ(a) of the sphere's term −(E*/π)x²/R (δ = 0).
    pub sphere_load: f64,
    pub sphere_edge: f64,
}

impl Solution {
    /// C(a) = δ/P of the flat punch.
    pub fn compliance(&self) -> f64 {
        1.0 / self.punch_load
    }
    /// The non-adhesive sphere at contact radius a: (depth δ_H', load P_H') with φ(a) = 0.
    pub fn hertzian(&self) -> (f64, f64) {
        self.with_edge(0.0)
    }
    /// The sphere at contact radius a with G = w at the edge (φ(a) < 0, tension):
    /// (depth, load).
    pub fn adhesive(&self, work_of_adhesion: f64) -> (f64, f64) {
        self.with_edge(-(2.0 * self.radius * self.contact_modulus * work_of_adhesion / PI).sqrt())
    }
    fn with_edge(&self, edge: f64) -> (f64, f64) {
        let depth = (edge - self.sphere_edge) / self.punch_edge;
        (depth, depth * self.punch_load + self.sphere_load)
    }
}

impl AxisymmetricLayer {
    /// A bonded or frictionless layer; `thickness = f64::INFINITY` is the half-space.
    pub fn new(thickness: f64, poisson_ratio: f64, base: LayerBase, contact_modulus: f64) -> Self {
        let mut excess = Vec::new();
        if thickness.is_finite() {
            let panel = 0.1;
            let rule = gauss_legendre(8, 0.0, panel);
            for j in 0..200 {
                for &(s, weight) in &rule {
                    let s = s + j as f64 * panel;
                    excess.push((s, weight * (1.0 - layer_compliance_factor(s, poisson_ratio, base))));
                }
            }
        }
        Self {
            thickness,
            contact_modulus,
            excess,
        }
    }

    /// M(u) = ∫₀^∞ (1 − f(kt)) cos(ku) dk = (1/t) ∫₀^∞ (1 − f(s)) cos(su/t) ds.
    fn kernel(&self, u: f64) -> f64 {
        let scaled = u / self.thickness;
        self.excess.iter().map(|&(s, w)| w * (s * scaled).cos()).sum::<f64>() / self.thickness
    }

    /// The two unit solutions at contact radius a for a sphere of radius R, on `nodes`
    /// Gauss–Legendre points.
    pub fn solve(&self, radius: f64, sphere_radius: f64, nodes: usize) -> Solution {
        let rule = gauss_legendre(nodes, 0.0, radius);
        let kernel_row = |x: f64| -> Vec<f64> {
            rule.iter()
                .map(|&(y, w)| w * (self.kernel(x - y) + self.kernel(x + y)) / PI)
                .collect()
        };
        let rows: Vec<Vec<f64>> = rule.iter().map(|&(x, _)| kernel_row(x)).collect();
        let scale = self.contact_modulus / PI;
        let punch_rhs = vec![scale; nodes];
        let sphere_rhs: Vec<f64> = rule.iter().map(|&(x, _)| -scale * x * x / sphere_radius).collect();
        let punch = solve_second_kind(&rows, &punch_rhs);
        let sphere = solve_second_kind(&rows, &sphere_rhs);
        // Nyström's interpolation to the edge x = a.
        let edge_row = kernel_row(radius);
        let edge = |phi: &[f64], rhs: f64| rhs + edge_row.iter().zip(phi).map(|(k, p)| k * p).sum::<f64>();
        let load = |phi: &[f64]| 2.0 * PI * rule.iter().zip(phi).map(|(&(_, w), p)| w * p).sum::<f64>();
        Solution {
            radius,
            contact_modulus: self.contact_modulus,
            punch_load: load(&punch),
            punch_edge: edge(&punch, scale),
            sphere_load: load(&sphere),
            sphere_edge: edge(&sphere, -scale * radius * radius / sphere_radius),
        }
    }
}

/// Solves (I − K)φ = b.
fn solve_second_kind(kernel: &[Vec<f64>], rhs: &[f64]) -> Vec<f64> {
    let matrix: Vec<Vec<f64>> = kernel
        .iter()
        .enumerate()
        .map(|(i, row)| {
            let mut row: Vec<f64> = row.iter().map(|k| -k).collect();
            row[i] += 1.0;
            row
        })
        .collect();
    solve_linear(&matrix, rhs)
}

/// Solves A x = b by Gaussian elimination with partial pivoting.
pub(super) fn solve_linear(matrix: &[Vec<f64>], rhs: &[f64]) -> Vec<f64> {
    let n = rhs.len();
    let mut matrix: Vec<Vec<f64>> = matrix
        .iter()
        .zip(rhs)
        .map(|(row, &b)| row.iter().copied().chain([b]).collect())
        .collect();
    for column in 0..n {
        let pivot = (column..n)
            .max_by(|&a, &b| matrix[a][column].abs().total_cmp(&matrix[b][column].abs()))
            .unwrap();
        matrix.swap(column, pivot);
        let (upper, lower) = matrix.split_at_mut(column + 1);
        let pivot_row = &upper[column];
        for row in lower.iter_mut() {
            let factor = row[column] / pivot_row[column];
            for (value, pivot) in row[column..].iter_mut().zip(&pivot_row[column..]) {
                *value -= factor * pivot;
            }
        }
    }
    let mut solution = vec![0.0; n];
    for row in (0..n).rev() {
        let tail: f64 = (row + 1..n).map(|k| matrix[row][k] * solution[k]).sum();
        solution[row] = (matrix[row][n] - tail) / matrix[row][row];
    }
    solution
}
