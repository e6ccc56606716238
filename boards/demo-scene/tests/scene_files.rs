//! The scene files the boards render (`demo_scene::scenes`, feature `scene-file`), built by
//! `demo_scene::spec::Player` on the host in f64 (the reference), f32 (the STM32F411 path) and
//! Fixed22 (the RP2040 path), band by band as the boards draw them: the frames agree with the
//! f64 frame within the backends' rounding, and the player refuses what it cannot hold.
#![cfg(feature = "scene-file")]

use arealight::raster::{Band, DrawStats, Encoding, Rgb565};
use arealight::{Fixed22, Real};
use demo_scene::scenes;
use demo_scene::spec::{
    CameraSpec, LightKind, LightSpec, MeshSpec, ObjectSpec, Player, SceneSpec, SpecBuffers,
    SpecError, SurfaceSpec,
};

const ROWS: u16 = 40;

type Buffers<T> = SpecBuffers<T, { scenes::VERTICES }, { scenes::TRIANGLES }>;

/// The frame (RGB565, row-major) and the draw statistics of `spec` in `T`.
fn render<T: Real>(spec: &SceneSpec) -> (Vec<Rgb565>, DrawStats) {
    let mut buffers = Box::new(Buffers::<T>::new());
    let mut player = Player::<T>::new(spec, &mut buffers).unwrap();
    let (w, h) = (spec.camera.width as usize, spec.camera.height as usize);
    let (mut px, mut depth) = (
        vec![Rgb565(0); w * ROWS as usize],
        vec![0u16; w * ROWS as usize],
    );
    let mut band = Band::new(&mut px, Some(&mut depth), spec.camera.width, 0).unwrap();
    let mut out = vec![Rgb565(0); w * h];
    let report = player
        .render_frame(&mut band, &mut || 0, |b| {
            let at = b.y0() as usize * w;
            let len = b.pixels().len().min(w * h - at);
            out[at..at + len].copy_from_slice(&b.pixels()[..len]);
            Ok::<(), ()>(())
        })
        .unwrap();
    (out, report.stats)
}

/// Per pixel, the largest channel difference in RGB565 steps; (max, mean, pixels that differ).
fn difference(a: &[Rgb565], b: &[Rgb565]) -> (i32, f64, usize) {
    let ch = |p: Rgb565| {
        [
            (p.0 >> 11) as i32,
            ((p.0 >> 5) & 63) as i32,
            (p.0 & 31) as i32,
        ]
    };
    let (mut max, mut sum, mut differ) = (0, 0i64, 0);
    for (x, y) in a.iter().zip(b) {
        let (x, y) = (ch(*x), ch(*y));
        let d = (0..3).map(|k| (x[k] - y[k]).abs()).max().unwrap_or(0);
        max = max.max(d);
        sum += i64::from(d);
        differ += usize::from(d > 0);
    }
    (max, sum as f64 / a.len() as f64, differ)
}

#[test]
fn every_scene_file_renders_as_in_f64() {
    for spec in scenes::ALL {
        let (reference, stats) = render::<f64>(spec);
        assert!(
            stats.pixels > 10_000 && stats.shaded > 1_000,
            "{}: {stats:?}",
            spec.name
        );
        let (f32_frame, f32_stats) = render::<f32>(spec);
        let (fixed_frame, fixed_stats) = render::<Fixed22>(spec);
        let f32_err = difference(&f32_frame, &reference);
        let fixed_err = difference(&fixed_frame, &reference);
        println!(
            "[scene-file] {}: pixels f64 {} f32 {} Fixed22 {}; f32 against f64: max {} mean {:.4} differ {}; Fixed22: max {} mean {:.4} differ {}",
            spec.name,
            stats.pixels,
            f32_stats.pixels,
            fixed_stats.pixels,
            f32_err.0,
            f32_err.1,
            f32_err.2,
            fixed_err.0,
            fixed_err.1,
            fixed_err.2
        );
        // The same pixels drawn (measured: equal in both scenes), and colours that differ by
        // one RGB565 step where a value lies near a rounding boundary: measured 3 and 1
        // pixels of 57 600 in f32, 10 and 78 in Fixed22 (1/1024 per model).
        for (name, s) in [("f32", f32_stats), ("Fixed22", fixed_stats)] {
            assert_eq!(
                (s.pixels, s.shaded),
                (stats.pixels, stats.shaded),
                "{} {name}",
                spec.name
            );
        }
        assert!(
            f32_err.0 <= 1 && f32_err.2 * 1000 <= reference.len(),
            "{}: f32 {f32_err:?}",
            spec.name
        );
        assert!(
            fixed_err.0 <= 1 && fixed_err.2 * 200 <= reference.len(),
            "{}: Fixed22 {fixed_err:?}",
            spec.name
        );
    }
}

const CAMERA: CameraSpec = CameraSpec {
    eye: [0.0, 1.0, 3.0],
    target: [0.0, 0.0, 0.0],
    up: [0.0, 1.0, 0.0],
    fov_deg: 45.0,
    width: 64,
    height: 64,
};

const BALL: ObjectSpec = ObjectSpec {
    mesh: MeshSpec::Sphere {
        radius: 0.5,
        stacks: 6,
        slices: 8,
    },
    scale: None,
    rotate: None,
    translate: None,
    surface: SurfaceSpec::Lit {
        diffuse: [0.5; 3],
        specular: [0.0; 3],
        exponent: 1,
    },
    gouraud: true,
    two_sided: false,
};

const AMBIENT: LightSpec = LightSpec {
    kind: LightKind::Ambient,
    colour: [0.1; 3],
};

fn scene(lights: &'static [LightSpec], objects: &'static [ObjectSpec]) -> SceneSpec {
    SceneSpec {
        name: "test",
        camera: CAMERA,
        exposure: 1.0,
        background: [0; 3],
        encoding: Encoding::Srgb,
        lights,
        objects,
    }
}

fn build_error(spec: &SceneSpec) -> SpecError {
    let mut buffers = Box::new(SpecBuffers::<f32, 64, 96>::new());
    match Player::<f32>::new(spec, &mut buffers) {
        Ok(_) => panic!("{spec:?} was built"),
        Err(e) => e,
    }
}

#[test]
fn the_player_refuses_what_it_cannot_hold() {
    // The ball alone fits: 7 x 9 = 63 vertices, 2 x 8 x 5 = 80 triangles.
    let mut buffers = Box::new(SpecBuffers::<f32, 64, 96>::new());
    assert!(Player::<f32>::new(&scene(&[AMBIENT], &[BALL]), &mut buffers).is_ok());
    assert_eq!(
        build_error(&scene(&[AMBIENT; 9], &[BALL])),
        SpecError::Capacity("lights")
    );
    assert_eq!(
        build_error(&scene(&[AMBIENT], &[BALL; 9])),
        SpecError::Capacity("meshes")
    );
    assert_eq!(
        build_error(&scene(&[AMBIENT], &[BALL, BALL])),
        SpecError::Buffers {
            vertices: 126,
            triangles: 160
        }
    );
    const NONAGON: [[f64; 3]; 9] = {
        let mut v = [[0.0, 2.0, 0.0]; 9];
        let mut i = 0;
        while i < 9 {
            v[i][0] = (i as f64) * 0.1;
            v[i][2] = (i * i) as f64 * 0.01;
            i += 1;
        }
        v
    };
    assert_eq!(
        build_error(&scene(
            &[LightSpec {
                kind: LightKind::Polygon(&NONAGON),
                colour: [1.0; 3],
            }],
            &[BALL]
        )),
        SpecError::Capacity("polygon vertices")
    );
    // A value the library refuses: a zero-radius sphere light.
    assert!(matches!(
        build_error(&scene(
            &[LightSpec {
                kind: LightKind::Sphere {
                    center: [0.0, 2.0, 0.0],
                    radius: 0.0
                },
                colour: [1.0; 3],
            }],
            &[BALL]
        )),
        SpecError::Raster(_)
    ));
}
