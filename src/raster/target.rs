//! Render targets: horizontal bands of a caller-provided pixel buffer (with an optional 16-bit
//! depth band), the RGB565 and RGB888 pixel formats, and (in `encode`, re-exported here) the
//! encoding of linear colour.

use super::RasterError;
use crate::Real;

mod encode;
pub use encode::{
    encode_pixel, EncodeTable, Encoding, ToneMap, ENCODE_ENTRIES, ENCODE_INDEX_BITS,
    TONE_WHITE_MAX_PERCENT,
};
pub(crate) use encode::{ENCODE_GUARD, ENCODE_GUARDS};

/// Rounds `x` in [0, 1] (clamped; NaN as 0) to an integer in `0..=max`.
#[inline]
pub(crate) fn quantize<T: Real>(x: T, max: u32) -> u32 {
    // In T's own arithmetic (no f64: soft-float on Cortex-M), and exact for the depth's
    // 65535 levels in fixed point, where `T::from_u32(65535)` would saturate.
    x.unit_to_u32(max)
}

/// A pixel format the renderer writes: built from three encoded channels in [0, 1].
pub trait PixelFormat: Copy {
    /// The pixel for encoded channels `r`, `g`, `b` in [0, 1] (clamped; NaN as 0), each
    /// rounded to nearest. Cost: 3 multiply-adds and conversions.
    fn from_unit<T: Real>(r: T, g: T, b: T) -> Self;
    /// The channels as 8-bit values (expanded by bit replication for fewer bits).
    fn to_rgb8(self) -> [u8; 3];
    /// The pixel for encoded channels given as 16-bit levels (`0..=65535` for [0, 1]), each
    /// rounded to the format's bits: what an [`EncodeTable`] hands the rasterizer. Cost: 3
    /// integer multiply-shifts.
    #[inline]
    fn from_levels(r: u16, g: u16, b: u16) -> Self {
        let unit = |l: u16| f32::from(l) / 65535.0;
        Self::from_unit(unit(r), unit(g), unit(b))
    }
    /// What an [`EncodeTable`] of this format stores for the 16-bit `level` of any channel:
    /// the level in whatever form [`PixelFormat::from_entries`] builds a pixel from fastest.
    /// The default is the level itself.
    #[inline]
    fn table_entry(level: u16) -> u16 {
        level
    }
    /// The pixel from the [`EncodeTable`] entries of its red, green and blue levels: always
    /// `from_levels` of those levels, bit for bit. The default calls it (a format that
    /// overrides one of `table_entry` and `from_entries` overrides both).
    #[inline]
    fn from_entries(r: u16, g: u16, b: u16) -> Self {
        Self::from_levels(r, g, b)
    }
    /// Fills `pixels` with `colour` ([`Band::clear`]). The default stores eight pixels a loop
    /// step; [`Rgb565`] with the `bytemuck` feature stores 32-bit words, two pixels each.
    #[inline]
    fn fill_pixels(pixels: &mut [Self], colour: Self) {
        // Eight at a time: the RP2040 demo's frame 1 11 407 102 -> 11 380 730 rp2040js cycles
        // against a plain `fill`.
        let mut chunks = pixels.chunks_exact_mut(8);
        for c in &mut chunks {
            c.fill(colour);
        }
        chunks.into_remainder().fill(colour);
    }
}

/// `round(level * max / 65535)` for a 16-bit level, in integers (`max <= 255`).
#[inline(always)]
const fn level_to(level: u16, max: u32) -> u32 {
    // round(x / 65535) for x = l max < 2^24 without a division: x / 65535 = (x + x / 65536
    // + ...) / 65536; exact (round half up) for every level with max 31, 63 and 255
    // (checked exhaustively in tests/raster_prepared.rs).
    let x = level as u32 * max;
    (x + (x >> 16) + 32768) >> 16
}

/// A 16-bit pixel: 5 bits red (high), 6 green, 5 blue (the usual SPI display format, in CPU
/// byte order: swap the bytes for a display that wants big-endian).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
#[repr(transparent)]
pub struct Rgb565(pub u16);

impl Rgb565 {
    /// From 5-, 6- and 5-bit channels (extra high bits are dropped).
    pub const fn new(r5: u8, g6: u8, b5: u8) -> Self {
        Rgb565((((r5 & 31) as u16) << 11) | (((g6 & 63) as u16) << 5) | ((b5 & 31) as u16))
    }
}

impl PixelFormat for Rgb565 {
    #[inline]
    fn from_unit<T: Real>(r: T, g: T, b: T) -> Self {
        Rgb565::new(
            quantize(r, 31) as u8,
            quantize(g, 63) as u8,
            quantize(b, 31) as u8,
        )
    }
    #[inline(always)]
    fn from_levels(r: u16, g: u16, b: u16) -> Self {
        Rgb565(((level_to(r, 31) << 11) | (level_to(g, 63) << 5) | level_to(b, 31)) as u16)
    }
    /// The level already packed into every channel's place: `Rgb565::new(l5, l6, l5)` with
    /// `l5`, `l6` the level rounded to 5 and 6 bits, so that a pixel is three masks and two
    /// ORs ([`Rgb565::from_entries`]) instead of three multiply-shifts: about 16 fewer
    /// Cortex-M0+ cycles a pixel (the RP2040 demo's scan conversion, rp2040js: 40 184 ->
    /// 38 465 us for 12 990 pixels; the Cortex-M4F's, QEMU: 2 324 720 -> 2 183 269
    /// instructions for 12 793).
    #[inline]
    fn table_entry(level: u16) -> u16 {
        ((level_to(level, 31) << 11) | (level_to(level, 63) << 5) | level_to(level, 31)) as u16
    }
    #[cfg(feature = "bytemuck")]
    #[inline]
    fn fill_pixels(pixels: &mut [Self], colour: Self) {
        // (The same size and alignment as `u16`: the cast cannot fail.)
        fill_u16(bytemuck::cast_slice_mut(pixels), colour.0);
    }
    /// Red's bits of `r`, green's of `g`, blue's of `b`. An entry holds its 5-bit level at
    /// both ends (bits 0-4 and 11-15), so red is the entry shifted up by 11 (the 16-bit
    /// result drops the rest) and blue the entry shifted down by 11: one shift each instead
    /// of a mask, whose constants the Cortex-M0+ keeps on the stack in the span loop.
    #[inline(always)]
    fn from_entries(r: u16, g: u16, b: u16) -> Self {
        Rgb565((r << 11) | (g & 0x07E0) | (b >> 11))
    }
    #[inline]
    fn to_rgb8(self) -> [u8; 3] {
        let (r, g, b) = ((self.0 >> 11) & 31, (self.0 >> 5) & 63, self.0 & 31);
        [
            ((r << 3) | (r >> 2)) as u8,
            ((g << 2) | (g >> 4)) as u8,
            ((b << 3) | (b >> 2)) as u8,
        ]
    }
}

/// A 24-bit pixel: 8 bits per channel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
#[repr(transparent)]
pub struct Rgb888(pub [u8; 3]);

impl PixelFormat for Rgb888 {
    #[inline]
    fn from_unit<T: Real>(r: T, g: T, b: T) -> Self {
        Rgb888([
            quantize(r, 255) as u8,
            quantize(g, 255) as u8,
            quantize(b, 255) as u8,
        ])
    }
    #[inline(always)]
    fn from_levels(r: u16, g: u16, b: u16) -> Self {
        Rgb888([
            level_to(r, 255) as u8,
            level_to(g, 255) as u8,
            level_to(b, 255) as u8,
        ])
    }
    #[inline]
    fn to_rgb8(self) -> [u8; 3] {
        self.0
    }
}

/// Fills `s` with `v`: with the `bytemuck` feature as 32-bit words, four a loop step, where
/// the slice is aligned to them (the rest as 16-bit values); otherwise [`slice::fill`].
#[inline(always)]
fn fill_u16(s: &mut [u16], v: u16) {
    #[cfg(feature = "bytemuck")]
    {
        let (head, words, tail) = bytemuck::pod_align_to_mut::<u16, u32>(s);
        head.fill(v);
        tail.fill(v);
        fill_words(words, u32::from(v) * 0x0001_0001);
    }
    #[cfg(not(feature = "bytemuck"))]
    s.fill(v);
}

/// Fills `words` with `w`, four words a loop step. The value is hidden from LLVM
/// (`black_box`), which would otherwise call `memset`: on the Cortex-M0+
/// compiler-builtins' stores one word a loop step. Out of line, so that the caller's live
/// values leave it the registers for `STM` (rp2040js frames 1 to 15, one core: 8 265 110 ->
/// 8 255 792 cycles against the inlined fill of one hidden copy).
#[cfg(feature = "bytemuck")]
#[inline(never)]
fn fill_words(words: &mut [u32], w: u32) {
    // Four copies, each hidden on its own: four registers, which the Cortex-M0+ stores with
    // one `STM` (5 cycles for 16 bytes, against 8 for four `STR` of one register).
    let q = [
        core::hint::black_box(w),
        core::hint::black_box(w),
        core::hint::black_box(w),
        core::hint::black_box(w),
    ];
    let mut chunks = words.chunks_exact_mut(4);
    for c in &mut chunks {
        c.copy_from_slice(&q);
    }
    chunks.into_remainder().fill(w);
}

/// The depth value of a cleared depth band (farthest).
pub const DEPTH_FAR: u16 = u16::MAX;

/// A horizontal band of a frame: `rows` rows of `width` pixels starting at frame row `y0`,
/// in a caller-provided buffer, with an optional depth band of the same size.
///
/// A full frame is the band with `y0 = 0` and all rows. To render a 240x240 display in
/// 240x16 strips, make one band of 16 rows (7.5 KiB of RGB565, 7.5 KiB of depth), and for
/// each `y0` in 0, 16, ... 224: [`Band::move_to`], clear it, draw the scene, send the rows.
#[derive(Debug)]
pub struct Band<'a, P> {
    pixels: &'a mut [P],
    depth: Option<&'a mut [u16]>,
    width: u16,
    rows: u16,
    y0: u16,
}

impl<'a, P: PixelFormat> Band<'a, P> {
    /// A band of `pixels.len() / width` rows at frame row `y0`.
    ///
    /// # Errors
    /// [`RasterError::BadSize`] for a zero `width`, a buffer that is empty or not a whole
    /// number of rows, or more than 65535 rows; [`RasterError::BufferTooSmall`] (`"depth"`)
    /// when a depth band is given whose length differs from the pixel buffer's.
    pub fn new(
        pixels: &'a mut [P],
        depth: Option<&'a mut [u16]>,
        width: u16,
        y0: u16,
    ) -> Result<Self, RasterError> {
        if width == 0 || pixels.is_empty() || pixels.len() % width as usize != 0 {
            return Err(RasterError::BadSize("band"));
        }
        let rows = pixels.len() / width as usize;
        if rows > u16::MAX as usize {
            return Err(RasterError::BadSize("band"));
        }
        if let Some(d) = &depth {
            if d.len() != pixels.len() {
                return Err(RasterError::BufferTooSmall {
                    what: "depth",
                    needed: pixels.len(),
                    got: d.len(),
                });
            }
        }
        Ok(Band {
            pixels,
            depth,
            width,
            rows: rows as u16,
            y0,
        })
    }

    /// Puts `pixels` in place of the band's pixel buffer and hands back the one it had (the
    /// rows, their place in the frame and the depth band stay; the new buffer's contents are
    /// kept: clear them): a finished band's buffer goes to a DMA transfer whole while the next
    /// band is drawn into another, with no copy (the RP2040 firmware, with the `bytemuck`
    /// feature to see the pixels as the DMA's words). `Err(pixels)`, the buffer handed back
    /// untouched, when its length differs from the band's.
    pub fn replace_pixels(&mut self, pixels: &'a mut [P]) -> Result<&'a mut [P], &'a mut [P]> {
        if pixels.len() != self.pixels.len() {
            return Err(pixels);
        }
        Ok(core::mem::replace(&mut self.pixels, pixels))
    }
    /// Moves the band to start at frame row `y0` (the contents are kept: clear them).
    pub fn move_to(&mut self, y0: u16) {
        self.y0 = y0;
    }
    /// Fills the pixels with `colour` and the depth band (if any) with [`DEPTH_FAR`]. With the
    /// `bytemuck` feature both go as 32-bit words ([`PixelFormat::fill_pixels`] for
    /// [`Rgb565`]), four a loop step: on the Cortex-M0+ `memset` (the depth's constant fill)
    /// stores one word a step, and the pixels went as 16-bit values. Measured in the demo's
    /// frames: rp2040js frames 1 to 15, 8 343 856 -> 8 305 760 cycles (the depth) -> 8 265 110
    /// (the pixels) on one core; STM32F411 Gouraud frame 0 (QEMU) 2 867 697 -> 2 786 654
    /// instructions.
    pub fn clear(&mut self, colour: P) {
        P::fill_pixels(self.pixels, colour);
        if let Some(d) = self.depth.as_deref_mut() {
            fill_u16(d, DEPTH_FAR);
        }
    }
    /// The frame row of the band's first row.
    pub fn y0(&self) -> u16 {
        self.y0
    }
    /// The number of rows.
    pub fn rows(&self) -> u16 {
        self.rows
    }
    /// The width in pixels.
    pub fn width(&self) -> u16 {
        self.width
    }
    /// The pixels, row-major.
    pub fn pixels(&self) -> &[P] {
        self.pixels
    }
    /// The pixels, row-major, mutable.
    pub fn pixels_mut(&mut self) -> &mut [P] {
        self.pixels
    }
    /// The depth band, if any (smaller is nearer).
    pub fn depth(&self) -> Option<&[u16]> {
        self.depth.as_deref()
    }
    /// The pixel at frame coordinates `(x, y)`, or `None` outside the band.
    pub fn get(&self, x: u16, y: u16) -> Option<P> {
        let i = self.index(x, y)?;
        self.pixels.get(i).copied()
    }

    #[inline]
    pub(crate) fn index(&self, x: u16, y: u16) -> Option<usize> {
        if x >= self.width || y < self.y0 || y - self.y0 >= self.rows {
            return None;
        }
        Some((y - self.y0) as usize * self.width as usize + x as usize)
    }

    /// Depth test and write at buffer index `i`: `true` if `z` is nearer than the stored depth
    /// (or there is no depth band), storing it.
    #[inline]
    pub(crate) fn depth_test(&mut self, i: usize, z: u16) -> bool {
        match self.depth.as_deref_mut().and_then(|d| d.get_mut(i)) {
            Some(stored) => {
                if z < *stored {
                    *stored = z;
                    true
                } else {
                    false
                }
            }
            None => true,
        }
    }

    /// `true` if a depth band is attached.
    pub(crate) fn has_depth(&self) -> bool {
        self.depth.is_some()
    }

    /// Row `y` (frame coordinates) of the pixels and of the depth band, or `None` outside
    /// the band.
    #[inline]
    pub(crate) fn row_mut(&mut self, y: u16) -> Option<(&mut [P], Option<&mut [u16]>)> {
        if y < self.y0 || y - self.y0 >= self.rows {
            return None;
        }
        let w = self.width as usize;
        let at = (y - self.y0) as usize * w;
        let pixels = self.pixels.get_mut(at..at + w)?;
        let depth = match self.depth.as_deref_mut() {
            Some(d) => Some(d.get_mut(at..at + w)?),
            None => None,
        };
        Some((pixels, depth))
    }

    #[inline]
    pub(crate) fn put(&mut self, i: usize, p: P) {
        if let Some(px) = self.pixels.get_mut(i) {
            *px = p;
        }
    }
}
