//! The line light's semantics (constructors, degenerate and symmetric cases), and invalid and
//! adversarial inputs: no panic, no NaN.

use super::*;

// ---------------------------------------------------------------------------------------------
// Semantics, invalid and adversarial inputs
// ---------------------------------------------------------------------------------------------

#[test]
fn semantics() {
    let z = Vec3::new(0.0, 0.0, 1.0);
    let line = LineLight::<f64>::new(Vec3::new(-1.0, 0.0, 2.0), Vec3::new(1.0, 0.0, 2.0)).unwrap();
    // Wholly below the horizon.
    assert_eq!(
        line.lambert(Vec3::new(0.0, 0.0, 0.0), -z, Decay::InverseSquare),
        0.0
    );
    // Half clipped: the symmetric segment with n along it gives half the k = 1 integral of
    // (s/rho^2) ... and the two halves sum to the unclipped value with n and -n.
    let p = Vec3::new(0.3, 0.1, 0.0);
    let n = Vec3::new(0.0, 0.0, 1.0);
    for k in 0..4 {
        let d = Decay::new(k).unwrap();
        let nx = Vec3::new(1.0, 0.0, 0.0);
        let both = line.lambert(p, nx, d) + line.lambert(p, -nx, d);
        // (L.n)+ + (L.-n)+ = |L.x|: positive everywhere except at the crossing.
        assert!(both > 0.0);
        assert!(line.lambert(p, n, d) > 0.0);
    }
    // Invalid inputs.
    assert_eq!(
        LineLight::<f64>::new(Vec3::new(1.0, 2.0, 3.0), Vec3::new(1.0, 2.0, 3.0)),
        Err(Error::ZeroLength("segment"))
    );
    assert_eq!(
        LineLight::<f32>::new(Vec3::new(f32::NAN, 0.0, 0.0), z.map32()),
        Err(Error::NotFinite("a"))
    );
    let on = Vec3::new(0.25, 0.0, 2.0);
    assert_eq!(
        line.try_lambert(on, z, Decay::Constant),
        Err(Error::PointOnSegment)
    );
    assert_eq!(
        line.try_lambert(line.a(), z, Decay::Constant),
        Err(Error::PointOnSegment)
    );
    let lobe = PhongLobe::new(8).unwrap();
    assert_eq!(
        line.try_phong_peak(&lobe, on, z),
        Err(Error::PointOnSegment)
    );
    assert_eq!(line.phong_peak(&lobe, on, z), 0.0);
    assert_eq!(
        line.try_lambert(p, Vec3::new(0.0, 0.0, 0.0), Decay::Constant),
        Err(Error::ZeroLength("n"))
    );
    assert_eq!(Decay::new(4), Err(Error::DecayOutOfRange));
    // Just beyond the segment, on its line: valid.
    let beyond = Vec3::new(1.5, 0.0, 2.0);
    assert!(
        line.try_lambert(beyond, Vec3::new(-1.0, 0.0, 0.0), Decay::Inverse)
            .unwrap()
            > 0.0
    );
    // m = 0: 1 if any point is in front of the plane normal to r, else 0.
    let l0 = PhongLobe::new(0).unwrap();
    assert_eq!(
        line.phong_peak(&l0, Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, -0.45)),
        1.0
    );
    assert_eq!(
        line.phong_peak(&l0, Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 0.0, -1.0)),
        0.0
    );
    // The closest angular point: r straight at the segment's middle gives 1.
    assert!((line.phong_peak(&lobe, Vec3::new(0.0, 0.0, 0.0), z) - 1.0).abs() < 1e-15);

    // Parallelogram.
    let rect = ParallelogramLight::<f64>::new(
        Vec3::new(-1.0, -1.0, 2.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 2.0, 0.0),
    )
    .unwrap();
    assert_eq!(
        rect.phong_peak(&lobe, Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.2, 0.3, 1.0)),
        1.0
    );
    // In the plane, the definition (the best over the light's points, all seen in the
    // plane): from inside every in-plane direction reaches the light; from outside only those
    // toward it. (Polygon models give 0 there; a peak is not one.)
    let x = Vec3::new(1.0, 0.0, 0.0);
    for (q, r, want) in [
        (Vec3::new(0.0, 0.0, 2.0), x, 1.0),
        (Vec3::new(5.0, 0.0, 2.0), x, 0.0),
        (Vec3::new(5.0, 0.0, 2.0), -x, 1.0),
    ] {
        assert_eq!(
            rect.try_phong_peak(&lobe, q, r),
            Ok(want),
            "p = {q:?}, r = {r:?}"
        );
    }
    // Out of the plane by r's tilt: (cos 0.3)^m from outside, in the plane.
    let tilted = Vec3::new(-0.3f64.cos(), 0.0, 0.3f64.sin());
    let got = rect.phong_peak(&lobe, Vec3::new(5.0, 0.0, 2.0), tilted);
    assert!(
        (got - 0.3f64.cos().powi(lobe.exponent() as i32)).abs() < 1e-13,
        "{got}"
    );
    // Behind: r away from the light.
    assert_eq!(rect.phong_peak(&lobe, Vec3::new(0.0, 0.0, 0.0), -z), 0.0);
    // From the back side it is lit too (two-sided).
    assert_eq!(rect.phong_peak(&lobe, Vec3::new(0.0, 0.0, 4.0), -z), 1.0);
    assert_eq!(
        ParallelogramLight::<f64>::new(z, Vec3::new(1.0, 1.0, 0.0), Vec3::new(2.0, 2.0, 0.0)),
        Err(Error::ZeroArea)
    );
    assert_eq!(
        ParallelogramLight::<f64>::new(z, Vec3::new(0.0, 0.0, 0.0), Vec3::new(2.0, 2.0, 0.0)),
        Err(Error::ZeroArea)
    );
}

trait Map32 {
    fn map32(self) -> Vec3<f32>;
}
impl Map32 for Vec3<f64> {
    fn map32(self) -> Vec3<f32> {
        Vec3::from_f64(self.to_f64())
    }
}

/// Values that break naive code: NaN, infinities, huge, tiny, subnormal, zero.
pub(super) fn nasty() -> Vec<f64> {
    vec![
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::MAX,
        -f64::MAX,
        1e300,
        -3e38,
        1e-300,
        5e-324,
        -1e-310,
        1e-45,
        0.0,
        -0.0,
        1.0,
        -0.5,
        2.0,
    ]
}

pub(super) fn adversarial_inputs<T: Real>() {
    let vals = nasty();
    let mut rng = Rng::new(0xbad);
    let pick = |rng: &mut Rng| -> V3 {
        let mut out = [0.0; 3];
        for o in &mut out {
            *o = if rng.below(3) == 0 {
                vals[rng.below(vals.len() as u64) as usize]
            } else {
                rng.range(-2.0, 2.0)
            };
        }
        out
    };
    let lobes: Vec<PhongLobe<T>> = [0u32, 1, 7, 128, 1 << 20]
        .iter()
        .map(|&m| PhongLobe::new(m).unwrap())
        .collect();
    for i in 0..20_000 {
        let (a, b, p, n, c) = (
            pick(&mut rng),
            pick(&mut rng),
            pick(&mut rng),
            pick(&mut rng),
            pick(&mut rng),
        );
        if let Ok(line) = LineLight::<T>::new(v(a), v(b)) {
            for k in 0..4 {
                let d = Decay::new(k).unwrap();
                let x = line.lambert(v(p), v(n), d).to_f64();
                assert!(
                    x.is_finite() && x >= 0.0,
                    "lambert {x} a={a:?} b={b:?} p={p:?} n={n:?} k={k}"
                );
                if let Ok(y) = line.try_lambert(v(p), v(n), d) {
                    assert_eq!(y.to_f64(), x);
                }
            }
            let x = line.phong_peak(&lobes[i % 5], v(p), v(n)).to_f64();
            assert!((0.0..=1.0).contains(&x), "line peak {x}");
        }
        if let Ok(rect) = ParallelogramLight::<T>::new(v(a), v(b), v(c)) {
            let x = rect.phong_peak(&lobes[i % 5], v(p), v(n)).to_f64();
            assert!(
                (0.0..=1.0).contains(&x),
                "rect peak {x} o={a:?} eu={b:?} ev={c:?} p={p:?} r={n:?}"
            );
        }
    }
    // Structured extremes: a huge segment seen from a huge distance, a subnormal segment.
    let big = T::from_f64(1e38);
    let line = LineLight::<T>::new(
        Vec3::new(-big, T::ZERO, T::ZERO),
        Vec3::new(big, T::ZERO, T::ZERO),
    )
    .unwrap();
    for k in 0..4 {
        let x = line.lambert(
            Vec3::new(T::ZERO, big, -big),
            Vec3::new(T::ZERO, -T::ONE, T::ONE),
            Decay::new(k).unwrap(),
        );
        assert!(x.is_finite() && x >= T::ZERO);
        if k == 0 {
            // Scale-free: the same as the unit geometry.
            let unit = LineLight::<T>::new(
                Vec3::new(-T::ONE, T::ZERO, T::ZERO),
                Vec3::new(T::ONE, T::ZERO, T::ZERO),
            )
            .unwrap()
            .lambert(
                Vec3::new(T::ZERO, T::ONE, -T::ONE),
                Vec3::new(T::ZERO, -T::ONE, T::ONE),
                Decay::Constant,
            );
            assert!((x - unit).abs().to_f64() < 1e-5, "{x:?} vs {unit:?}");
        }
    }
}

#[test]
fn adversarial_inputs_never_panic_or_give_nan() {
    adversarial_inputs::<f64>();
    adversarial_inputs::<f32>();
    adversarial_inputs::<Fast32>();
}

/// `[rect_phong_peak]` with p in the parallelogram's plane, outside it: the definition (the
/// largest `((u.r)+)^m` over the light's points) holds there too; it is not a polygon model's
/// degenerate case (a peak has a value wherever some point of the light is seen: in the plane
/// every direction toward the light lies in the plane). The case: p = (3, 0, 2),
/// r = (-1, 0.2, 0), origin (-1, -1, 2), eu = (2, 0, 0), ev = (0, 2, 0), m = 8 gives 1 (r
/// points at the light); then random in-plane configurations against the brute force.
#[test]
fn rect_peak_in_plane_follows_the_definition() {
    let light = ParallelogramLight::<f64>::new(
        Vec3::new(-1.0, -1.0, 2.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 2.0, 0.0),
    )
    .unwrap();
    let lobe = PhongLobe::<f64>::new(8).unwrap();
    let got = light.phong_peak(&lobe, Vec3::new(3.0, 0.0, 2.0), Vec3::new(-1.0, 0.2, 0.0));
    assert_eq!(got, 1.0, "the issue's case");
    let mut rng = Rng::new(0x1a7e);
    let mut e = MaxErr::new("rect_phong_peak f64 vs brute force, p in the plane (outside)");
    for _ in 0..200 {
        let o = rbox(&mut rng, 2.0);
        let eu = scale(rng.dir(), rng.range(0.3, 2.0));
        let ev = scale(
            normalize(cross(cross(eu, rng.dir()), eu)),
            rng.range(0.3, 2.0),
        );
        let nu = normalize(cross(eu, ev));
        // p in the plane, outside: beyond an edge or a corner.
        let (s, t) = match rng.below(3) {
            0 => (rng.range(1.2, 3.0), rng.range(0.0, 1.0)),
            1 => (rng.range(-2.0, -0.2), rng.range(-2.0, 3.0)),
            _ => (rng.range(1.2, 3.0), rng.range(1.2, 3.0)),
        };
        let p = add(o, add(scale(eu, s), scale(ev, t)));
        // r toward a point of the light (peak 1), or tilted off the plane, or away.
        let x = add(o, add(scale(eu, rng.unit()), scale(ev, rng.unit())));
        let toward = normalize(sub(x, p));
        let r = match rng.below(3) {
            0 => toward,
            1 => normalize(add(toward, scale(nu, rng.range(-0.5, 0.5)))),
            _ => rng.dir(),
        };
        let cos = lq::rect_max_cos(o, eu, ev, p, r);
        let pl = ParallelogramLight::<f64>::new(v(o), v(eu), v(ev)).unwrap();
        for m in [0u32, 1, 8, 128] {
            let got = pl.phong_peak(&PhongLobe::new(m).unwrap(), v(p), v(r));
            e.add(got, lq::lobe(cos, m), || {
                format!("m={m} o={o:?} eu={eu:?} ev={ev:?} p={p:?} r={r:?}")
            });
        }
    }
    e.check(tol_f64("rect_phong_peak"));
}
