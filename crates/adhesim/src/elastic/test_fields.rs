//! Reproducible pseudo-random fields for the operators' tests.

/// `len` values in [0, 1) from Marsaglia's xorshift (13, 7, 17), advancing `state`.
pub(crate) fn xorshift_field(state: &mut u64, len: usize) -> Vec<f64> {
    (0..len)
        .map(|_| {
            *state ^= *state << 13;
            *state ^= *state >> 7;
            *state ^= *state << 17;
            (*state >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect()
}

/// `len` values in [−0.5, 0.5) from Knuth's 64-bit linear congruential generator (MMIX),
/// advancing `state`.
pub(crate) fn lcg_field(state: &mut u64, len: usize) -> Vec<f64> {
    (0..len)
        .map(|_| {
            *state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (*state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect()
}
