//! The tests' one pseudo-random generator (Marsaglia's xorshift32), so that every test module
//! draws from the same code: deterministic sequences from a seed, no dependency.

/// The xorshift32 sequence from `seed` (nonzero): each call the next 32-bit state.
#[allow(dead_code)] // as `uniform`
pub(crate) fn xorshift32(seed: u32) -> impl FnMut() -> u32 {
    let mut x = seed;
    move || {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        x
    }
}

/// [`xorshift32`]'s states as uniform values in `[0, 1)`.
#[allow(dead_code)] // its tests are feature-gated
pub(crate) fn uniform(seed: u32) -> impl FnMut() -> f64 {
    let mut next = xorshift32(seed);
    move || f64::from(next()) / 4_294_967_296.0
}
