//! Another draw of a sweep: a small deterministic generator (xorshift64) the sweeps use to move
//! their scenes off the grid's values when a seed is given, so that scenes nobody tuned for are
//! drawn. Deterministic, so a seed's failures reproduce.

/// The seed a sweep's environment variable `var` names (`ZSHIFT_…_SEED=<n>`), 0 (the grid CI
/// runs) when it is unset or not a number.
pub fn seed(var: &str) -> u64 {
    std::env::var(var)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0)
}

/// Marsaglia's xorshift64 (13, 7, 17). The state must not be 0 (it would stay 0).
#[derive(Debug, Clone, Copy)]
pub struct Xorshift(pub u64);

impl Xorshift {
    /// The next state.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// An index in `0..n` (`n > 0`).
    pub fn index(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// A number in `[0, 1)` on a grid of 2⁻²⁰.
    pub fn unit(&mut self) -> f64 {
        self.index(1 << 20) as f64 / f64::from(1u32 << 20)
    }
}
