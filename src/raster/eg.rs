//! `embedded-graphics` integration (`embedded-graphics` feature): the pixel formats convert to
//! and from `embedded-graphics-core` colours, a [`Band`] is a `DrawTarget` (draw text or
//! shapes over a rendered band, in frame coordinates, clipped to the band's rows), and
//! [`Band::flush_to`] sends a band to any display `DrawTarget` with one `fill_contiguous`.

use embedded_graphics_core::{
    draw_target::DrawTarget,
    geometry::{Dimensions, Point, Size},
    pixelcolor::{self, raw::RawData, raw::RawU16, PixelColor, RgbColor},
    primitives::Rectangle,
    Pixel,
};

use super::target::{Band, PixelFormat, Rgb565, Rgb888};

impl From<Rgb565> for pixelcolor::Rgb565 {
    fn from(p: Rgb565) -> Self {
        RawU16::new(p.0).into()
    }
}

impl From<pixelcolor::Rgb565> for Rgb565 {
    fn from(c: pixelcolor::Rgb565) -> Self {
        Rgb565(RawU16::from(c).into_inner())
    }
}

impl From<Rgb888> for pixelcolor::Rgb888 {
    fn from(p: Rgb888) -> Self {
        pixelcolor::Rgb888::new(p.0[0], p.0[1], p.0[2])
    }
}

impl From<pixelcolor::Rgb888> for Rgb888 {
    fn from(c: pixelcolor::Rgb888) -> Self {
        Rgb888([c.r(), c.g(), c.b()])
    }
}

/// A pixel format with an `embedded-graphics` colour type of the same bits.
pub trait EgPixel: PixelFormat + From<Self::Color> + Into<Self::Color> {
    /// The `embedded-graphics` colour.
    type Color: PixelColor;
}

impl EgPixel for Rgb565 {
    type Color = pixelcolor::Rgb565;
}

impl EgPixel for Rgb888 {
    type Color = pixelcolor::Rgb888;
}

impl<P: EgPixel> Band<'_, P> {
    /// Sends the band's rows to `display` at frame rows `y0..y0 + rows` with one
    /// `fill_contiguous` call (which a display driver turns into one window write).
    ///
    /// # Errors
    /// The display's error.
    pub fn flush_to<D: DrawTarget<Color = P::Color>>(
        &self,
        display: &mut D,
    ) -> Result<(), D::Error> {
        let area = Rectangle::new(
            Point::new(0, self.y0() as i32),
            Size::new(self.width() as u32, self.rows() as u32),
        );
        display.fill_contiguous(&area, self.pixels().iter().map(|&p| p.into()))
    }

    /// Frame row range `[top, bottom)` and column range of `area` inside the band, as indices.
    fn clip_rect(&self, area: &Rectangle) -> Option<(i32, i32, i32, i32)> {
        let r = area.intersection(&self.bounding_box());
        if r.size.width == 0 || r.size.height == 0 {
            return None;
        }
        Some((
            r.top_left.x,
            r.top_left.y,
            r.top_left.x + r.size.width as i32,
            r.top_left.y + r.size.height as i32,
        ))
    }
}

impl<P: PixelFormat> Dimensions for Band<'_, P> {
    /// The band's rectangle in frame coordinates: columns `0..width`, rows `y0..y0 + rows`.
    fn bounding_box(&self) -> Rectangle {
        Rectangle::new(
            Point::new(0, self.y0() as i32),
            Size::new(self.width() as u32, self.rows() as u32),
        )
    }
}

impl<P: EgPixel> DrawTarget for Band<'_, P> {
    type Color = P::Color;
    type Error = core::convert::Infallible;

    /// Writes the pixels inside the band; the others are dropped.
    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        for Pixel(pt, c) in pixels {
            if pt.x < 0 || pt.y < 0 || pt.x > u16::MAX as i32 || pt.y > u16::MAX as i32 {
                continue;
            }
            if let Some(i) = self.index(pt.x as u16, pt.y as u16) {
                self.put(i, P::from(c));
            }
        }
        Ok(())
    }

    /// Row by row: the colours of rows outside the band are skipped without a per-pixel
    /// test, those inside are copied into the row's slice.
    fn fill_contiguous<I>(&mut self, area: &Rectangle, colors: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Self::Color>,
    {
        let Some((x0, y0, x1, y1)) = self.clip_rect(area) else {
            return Ok(());
        };
        let (ax0, ay0) = (area.top_left.x, area.top_left.y);
        let aw = area.size.width as usize;
        let mut it = colors.into_iter();
        let (width, top) = (self.width() as usize, self.y0() as i32);
        // Skip the area's rows above the band.
        let skip = (y0 - ay0) as usize * aw;
        if skip > 0 && it.nth(skip - 1).is_none() {
            return Ok(());
        }
        let pixels = self.pixels_mut();
        for y in y0..y1 {
            let row = (y - top) as usize * width;
            // The row's colours before x0, inside, after x1.
            let (before, inside) = ((x0 - ax0) as usize, (x1 - x0) as usize);
            let after = aw - before - inside;
            if before > 0 && it.nth(before - 1).is_none() {
                return Ok(());
            }
            let Some(dst) = pixels.get_mut(row + x0 as usize..row + x1 as usize) else {
                return Ok(());
            };
            for px in dst.iter_mut() {
                match it.next() {
                    Some(c) => *px = P::from(c),
                    None => return Ok(()),
                }
            }
            if after > 0 && it.nth(after - 1).is_none() {
                return Ok(());
            }
        }
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, color: Self::Color) -> Result<(), Self::Error> {
        let Some((x0, y0, x1, y1)) = self.clip_rect(area) else {
            return Ok(());
        };
        let (width, top) = (self.width() as usize, self.y0() as i32);
        let p = P::from(color);
        let pixels = self.pixels_mut();
        for y in y0..y1 {
            let row = (y - top) as usize * width;
            if let Some(dst) = pixels.get_mut(row + x0 as usize..row + x1 as usize) {
                dst.fill(p);
            }
        }
        Ok(())
    }

    fn clear(&mut self, color: Self::Color) -> Result<(), Self::Error> {
        self.pixels_mut().fill(P::from(color));
        Ok(())
    }
}
