//! Cerruti's influence coefficients of a uniformly sheared rectangular element.
//!
//! A tangential point force Q_x at the origin of an elastic half-space (shear modulus G,
//! Poisson's ratio ν) moves the surface by (Johnson, *Contact Mechanics*, 1985, §3.2)
//!
//! u_x = Q_x/(2πG)·[(1 − ν)/r + ν x²/r³],  u_y = Q_x/(2πG)·ν xy/r³,
//!
//! and by a normal displacement (1 − 2ν)x/r² that Goodman's approximation leaves out (it
//! vanishes at ν = 1/2). Integrated over a Δx × Δy element with the primitives
//! ∫∫ 1/r = s·asinh(t/|s|) + t·asinh(s/|t|) (Love 1929), ∫∫ s²/r³ = t·asinh(s/|t|),
//! ∫∫ t²/r³ = s·asinh(t/|s|) and ∫∫ st/r³ = −r (docs/physics.md §8.1), each taken over the
//! element's four corners.

use super::influence::love_primitive;

/// A half-space's constants for tangential loads: shear modulus G and Poisson's ratio ν.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShearMaterial {
    /// Shear modulus G.
    pub shear_modulus: f64,
    /// Poisson's ratio ν in (−1, 1/2].
    pub poisson_ratio: f64,
}

impl ShearMaterial {
    /// G = E*(1 − ν)/2 from the contact modulus E* = 2G/(1 − ν) and ν.
    pub fn from_contact_modulus(contact_modulus: f64, poisson_ratio: f64) -> Self {
        Self {
            shear_modulus: 0.5 * contact_modulus * (1.0 - poisson_ratio),
            poisson_ratio,
        }
    }

    /// Mindlin's no-slip stiffness factor G* = G/(2 − ν): a stuck circle of radius a has
    /// the tangential stiffness 8G*a.
    ///
    /// # Example
    /// ```
    /// use adhesim::ShearMaterial;
    ///
    /// // Rubber: E* = 4, ν = 1/2 gives G = 1 and G* = 2/3; a stuck circle of radius a = 0.1
    /// // has the tangential stiffness 8G*a.
    /// let rubber = ShearMaterial::from_contact_modulus(4.0, 0.5);
    /// assert_eq!(rubber.shear_modulus, 1.0);
    /// assert!((8.0 * rubber.mindlin_modulus() * 0.1 - 0.5333333333333333).abs() < 1e-15);
    /// ```
    pub fn mindlin_modulus(&self) -> f64 {
        self.shear_modulus / (2.0 - self.poisson_ratio)
    }
}

/// The three coefficients of a Δx × Δy element carrying unit uniform shear traction, seen
/// at offset (ξ, η) from its centre: u_x = K_xx q_x + K_xy q_y, u_y = K_xy q_x + K_yy q_y.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CerrutiCoefficients {
    /// u_x per unit q_x.
    pub xx: f64,
    /// u_x per unit q_y (= u_y per unit q_x).
    pub xy: f64,
    /// u_y per unit q_y.
    pub yy: f64,
}

/// The t·asinh(s/|t|) part of Love's primitive (∫∫ s²/r³); zero at t = 0.
fn primitive_along(s: f64, t: f64) -> f64 {
    if t == 0.0 {
        0.0
    } else {
        t * (s / t.abs()).asinh()
    }
}

/// Sum over the four corners (ξ ± a, η ± b) of `primitive`, with the signs of ∫∫ over the
/// element: + at (+a, +b) and (−a, −b), − at the other two.
fn corners(xi: f64, eta: f64, a: f64, b: f64, primitive: impl Fn(f64, f64) -> f64) -> f64 {
    primitive(xi + a, eta + b) - primitive(xi + a, eta - b) - primitive(xi - a, eta + b) + primitive(xi - a, eta - b)
}

/// Cerruti's coefficients (see the module) of a Δx × Δy element at offset (ξ, η).
///
/// K_xx(0,0) = (2 − ν)·Δ·asinh(1)/(πG) on a square; far away K_xx → ΔxΔy/(2πG)·[(1 − ν)/r
/// + νξ²/r³]. At ν = 0 K_xx = K_yy equals Love's normal coefficient with E* = 2G.
pub fn cerruti_rectangle(
    xi: f64,
    eta: f64,
    element_x: f64,
    element_y: f64,
    material: ShearMaterial,
) -> CerrutiCoefficients {
    let (a, b) = (0.5 * element_x, 0.5 * element_y);
    let nu = material.poisson_ratio;
    let scale = 1.0 / (2.0 * std::f64::consts::PI * material.shear_modulus);
    let love = corners(xi, eta, a, b, love_primitive);
    let along_x = corners(xi, eta, a, b, primitive_along);
    let along_y = love - along_x;
    let cross = corners(xi, eta, a, b, |s, t| -s.hypot(t));
    CerrutiCoefficients {
        xx: scale * ((1.0 - nu) * along_y + along_x),
        xy: scale * nu * cross,
        yy: scale * (along_y + (1.0 - nu) * along_x),
    }
}

#[cfg(test)]
mod tests {
    use super::super::influence::{love_rectangle, rectangle_quadrature};
    use super::*;
    use std::f64::consts::PI;

    const RUBBER: ShearMaterial = ShearMaterial {
        shear_modulus: 1.0,
        poisson_ratio: 0.5,
    };

    /// Cerruti's point-force kernels (u_x/Q_x, u_x/Q_y, u_y/Q_y) at (x, y).
    fn point(x: f64, y: f64, material: ShearMaterial) -> [f64; 3] {
        let (g, nu) = (material.shear_modulus, material.poisson_ratio);
        let r = x.hypot(y);
        let scale = 1.0 / (2.0 * PI * g);
        [
            scale * ((1.0 - nu) / r + nu * x * x / r.powi(3)),
            scale * nu * x * y / r.powi(3),
            scale * ((1.0 - nu) / r + nu * y * y / r.powi(3)),
        ]
    }

    #[test]
    fn matches_quadrature_of_the_point_force_near_the_element() {
        // The integrand is smooth for offsets of one element or more: composite
        // Gauss–Legendre converges to ~1e-10 there.
        let material = ShearMaterial {
            shear_modulus: 0.7,
            poisson_ratio: 0.3,
        };
        let (wx, wy) = (1.0, 0.6);
        for &(xi, eta) in &[(1.0, 0.0), (0.0, 1.0), (1.5, -2.0), (-3.0, 0.7), (2.0, 2.0)] {
            let closed = cerruti_rectangle(xi, eta, wx, wy, material);
            for (component, value) in [closed.xx, closed.xy, closed.yy].into_iter().enumerate() {
                let numeric = rectangle_quadrature(wx, wy, 16, |x, y| point(xi - x, eta - y, material)[component]);
                assert!(
                    (value - numeric).abs() < 1e-10 * numeric.abs().max(1e-3),
                    "({xi},{eta}) component {component}: {value} vs {numeric}"
                );
            }
        }
    }

    #[test]
    fn far_field_is_cerruti_and_centre_is_closed_form() {
        // Far away the element acts as a point force ΔxΔy: relative error O((Δ/r)²), 1e-4
        // at r = 100Δ.
        let r = 100.0;
        for &(x, y) in &[(r, 0.0), (0.6 * r, 0.8 * r)] {
            let closed = cerruti_rectangle(x, y, 1.0, 1.0, RUBBER);
            let far = point(x, y, RUBBER);
            assert!((closed.xx / far[0] - 1.0).abs() < 1e-4, "{} vs {}", closed.xx, far[0]);
            assert!((closed.yy / far[2] - 1.0).abs() < 1e-4);
            if y != 0.0 {
                assert!((closed.xy / far[1] - 1.0).abs() < 1e-4);
            } else {
                assert_eq!(closed.xy, 0.0);
            }
        }
        // Centre of a square: (2 − ν)Δ·asinh(1)/(πG), no cross term.
        let centre = cerruti_rectangle(0.0, 0.0, 2.0, 2.0, RUBBER);
        let expected = 1.5 * 2.0 * 1f64.asinh() / PI;
        assert!((centre.xx / expected - 1.0).abs() < 1e-14);
        assert!((centre.yy / expected - 1.0).abs() < 1e-14);
        assert_eq!(centre.xy, 0.0);
    }

    #[test]
    fn at_zero_poisson_ratio_both_are_love_with_twice_the_shear_modulus() {
        let material = ShearMaterial {
            shear_modulus: 1.3,
            poisson_ratio: 0.0,
        };
        for &(xi, eta) in &[(0.0, 0.0), (1.0, 0.0), (2.0, -3.0)] {
            let c = cerruti_rectangle(xi, eta, 1.0, 1.0, material);
            let love = love_rectangle(xi, eta, 1.0, 1.0, 2.0 * 1.3);
            assert!((c.xx / love - 1.0).abs() < 1e-13);
            assert!((c.yy / love - 1.0).abs() < 1e-13);
            assert_eq!(c.xy, 0.0);
        }
        // Symmetries: K_xx even in ξ and η, K_xy odd in each; exchanging axes swaps xx, yy.
        let (p, m) = (
            cerruti_rectangle(1.5, 2.5, 1.0, 1.0, RUBBER),
            cerruti_rectangle(-1.5, 2.5, 1.0, 1.0, RUBBER),
        );
        assert!((p.xx - m.xx).abs() < 1e-15 && (p.xy + m.xy).abs() < 1e-15);
        let swapped = cerruti_rectangle(2.5, 1.5, 1.0, 1.0, RUBBER);
        assert!((p.xx - swapped.yy).abs() < 1e-15 && (p.xy - swapped.xy).abs() < 1e-15);
    }
}
