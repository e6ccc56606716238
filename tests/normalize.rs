//! Normalization of the float types (`Real::normalize3`, `Vec3::normalize`): every finite
//! nonzero vector has a direction, however small or large its length.
//!
//! - Direct: f32 and f64 vectors over the whole exponent range (subnormal components, lengths
//!   whose squares under- or overflow) against the direction and length computed in a wider
//!   type (f64 for f32; for f64, double-double arithmetic on the vector scaled into the middle
//!   of the range by a power of two, which is exact).
//! - Through the models' public calls: a normal (or reflected direction) of length 1e-30 in
//!   f32 and 1e-200 in f64, and of length 1e30 / 1e200, gives the same result as the same call
//!   with the normal scaled to unit length. These inputs used to be refused ("n has zero
//!   length") or answered 0.
//! - Zero, infinite and NaN vectors are still refused.

use arealight::{
    CapLight, Error, Fast32, HemisphereLight, LineLight, PhongLobe, PolygonLight, Real, Sh9,
    SkyGround, SphereLight, Vec3,
};

fn v<T: Real>(a: [f64; 3]) -> Vec3<T> {
    Vec3::from_f64(a)
}

/// A deterministic generator (xorshift64*).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn signed(&mut self) -> f64 {
        2.0 * self.unit() - 1.0
    }
}

/// f32 against f64: components with independent exponents over the whole f32 range
/// (including subnormals), both for the unit vector (within 3 ULPs of 1 per component,
/// measured as an absolute error since every component is at most 1) and the length (within
/// 2 ULPs, relative).
#[test]
fn f32_every_exponent_against_f64() {
    let mut rng = Rng(0x5eed_0f32);
    let (mut worst_dir, mut worst_len, mut cold) = (0f64, 0f64, 0u32);
    for i in 0..400_000 {
        // A common exponent in [-150, 128] and per-component spreads of up to 2^40.
        let e = -150.0 + 278.0 * rng.unit();
        let c: [f32; 3] = core::array::from_fn(|_| {
            let spread = if i % 3 == 0 { 0.0 } else { -40.0 * rng.unit() };
            (rng.signed() * 2f64.powf(e + spread)) as f32
        });
        let c64 = c.map(f64::from);
        let n64 = (c64[0] * c64[0] + c64[1] * c64[1] + c64[2] * c64[2]).sqrt();
        let got = Vec3::new(c[0], c[1], c[2]).normalize_with_length();
        if c.iter().all(|&x| x == 0.0) {
            assert!(got.is_none(), "{c:?}");
            continue;
        }
        let (u, len) = got.unwrap_or_else(|| panic!("refused {c:?}"));
        let s2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
        if !(s2 >= 2f32.powi(-100) && s2 <= f32::MAX) {
            cold += 1;
        }
        for (a, b) in u.to_f64().iter().zip(c64.iter().map(|x| x / n64)) {
            worst_dir = worst_dir.max((a - b).abs() / f64::from(f32::EPSILON));
        }
        if n64 <= f64::from(f32::MAX) && n64 >= f64::from(f32::MIN_POSITIVE) {
            worst_len = worst_len.max((f64::from(len) / n64 - 1.0).abs() / f64::from(f32::EPSILON));
        } else if n64 > f64::from(f32::MAX) {
            assert!(len == f32::INFINITY, "{c:?}: length {len}");
        }
        let u_len = u.to_f64().iter().map(|x| x * x).sum::<f64>().sqrt();
        assert!(
            (u_len - 1.0).abs() <= 4.0 * f64::from(f32::EPSILON),
            "{c:?}: |u| = {u_len}"
        );
    }
    println!(
        "f32 normalize: direction within {worst_dir:.2} ULP (of 1), length within {worst_len:.2} \
         ULP; {cold} of 400000 vectors took the cold path"
    );
    assert!(cold > 100_000, "the sweep must exercise the cold path");
    assert!(worst_dir <= 3.0, "direction {worst_dir} ULP");
    assert!(worst_len <= 2.0, "length {worst_len} ULP");
}

/// Fast32 normalizes with f32's operations: the same bits as f32 (checked against f64 above)
/// for every vector of the same sweep over the whole f32 range, with and without the length,
/// and the same refusals.
#[test]
fn fast32_normalizes_as_f32() {
    let mut rng = Rng(0x5eed_fa32);
    let mut tiny = 0u32;
    for i in 0..200_000 {
        let e = -150.0 + 278.0 * rng.unit();
        let c: [f32; 3] = core::array::from_fn(|_| {
            let spread = if i % 3 == 0 { 0.0 } else { -40.0 * rng.unit() };
            (rng.signed() * 2f64.powf(e + spread)) as f32
        });
        let fast = Vec3::new(Fast32(c[0]), Fast32(c[1]), Fast32(c[2]));
        let plain = Vec3::new(c[0], c[1], c[2]);
        let bits = |u: Vec3<Fast32>| [u.x.0, u.y.0, u.z.0].map(f32::to_bits);
        let want = plain.normalize_with_length();
        let got = fast.normalize_with_length();
        assert_eq!(
            got.map(|(u, len)| (bits(u), len.0.to_bits())),
            want.map(|(u, len)| ([u.x, u.y, u.z].map(f32::to_bits), len.to_bits())),
            "{c:?}"
        );
        assert_eq!(
            fast.normalize().map(bits),
            plain.normalize().map(|u| [u.x, u.y, u.z].map(f32::to_bits)),
            "{c:?}"
        );
        // Below the former rescaled form's threshold (`Real::TINY`), which refused them.
        if want.is_some() && plain.max_abs() <= 1e-18 {
            tiny += 1;
        }
    }
    assert!(
        tiny > 10_000,
        "the sweep must reach vectors below TINY: {tiny}"
    );
}

/// The length of `s` (components near 1) in double-double arithmetic, as `(hi, lo)`: the
/// squares and their sum error-free (`mul_add` and two-sum), then one Newton correction of
/// the square root. Within a few units of 2^-106, relative.
fn length_dd(s: [f64; 3]) -> (f64, f64) {
    let (mut hi, mut lo) = (0.0f64, 0.0f64);
    for x in s {
        let p = x * x;
        let pe = x.mul_add(x, -p);
        let t = hi + p;
        let bb = t - hi;
        let e = (hi - (t - bb)) + (p - bb);
        hi = t;
        lo += e + pe;
    }
    let (h, l) = (hi + lo, lo - ((hi + lo) - hi));
    let r = h.sqrt();
    let resid = (-r).mul_add(r, h) + l;
    (r, resid / (2.0 * r))
}

/// f64: the reference is the same vector scaled by a power of two that brings it to length
/// ~1 (exact), its length in double-double ([`length_dd`]) and each component divided by it
/// with one correction term.
#[test]
fn f64_every_exponent_against_double_double() {
    let mut rng = Rng(0x5eed_0f64);
    let (mut worst_dir, mut worst_len, mut cold) = (0f64, 0f64, 0u32);
    for i in 0..200_000 {
        let e = -1075.0 + 2099.0 * rng.unit();
        let c: [f64; 3] = core::array::from_fn(|_| {
            let spread = if i % 3 == 0 { 0.0 } else { -200.0 * rng.unit() };
            rng.signed() * 2f64.powf((e + spread).max(-1074.0))
        });
        let m = c.iter().fold(0f64, |m, x| m.max(x.abs()));
        if m == 0.0 || !m.is_finite() {
            continue;
        }
        let s2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
        if !(s2 >= 2f64.powi(-960) && s2 <= f64::MAX) {
            cold += 1;
        }
        let k = -(m.log2().floor() as i32);
        // Two steps: 2^k alone may not be representable.
        let (k1, k2) = (k / 2, k - k / 2);
        let s = c.map(|x| x * 2f64.powi(k1) * 2f64.powi(k2));
        let (lh, ll) = length_dd(s);
        let (u, len) = Vec3::new(c[0], c[1], c[2])
            .normalize_with_length()
            .unwrap_or_else(|| panic!("refused {c:?}"));
        for (a, x) in u.to_f64().iter().zip(s) {
            // x / (lh + ll) to first order in ll / lh.
            let q = x / lh;
            let want = q - q * (ll / lh) + (-q).mul_add(lh, x) / lh;
            worst_dir = worst_dir.max((a - want).abs() / f64::EPSILON);
        }
        let scale = 2f64.powi(-k1) * 2f64.powi(-k2);
        let want = lh * scale;
        if want.is_finite() && want >= f64::MIN_POSITIVE {
            let rel = ((len - want) / scale - ll) / lh;
            worst_len = worst_len.max(rel.abs() / f64::EPSILON);
        }
    }
    println!(
        "f64 normalize: direction within {worst_dir:.2} ULP (of 1), length within {worst_len:.2} \
         ULP; {cold} of 200000 vectors took the cold path"
    );
    assert!(cold > 50_000, "the sweep must exercise the cold path");
    assert!(worst_dir <= 3.0, "direction {worst_dir} ULP");
    assert!(worst_len <= 2.0, "length {worst_len} ULP");
}

#[test]
fn zero_infinite_and_nan_are_refused() {
    fn check<T: Real>() {
        let z = T::ZERO;
        for c in [
            [0.0, 0.0, 0.0],
            [-0.0, 0.0, -0.0],
            [f64::INFINITY, 0.0, 0.0],
            [1.0, f64::NEG_INFINITY, 1.0],
            [f64::NAN, 1.0, 1.0],
            [1.0, 1.0, f64::NAN],
        ] {
            assert!(v::<T>(c).normalize().is_none(), "{c:?}");
            assert!(v::<T>(c).normalize_with_length().is_none(), "{c:?}");
        }
        assert!(Vec3::new(z, z, z).normalize().is_none());
    }
    check::<f32>();
    check::<f64>();
    // Fast32 has f32's normalization (see `fast32_normalizes_as_f32`).
    check::<Fast32>();
    // The smallest subnormal has a direction.
    let t = f32::from_bits(1);
    let (u, len) = Vec3::new(0.0, -t, 0.0).normalize_with_length().unwrap();
    assert_eq!((u, len), (Vec3::new(0.0, -1.0, 0.0), t));
    let t = f64::from_bits(1);
    let (u, len) = Vec3::new(t, 0.0, 0.0).normalize_with_length().unwrap();
    assert_eq!((u, len), (Vec3::new(1.0, 0.0, 0.0), t));
    // Components at the top of the range: a direction, and an infinite length.
    let m = f32::MAX;
    let (u, len) = Vec3::new(m, m, 0.0).normalize_with_length().unwrap();
    let h = core::f32::consts::FRAC_1_SQRT_2;
    assert!((u.x - h).abs() <= f32::EPSILON && (u.y - h).abs() <= f32::EPSILON && u.z == 0.0);
    assert_eq!(len, f32::INFINITY);
}

/// One model call with a normal (or direction) `n`: `Ok` value or the error.
type Call<T> = Box<dyn Fn(Vec3<T>) -> Result<f64, Error>>;

/// The calls under test: every model family's per-sample function that normalizes a direction.
fn calls<T: Real + 'static>() -> Vec<(&'static str, Call<T>)> {
    let axis = v::<T>([0.2, -0.3, 0.9]);
    let p = v::<T>([0.1, 0.2, 0.0]);
    let quad = [
        v::<T>([-0.5, -0.4, 1.5]),
        v::<T>([0.6, -0.5, 1.5]),
        v::<T>([0.5, 0.7, 1.5]),
        v::<T>([-0.6, 0.5, 1.5]),
    ];
    let cap = CapLight::new(axis, T::from_f64(0.4)).unwrap();
    let sphere = SphereLight::new(v([0.3, -0.2, 2.0]), T::from_f64(0.7)).unwrap();
    let poly = PolygonLight::<T, 4>::new(&quad).unwrap();
    let hemi = HemisphereLight::new(axis).unwrap();
    let sky = SkyGround::new(
        axis,
        arealight::Rgb::new(T::ONE, T::from_f64(0.5), T::from_f64(0.25)),
        arealight::Rgb::splat(T::from_f64(0.1)),
    )
    .unwrap();
    let sh9 = Sh9::disc(axis, T::from_f64(0.5), arealight::Rgb::splat(T::ONE))
        .unwrap()
        .prepare();
    let line = LineLight::new(v([-0.5, 0.3, 1.0]), v([0.7, 0.1, 1.4])).unwrap();
    let lobe = PhongLobe::<T>::new(15).unwrap();
    let cap2 = cap;
    vec![
        (
            "cap lambert",
            Box::new(move |n| Ok(cap.lambert(n).to_f64())),
        ),
        (
            "cap lambert_hermite",
            Box::new(move |n| Ok(cap2.lambert_hermite(n).to_f64())),
        ),
        (
            "sphere try_lambert",
            Box::new(move |n| sphere.try_lambert(p, n).map(T::to_f64)),
        ),
        (
            "polygon try_lambert",
            Box::new(move |n| poly.try_lambert(p, n).map(T::to_f64)),
        ),
        (
            "polygon try_phong m=15",
            Box::new(move |r| {
                PolygonLight::<T, 4>::new(&quad)
                    .unwrap()
                    .try_phong(&lobe, p, r)
                    .map(T::to_f64)
            }),
        ),
        (
            "hemisphere lambert_const",
            Box::new(move |n| Ok(hemi.lambert_const(n).to_f64())),
        ),
        (
            "sky_ground irradiance",
            Box::new(move |n| Ok(sky.irradiance(n).r.to_f64())),
        ),
        (
            "sh9 irradiance",
            Box::new(move |n| Ok(sh9.irradiance(n).g.to_f64())),
        ),
        (
            "line try_lambert k=1",
            Box::new(move |n| {
                line.try_lambert(p, n, arealight::Decay::new(1).unwrap())
                    .map(T::to_f64)
            }),
        ),
        (
            "cap phong m=15",
            Box::new(move |r| Ok(cap.phong(&lobe, r).to_f64())),
        ),
    ]
}

/// Each call with `dir * scale` against the same call with `dir` itself (unit length): within
/// `tol` (absolute; the results are at most about 1).
fn scaled_normal_matches_unit<T: Real + 'static>(scales: &[f64], tol: f64) {
    let dirs = [
        [0.0, 0.0, 1.0],
        [0.36, -0.48, 0.8],
        [-0.6, 0.0, 0.8],
        [0.48, 0.6, -0.64],
    ];
    for (name, call) in calls::<T>() {
        for d in dirs {
            let unit = call(v(d)).unwrap_or_else(|e| panic!("{name}: unit {d:?}: {e:?}"));
            for &s in scales {
                let n = v::<T>(d) * T::from_f64(s);
                let got = call(n).unwrap_or_else(|e| panic!("{name}: {d:?} x {s:e}: {e:?}"));
                assert!(
                    (got - unit).abs() <= tol,
                    "{name}: {d:?} x {s:e}: {got:e} against {unit:e} at unit length"
                );
            }
        }
    }
}

#[test]
fn f32_normal_of_length_1e_minus_30_and_1e30() {
    scaled_normal_matches_unit::<f32>(&[1e-30, 1e-35, 1e30, 3e37], 8.0 * f64::from(f32::EPSILON));
}

#[test]
fn f64_normal_of_length_1e_minus_200_and_1e200() {
    scaled_normal_matches_unit::<f64>(&[1e-200, 1e-300, 1e200, 1e307], 8.0 * f64::EPSILON);
}
