//! The Bessel functions the layer's kernel tables integrate against (J₀, J₁(x)/x and J₂),
//! each its power series below x = 13 and Hankel's asymptotic expansion above
//! (Abramowitz & Stegun 1964, 9.1.10 and 9.2.5), and their evaluation on a whole row of
//! quadrature nodes at once.
//!
//! A table entry sums thousands of them at one radius ([`super::layer`]'s `PointCorrection`).
//! One power series is a chain of dependent divisions, so one evaluation at a time waits on
//! each division's latency; [`Bessel::fill`] runs the series of [`LANES`] arguments side by
//! side, each with exactly the operations of `Bessel::at` in the same order, so that the
//! tables keep their bits.

use std::f64::consts::PI;

/// Arguments whose power series run side by side in [`Bessel::fill`].
const LANES: usize = 8;
/// Below it the power series (largest term ≈ 4e3 at 13, rounding ≈ 1e-12), above it
/// Hankel's expansion (its smallest term ≈ e^{−2x} < 1e-11).
const SERIES_LIMIT: f64 = 13.0;
/// A series ends at the first term at or below it.
const SERIES_END: f64 = 1e-18;
/// Hankel's expansion is cut after at most this many terms.
const HANKEL_TERMS: u32 = 64;

/// A Bessel function of a layer's table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Bessel {
    /// J₀(x).
    J0,
    /// J₁(x)/x, even and smooth at 0.
    J1OverX,
    /// J₂(x).
    J2,
}

impl Bessel {
    /// n of the series' recurrence a_{m+1} = −a_m (x/2)²/((m + 1)(m + 1 + n)).
    fn order(self) -> f64 {
        match self {
            Self::J0 => 0.0,
            Self::J1OverX => 1.0,
            Self::J2 => 2.0,
        }
    }

    /// The series' first term a₀ at x ≥ 0.
    fn first(self, x: f64) -> f64 {
        match self {
            Self::J0 => 1.0,
            Self::J1OverX => 0.5,
            Self::J2 => 0.125 * x * x,
        }
    }

    /// μ = 4n² of Hankel's expansion.
    fn hankel_mu(self) -> f64 {
        match self {
            Self::J0 => 0.0,
            Self::J1OverX => 4.0,
            Self::J2 => 16.0,
        }
    }

    /// The function at x ≥ 13 from the sums (P, Q) of Hankel's expansion at x, at the phase
    /// x − (n/2 + 1/4)π.
    fn far(self, x: f64, (p, q): (f64, f64)) -> f64 {
        let phase = match self {
            Self::J0 => x - 0.25 * PI,
            Self::J1OverX => x - 0.75 * PI,
            Self::J2 => x - 1.25 * PI,
        };
        let value = (2.0 / (PI * x)).sqrt() * (p * phase.cos() - q * phase.sin());
        match self {
            Self::J1OverX => value / x,
            Self::J0 | Self::J2 => value,
        }
    }

    /// The function at x (each is even), one at a time: the reference that [`Self::fill`]
    /// is tested against.
    #[cfg(test)]
    pub(super) fn at(self, x: f64) -> f64 {
        let x = x.abs();
        if x < SERIES_LIMIT {
            return bessel_power_series(x, self.order(), self.first(x));
        }
        self.far(x, hankel_sums(self.hankel_mu(), x))
    }

    /// `values[i]` = `Self::at``(nodes[i] * scale)`, bit for bit: the power series and
    /// Hankel's expansions of [`LANES`] arguments advance together, each lane stopping where
    /// its own sum stops.
    pub(super) fn fill(self, nodes: &[f64], scale: f64, values: &mut [f64]) {
        assert_eq!(nodes.len(), values.len(), "one value per node");
        for (chunk, out) in nodes.chunks(LANES).zip(values.chunks_mut(LANES)) {
            let mut arguments = [0.0f64; LANES];
            let mut series = [false; LANES];
            for (lane, &node) in chunk.iter().enumerate() {
                arguments[lane] = (node * scale).abs();
                series[lane] = arguments[lane] < SERIES_LIMIT;
            }
            let live = chunk.len();
            let sums = self.series_lanes(&arguments, &series);
            let far = std::array::from_fn(|lane| lane < live && !series[lane]);
            let hankel = hankel_lanes(self.hankel_mu(), &arguments, &far);
            for (lane, value) in out.iter_mut().enumerate() {
                let x = arguments[lane];
                *value = if series[lane] {
                    sums[lane]
                } else {
                    self.far(x, hankel[lane])
                };
            }
        }
    }

    /// The power series (those of `Self::at`) of the lanes marked in `series`, side by
    /// side; a lane off the series holds a zero term, which never passes the series' test.
    fn series_lanes(self, arguments: &[f64; LANES], series: &[bool; LANES]) -> [f64; LANES] {
        let (mut term, mut sum, mut step) = ([0.0f64; LANES], [0.0f64; LANES], [0.0f64; LANES]);
        for lane in (0..LANES).filter(|&lane| series[lane]) {
            let x = arguments[lane];
            let first = self.first(x);
            (term[lane], sum[lane], step[lane]) = (first, first, -0.25 * x * x);
        }
        let order = self.order();
        let mut m = 0.0f64;
        loop {
            let denominator = (m + 1.0) * (m + 1.0 + order);
            let mut running = false;
            for lane in 0..LANES {
                if term[lane].abs() > SERIES_END {
                    term[lane] *= step[lane] / denominator;
                    sum[lane] += term[lane];
                    running = true;
                }
            }
            if !running {
                return sum;
            }
            m += 1.0;
        }
    }
}

/// Bessel J0: its power series below x = 13 and Hankel's expansion above.
#[cfg(test)]
pub(super) fn bessel_j0(x: f64) -> f64 {
    Bessel::J0.at(x)
}

/// Bessel J2: its power series below x = 13 and Hankel's expansion (μ = 16) above.
#[cfg(test)]
pub(super) fn bessel_j2(x: f64) -> f64 {
    Bessel::J2.at(x)
}

/// J₁(x)/x, even in x: its power series below x = 13 and Hankel's expansion (μ = 4) above.
#[cfg(test)]
pub(super) fn bessel_j1_over_x(x: f64) -> f64 {
    Bessel::J1OverX.at(x)
}

/// Σ_m a_m with a_0 = `first` and a_{m+1} = −a_m (x/2)²/((m + 1)(m + 1 + n)), n = `order`,
/// summed until a term falls below 1e-18: J_n(x)/(x/2)^n·(first·n!) — J₀ with first = 1,
/// J₁/x with ½, J₂ with x²/8 (Abramowitz & Stegun 9.1.10).
#[cfg(test)]
fn bessel_power_series(x: f64, order: f64, first: f64) -> f64 {
    let step = -0.25 * x * x;
    let (mut term, mut sum) = (first, first);
    let mut m = 0.0f64;
    while term.abs() > SERIES_END {
        term *= step / ((m + 1.0) * (m + 1.0 + order));
        sum += term;
        m += 1.0;
    }
    sum
}

/// The sums (P, Q) of Hankel's asymptotic expansion of J_n(x), μ = 4n², truncated at its
/// smallest term (Abramowitz & Stegun 9.2.5): a_{k+1} = a_k (μ − (2k + 1)²)/(8(k + 1)x);
/// P takes the even k with signs + − + …, Q the odd k. J_n(x) ≈ √(2/(πx))·(P cos φ −
/// Q sin φ), φ = x − (n/2 + 1/4)π.
#[cfg(test)]
fn hankel_sums(mu: f64, x: f64) -> (f64, f64) {
    let (mut p, mut q) = (1.0, 0.0);
    let mut term = 1.0f64;
    for k in 0..HANKEL_TERMS {
        let next = term * (mu - f64::from(2 * k + 1).powi(2)) / (8.0 * f64::from(k + 1) * x);
        if next.abs() >= term.abs() || next.abs() < SERIES_END {
            break;
        }
        term = next;
        let index = k + 1;
        let sign = if (index / 2).is_multiple_of(2) { 1.0 } else { -1.0 };
        if index.is_multiple_of(2) {
            p += sign * term;
        } else {
            q += sign * term;
        }
    }
    (p, q)
}

/// The sums (P, Q) of Hankel's expansion (those of `Bessel::at`) of the lanes marked in
/// `far`, side by side, with the same operations in the same order; (1, 0) in the others.
fn hankel_lanes(mu: f64, arguments: &[f64; LANES], far: &[bool; LANES]) -> [(f64, f64); LANES] {
    let (mut p, mut q, mut term) = ([1.0f64; LANES], [0.0f64; LANES], [1.0f64; LANES]);
    let mut running = *far;
    for k in 0..HANKEL_TERMS {
        if !running.contains(&true) {
            break;
        }
        let factor = mu - f64::from(2 * k + 1).powi(2);
        let divisor = 8.0 * f64::from(k + 1);
        let index = k + 1;
        let sign = if (index / 2).is_multiple_of(2) { 1.0 } else { -1.0 };
        for lane in 0..LANES {
            if !running[lane] {
                continue;
            }
            let next = term[lane] * factor / (divisor * arguments[lane]);
            if next.abs() >= term[lane].abs() || next.abs() < SERIES_END {
                running[lane] = false;
                continue;
            }
            term[lane] = next;
            if index.is_multiple_of(2) {
                p[lane] += sign * next;
            } else {
                q[lane] += sign * next;
            }
        }
    }
    std::array::from_fn(|lane| (p[lane], q[lane]))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The batched evaluation is the scalar one bit for bit (the tables' bits rest on it):
    /// arguments on both sides of the series' limit, at 0, negative, and chunks that end
    /// part-way, for each function.
    #[test]
    fn filled_values_are_the_scalar_values_bit_for_bit() {
        let nodes: Vec<f64> = (0..203)
            .map(|k| -0.37 + 0.0731 * k as f64)
            .chain([0.0, 13.0, -13.0])
            .collect();
        for bessel in [Bessel::J0, Bessel::J1OverX, Bessel::J2] {
            for scale in [0.0, 0.5, 1.0, 3.7, 41.0] {
                for len in [nodes.len(), 5, 1] {
                    let mut values = vec![f64::NAN; len];
                    bessel.fill(&nodes[..len], scale, &mut values);
                    for (&node, &value) in nodes.iter().zip(&values) {
                        let expected = bessel.at(node * scale);
                        assert_eq!(value.to_bits(), expected.to_bits(), "{bessel:?} at {node}·{scale}");
                    }
                }
            }
        }
    }
}
