//! The encoding of linear colour into a pixel's channels: [`Encoding`] (with its tone curve,
//! [`ToneMap`]), per pixel ([`encode_pixel`]) or tabulated once ([`EncodeTable`], which the
//! prepared path's span loops index).

use super::{quantize, PixelFormat, Rgb565};
use crate::raster::RasterError;
use crate::{Real, Rgb};
use core::marker::PhantomData;

/// How a linear colour (after the exposure) is encoded into a pixel's channels.
///
/// The first three clamp the linear value to [0, 1] first (a highlight above the display's
/// white clips to white); [`Encoding::SrgbTone`] compresses highlights with a tone curve
/// instead.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Encoding {
    /// No transfer function: `round(255 x)` (cheapest; looks dark on a display).
    Linear,
    /// Gamma 2: `sqrt(x)` (1 square root per channel; within 0.05 of sRGB everywhere).
    Gamma2,
    /// The sRGB transfer function (1 `powf` per channel: an `exp` and a `ln`).
    Srgb,
    /// The tone curve ([`ToneMap::apply`]) in linear light, then the sRGB transfer function:
    /// values up to the curve's knee are shown as [`Encoding::Srgb`] shows them, brighter ones
    /// are compressed to reach white at the curve's white point instead of clipping at 1.
    /// Cost: `Srgb`'s plus, above the knee, 3 divisions and 3 multiplies per channel through
    /// [`Encoding::encode`]; nothing extra per pixel through an [`EncodeTable`] (the curve is
    /// folded into the table: see [`EncodeTable::exposure_scale`]).
    SrgbTone(ToneMap),
}

/// A highlight-compressing tone curve: the identity up to the knee `k`, then a Reinhard
/// shoulder that reaches display white at the white point `W` (`k < 1 < W`):
///
/// `f(x) = x` for `x <= k`; `f(x) = k + s h((x - k) / s)` for `k < x < W`, with `s = 1 - k`
/// and the extended Reinhard curve `h(u) = u (1 + u / U^2) / (1 + u)`, `U = (W - k) / s`;
/// `f(x) = 1` for `x >= W`. `f` is continuous with a continuous slope at the knee (1 on both
/// sides), increasing, and `f(W) = 1`; with `k = 0` it is Reinhard's extended operator
/// `x (1 + x / W^2) / (1 + x)`. Negative values and NaN map to 0.
///
/// The parameters are whole percent of the display's white (so that the type is `Eq` and
/// `Hash` like [`Encoding`]): `ToneMap::new(60, 400)` keeps everything below 60 % as it was
/// and compresses 60 % .. 400 % into 60 % .. 100 %.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ToneMap {
    knee: u8,
    white: u16,
}

/// The largest white point of a [`ToneMap`], in percent: 128 times the display's white (the
/// largest linear colour the fixed-point rasterizer carries).
pub const TONE_WHITE_MAX_PERCENT: u16 = 12_800;

impl ToneMap {
    /// The curve with its knee at `knee_percent` % and its white point at `white_percent` %
    /// of the display's white.
    ///
    /// # Errors
    /// [`RasterError::BadParameter`] (`"knee_percent"`) for a knee of 100 % or more;
    /// (`"white_percent"`) for a white point of 100 % or less or above
    /// [`TONE_WHITE_MAX_PERCENT`].
    pub const fn new(knee_percent: u8, white_percent: u16) -> Result<Self, RasterError> {
        if knee_percent >= 100 {
            return Err(RasterError::BadParameter("knee_percent"));
        }
        if white_percent <= 100 || white_percent > TONE_WHITE_MAX_PERCENT {
            return Err(RasterError::BadParameter("white_percent"));
        }
        Ok(ToneMap {
            knee: knee_percent,
            white: white_percent,
        })
    }
    /// The knee, in percent of the display's white.
    pub const fn knee_percent(self) -> u8 {
        self.knee
    }
    /// The white point, in percent of the display's white.
    pub const fn white_percent(self) -> u16 {
        self.white
    }
    /// The white point as a linear value (`white_percent / 100`).
    #[inline]
    pub fn white<T: Real>(self) -> T {
        // Whole and hundredths apart: Fixed22 holds at most 512, not 12800.
        let w = self.white as u32;
        T::from_u32(w / 100) + T::from_u32(w % 100).div_u32(100)
    }
    /// `f(x)` (see the type), in `T`'s own arithmetic: in [0, 1] for every input. Accuracy
    /// against the definition in f64 (measured over [-1, 2 W] for six curves in
    /// `tests/raster_tone.rs`): 2.2e-16 in f64, 1.7e-7 in f32 and `Fast32`, 4.6e-7 in `Fixed22`. Cost: 3 divisions,
    /// 3 multiplies, 2 comparisons (only 1 at or below the knee).
    #[inline]
    pub fn apply<T: Real>(self, x: T) -> T {
        let k = T::from_u32(self.knee as u32).div_u32(100);
        let w = self.white::<T>();
        if x > k {
            if x < w {
                // k + s h(t / s) with t = x - k, multiplied out: k + s t (1 + c t) / (s + t),
                // c t = s (t / d) / d, d = W - k (no d^2: it would leave Fixed22's range for a
                // white point near 128, and a tiny c would lose its bits there).
                let s = T::ONE - k;
                let t = x - k;
                let d = w - k;
                let ct = s * (t / d) / d;
                let h = t * (T::ONE + ct) / (s + t);
                (k + s * h).clamp01()
            } else {
                T::ONE
            }
        } else {
            // At or below the knee, negative or NaN.
            x.clamp01()
        }
    }
}

impl Encoding {
    /// Encodes one linear channel value: clamped to [0, 1] (NaN as 0), or tone-mapped for
    /// [`Encoding::SrgbTone`], then the transfer function. Exact to the backend's
    /// `sqrt`/`powf`. Cost: see the variants.
    #[inline]
    pub fn encode<T: Real>(self, x: T) -> T {
        let x = match self {
            Encoding::SrgbTone(t) => t.apply(x),
            _ => x.clamp01(),
        };
        match self {
            Encoding::Linear => x,
            Encoding::Gamma2 => x.sqrt(),
            Encoding::Srgb | Encoding::SrgbTone(_) => {
                if x <= T::from_f64(0.003_130_8) {
                    T::from_f64(12.92) * x
                } else {
                    (T::from_f64(1.055) * x.powf(T::from_f64(1.0 / 2.4)) - T::from_f64(0.055))
                        .clamp01()
                }
            }
        }
    }
    /// The linear value that encodes as white: 1, or the tone curve's white point.
    #[inline]
    pub fn white<T: Real>(self) -> T {
        match self {
            Encoding::SrgbTone(t) => t.white(),
            _ => T::ONE,
        }
    }
}

/// Encodes a linear colour times `exposure` into a pixel.
#[inline]
pub fn encode_pixel<T: Real, P: PixelFormat>(c: Rgb<T>, exposure: T, enc: Encoding) -> P {
    P::from_unit(
        enc.encode(c.r * exposure),
        enc.encode(c.g * exposure),
        enc.encode(c.b * exposure),
    )
}

/// Fraction bits of the linear colour index of an [`EncodeTable`]: linear 1.0 is index 4096.
pub const ENCODE_INDEX_BITS: u32 = 12;
/// Entries of an [`EncodeTable`]: indices `0..=4096`.
pub const ENCODE_ENTRIES: usize = (1 << ENCODE_INDEX_BITS) + 1;
/// Whether an [`EncodeTable`] has its guards (the `encode-guards` feature; always in the
/// crate's own unit tests, which check the guarded span loop against the clamped one).
pub(crate) const ENCODE_GUARDS: bool = cfg!(any(feature = "encode-guards", test));
/// The slots of an [`EncodeTable`]: with the guards, the 4097 entries at `ENCODE_GUARD..`,
/// after copies of the first and before copies of the last, 2^13 in all, so that the 13 bits
/// [`EncodeTable::pixel_guarded`] takes from a value always index a slot; without, the entries.
const ENCODE_SLOTS: usize = if ENCODE_GUARDS {
    1 << (ENCODE_INDEX_BITS + 1)
} else {
    ENCODE_ENTRIES
};
/// The slot of index 0: the copies of entry 0 before it (none without the guards).
pub(crate) const ENCODE_GUARD: usize = (ENCODE_SLOTS - ENCODE_ENTRIES) / 2;

/// An [`Encoding`] tabulated once: linear colour (after the exposure) in steps of 1/4096 to
/// 16-bit encoded levels, so that a pixel costs three table loads instead of three transfer
/// functions (a square root each for [`Encoding::Gamma2`], a `powf` for [`Encoding::Srgb`]:
/// about 3300 instructions per pixel in `Fixed22` on a Cortex-M0+).
///
/// A tone-mapped table ([`Encoding::SrgbTone`]) spans the curve's white point `W` instead of
/// 1 in the same 4097 entries (steps of `W`/4096; every value at or above `W` is white, which
/// the index clamp gives for free), so the tone curve costs nothing per pixel: draw through it
/// with the exposure multiplied by [`EncodeTable::exposure_scale`] (`1 / W`).
///
/// Accuracy: the linear value is rounded to 1/4096 before encoding, so a channel can differ
/// from [`encode_pixel`]'s where the exact value lies near a rounding boundary: by at most one
/// level of RGB565 for every encoding, and of RGB888 for `Linear` and `Srgb`; by up to 3
/// levels of RGB888 for `Gamma2` near black, where the square root is steep (measured over
/// every input on a 1/65536 grid in `tests/raster_prepared.rs`). A tone-mapped table's coarser
/// steps (`W`/4096) cost more near black, where sRGB is steep: indexed as the prepared path
/// does (the scaled value truncated to a step), up to 1 level of RGB565 and 4 of RGB888 with
/// `W` = 4, 1 and 2 with `W` = 2 (measured in `tests/raster_tone.rs`).
///
/// A table is for one pixel format `P` (the bands it draws into): each entry is the level in
/// `P`'s form ([`PixelFormat::table_entry`]; for [`Rgb565`] the level already rounded to its
/// channels' bits, which saves the per-pixel rounding), the same pixels as from the levels.
/// Size: 8 KiB (4097 16-bit entries); with the `encode-guards` feature 16 KiB (2^13 slots: the
/// entries between copies of the first and the last, which let the Gouraud span loop on
/// ARMv6-M index most triangles' pixels without the clamp: RP2040 demo, rp2040js frames 1 to
/// 15, one core 8 100 916 -> 7 925 968 cycles). Build it once (`static`, `singleton!` or
/// `main`'s frame) and share it between draw calls. Cost to build: 4097
/// [`Encoding::encode`] calls (and the copies).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EncodeTable<P: PixelFormat = Rgb565> {
    encoding: Encoding,
    slots: [u16; ENCODE_SLOTS],
    format: PhantomData<P>,
}

impl<P: PixelFormat> EncodeTable<P> {
    /// The table of `encoding`, computed in `T`'s own arithmetic (so firmware and host agree
    /// bit for bit when they build it with the same `T`).
    pub fn new<T: Real>(encoding: Encoding) -> Self {
        let mut table = Self::zeroed();
        table.fill::<T>(encoding);
        table
    }
    /// A table of zeros (every pixel black) to [`EncodeTable::fill`] later: a `const fn`, so
    /// that it can initialize a `static` (all zero bits: `.bss`, no flash).
    pub const fn zeroed() -> Self {
        EncodeTable {
            encoding: Encoding::Linear,
            slots: [0; ENCODE_SLOTS],
            format: PhantomData,
        }
    }
    /// Tabulates `encoding` in place (see [`EncodeTable::new`]): entry `i` holds the encoding
    /// of the linear value `i W / 4096`, `W` = [`Encoding::white`] (1 unless tone-mapped), as a
    /// 16-bit level in `P`'s form ([`PixelFormat::table_entry`]).
    pub fn fill<T: Real>(&mut self, encoding: Encoding) {
        let white = encoding.white::<T>();
        let tone = matches!(encoding, Encoding::SrgbTone(_));
        let (below, rest) = self.slots.split_at_mut(ENCODE_GUARD);
        let (entries, above) = rest.split_at_mut(ENCODE_ENTRIES);
        for (i, e) in entries.iter_mut().enumerate() {
            let x = T::from_fixed_i32(i as i32, ENCODE_INDEX_BITS);
            // Untoned tables keep `x` exactly as before (no multiplication by 1).
            let x = if tone { x * white } else { x };
            *e = P::table_entry(quantize(encoding.encode(x), u16::MAX as u32) as u16);
        }
        below.fill(entries[0]);
        above.fill(entries[ENCODE_ENTRIES - 1]);
        self.encoding = encoding;
    }
    /// The encoding tabulated.
    pub fn encoding(&self) -> Encoding {
        self.encoding
    }
    /// What to multiply the draw call's exposure by when drawing through this table: 1, or
    /// `1 / W` for a tone-mapped table (whose entries span the curve's white point `W`).
    pub fn exposure_scale<T: Real>(&self) -> T {
        T::ONE / self.encoding.white::<T>()
    }
    /// The pixel for linear channels given as indices (1.0 = 4096, or `W` for a tone-mapped
    /// table; clamped to `0..=4096`). Cost: 3 unsigned comparisons, 3 loads, the format's
    /// packing ([`PixelFormat::from_entries`]); an index out of range calls the clamp out
    /// of line. With the clamp inline (two comparisons a channel, whose constants the
    /// Cortex-M0+ keeps on the stack in the span loop), the RP2040 demo's frames took 1.6 %
    /// longer (rp2040js frames 1 to 15, one core: 8 590 585 -> 8 452 988 cycles when it
    /// moved out of line; the depth's clamp likewise, 8 452 988 -> 8 402 628).
    #[inline(always)]
    pub fn pixel(&self, r: i32, g: i32, b: i32) -> P {
        let at = |i: i32| {
            // One unsigned comparison on the common path (an index in range), the clamp
            // only out of it.
            let i = if (i as u32) < ENCODE_ENTRIES as u32 {
                i as usize
            } else {
                index_out_of_range(i)
            };
            // (`i` is in range: the fallback is never taken.)
            self.slots
                .get(i + ENCODE_GUARD)
                .copied()
                .unwrap_or(P::table_entry(u16::MAX))
        };
        P::from_entries(at(r), at(g), at(b))
    }
    /// The pixel for linear channels given as 32-bit values whose top 13 bits are the
    /// index plus `ENCODE_GUARD` (the guards' slots first): the same pixel as
    /// [`EncodeTable::pixel`] of the index `(v >> 19) - ENCODE_GUARD`, the guards giving the
    /// clamp's entries for indices in `[-2047, 6144]`. No comparison and no mask: a shift
    /// and a load a channel. (Only with the guards: without, a slot beyond the table reads
    /// 0.)
    #[inline(always)]
    pub(crate) fn pixel_guarded(&self, r: u32, g: u32, b: u32) -> P {
        // (With the guards `v >> 19` is below the table's length: no bounds test is left.)
        let at = |v: u32| self.slots.get((v >> 19) as usize).copied().unwrap_or(0);
        P::from_entries(at(r), at(g), at(b))
    }
}

/// An [`EncodeTable`] index below 0 or above 4096, clamped (cold: out of line, so that the
/// span loops keep one comparison per channel).
#[cold]
#[inline(never)]
fn index_out_of_range(i: i32) -> usize {
    i.clamp(0, (ENCODE_ENTRIES - 1) as i32) as usize
}
