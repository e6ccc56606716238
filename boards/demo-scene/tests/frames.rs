//! Renders the firmware's frames on the host, in f32 (the STM32F411 path) and Fixed22 (the
//! RP2040 path), band by band exactly as the boards do, and checks that they show the scene
//! and agree. `DEMO_SCENE_PPM=dir cargo test -- --nocapture` also writes the frames as PPM.

use arealight::raster::{Band, DrawStats, EncodeTable, Rgb565, Shading};
use arealight::{Fixed22, Real};
use demo_scene::{Demo, MeshBuffers, BACKGROUND, BAND_PIXELS, HEIGHT, PERIOD, WIDTH};

const FRAME_PIXELS: usize = WIDTH as usize * HEIGHT as usize;

/// Frame `n` rendered as the boards render it (`Demo::render_frame`) through a band of `rows`
/// rows (after an earlier frame, so that the per-frame vertex data holds stale values).
fn render_rows<T: Real>(
    shading: Shading,
    n: u32,
    rows: u16,
) -> (Vec<Rgb565>, DrawStats, std::time::Duration) {
    let mut buffers = Box::new(MeshBuffers::<T>::new());
    let mut table = Box::new(EncodeTable::zeroed());
    let mut demo = Demo::new(&mut buffers, &mut table, shading).unwrap();
    let rows_px = WIDTH as usize * rows as usize;
    let (mut pixels, mut depth) = (vec![Rgb565(0); rows_px], vec![0u16; rows_px]);
    let mut band = Band::new(&mut pixels, Some(&mut depth), WIDTH, 0).unwrap();
    let mut out = vec![Rgb565(0); FRAME_PIXELS];
    demo.render_frame(n + 7, &mut band, &mut || 0, |_| Ok::<(), ()>(()))
        .unwrap();
    let start = std::time::Instant::now();
    let report = demo
        .render_frame(n, &mut band, &mut || 0, |b| {
            let at = b.y0() as usize * WIDTH as usize;
            let len = b.pixels().len().min(FRAME_PIXELS - at);
            out[at..at + len].copy_from_slice(&b.pixels()[..len]);
            Ok::<(), ()>(())
        })
        .unwrap();
    (out, report.stats, start.elapsed())
}

fn render<T: Real>(shading: Shading, n: u32) -> (Vec<Rgb565>, DrawStats, std::time::Duration) {
    render_rows::<T>(shading, n, (BAND_PIXELS / WIDTH as usize) as u16)
}

fn channels(p: Rgb565) -> [i32; 3] {
    [
        (p.0 >> 11) as i32,
        ((p.0 >> 5) & 63) as i32,
        (p.0 & 31) as i32,
    ]
}

fn write_ppm(name: &str, pixels: &[Rgb565]) {
    let Ok(dir) = std::env::var("DEMO_SCENE_PPM") else {
        return;
    };
    use arealight::raster::PixelFormat;
    let mut data = format!("P6\n{WIDTH} {HEIGHT}\n255\n").into_bytes();
    for p in pixels {
        data.extend_from_slice(&p.to_rgb8());
    }
    std::fs::write(std::path::Path::new(&dir).join(name), data).unwrap();
}

#[test]
fn frames_show_the_scene_and_fixed_point_agrees_with_f32() {
    for shading in [Shading::PerPixel, Shading::Gouraud] {
        for n in [0, PERIOD / 4, PERIOD / 2, 3 * PERIOD / 4] {
            let (f, fs, ft) = render::<f32>(shading, n);
            let (x, xs, xt) = render::<Fixed22>(shading, n);
            let covered = f.iter().filter(|&&p| p != BACKGROUND).count();
            let (mut differ, mut max) = (0, 0);
            for (a, b) in f.iter().zip(&x) {
                let d = channels(*a)
                    .iter()
                    .zip(channels(*b))
                    .map(|(u, v)| (u - v).abs())
                    .max()
                    .unwrap();
                max = max.max(d);
                if d > 2 {
                    differ += 1;
                }
            }
            println!(
                "{shading:?} frame {n}: {covered} pixels covered; f32 {fs:?} in {ft:?}; \
                 Fixed22 {xs:?} in {xt:?}; {differ} pixels differ by more than 2 levels (max {max})"
            );
            write_ppm(&format!("{shading:?}-{n}-f32.ppm"), &f);
            write_ppm(&format!("{shading:?}-{n}-fixed.ppm"), &x);
            // The two objects cover a good part of the screen, in both backends.
            assert!(covered > FRAME_PIXELS / 6, "{covered}");
            assert!(x.iter().filter(|&&p| p != BACKGROUND).count() > FRAME_PIXELS / 6);
            // Fixed22 shades as f32 does, but for a few silhouette and depth-tie pixels.
            assert!(differ < FRAME_PIXELS / 200, "{differ}");
        }
    }
}

#[test]
fn bands_give_the_whole_frame_bit_for_bit() {
    // The per-frame vertex data is shared by every band, and the integer scan conversion
    // anchors each triangle's attributes at the triangle, not the band: 16-row bands (the
    // boards'), 7-row bands and one 240-row band must give the same pixels.
    for shading in [Shading::Gouraud, Shading::PerPixel] {
        for n in [0, PERIOD / 3] {
            let (whole, ws, _) = render_rows::<Fixed22>(shading, n, HEIGHT);
            for rows in [16, 7] {
                let (banded, bs, _) = render_rows::<Fixed22>(shading, n, rows);
                assert!(banded == whole, "{shading:?} frame {n}, {rows}-row bands");
                assert_eq!(bs.pixels, ws.pixels);
            }
        }
    }
}

#[test]
fn empty_bands_are_the_background_and_polling_shades_the_same() {
    // The two-core RP2040 firmware sends the bands `band_is_empty` names as the background,
    // without drawing them: drawn, they must be exactly that. Its core 1 shades through
    // `shade_share_polling`: one poll per shader call, the same colours as `shade_share`.
    let mut buffers = Box::new(MeshBuffers::<Fixed22>::new());
    let mut table = Box::new(EncodeTable::zeroed());
    let mut demo = Demo::new(&mut buffers, &mut table, Shading::Gouraud).unwrap();
    let mut buffers2 = Box::new(MeshBuffers::<Fixed22>::new());
    let mut table2 = Box::new(EncodeTable::zeroed());
    let mut polled = Demo::new(&mut buffers2, &mut table2, Shading::Gouraud).unwrap();
    let (mut pixels, mut depth) = (vec![Rgb565(0); BAND_PIXELS], vec![0u16; BAND_PIXELS]);
    let rows = (BAND_PIXELS / WIDTH as usize) as u16;
    let (mut empty, mut drawn) = (0, 0);
    for n in (0..PERIOD).step_by(5) {
        let frame = demo.frame(n).unwrap();
        let calls = demo.prepare(&frame);
        polled.transform(&frame);
        let mut polls = 0u32;
        assert_eq!(
            polled.shade_share_polling(&frame, 0, 1, || polls += 1),
            calls
        );
        assert_eq!(polls, calls, "frame {n}");
        for k in 0..HEIGHT / rows {
            let mut draw = |d: &Demo<'_, Fixed22>| {
                let mut band = Band::new(&mut pixels, Some(&mut depth), WIDTH, k * rows).unwrap();
                band.clear(BACKGROUND);
                let mut stats = DrawStats::default();
                d.draw_band(&frame, &mut band, &mut stats).unwrap();
                (band.pixels().to_vec(), stats)
            };
            let (px, stats) = draw(&demo);
            assert_eq!(draw(&polled).0, px, "frame {n}, band {k}: polled shading");
            if demo.band_is_empty(k * rows, rows) {
                empty += 1;
                assert!(px.iter().all(|&p| p == BACKGROUND), "frame {n}, band {k}");
                assert_eq!(stats.rasterized, 0, "frame {n}, band {k}");
            } else {
                drawn += 1;
            }
        }
    }
    // Both kinds occur (the test is not vacuous): the objects fill the middle bands only.
    assert!(
        empty >= 4 * 24 && drawn >= 6 * 24,
        "{empty} empty, {drawn} drawn"
    );
}

#[test]
fn every_position_fits_fixed_point() {
    // Demo::frame builds the lights through constructors that refuse positions beyond
    // Fixed22::COORDINATE_LIMIT: every frame of the period must build.
    let mut buffers = Box::new(MeshBuffers::<Fixed22>::new());
    let mut table = Box::new(EncodeTable::zeroed());
    let demo = Demo::new(&mut buffers, &mut table, Shading::PerPixel).unwrap();
    for n in 0..PERIOD {
        demo.frame(n).unwrap();
    }
}

/// Every band of frame `n` as `demo` draws it (after its transform and shade, whichever way
/// they were done), as one image.
fn drawn(demo: &Demo<'_, Fixed22>, frame: &demo_scene::Frame<Fixed22>) -> Vec<Rgb565> {
    let rows = (BAND_PIXELS / WIDTH as usize) as u16;
    let (mut pixels, mut depth) = (vec![Rgb565(0); BAND_PIXELS], vec![0u16; BAND_PIXELS]);
    let mut out = Vec::with_capacity(FRAME_PIXELS);
    for y0 in (0..HEIGHT).step_by(rows as usize) {
        let mut band = Band::new(&mut pixels, Some(&mut depth), WIDTH, y0).unwrap();
        band.clear(BACKGROUND);
        demo.draw_band(frame, &mut band, &mut DrawStats::default())
            .unwrap();
        let take = (FRAME_PIXELS - out.len()).min(BAND_PIXELS);
        out.extend_from_slice(&band.pixels()[..take]);
    }
    out
}

#[test]
fn a_demo_that_drew_earlier_frames_draws_each_frame_as_a_new_one() {
    // The sphere stands still: from the second frame on, `Demo::transform` and
    // `Demo::transform_share` keep its vertex data (and the exchange leaves them out), and
    // its shade skips finding the visible vertices. Every frame must still be the pixels of
    // a `Demo` that never drew before, on one core and on two (the firmware's exchange,
    // here between two `Demo`s on the host), Gouraud and (one core) per pixel.
    use demo_scene::{ColourExchange, ScreenExchange, VisibleExchange};
    let frames = [0, 1, 2, PERIOD / 3, PERIOD / 3 + 1, PERIOD - 1, 0];
    for shading in [Shading::Gouraud, Shading::PerPixel] {
        let mut kept_buffers = Box::new(MeshBuffers::<Fixed22>::new());
        let mut kept_table = Box::new(EncodeTable::zeroed());
        let mut kept = Demo::new(&mut kept_buffers, &mut kept_table, shading).unwrap();
        for n in frames {
            let mut fresh_buffers = Box::new(MeshBuffers::<Fixed22>::new());
            let mut fresh_table = Box::new(EncodeTable::zeroed());
            let mut fresh = Demo::new(&mut fresh_buffers, &mut fresh_table, shading).unwrap();
            let frame = fresh.frame(n).unwrap();
            let calls = fresh.prepare(&frame);
            let want = drawn(&fresh, &frame);
            assert_eq!(kept.prepare(&frame), calls, "{shading:?} frame {n}");
            assert!(
                drawn(&kept, &frame) == want,
                "{shading:?} frame {n}, one core"
            );
        }
    }
    // Two cores, each shading its half of the visible vertices, with the visible-vertex
    // pass made by each core over all the triangles or (the firmware's way) shared: each
    // core's half of the triangles, the marks and rows exchanged.
    for share_visible in [false, true] {
        let (mut b0, mut b1) = (
            Box::new(MeshBuffers::<Fixed22>::new()),
            Box::new(MeshBuffers::<Fixed22>::new()),
        );
        // The cores' two scenes share one encoding table, as in the firmware.
        let mut table = Box::new(EncodeTable::zeroed());
        let first = Demo::new(&mut b0, &mut table, Shading::Gouraud).unwrap();
        let second = Demo::sharing(&mut b1, first.table(), Shading::Gouraud).unwrap();
        let mut cores = [first, second];
        let mut screen = Box::new([ScreenExchange::<Fixed22>::new(), ScreenExchange::new()]);
        let mut visible = Box::new([VisibleExchange::new(), VisibleExchange::new()]);
        let mut colours = Box::new([ColourExchange::new(), ColourExchange::new()]);
        for (i, n) in frames.into_iter().enumerate() {
            let mut fresh_buffers = Box::new(MeshBuffers::<Fixed22>::new());
            let mut fresh_table = Box::new(EncodeTable::zeroed());
            let mut fresh =
                Demo::new(&mut fresh_buffers, &mut fresh_table, Shading::Gouraud).unwrap();
            let frame = fresh.frame(n).unwrap();
            let calls = fresh.prepare(&frame);
            let want = drawn(&fresh, &frame);
            for (k, demo) in cores.iter_mut().enumerate() {
                demo.transform_share(&frame, k, 2);
                demo.export_screen(&mut screen[k], k);
            }
            for (k, demo) in cores.iter_mut().enumerate() {
                demo.import_screen(&screen[1 - k], 1 - k);
                if share_visible {
                    // The torus's and the lamp's passes every frame, the sphere's (which
                    // stands still) in the first.
                    let due = if i == 0 { 3 } else { 2 };
                    assert_eq!(demo.find_visible_share(k, 2), due, "frame {n}");
                    demo.export_visible(&mut visible[k], k);
                }
            }
            let mut shared = 0;
            for (k, demo) in cores.iter_mut().enumerate() {
                if share_visible {
                    demo.import_visible(&visible[1 - k], 1 - k);
                    // Every pass complete: the shading makes none.
                    assert_eq!(demo.find_visible_share(k, 2), 0, "frame {n}");
                }
                shared += demo.shade_share(&frame, k, 2);
                demo.export_colours(&mut colours[k]);
            }
            assert_eq!(
                shared, calls,
                "frame {n}, visible pass shared: {share_visible}"
            );
            for (k, demo) in cores.iter_mut().enumerate() {
                demo.import_colours(&colours[1 - k], 1 - k, 2);
                assert!(
                    drawn(demo, &frame) == want,
                    "frame {n}, core {k} of two, visible pass shared: {share_visible}"
                );
            }
        }
    }
}

#[test]
fn a_carried_last_band_gives_the_frames_of_render_frame() {
    // `render_frame_carrying` keeps an empty last band and hands it back after the next
    // frame's transform: a display that applies its outputs in order shows, once the kept
    // band is sent, exactly the frame `render_frame` draws; the next frame's bands come only
    // after that.
    for rows in [40u16, 16] {
        let rows_px = WIDTH as usize * rows as usize;
        let mut buffers = Box::new(MeshBuffers::<Fixed22>::new());
        let mut table = Box::new(EncodeTable::zeroed());
        let mut demo = Demo::new(&mut buffers, &mut table, Shading::Gouraud).unwrap();
        let (mut pixels, mut depth) = (vec![Rgb565(0); rows_px], vec![0u16; rows_px]);
        let mut band = Band::new(&mut pixels, Some(&mut depth), WIDTH, 0).unwrap();
        let mut display = vec![Rgb565(0); FRAME_PIXELS];
        let mut kept: Option<(u16, u16)> = None;
        let mut keeps = 0;
        let mut shown: Vec<Vec<Rgb565>> = Vec::new();
        let frames = [0u32, 1, 2, 60, 61, 119];
        for &n in &frames {
            demo.render_frame_carrying(n, &mut band, &mut || 0, |out| {
                match &out {
                    demo_scene::Output::Band(b) => {
                        assert!(kept.is_none(), "frame {n}: a band before the kept one");
                        let at = b.y0() as usize * WIDTH as usize;
                        let len = b.pixels().len().min(FRAME_PIXELS - at);
                        display[at..at + len].copy_from_slice(&b.pixels()[..len]);
                    }
                    demo_scene::Output::Keep { y0, rows } => {
                        assert!(kept.is_none());
                        assert_eq!(y0 + rows, HEIGHT, "frame {n}: only the last band");
                        kept = Some((*y0, *rows));
                        keeps += 1;
                        return Ok::<(), ()>(());
                    }
                    demo_scene::Output::Carried => {
                        if let Some((y0, _)) = kept.take() {
                            let at = y0 as usize * WIDTH as usize;
                            display[at..].fill(BACKGROUND);
                        } else {
                            return Ok(());
                        }
                    }
                }
                // The frame is whole once its last pixel is written (the emulator's rule).
                if kept.is_none() && display[FRAME_PIXELS - 1] != Rgb565(0) {
                    let last_written = match &out {
                        demo_scene::Output::Band(b) => b.y0() + b.rows() >= HEIGHT,
                        _ => true,
                    };
                    if last_written {
                        shown.push(display.clone());
                    }
                }
                Ok(())
            })
            .unwrap();
        }
        // The last frame's kept band, as the next frame would send it.
        if let Some((y0, _)) = kept.take() {
            display[y0 as usize * WIDTH as usize..].fill(BACKGROUND);
            shown.push(display.clone());
        }
        assert_eq!(shown.len(), frames.len(), "{rows} rows");
        // Not vacuous: the objects never reach the bottom rows, so every frame keeps its band.
        assert_eq!(keeps, frames.len(), "{rows} rows");
        for (k, &n) in frames.iter().enumerate() {
            let (want, _, _) = render_rows::<Fixed22>(Shading::Gouraud, n, rows);
            assert!(shown[k] == want, "{rows} rows, frame {n}");
        }
    }
}

#[test]
fn sharing_refuses_a_table_no_demo_filled() {
    let mut buffers = Box::new(MeshBuffers::<Fixed22>::new());
    let zeroed = Box::new(EncodeTable::zeroed());
    assert!(matches!(
        Demo::sharing(&mut buffers, &zeroed, Shading::Gouraud),
        Err(arealight::raster::RasterError::BadParameter("table"))
    ));
    // A filled one is taken: the second scene draws through the first one's table.
    let mut table = Box::new(EncodeTable::zeroed());
    let mut other = Box::new(MeshBuffers::<Fixed22>::new());
    let first = Demo::new(&mut other, &mut table, Shading::Gouraud).unwrap();
    let second = Demo::sharing(&mut buffers, first.table(), Shading::Gouraud).unwrap();
    assert!(core::ptr::eq(first.table(), second.table()));
}
