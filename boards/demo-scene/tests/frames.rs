//! Renders the firmware's frames on the host, in f32 (the STM32F411 path) and Fixed22 (the
//! RP2040 path), band by band exactly as the boards do, and checks that they show the scene
//! and agree. `DEMO_SCENE_PPM=dir cargo test -- --nocapture` also writes the frames as PPM.

use arealight::raster::{render_in_bands, Band, DrawStats, RasterError, Rgb565, Shading};
use arealight::{Fixed22, Real};
use demo_scene::{Demo, MeshBuffers, VertexCache, BACKGROUND, BAND_PIXELS, HEIGHT, PERIOD, WIDTH};

const FRAME_PIXELS: usize = WIDTH as usize * HEIGHT as usize;

fn render<T: Real>(
    shading: Shading,
    cached: bool,
    n: u32,
) -> (Vec<Rgb565>, DrawStats, std::time::Duration) {
    let mut buffers = MeshBuffers::<T>::new();
    let mut cache = Box::new(VertexCache::<T>::new());
    let demo = Demo::new(&mut buffers, shading, cached.then_some(&mut *cache)).unwrap();
    // An earlier frame first, so that the cache holds stale entries.
    demo.frame(n + 7).unwrap();
    let (mut pixels, mut depth) = ([Rgb565(0); BAND_PIXELS], [0u16; BAND_PIXELS]);
    let mut band = Band::new(&mut pixels, Some(&mut depth), WIDTH, 0).unwrap();
    let mut out = vec![Rgb565(0); FRAME_PIXELS];
    let mut stats = DrawStats::default();
    let start = std::time::Instant::now();
    let frame = demo.frame(n).unwrap();
    render_in_bands(
        &mut band,
        HEIGHT,
        BACKGROUND,
        |b| demo.draw_band(&frame, b, &mut stats),
        |b| {
            let at = b.y0() as usize * WIDTH as usize;
            let len = b.pixels().len().min(FRAME_PIXELS - at);
            out[at..at + len].copy_from_slice(&b.pixels()[..len]);
            Ok::<(), RasterError>(())
        },
    )
    .unwrap();
    (out, stats, start.elapsed())
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
            let cached = shading == Shading::Gouraud;
            let (f, fs, ft) = render::<f32>(shading, cached, n);
            let (x, xs, xt) = render::<Fixed22>(shading, cached, n);
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
fn the_vertex_cache_changes_no_pixel() {
    for n in [0, PERIOD / 3] {
        let (a, sa, _) = render::<Fixed22>(Shading::Gouraud, false, n);
        let (b, sb, _) = render::<Fixed22>(Shading::Gouraud, true, n);
        assert!(a == b, "frame {n}");
        assert_eq!(sa.pixels, sb.pixels);
        println!("frame {n}: shader calls without the cache {}, with it (counted by draw, hits included) {}", sa.shaded, sb.shaded);
    }
}

#[test]
fn every_position_fits_fixed_point() {
    // Demo::frame builds the lights through constructors that refuse positions beyond
    // Fixed22::COORDINATE_LIMIT: every frame of the period must build.
    let mut buffers = MeshBuffers::<Fixed22>::new();
    let demo = Demo::new(&mut buffers, Shading::PerPixel, None).unwrap();
    for n in 0..PERIOD {
        demo.frame(n).unwrap();
    }
}
