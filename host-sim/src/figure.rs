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

/// `s` broken into lines at most `max_w` pixels wide in `font`: at spaces where it can, inside
/// a word only when the word alone is wider than a line.
pub fn wrap(s: &str, font: Font, max_w: i32) -> Vec<String> {
    let per = text_width("x", font).max(1);
    let max_chars = (max_w / per).max(1) as usize;
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in s.split(' ') {
        let mut word: Vec<char> = word.chars().collect();
        // A word wider than a line: full lines of it first.
        while word.len() > max_chars {
            if !line.is_empty() {
                lines.push(std::mem::take(&mut line));
            }
            lines.push(word.drain(..max_chars).collect());
        }
        let word: String = word.into_iter().collect();
        let len = line.chars().count();
        if len == 0 {
            line = word;
        } else if len + 1 + word.chars().count() <= max_chars {
            line.push(' ');
            line.push_str(&word);
        } else {
            lines.push(std::mem::replace(&mut line, word));
        }
    }
    if !line.is_empty() || lines.is_empty() {
        lines.push(line);
    }
    lines
}

/// Line heights of the two fonts.
fn line_h(font: Font) -> u32 {
    match font {
        Font::Small => 11,
        Font::Big => 17,
    }
}

/// Draws `lines` from `(x, y)` down; returns the height used.
fn lines_at(pix: &mut Pixmap, lines: &[String], x: i32, y: i32, c: [u8; 3], font: Font) -> u32 {
    for (i, l) in lines.iter().enumerate() {
        text(pix, l, x, y + (i as u32 * line_h(font)) as i32, c, font);
    }
    lines.len() as u32 * line_h(font)
}

const MARGIN: u32 = 10;

/// A sheet of `panels` in a grid of `cols` columns (all panels the size of the first), the
/// title on top, each panel's title under it, `caption` at the bottom. The sheet is as wide as
/// the grid; the title, the panel titles and the caption are wrapped to fit (a panel title to
/// its panel's width), so no text runs into another.
pub fn sheet(title: &str, panels: &[Panel], cols: usize, caption: &str) -> Pixmap {
    let (pw, ph) = panels.first().map_or((1, 1), |p| (p.w, p.h));
    let cols = cols.max(1) as u32;
    let rows = (panels.len() as u32).div_ceil(cols).max(1);
    let w = (MARGIN + cols * (pw + MARGIN)).max(240);
    let text_w = (w - 2 * MARGIN) as i32;
    let title_lines = wrap(title, Font::Big, text_w);
    let cap_lines = if caption.is_empty() {
        Vec::new()
    } else {
        wrap(caption, Font::Small, text_w)
    };
    let labels: Vec<Vec<String>> = panels
        .iter()
        .map(|p| wrap(&p.title, Font::Small, pw as i32))
        .collect();
    // Each row's label band fits its tallest label.
    let label_h: Vec<u32> = (0..rows)
        .map(|r| {
            let most = labels
                .iter()
                .skip((r * cols) as usize)
                .take(cols as usize)
                .map(Vec::len)
                .max()
                .unwrap_or(1) as u32;
            most * line_h(Font::Small) + 9
        })
        .collect();
    let header = 8 + title_lines.len() as u32 * line_h(Font::Big) + 5;
    let cap_h = if cap_lines.is_empty() {
        0
    } else {
        cap_lines.len() as u32 * line_h(Font::Small) + 4
    };
    let h = header + rows * ph + label_h.iter().sum::<u32>() + cap_h + MARGIN;
    let mut pix = Pixmap::new(w, h).expect("sheet size is positive and small");
    pix.fill(Color::from_rgba8(BG[0], BG[1], BG[2], 255));
    lines_at(
        &mut pix,
        &title_lines,
        MARGIN as i32,
        8,
        [235, 235, 235],
        Font::Big,
    );
    let mut row_y = Vec::with_capacity(rows as usize);
    let mut y = header;
    for lh in &label_h {
        row_y.push(y);
        y += ph + lh;
    }
    for (k, (p, label)) in panels.iter().zip(&labels).enumerate() {
        let (c, r) = (k as u32 % cols, k as u32 / cols);
        let (x, y) = (MARGIN + c * (pw + MARGIN), row_y[r as usize]);
        blit(&mut pix, &p.rgb, p.w, p.h, x, y);
        lines_at(
            &mut pix,
            label,
            x as i32,
            (y + ph + 5) as i32,
            [200, 200, 205],
            Font::Small,
        );
    }
    lines_at(
        &mut pix,
        &cap_lines,
        MARGIN as i32,
        y as i32,
        [150, 150, 160],
        Font::Small,
    );
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_breaks_at_spaces_and_inside_words_only_when_needed() {
        // 6 px per character: 60 px is 10 characters.
        assert_eq!(wrap("up +y", Font::Small, 60), ["up +y"]);
        assert_eq!(
            wrap("sky (.5,.5,1), ground (.2,1,.2)", Font::Small, 60),
            ["sky", "(.5,.5,1),", "ground", "(.2,1,.2)"]
        );
        assert_eq!(
            wrap("a host-sim/scenes/example.toml", Font::Small, 60),
            ["a", "host-sim/s", "cenes/exam", "ple.toml"]
        );
        assert_eq!(wrap("", Font::Big, 60), [""]);
        for line in wrap("the same, seen from above-right of it all", Font::Small, 90) {
            assert!(text_width(&line, Font::Small) <= 90, "{line}");
        }
    }
}
