//! Per-pixel shading on a chip without an FPU (Cortex-M0/M0+ such as the RP2040, RV32IMC such
//! as the ESP32-C3): a sphere under a square panel light and a spherical lamp, Lambert plus
//! Phong, shaded in `Fixed22` (integer arithmetic only) straight into an RGB565 frame buffer
//! as an SPI display takes it; then, on the host, the same shader in `f32` for comparison and
//! the frame written as a PPM image.
//!
//! ```sh
//! cargo run --release --example fixed_pixel > sphere.ppm   # to standard output
//! cargo run --release --example fixed_pixel -- sphere.ppm  # or to a file
//! ```
//!
//! The firmware part is `Shader` (generic over the scalar type, instantiated with `Fixed22`):
//! the lights and the Phong lobe are built and validated once, then `Shader::pixel` runs per
//! pixel with no allocation, no float and no panic. `Fixed22` holds positions within
//! `[-4, 4]` (`Fixed22::COORDINATE_LIMIT`); the models are scale invariant, so a scene is
//! scaled into that cube. For a whole scene of triangles, `arealight::raster` (see
//! `examples/band_render.rs`) does the same per pixel or per vertex.

use std::io::{IsTerminal, Write};

use arealight::{Fixed22, PhongLobe, PolygonLight, Real, SphereLight, Vec3};

const WIDTH: u16 = 96;
const HEIGHT: u16 = 96;
/// The Phong exponent of the sphere's material.
const SHININESS: u32 = 24;

/// The per-frame constants: lights, lobe, exposure, colours.
struct Shader<T: Real> {
    panel: PolygonLight<T, 4>,
    lamp: SphereLight<T>,
    lobe: PhongLobe<T>,
    /// Scales the diffuse sum so that the brightest point of the sphere shows at about 90 %.
    exposure: T,
    albedo: [T; 3],
    specular: T,
}

impl<T: Real> Shader<T> {
    /// Once at start-up. `from_f64` of a constant is folded at compile time for the float types
    /// and costs one soft-float conversion each on the M0: a few dozen in all, never per pixel.
    fn new() -> Result<Self, arealight::Error> {
        let v = |x: f64, y: f64, z: f64| Vec3::new(T::from_f64(x), T::from_f64(y), T::from_f64(z));
        // A 1.6 x 1.6 panel above and in front of the sphere, facing down.
        let panel = PolygonLight::new(&[
            v(-1.2, 2.0, 0.2),
            v(0.4, 2.0, 0.2),
            v(0.4, 2.0, 1.8),
            v(-1.2, 2.0, 1.8),
        ])?;
        // A small warm lamp to the right, low.
        let lamp = SphereLight::new(v(2.2, 0.2, 1.6), T::from_f64(0.4))?;
        let lobe = PhongLobe::new(SHININESS)?;
        // Expose on the diffuse light at the point of the sphere facing the panel's centre.
        let top = v(-0.176, 0.880, 0.440);
        let brightest = panel.lambert(top, top) + lamp.lambert_hermite(top, top);
        let exposure = T::from_f64(0.9) / brightest.max(T::from_f64(1e-3));
        Ok(Shader {
            panel,
            lamp,
            lobe,
            exposure,
            albedo: [T::from_f64(0.85), T::from_f64(0.35), T::from_f64(0.2)],
            specular: T::from_f64(0.5),
        })
    }

    /// The RGB565 pixel `(x, y)` of a unit sphere at the origin seen head-on (orthographic,
    /// viewer at +z), or `None` off the sphere. Per pixel: a square root, two light models
    /// each for Lambert and Phong, a few products; everything in `T`.
    fn pixel(&self, x: u16, y: u16) -> Option<u16> {
        // The pixel's centre in [-1, 1]^2 (y up): (2x + 1 - W) / W, in integers then one division.
        let u = T::from_fixed_i32(2 * i32::from(x) + 1 - i32::from(WIDTH), 0).div_u32(WIDTH.into());
        let w =
            T::from_fixed_i32(i32::from(HEIGHT) - 2 * i32::from(y) - 1, 0).div_u32(HEIGHT.into());
        let zz = T::ONE - u * u - w * w;
        if zz <= T::ZERO {
            return None;
        }
        let z = zz.sqrt();
        // On a unit sphere the surface point and its normal are the same vector.
        let n = Vec3::new(u, w, z);
        // The view direction (0, 0, 1) mirrored about n: 2 (n.v) n - v.
        let two_z = z + z;
        let r = Vec3::new(two_z * u, two_z * w, two_z * z - T::ONE);
        let diffuse = (self.panel.lambert(n, n) + self.lamp.lambert_hermite(n, n)) * self.exposure;
        let shine = (self.panel.phong(&self.lobe, n, r) + self.lamp.phong(&self.lobe, n, r))
            * self.specular;
        let channel = |albedo: T, levels: u32| (albedo * diffuse + shine).unit_to_u32(levels);
        let (red, green, blue) = (
            channel(self.albedo[0], 31),
            channel(self.albedo[1], 63),
            channel(self.albedo[2], 31),
        );
        // Linear values, no gamma: a display's own response darkens them (band_render.rs
        // shows an sRGB encoding table, `arealight::raster::EncodeTable`).
        Some((red << 11 | green << 5 | blue) as u16)
    }
}

/// RGB565 to 8-bit RGB, for the host's image.
fn rgb8(p: u16) -> [u8; 3] {
    let (r, g, b) = (p >> 11, (p >> 5) & 63, p & 31);
    [
        (r * 255 / 31) as u8,
        (g * 255 / 63) as u8,
        (b * 255 / 31) as u8,
    ]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    const BACKGROUND: u16 = 0x18e3; // dark grey
                                    // --- Firmware: Fixed22 into the frame buffer. ---
    let shader = Shader::<Fixed22>::new()?;
    let mut frame = [BACKGROUND; WIDTH as usize * HEIGHT as usize];
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            if let Some(p) = shader.pixel(x, y) {
                frame[usize::from(y) * usize::from(WIDTH) + usize::from(x)] = p;
            }
        }
    }

    // --- Host: the same shader in f32, and the largest difference in RGB565 levels. ---
    let reference = Shader::<f32>::new()?;
    let (mut lit, mut worst) = (0u32, 0u16);
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            let fixed = frame[usize::from(y) * usize::from(WIDTH) + usize::from(x)];
            if let Some(p) = reference.pixel(x, y) {
                lit += 1;
                let d = |s: u16, m: u16| ((fixed >> s) & m).abs_diff((p >> s) & m);
                worst = worst.max(d(11, 31)).max(d(5, 63)).max(d(0, 31));
            }
        }
    }
    eprintln!(
        "{WIDTH}x{HEIGHT}: {lit} pixels shaded in Fixed22; largest difference from f32: {worst} level(s) of RGB565"
    );

    let mut ppm = format!("P6\n{WIDTH} {HEIGHT}\n255\n").into_bytes();
    for p in frame {
        ppm.extend_from_slice(&rgb8(p));
    }
    match std::env::args_os().nth(1) {
        Some(path) => std::fs::write(&path, &ppm)?,
        None if std::io::stdout().is_terminal() => {
            std::fs::write("fixed_pixel.ppm", &ppm)?;
            eprintln!("stdout is a terminal: wrote fixed_pixel.ppm instead");
        }
        None => std::io::stdout().lock().write_all(&ppm)?,
    }
    Ok(())
}
