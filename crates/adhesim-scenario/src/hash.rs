//! The 64-bit FNV-1a hash of a text, shared by the batch engine, the sweep plan and the
//! output layer: a case's results hash and id (`batch/cases.rs`, `sweep/plan.rs`) and a checkpoint's checksum
//! (`output/checkpoint.rs`). It imports nothing, so the output layer takes it without
//! importing the batch engine above it.

/// 64-bit FNV-1a (stable across platforms and Rust versions, unlike `DefaultHasher`).
pub fn fnv1a(text: &str) -> u64 {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for byte in text.bytes() {
        hash ^= u64::from(byte);
        hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
    }
    hash
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a_is_the_standard_hash() {
        assert_eq!(fnv1a(""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a("a"), 0xaf63_dc4c_8601_ec8c);
    }
}
