//! The host reference for `boards/rp2040-emu`: renders frames 0..N of the scene exactly as the
//! RP2040 firmware does (`Fixed22`, Gouraud shading, 240x16 bands (a frame does not depend on the band height), one `Demo` for all frames in
//! order) and writes each as `frame_NNN.rgb565`: the bytes the ST7789 receives, big-endian
//! RGB565 in display order (240x240x2 bytes), to compare byte for byte with the frames the
//! emulated firmware sends.
//!
//! ```sh
//! cargo run --release --example reference_frames -- DIR [N]   # N: 2 by default
//! ```

use std::path::PathBuf;

use arealight::raster::{Band, EncodeTable, Rgb565, Shading};
use arealight::Fixed22;
use demo_scene::{Demo, MeshBuffers, BAND_PIXELS, HEIGHT, WIDTH};

/// Frames 0..`count` as the firmware draws them, each its pixels in display order. The only
/// use of the demo-scene API here (keep it in step with the firmware's frame loop).
fn render(count: u32) -> Vec<Vec<Rgb565>> {
    let mut buffers = Box::new(MeshBuffers::<Fixed22>::new());
    let mut table = Box::new(EncodeTable::zeroed());
    let mut demo =
        Demo::new(&mut buffers, &mut table, Shading::Gouraud).expect("the scene's constants");
    let (mut pixels, mut depth) = (vec![Rgb565(0); BAND_PIXELS], vec![0u16; BAND_PIXELS]);
    let mut band = Band::new(&mut pixels, Some(&mut depth), WIDTH, 0).expect("a WIDTH-wide band");
    (0..count)
        .map(|n| {
            let mut frame = vec![Rgb565(0); usize::from(WIDTH) * usize::from(HEIGHT)];
            demo.render_frame(n, &mut band, &mut || 0, |b| {
                let at = usize::from(b.y0()) * usize::from(WIDTH);
                let len = b.pixels().len().min(frame.len() - at);
                frame[at..at + len].copy_from_slice(&b.pixels()[..len]);
                Ok::<(), ()>(())
            })
            .expect("the frame renders");
            frame
        })
        .collect()
}

fn main() {
    let mut args = std::env::args().skip(1);
    let (Some(dir), count) = (args.next().map(PathBuf::from), args.next()) else {
        eprintln!("usage: reference_frames DIR [N]");
        std::process::exit(2);
    };
    let count: u32 = count.map_or(2, |s| s.parse().expect("N: a frame count"));
    std::fs::create_dir_all(&dir).expect("the output directory");
    for (n, frame) in render(count).iter().enumerate() {
        let bytes: Vec<u8> = frame.iter().flat_map(|p| p.0.to_be_bytes()).collect();
        let path = dir.join(format!("frame_{n:03}.rgb565"));
        std::fs::write(&path, bytes).expect("writing a frame");
        println!("{}", path.display());
    }
}
