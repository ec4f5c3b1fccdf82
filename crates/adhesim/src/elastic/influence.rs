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
///
/// K(ξ,η) = [Φ(ξ+s,η+s) − Φ(ξ+s,η−s) − Φ(ξ−s,η+s) + Φ(ξ−s,η−s)] / (πE*),  s = Δ/2.
///
/// K(0,0) = 4 ln(1+√2)·Δ/(πE*); far away K → Δ²/(πE* r) (Boussinesq).
pub fn love_coefficient(xi: f64, eta: f64, element_size: f64, contact_modulus: f64) -> f64 {
    let s = 0.5 * element_size;
    (love_primitive(xi + s, eta + s) - love_primitive(xi + s, eta - s) - love_primitive(xi - s, eta + s)
        + love_primitive(xi - s, eta - s))
        / (std::f64::consts::PI * contact_modulus)
}

/// K(0,0)·E*/Δ = 4 ln(1+√2)/π: the dimensionless self-compliance of a square element.
pub const SELF_COMPLIANCE_FACTOR: f64 = 1.1221997046783603;

/// ∫∫ f over the square [−side/2, side/2]², composite 8-point Gauss–Legendre on
/// divisions² sub-squares (test helper).
#[cfg(test)]
pub(crate) fn square_quadrature(side: f64, divisions: usize, f: impl Fn(f64, f64) -> f64) -> f64 {
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
    let h = side / divisions as f64;
    let mut sum = 0.0;
    for a in 0..divisions {
        for b in 0..divisions {
            let cx = -0.5 * side + (a as f64 + 0.5) * h;
            let cy = -0.5 * side + (b as f64 + 0.5) * h;
            for (i, &ni) in NODES.iter().enumerate() {
                for si in [-1.0, 1.0] {
                    for (j, &nj) in NODES.iter().enumerate() {
                        for sj in [-1.0, 1.0] {
                            let (x, y) = (cx + 0.5 * si * ni * h, cy + 0.5 * sj * nj * h);
                            sum += WEIGHTS[i] * WEIGHTS[j] * 0.25 * h * h * f(x, y);
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
}
