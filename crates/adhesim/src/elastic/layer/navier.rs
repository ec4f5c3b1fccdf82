//! A test reference: the surface response of a layer on a rigid base to a traction wave,
//! by integrating Navier's equations across the layer, independently of the closed forms
//! of `layer` and `layer_shear`.

use super::LayerBase;

/// The surface traction wave: a pressure p cos(kx), or a shear traction q sin(kx) along x.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Load {
    Pressure,
    Shear,
}

/// [U(0), W(0)] of the plane-strain layer (G = k = 1, z into the layer) under a unit
/// `load`, with u_x = −U(z) sin kx and u_z = W(z) cos kx:
///   G U'' − (λ + 2G) k² U + (λ + G) k W' = 0,   (λ + 2G) W'' − G k² W − (λ + G) k U' = 0,
/// σ_zz = λ(W' − kU) + 2G W', σ_xz ∝ U' + kW. Shooting from the base (bonded: U = W = 0;
/// frictionless: W = 0, U' = 0) with RK4 in `steps` steps, then at the surface
/// σ_zz(0) = −1, σ_xz(0) = 0 (pressure) or σ_zz(0) = 0, σ_xz(0) = 1 (shear). A shear
/// traction sin(kx) along +x moves the surface by −U(0) sin(kx) along x.
pub(crate) fn surface_displacement(kt: f64, poisson_ratio: f64, base: LayerBase, steps: usize, load: Load) -> [f64; 2] {
    let lambda = 2.0 * poisson_ratio / (1.0 - 2.0 * poisson_ratio);
    let derivative = |y: [f64; 4]| -> [f64; 4] {
        let [u, du, w, dw] = y;
        [
            du,
            (lambda + 2.0) * u - (lambda + 1.0) * dw,
            dw,
            (w + (lambda + 1.0) * du) / (lambda + 2.0),
        ]
    };
    let integrate = |mut y: [f64; 4]| -> [f64; 4] {
        let h = -kt / steps as f64;
        let add =
            |a: [f64; 4], b: [f64; 4], s: f64| [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2], a[3] + s * b[3]];
        for _ in 0..steps {
            let k1 = derivative(y);
            let k2 = derivative(add(y, k1, 0.5 * h));
            let k3 = derivative(add(y, k2, 0.5 * h));
            let k4 = derivative(add(y, k3, h));
            for i in 0..4 {
                y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
        }
        y
    };
    let (first, second) = match base {
        LayerBase::Bonded => ([0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]),
        LayerBase::Frictionless => ([1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]),
    };
    let (a, b) = (integrate(first), integrate(second));
    let normal = |y: [f64; 4]| lambda * (y[3] - y[0]) + 2.0 * y[3];
    let shear = |y: [f64; 4]| y[1] + y[2];
    // α·normal(a) + β·normal(b) = σ_zz, α·shear(a) + β·shear(b) = σ_xz.
    let (target_normal, target_shear) = match load {
        Load::Pressure => (-1.0, 0.0),
        Load::Shear => (0.0, 1.0),
    };
    let det = normal(a) * shear(b) - normal(b) * shear(a);
    let alpha = (target_normal * shear(b) - target_shear * normal(b)) / det;
    let beta = (normal(a) * target_shear - shear(a) * target_normal) / det;
    [alpha * a[0] + beta * b[0], alpha * a[2] + beta * b[2]]
}
