//! Love's influence coefficient of a uniformly loaded square element.
//!
//! Love, A. E. H. (1929), *Phil. Trans. R. Soc. A* 228, 377–420: the normal surface
//! displacement of an elastic half-space under unit uniform pressure on a rectangle.

/// Φ(X, Y) = X·asinh(Y/|X|) + Y·asinh(X/|Y|), each term taken as zero when its prefactor
/// vanishes. This form of Love's primitive has no cancellation for negative arguments.
///
/// Bitwise, Φ(−X, Y) = Φ(X, −Y) = −Φ(X, Y) (asinh is odd by `copysign`, and a sum of
/// negated terms is the negated sum) and Φ(Y, X) = Φ(X, Y) (the two terms commute): the free
/// operator uses this to evaluate Love's coefficients on one octant.
#[inline]
pub(crate) fn love_primitive(x: f64, y: f64) -> f64 {
    let mut value = 0.0;
    if x != 0.0 {
        value += x * (y / x.abs()).asinh();
    }
    if y != 0.0 {
        value += y * (x / y.abs()).asinh();
    }
    value
}

/// Surface displacement at offset (ξ, η) from the centre of a square element of side
/// `element_size` carrying unit uniform pressure, on a half-space of contact modulus E*:
/// [`love_rectangle`] with Δx = Δy = Δ (the same operations, so the same bits).
///
/// K(0,0) = 4 ln(1+√2)·Δ/(πE*); far away K → Δ²/(πE* r) (Boussinesq).
pub fn love_coefficient(xi: f64, eta: f64, element_size: f64, contact_modulus: f64) -> f64 {
    love_rectangle(xi, eta, element_size, element_size, contact_modulus)
}

/// Surface displacement at offset (ξ, η) from the centre of a Δx × Δy rectangular element
/// carrying unit uniform pressure, on a half-space of contact modulus E* (Love 1929):
///
/// K(ξ,η) = [Φ(ξ+a,η+b) − Φ(ξ+a,η−b) − Φ(ξ−a,η+b) + Φ(ξ−a,η−b)] / (πE*),  a = Δx/2, b = Δy/2.
///
/// K(0,0) = 4[a·asinh(b/a) + b·asinh(a/b)]/(πE*); far away K → ΔxΔy/(πE* r) (Boussinesq).
pub fn love_rectangle(xi: f64, eta: f64, element_x: f64, element_y: f64, contact_modulus: f64) -> f64 {
    let (a, b) = (0.5 * element_x, 0.5 * element_y);
    (love_primitive(xi + a, eta + b) - love_primitive(xi + a, eta - b) - love_primitive(xi - a, eta + b)
        + love_primitive(xi - a, eta - b))
        / (std::f64::consts::PI * contact_modulus)
}

/// K(0,0)·E*/Δ = 4 ln(1+√2)/π: the dimensionless self-compliance of a square element.
pub const SELF_COMPLIANCE_FACTOR: f64 = 1.1221997046783603;

/// ∫∫ f over the square [−side/2, side/2]², composite 8-point Gauss–Legendre on
/// divisions² sub-squares (test helper).
#[cfg(test)]
pub(crate) fn square_quadrature(side: f64, divisions: usize, f: impl Fn(f64, f64) -> f64) -> f64 {
    rectangle_quadrature(side, side, divisions, f)
}

/// ∫∫ f over the rectangle [−wx/2, wx/2] × [−wy/2, wy/2], composite 8-point
/// Gauss–Legendre on divisions² sub-rectangles (test helper).
#[cfg(test)]
pub(crate) fn rectangle_quadrature(wx: f64, wy: f64, divisions: usize, f: impl Fn(f64, f64) -> f64) -> f64 {
    const NODES: [f64; 4] = [
        0.183_434_642_495_649_8,
        0.525_532_409_916_329,
        0.796_666_477_413_626_7,
        0.960_289_856_497_536_3,
    ];
    const WEIGHTS: [f64; 4] = [
        0.362_683_783_378_362,
        0.313_706_645_877_887_3,
        0.222_381_034_453_374_5,
        0.101_228_536_290_376_3,
    ];
    let (hx, hy) = (wx / divisions as f64, wy / divisions as f64);
    let mut sum = 0.0;
    for a in 0..divisions {
        for b in 0..divisions {
            let cx = -0.5 * wx + (a as f64 + 0.5) * hx;
            let cy = -0.5 * wy + (b as f64 + 0.5) * hy;
            for (i, &ni) in NODES.iter().enumerate() {
                for si in [-1.0, 1.0] {
                    for (j, &nj) in NODES.iter().enumerate() {
                        for sj in [-1.0, 1.0] {
                            let (x, y) = (cx + 0.5 * si * ni * hx, cy + 0.5 * sj * nj * hy);
                            sum += WEIGHTS[i] * WEIGHTS[j] * 0.25 * hx * hy * f(x, y);
                        }
                    }
                }
            }
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫∫ over the unit-pressure element of 1/(πE*|r − r′|): an independent check of the
    /// closed form away from the element.
    fn quadrature(xi: f64, eta: f64, element_size: f64) -> f64 {
        square_quadrature(element_size, 16, |x, y| {
            1.0 / ((xi - x).powi(2) + (eta - y).powi(2)).sqrt()
        }) / std::f64::consts::PI
    }

    #[test]
    fn centre_value_is_the_closed_form() {
        let value = love_coefficient(0.0, 0.0, 2.0, 3.0);
        let expected = 4.0 * (1.0 + 2f64.sqrt()).ln() * 2.0 / (std::f64::consts::PI * 3.0);
        assert!((value / expected - 1.0).abs() < 1e-14);
        assert!((SELF_COMPLIANCE_FACTOR - 4.0 * (1.0 + 2f64.sqrt()).ln() / std::f64::consts::PI).abs() < 1e-15);
    }

    #[test]
    fn matches_quadrature_at_neighbours() {
        // Smooth integrand for |offset| >= Δ; composite Gauss converges to ~1e-12.
        for &(xi, eta) in &[(1.0, 0.0), (1.0, 1.0), (2.0, -3.0), (-5.0, 0.5)] {
            let closed = love_coefficient(xi, eta, 1.0, 1.0);
            let numeric = quadrature(xi, eta, 1.0);
            assert!(
                (closed / numeric - 1.0).abs() < 1e-10,
                "({xi},{eta}): {closed} vs {numeric}"
            );
        }
    }

    #[test]
    fn far_field_is_boussinesq() {
        // K = Δ²/(πE*r)·(1 + O(Δ²/r²)): relative difference ≈ 4e-6 at r = 100Δ.
        let r = 100.0;
        let ratio = love_coefficient(r, 0.0, 1.0, 1.0) / (1.0 / (std::f64::consts::PI * r));
        assert!((ratio - 1.0).abs() < 1e-5 && (ratio - 1.0).abs() > 1e-7, "{ratio}");
        // symmetric in both arguments and under exchange
        assert_eq!(
            love_coefficient(3.0, 2.0, 1.0, 1.0),
            love_coefficient(-3.0, 2.0, 1.0, 1.0)
        );
        assert!((love_coefficient(3.0, 2.0, 1.0, 1.0) - love_coefficient(2.0, 3.0, 1.0, 1.0)).abs() < 1e-16);
    }

    #[test]
    fn rectangle_matches_its_closed_form_and_quadrature() {
        // Centre: K(0,0) = 4[a·asinh(b/a) + b·asinh(a/b)]/(πE*), a = Δx/2, b = Δy/2.
        let (wx, wy, modulus): (f64, f64, f64) = (0.5, 2.0, 1.5);
        let (a, b) = (0.5 * wx, 0.5 * wy);
        let centre = 4.0 * (a * (b / a).asinh() + b * (a / b).asinh()) / (std::f64::consts::PI * modulus);
        assert!((love_rectangle(0.0, 0.0, wx, wy, modulus) / centre - 1.0).abs() < 1e-14);
        // Away from the element the integrand is smooth: composite Gauss to ~1e-10.
        for &(xi, eta) in &[(0.5, 0.0), (0.0, 2.0), (1.0, -4.0), (-2.5, 3.0)] {
            let closed = love_rectangle(xi, eta, wx, wy, modulus);
            let numeric = rectangle_quadrature(wx, wy, 16, |x, y| 1.0 / ((xi - x).powi(2) + (eta - y).powi(2)).sqrt())
                / (std::f64::consts::PI * modulus);
            assert!(
                (closed / numeric - 1.0).abs() < 1e-10,
                "({xi},{eta}): {closed} vs {numeric}"
            );
        }
        // Boussinesq far away: ΔxΔy/(πE*r)(1 + O(Δ²/r²)), 1e-4 at r = 100·max(Δx, Δy).
        let r = 200.0;
        let ratio = love_rectangle(0.0, r, wx, wy, modulus) / (wx * wy / (std::f64::consts::PI * modulus * r));
        assert!((ratio - 1.0).abs() < 1e-4, "{ratio}");
        // Exchanging the element's sides exchanges the offsets.
        let swapped = love_rectangle(2.0, 1.0, wy, wx, modulus);
        assert!((love_rectangle(1.0, 2.0, wx, wy, modulus) - swapped).abs() < 1e-15);
    }
}
