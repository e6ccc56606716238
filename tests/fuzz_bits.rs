//! The bit-pattern fuzzer that always runs in `cargo test`: proptest feeds every model family
//! and the rasterizer (tests/fuzzing: every public constructor and per-sample function) with
//! arbitrary f32 bit patterns, biased toward NaN, infinities, zeros of both signs, subnormals,
//! the extremes of the range and values near the geometric degeneracies (tiny, huge, 1 +- ULP),
//! on f64, f32, Fast32 and Fixed22, with planar polygons made on purpose (every shape and
//! vertex count up to the capacity, near-degenerate ones). No panic and no NaN or infinity
//! out, ever.
//!
//! Cases per family: `AREALIGHT_FUZZ_CASES` (default 2000; STABILITY.md gives the counts of
//! the longer local runs). The cargo-fuzz targets in `fuzz/` run the same bodies under
//! libFuzzer. Crash inputs found by either are kept below as regression tests.

mod fuzzing;

use fuzzing::{run, shaded_counts, Family, FAMILIES};
use proptest::prelude::*;

fn cases() -> u32 {
    std::env::var("AREALIGHT_FUZZ_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2000)
}

/// One 32-bit word of fuzz input: raw bits, a special value, or an ordinary-looking value.
fn word() -> impl Strategy<Value = u32> {
    let specials: Vec<u32> = [
        f32::NAN,
        -f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        0.0,
        -0.0,
        f32::MIN_POSITIVE,
        -f32::MIN_POSITIVE,
        f32::from_bits(1),
        f32::from_bits(0x8000_0001),
        f32::from_bits(0x007f_ffff),
        f32::MAX,
        f32::MIN,
        1.0,
        -1.0,
        1.0 + f32::EPSILON,
        1.0 - f32::EPSILON / 2.0,
        1e-20,
        1e-10,
        1e10,
        1e19,
        1e30,
        std::f32::consts::FRAC_PI_2,
        std::f32::consts::PI,
    ]
    .iter()
    .map(|x| x.to_bits())
    .chain([u32::MAX, u32::MAX - 1, u32::MAX - 2, 0, 1, 2, 3, 64, 1001])
    .collect();
    prop_oneof![
        3 => any::<u32>(),
        3 => proptest::sample::select(specials),
        4 => (-4.0f32..4.0).prop_map(f32::to_bits),
        1 => (-30i32..30, -1.0f32..1.0).prop_map(|(e, x)| (x * 10f32.powi(e)).to_bits()),
    ]
}

fn bytes() -> impl Strategy<Value = Vec<u8>> {
    prop::collection::vec(word(), 0..64)
        .prop_map(|ws| ws.iter().flat_map(|w| w.to_le_bytes()).collect())
}

macro_rules! fuzz_family {
    ($name:ident, $fam:expr) => {
        proptest! {
            #![proptest_config(ProptestConfig {
                cases: cases(),
                failure_persistence: None,
                ..ProptestConfig::default()
            })]
            #[test]
            fn $name(data in bytes()) {
                run($fam, &data);
            }
        }
    };
}

fuzz_family!(fuzz_hemisphere, Family::Hemisphere);
fuzz_family!(fuzz_cap, Family::Cap);
fuzz_family!(fuzz_polygon, Family::Polygon);
fuzz_family!(fuzz_moments, Family::Moments);
fuzz_family!(fuzz_sh9, Family::Sh9);
fuzz_family!(fuzz_line, Family::Line);
fuzz_family!(fuzz_shaping, Family::Shaping);
fuzz_family!(fuzz_raster, Family::Raster);

proptest! {
    #![proptest_config(ProptestConfig {
        cases: cases(),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]
    /// The rasterizer's integer geometry on any `i32` coordinates (`raster_edges`).
    #[test]
    fn fuzz_raster_edges(data in bytes()) {
        run(Family::RasterEdges, &data);
    }
}

/// The two panics `fuzz_raster_edges` finds, as fixed inputs.
#[test]
fn raster_edge_setup_is_total() {
    use arealight::raster::edge::is_top_left;
    use arealight::raster::{Cull, EdgeTriangle, FixedPoint};
    let (lo, hi) = (
        FixedPoint::new(i32::MIN, i32::MIN),
        FixedPoint::new(i32::MAX, i32::MAX),
    );
    assert!(is_top_left(hi, lo), "an edge running up is a left edge");
    assert!(!is_top_left(lo, hi));
    let t = [lo, FixedPoint::new(0, 0), FixedPoint::new(16, 0)];
    assert_eq!(
        EdgeTriangle::new(t, Cull::None),
        None,
        "beyond MAX_COORD: refused"
    );
    let t = EdgeTriangle::new(
        [
            FixedPoint::new(0, 0),
            FixedPoint::new(64, 0),
            FixedPoint::new(0, 64),
        ],
        Cull::None,
    )
    .unwrap();
    assert_eq!(t.pixel_bounds(i32::MIN, 0, 4), None, "no columns");
    assert_eq!(t.pixel_bounds(4, 0, i32::MIN), None, "no rows");
}

/// Every family on the empty input, all-ones bits (NaN everywhere) and all zeros.
#[test]
fn fuzz_fixed_inputs() {
    for fam in FAMILIES {
        run(fam, &[]);
        run(fam, &[0xff; 256]);
        run(fam, &[0; 256]);
        run(fam, &[0x7f; 256]); // 3.39e38, near f32::MAX
    }
}

/// The polygon family reaches the shading code with every vertex count up to the capacity,
/// non-convex shapes included (random vertices alone rarely make a planar polygon: about 68
/// triangles, 18 quads, 3 pentagons and no 7- or 8-gons per 2000 inputs before the planar
/// generator): the counts over `cases()` inputs of the fuzzer's own distribution.
#[test]
fn planar_polygons_reach_the_shading_code() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let n = cases();
    let before = shaded_counts();
    for _ in 0..n {
        let data = bytes().new_tree(&mut runner).unwrap().current();
        run(Family::Polygon, &data);
    }
    let after = shaded_counts();
    for (b, name, min_per_2000) in [(0, "f64", 50), (1, "Fixed22", 25)] {
        let got: Vec<usize> = (0..9).map(|k| after[b][k] - before[b][k]).collect();
        println!("[fuzz] {name}: polygons shaded per {n} inputs, by vertex count 0..=8: {got:?}");
        for (k, &c) in got.iter().enumerate().skip(3) {
            assert!(
                c * 2000 >= min_per_2000 * n as usize,
                "{name}: {k}-gons: {c} of {n} inputs reach the shading code"
            );
        }
    }
}

/// `Real::to_fixed_i32` saturates for every backend and input, and the prepared rasterizer path
/// shades a material with negative colours (below -128 after the exposure) without a panic.
#[test]
fn to_fixed_i32_saturates() {
    use arealight::raster::{
        Affine, Camera, DrawOptions, Lit, Material, Mesh, PreparedMesh, PreparedVertex, Projection,
        Shading, Vertex,
    };
    use arealight::{HemisphereLight, Real, Rgb, Vec3};
    let _ = fuzzing::NEGATIVE_COLOURS_OVERFLOW;
    let v = |x: f64, y: f64, z: f64| Vec3::new(x, y, z);
    let cam = Camera::new(
        v(0.0, 0.0, 3.0),
        v(0.0, 0.0, 0.0),
        v(0.0, 1.0, 0.0),
        Projection::Perspective { fov_y: 1.0 },
        16,
        16,
    )
    .unwrap();
    let verts = [
        Vertex::new(v(-1.0, -1.0, 0.0), v(0.0, 0.0, 1.0)),
        Vertex::new(v(1.0, -1.0, 0.0), v(0.0, 0.0, 1.0)),
        Vertex::new(v(0.0, 1.0, 0.0), v(0.0, 0.0, 1.0)),
    ];
    let tris = [[0u16, 1, 2]];
    let mesh = Mesh::new(&verts, &tris).unwrap();
    let light = HemisphereLight::new(v(0.0, 0.0, 1.0)).unwrap();
    let opts = DrawOptions::new(Shading::Gouraud);
    for c in [1e3, -1e3] {
        let material = Material::matte(Rgb::splat(c)).unwrap();
        let mut storage = [PreparedVertex::<f64>::EMPTY; 3];
        let mut p = PreparedMesh::new(mesh, &mut storage).unwrap();
        p.transform(&cam, &Affine::identity());
        assert_eq!(p.shade(&cam, &Lit::new(&light, &material), &opts), 3);
    }
    for x in [-1e30, -3e9, f64::NEG_INFINITY] {
        assert_eq!(x.to_fixed_i32(24), i32::MIN, "f64 {x:e}");
        assert_eq!((x as f32).to_fixed_i32(24), i32::MIN, "f32 {x:e}");
    }
    assert_eq!(1e30f64.to_fixed_i32(24), i32::MAX);
}
