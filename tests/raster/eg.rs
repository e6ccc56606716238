//! The `embedded-graphics` adapter: a band as a `DrawTarget`.

use super::*;
use embedded_graphics_core::draw_target::DrawTarget;
use embedded_graphics_core::geometry::{Dimensions, OriginDimensions, Point, Size};
use embedded_graphics_core::pixelcolor::Rgb565 as EgRgb565;
use embedded_graphics_core::primitives::Rectangle;
use embedded_graphics_core::Pixel;

/// A frame buffer display that records pixels.
struct Frame(Vec<EgRgb565>, u32, u32);
impl OriginDimensions for Frame {
    fn size(&self) -> Size {
        Size::new(self.1, self.2)
    }
}
impl DrawTarget for Frame {
    type Color = EgRgb565;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<EgRgb565>>>(
        &mut self,
        it: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in it {
            if p.x >= 0 && p.y >= 0 && (p.x as u32) < self.1 && (p.y as u32) < self.2 {
                self.0[(p.y as u32 * self.1 + p.x as u32) as usize] = c;
            }
        }
        Ok(())
    }
}

#[test]
fn fill_contiguous_matches_draw_iter_and_flush_sends_the_band() {
    let mut rng = Lcg(7);
    for _ in 0..300 {
        let (w, rows, y0) = (13u16, 5u16, rng.range(12) as u16);
        let area = Rectangle::new(
            Point::new(rng.range(20) - 5, rng.range(24) - 4),
            Size::new(rng.range(18) as u32, rng.range(12) as u32),
        );
        let colours: Vec<EgRgb565> = (0..area.size.width * area.size.height)
            .map(|_| {
                EgRgb565::from(embedded_graphics_core::pixelcolor::raw::RawU16::new(
                    rng.next() as u16,
                ))
            })
            .collect();
        let (mut a, mut b) = (vec![Rgb565(1); 65], vec![Rgb565(1); 65]);
        let mut ba = Band::new(&mut a, None, w, y0).unwrap();
        let mut bb = Band::new(&mut b, None, w, y0).unwrap();
        ba.fill_contiguous(&area, colours.iter().copied()).unwrap();
        let (aw, ah) = (area.size.width as i32, area.size.height as i32);
        let points = (0..ah).flat_map(|y| (0..aw).map(move |x| (x, y)));
        let at = area.top_left;
        bb.draw_iter(
            points
                .zip(colours.iter().copied())
                .map(|((x, y), c)| Pixel(Point::new(at.x + x, at.y + y), c)),
        )
        .unwrap();
        assert_eq!(ba.pixels(), bb.pixels());
        assert_eq!(ba.bounding_box().top_left.y, y0 as i32);
        let _ = rows;
    }
    // flush_to writes the band's rows, converted.
    let mut px: Vec<Rgb565> = (0..26).map(|i| Rgb565(i as u16 * 999)).collect();
    let band = Band::new(&mut px, None, 13, 3).unwrap();
    let mut frame = Frame(
        vec![EgRgb565::from(embedded_graphics_core::pixelcolor::raw::RawU16::new(0)); 13 * 8],
        13,
        8,
    );
    band.flush_to(&mut frame).unwrap();
    for i in 0..26 {
        assert_eq!(Rgb565::from(frame.0[3 * 13 + i]), band.pixels()[i]);
    }
    assert!(frame.0[..39].iter().all(|c| Rgb565::from(*c) == Rgb565(0)));
}
