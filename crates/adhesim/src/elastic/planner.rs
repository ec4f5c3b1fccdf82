//! The library's one spectral planner service: every transform of the operators (normal,
//! periodic, tangential, coupling, layer), the preconditioner, the local peel's lattice inverse and
//! the surfaces is planned here. A plan is made once per length, precision and thread and
//! then shared (`Arc`): rustfft's planners cache what they make, and their choice of
//! algorithm depends only on the length and the CPU, so a shared plan gives the bits of a
//! fresh one.
//!
//! rustfft's planners are not `Send` (their recipe caches are reference-counted), so each
//! thread keeps its own; the plans they hand out are `Send + Sync`. A compute backend
//! other than the CPU would supply its plans here and the engine that runs them
//! (`spectral.rs`; ARCHITECTURE.md, "Compute backends").

use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftNum, FftPlanner};
use std::cell::RefCell;
use std::sync::Arc;
use std::thread::LocalKey;

/// The real and complex planners of one precision.
pub(crate) struct Planners<T: FftNum> {
    real: RealFftPlanner<T>,
    complex: FftPlanner<T>,
}

impl<T: FftNum> Planners<T> {
    fn new() -> Self {
        Self {
            real: RealFftPlanner::new(),
            complex: FftPlanner::new(),
        }
    }
}

thread_local! {
    static DOUBLE: RefCell<Planners<f64>> = RefCell::new(Planners::new());
    static SINGLE: RefCell<Planners<f32>> = RefCell::new(Planners::new());
}

/// A precision the service plans for (f64, f32).
pub(crate) trait Planned: FftNum {
    /// This thread's planners of the precision.
    fn planners() -> &'static LocalKey<RefCell<Planners<Self>>>;
}

impl Planned for f64 {
    fn planners() -> &'static LocalKey<RefCell<Planners<Self>>> {
        &DOUBLE
    }
}

impl Planned for f32 {
    fn planners() -> &'static LocalKey<RefCell<Planners<Self>>> {
        &SINGLE
    }
}

/// Real-to-complex transform of `len` values.
pub(crate) fn real_forward<T: Planned>(len: usize) -> Arc<dyn RealToComplex<T>> {
    T::planners().with(|p| p.borrow_mut().real.plan_fft_forward(len))
}

/// Complex-to-real transform back to `len` values.
pub(crate) fn real_inverse<T: Planned>(len: usize) -> Arc<dyn ComplexToReal<T>> {
    T::planners().with(|p| p.borrow_mut().real.plan_fft_inverse(len))
}

/// Complex transform of `len` values, forward (e^(−iqx)).
pub(crate) fn complex_forward<T: Planned>(len: usize) -> Arc<dyn Fft<T>> {
    T::planners().with(|p| p.borrow_mut().complex.plan_fft_forward(len))
}

/// Complex transform of `len` values, inverse (e^(+iqx), unnormalised).
pub(crate) fn complex_inverse<T: Planned>(len: usize) -> Arc<dyn Fft<T>> {
    T::planners().with(|p| p.borrow_mut().complex.plan_fft_inverse(len))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A plan asked for twice is the same plan (shared, not made again), and it transforms
    /// as a fresh planner's plan does, bit for bit.
    #[test]
    fn plans_are_shared_and_give_the_bits_of_a_fresh_plan() {
        let first = complex_forward::<f64>(96);
        let again = complex_forward::<f64>(96);
        assert!(Arc::ptr_eq(&first, &again));
        let fresh = FftPlanner::<f64>::new().plan_fft_forward(96);
        let signal: Vec<rustfft::num_complex::Complex<f64>> = (0..96)
            .map(|k| rustfft::num_complex::Complex::new((k as f64 * 0.37).sin(), (k as f64 * 0.11).cos()))
            .collect();
        let (mut shared, mut own) = (signal.clone(), signal);
        first.process(&mut shared);
        fresh.process(&mut own);
        assert_eq!(format!("{shared:?}"), format!("{own:?}"));
        let real = real_forward::<f32>(64);
        assert!(Arc::ptr_eq(&real, &real_forward::<f32>(64)));
        assert_eq!(real.len(), 64);
    }
}
