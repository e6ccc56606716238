// The measured region of an instruction counter, written once for every target's counter
// (`counter.rs`: TIM2 on the ARM images; `instret.rs`: the `instret` CSR on RISC-V), each of
// which `include!`s this file and invokes the macro for its type. It expects, in the including
// module: `cnt()` (the counter's current value), `fail`, `Line`, `black_box`,
// `compiler_fence` and `SeqCst`.

/// `net` and `raw` for the counter type `$counter`, whose regions `$what` names in a failure.
macro_rules! measured_region {
    ($counter:ident, $what:literal) => {
        impl $counter {
            /// The instructions of a measured region whose raw counter difference is `raw`:
            /// `raw` less the empty region's count (`empty`). A region reads at least the
            /// empty region's count (it holds the same reads), so `raw < empty` means the
            /// counter does not count instructions: that stops the run with a `FAIL` line
            /// instead of wrapping to a count near 2^32.
            #[inline]
            pub fn net(&self, raw: u32) -> u32 {
                match raw.checked_sub(self.empty) {
                    Some(n) => n,
                    None => fail(
                        &mut Line::new(),
                        format_args!(
                            concat!(
                                "a measured region read {} on ",
                                $what,
                                ", fewer than the empty region's {}: the counter does not \
                                 count instructions"
                            ),
                            raw, self.empty
                        ),
                    ),
                }
            }

            /// The raw counter difference around `f`.
            #[inline(always)]
            pub fn raw<R>(&mut self, f: impl Fn() -> R) -> (R, u32) {
                compiler_fence(SeqCst);
                let t0 = cnt();
                compiler_fence(SeqCst);
                let r = black_box(f());
                compiler_fence(SeqCst);
                let t1 = cnt();
                compiler_fence(SeqCst);
                (r, t1.wrapping_sub(t0))
            }
        }
    };
}
