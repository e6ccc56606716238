//! Shared picture plumbing: panels, labelled sheets, text, PNG output.

use std::path::{Path, PathBuf};

use embedded_graphics::{
    mono_font::{
        ascii::{FONT_6X10, FONT_9X15},
        MonoTextStyle,
    },
    pixelcolor::{Rgb888, RgbColor},
    prelude::{DrawTarget, OriginDimensions, Point, Size},
    text::{Baseline, Text},
    Drawable, Pixel,
};
use tiny_skia::{Color, Pixmap, PremultipliedColorU8};

/// The sheets' background.
pub const BG: [u8; 3] = [24, 24, 28];

/// embedded-graphics drawing onto a tiny-skia pixmap (opaque pixels).
pub struct Canvas<'a>(pub &'a mut Pixmap);

impl OriginDimensions for Canvas<'_> {
    fn size(&self) -> Size {
        Size::new(self.0.width(), self.0.height())
    }
}

impl DrawTarget for Canvas<'_> {
    type Color = Rgb888;
    type Error = core::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        let (w, h) = (self.0.width() as i32, self.0.height() as i32);
        let data = self.0.pixels_mut();
        for Pixel(pt, c) in pixels {
            if (0..w).contains(&pt.x) && (0..h).contains(&pt.y) {
                if let Some(px) = PremultipliedColorU8::from_rgba(c.r(), c.g(), c.b(), 255) {
                    data[(pt.y * w + pt.x) as usize] = px;
                }
            }
        }
        Ok(())
    }
}

/// Text sizes.
#[derive(Clone, Copy)]
pub enum Font {
    /// 6x10.
    Small,
    /// 9x15.
    Big,
}

/// Draws `s` with its top-left corner at `(x, y)`.
pub fn text(pix: &mut Pixmap, s: &str, x: i32, y: i32, colour: [u8; 3], font: Font) {
    let c = Rgb888::new(colour[0], colour[1], colour[2]);
    let style = match font {
        Font::Small => MonoTextStyle::new(&FONT_6X10, c),
        Font::Big => MonoTextStyle::new(&FONT_9X15, c),
    };
    // Infallible.
    let _ = Text::with_baseline(s, Point::new(x, y), style, Baseline::Top).draw(&mut Canvas(pix));
}

/// Width in pixels of `s` in `font`.
pub fn text_width(s: &str, font: Font) -> i32 {
    s.chars().count() as i32
        * match font {
            Font::Small => 6,
            Font::Big => 9,
        }
}

/// sRGB encoding of a linear value, to 8 bits.
pub fn srgb8(x: f32) -> u8 {
    let x = x.clamp(0.0, 1.0);
    let e = if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    };
    (e * 255.0 + 0.5) as u8
}

/// An RGB picture with a title.
pub struct Panel {
    /// Shown under the picture.
    pub title: String,
    /// Width.
    pub w: u32,
    /// Height.
    pub h: u32,
    /// Row-major pixels.
    pub rgb: Vec<[u8; 3]>,
}

/// Copies `rgb` (`w` x `h`) into `pix` at `(x0, y0)`.
pub fn blit(pix: &mut Pixmap, rgb: &[[u8; 3]], w: u32, h: u32, x0: u32, y0: u32) {
    let pw = pix.width();
    let ph = pix.height();
    let data = pix.pixels_mut();
    for y in 0..h.min(ph.saturating_sub(y0)) {
        for x in 0..w.min(pw.saturating_sub(x0)) {
            let c = rgb[(y * w + x) as usize];
            if let Some(p) = PremultipliedColorU8::from_rgba(c[0], c[1], c[2], 255) {
                data[((y0 + y) * pw + x0 + x) as usize] = p;
            }
        }
    }
}

const MARGIN: u32 = 10;
const HEADER: u32 = 30;
const LABEL: u32 = 20;

/// A sheet of `panels` in a grid of `cols` columns (all panels the size of the first), the
/// title on top, each panel's title under it, `caption` at the bottom.
pub fn sheet(title: &str, panels: &[Panel], cols: usize, caption: &str) -> Pixmap {
    let (pw, ph) = panels.first().map_or((1, 1), |p| (p.w, p.h));
    let cols = cols.max(1) as u32;
    let rows = (panels.len() as u32).div_ceil(cols).max(1);
    let cap_h = if caption.is_empty() { 0 } else { 16 };
    let fit =
        (text_width(title, Font::Big).max(text_width(caption, Font::Small)) as u32) + 2 * MARGIN;
    let w = (MARGIN + cols * (pw + MARGIN)).max(fit);
    let h = HEADER + rows * (ph + LABEL) + cap_h + MARGIN;
    let mut pix = Pixmap::new(w, h).expect("sheet size is positive and small");
    pix.fill(Color::from_rgba8(BG[0], BG[1], BG[2], 255));
    text(
        &mut pix,
        title,
        MARGIN as i32,
        8,
        [235, 235, 235],
        Font::Big,
    );
    for (k, p) in panels.iter().enumerate() {
        let (c, r) = (k as u32 % cols, k as u32 / cols);
        let (x, y) = (MARGIN + c * (pw + MARGIN), HEADER + r * (ph + LABEL));
        blit(&mut pix, &p.rgb, p.w, p.h, x, y);
        text(
            &mut pix,
            &p.title,
            x as i32,
            (y + ph + 5) as i32,
            [200, 200, 205],
            Font::Small,
        );
    }
    if !caption.is_empty() {
        text(
            &mut pix,
            caption,
            MARGIN as i32,
            (h - MARGIN - 12) as i32,
            [150, 150, 160],
            Font::Small,
        );
    }
    pix
}

/// Writes `pix` as `dir/name` (creating `dir`); returns the path.
pub fn save(pix: &Pixmap, dir: &Path, name: &str) -> Result<PathBuf, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let path = dir.join(name);
    pix.save_png(&path)
        .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    Ok(path)
}
