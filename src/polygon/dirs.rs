//! The unit directions from one shading point to a polygon's vertices, shared by the Phong
//! term's two uses of them in fixed point: its negligibility test and its walk. Each is
//! `(v_i - p).to_unit()` of the same offset, so the same bits whichever asks first:
//! [`VertexDirs`] normalizes each at most once per sample. (A normalization is about 270
//! Cortex-M0 instructions in `Fixed22`. Measured with the cache, when the Lambert term shared
//! it too: the QEMU budget's 32 demo shader calls 516 053 -> 508 049 M0 instructions, the
//! RP2040 demo's frame 1 10 687 086 -> 10 638 442 cycles in rp2040js. The fixed-point Lambert
//! term now normalizes in 16-bit form on its own, `Sealed::unit3_q15`, at about a fifth of
//! that cost.)

use crate::{Real, UnitVec3, Vec3};

/// The directions of up to `N` vertices from one shading point, each normalized when first
/// asked for (see the module docs). Make one per sample and shading point.
#[derive(Clone, Copy, Debug)]
pub(crate) struct VertexDirs<T, const N: usize> {
    dirs: [Option<UnitVec3<T>>; N],
    /// Bit `i`: `dirs[i]` is vertex `i`'s direction (`None` there: it has none).
    known: u32,
}

/// Where a polygon term takes its vertices' unit directions from: [`VertexDirs`] (shared by
/// the terms of one sample) or [`Uncached`] (a term called alone, which normalizes each
/// vertex's direction at most once by itself: its code is then that of no cache at all).
pub(crate) trait VertexDirections<T> {
    /// Whether `get` keeps what it computes (a caller that asks once per vertex anyway may
    /// then call `to_unit` itself, as it would without a cache).
    const CACHED: bool;

    /// The unit direction of vertex `i`, whose offset from the shading point is `u` (`v_i -
    /// p`, as every caller takes it: [`Vec3::offset_from`]): `u.to_unit()`'s bits.
    fn get(&mut self, i: usize, u: Vec3<T>) -> Option<UnitVec3<T>>;
}

/// No cache: `u.to_unit()` every time (see [`VertexDirections`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Uncached;

impl<T: Real> VertexDirections<T> for Uncached {
    const CACHED: bool = false;
    /// `Real::unit3` inlined (`u.to_unit()`'s bits, without its call).
    #[inline(always)]
    fn get(&mut self, _i: usize, u: Vec3<T>) -> Option<UnitVec3<T>> {
        T::unit3([u.x, u.y, u.z]).map(|[x, y, z]| UnitVec3::new_unchecked(Vec3::new(x, y, z)))
    }
}

impl<T: Real, const N: usize> VertexDirections<T> for VertexDirs<T, N> {
    const CACHED: bool = true;
    #[inline(always)]
    fn get(&mut self, i: usize, u: Vec3<T>) -> Option<UnitVec3<T>> {
        VertexDirs::get(self, i, u)
    }
}

impl<T: Real, const N: usize> VertexDirs<T, N> {
    /// None known yet.
    #[inline(always)]
    pub(crate) fn new() -> Self {
        VertexDirs {
            dirs: [None; N],
            known: 0,
        }
    }

    /// The unit direction of vertex `i`, whose offset from the shading point is `u` (`v_i -
    /// p`, as every caller takes it: [`Vec3::offset_from`]): `u.to_unit()`, computed once. An
    /// index beyond the capacity (or 32) is computed every time.
    #[inline(always)]
    pub(crate) fn get(&mut self, i: usize, u: Vec3<T>) -> Option<UnitVec3<T>> {
        let bit = 1u32.checked_shl(i as u32).unwrap_or(0);
        let Some(slot) = self.dirs.get_mut(i) else {
            return u.to_unit();
        };
        if self.known & bit != 0 {
            return *slot;
        }
        let d = u.to_unit();
        *slot = d;
        self.known |= bit;
        d
    }
}
