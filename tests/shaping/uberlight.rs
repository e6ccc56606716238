//! `LightFrame` and `Uberlight` against the reference light space built here by Gram-Schmidt.

use super::*;

// ---------------------------------------------------------------------------------------------
// LightFrame and Uberlight
// ---------------------------------------------------------------------------------------------

/// The reference light space: the basis built here from `direction` and `up` by Gram-Schmidt.
pub(super) fn ref_to_light(origin: V3, direction: V3, up: V3, p: V3) -> V3 {
    let ez = normalize(direction);
    let upn = normalize(up);
    let ey = normalize(sub(upn, scale(ez, dot(upn, ez))));
    let ex = cross(ey, ez);
    let dp = sub(p, origin);
    [dot(dp, ex), dot(dp, ey), dot(dp, ez)]
}

/// Random uberlights (frame, one of the case parameter sets) and points mostly in the beam:
/// `(origin, direction, up, s, f, points)`, inputs rounded to `T`.
pub(super) type UberCase = (V3, V3, V3, [f64; 5], [f64; 7], Vec<V3>);

pub(super) fn uber_cases<T: Real>(seed: u64) -> Vec<UberCase> {
    let mut rng = Rng::new(seed);
    let shapes = shape_params(&mut rng, 0);
    let falloffs = falloff_params(&mut rng, 0);
    let mut out = Vec::new();
    while out.len() < 300 {
        let origin = scale(rng.dir(), rng.range(0.0, 5.0));
        let direction = rng.sdir();
        let up = rng.sdir();
        if norm(cross(normalize(direction), normalize(up))) < 0.05 {
            continue;
        }
        let (origin, direction, up) = (rdv::<T>(origin), rdv::<T>(direction), rdv::<T>(up));
        let s = shapes[rng.below(shapes.len() as u64) as usize].map(rd::<T>);
        let f = falloffs[1 + rng.below(falloffs.len() as u64 - 1) as usize].map(rd::<T>);
        let points = (0..100)
            .map(|_| {
                // A point on the axis at depth z, pushed sideways by up to 1.3 max(A, B) z.
                let z = rng.range(0.05, 6.0);
                let side = scale(rng.dir(), z * rng.range(0.0, 1.3) * s[2].max(s[3]));
                rdv::<T>(add(add(origin, scale(normalize(direction), z)), side))
            })
            .collect();
        out.push((origin, direction, up, s, f, points));
    }
    out
}

pub(super) fn uber<T: Real>(
    origin: V3,
    direction: V3,
    up: V3,
    s: [f64; 5],
    f: [f64; 7],
) -> Option<Uberlight<T>> {
    let frame = LightFrame::<T>::new(v(origin), v(direction), v(up)).ok()?;
    Some(Uberlight::new(frame, se::<T>(s).ok()?, fo::<T>(f).ok()?))
}

/// The frame's checks shared by every backend: orthonormal (to `ortho`), right-handed, +y
/// toward `up`; behind the light and at non-finite or overflowing points the factor is 0 or
/// finite.
pub(super) fn frame_checks<T: Real>(
    name: &str,
    u: &Uberlight<T>,
    origin: V3,
    direction: V3,
    up: V3,
    ortho: f64,
) {
    let fr = &u.frame;
    let (ex, ey, ez) = (
        fr.right().to_f64(),
        fr.up().to_f64(),
        fr.direction().to_f64(),
    );
    for (a, b) in [(ex, ey), (ey, ez), (ez, ex)] {
        assert!(dot(a, b).abs() <= ortho, "{name}: {}", dot(a, b));
    }
    for a in [ex, ey, ez] {
        assert!((norm(a) - 1.0).abs() <= ortho, "{name}: {}", norm(a));
    }
    assert!(dot(cross(ex, ey), ez) > 0.99 && dot(ey, up) > 0.0);
    let behind = sub(origin, scale(normalize(direction), 1.0));
    assert_eq!(u.factor(v(behind)).to_f64(), 0.0);
    assert_eq!(u.factor(v(origin)).to_f64(), 0.0);
    let big = t_max::<T>();
    for p in [
        [f64::NAN, 0.0, 0.0],
        [f64::INFINITY, 0.0, 0.0],
        [big, -big, big],
        [-big, big, -big],
    ] {
        let val = u.factor(v(p)).to_f64();
        assert!(val.is_finite() && val >= 0.0, "{name} p={p:?}: {val}");
    }
}

#[test]
fn uberlight_f64_vs_reference() {
    let mut e = MaxErr::new("uberlight factor f64 vs reference (rel)");
    let mut e_frame = MaxErr::new("light frame f64 to_light vs reference (rel)");
    for (origin, direction, up, s, f, points) in uber_cases::<f64>(0x0be7) {
        let u = uber::<f64>(origin, direction, up, s, f).unwrap();
        frame_checks("f64", &u, origin, direction, up, 8.0 * f64::EPSILON);
        for p in points {
            let l = ref_to_light(origin, direction, up, p);
            let got_l = u.frame.to_light(v(p)).to_f64();
            let r = norm(sub(p, origin));
            for k in 0..3 {
                e_frame.add(got_l[k] / r, l[k] / r, || format!("p={p:?}"));
            }
            let want = ref_shape(l, s) * ref_falloff(l[2].max(0.0), f);
            let got = u.factor(v(p));
            let sc = want.abs().max(1.0);
            e.add(got / sc, want / sc, || {
                format!("origin={origin:?} dir={direction:?} up={up:?} s={s:?} f={f:?} p={p:?}")
            });
        }
    }
    check_all(&[(&e_frame, 1e-14), (&e, tol_f64("uberlight"))]);
}

pub(super) fn uberlight_vs_f64_for<T: Real>(name: &str, bounds: LowpBounds) {
    let mut e = Bounded::new(&format!("uberlight factor {name} vs f64 (rel)"), bounds);
    let mut e_frame = MaxErr::new(&format!(
        "light frame {name} to_light vs f64 (rel to |p - origin|)"
    ));
    let ortho = 8.0 * T::EPSILON.to_f64();
    for (origin, direction, up, s, f, points) in uber_cases::<T>(0x0be8) {
        let lo = uber::<T>(origin, direction, up, s, f).unwrap();
        let hi = uber::<f64>(origin, direction, up, s, f).unwrap();
        frame_checks(name, &lo, origin, direction, up, ortho);
        for p in points {
            let r = norm(sub(p, origin));
            let (got_l, want_l) = (
                lo.frame.to_light(v(p)).to_f64(),
                hi.frame.to_light(v(p)).to_f64(),
            );
            for k in 0..3 {
                e_frame.add(got_l[k] / r, want_l[k] / r, || format!("p={p:?}"));
            }
            let want = hi.factor(v(p));
            let got = lo.factor(v(p)).to_f64();
            assert!(got.is_finite() && got >= 0.0);
            let sc = want.abs().max(1.0);
            let x = flat(&[origin, direction, up, p], &[&s[..], &f[..]].concat());
            let sens = sensitivity(
                |x| {
                    let s = [x[12], x[13], x[14], x[15], x[16]];
                    let f = [x[17], x[18], x[19], x[20], x[21], x[22], x[23]];
                    let u = uber::<f64>(v3_at(x, 0), v3_at(x, 1), v3_at(x, 2), s, f)?;
                    Some(u.factor(v(v3_at(x, 3))) / sc)
                },
                &x,
            );
            let c = Cond {
                m: 0,
                sens,
                near: None,
            };
            e.add(got / sc, want / sc, c, || {
                format!("origin={origin:?} dir={direction:?} up={up:?} s={s:?} f={f:?} p={p:?}")
            });
        }
    }
    // The frame: a few ULPs of |p - origin| (its axes get a Newton step toward unit length, so
    // Fast32's cheap sqrt does not show).
    let frame_tol = 16.0 * T::EPSILON.to_f64();
    check_all(&[(&e_frame, frame_tol)]);
    check_bounded(&[&e]);
}

#[test]
fn light_frame_validation() {
    let o = Vec3::new(0.0, 0.0, 0.0);
    let z = Vec3::new(0.0, 0.0, 1.0);
    let y = Vec3::new(0.0, 1.0, 0.0);
    assert_eq!(
        LightFrame::<f64>::new(Vec3::new(f64::NAN, 0.0, 0.0), z, y),
        Err(Error::NotFinite("origin"))
    );
    assert_eq!(
        LightFrame::new(o, Vec3::new(0.0, 0.0, 0.0), y),
        Err(Error::ZeroLength("direction"))
    );
    assert_eq!(
        LightFrame::new(o, z, Vec3::new(0.0, 0.0, 0.0)),
        Err(Error::ZeroLength("up"))
    );
    assert_eq!(
        LightFrame::new(o, z, Vec3::new(0.0, f64::INFINITY, 0.0)),
        Err(Error::NotFinite("up"))
    );
    let parallel = Err(Error::Parallel {
        a: "up",
        b: "direction",
    });
    assert_eq!(LightFrame::new(o, z, z), parallel);
    assert_eq!(LightFrame::new(o, z, Vec3::new(0.0, 0.0, -3.0)), parallel);
    assert_eq!(LightFrame::new(o, z, Vec3::new(1e-300, 0.0, 1.0)), parallel);
    // Nearly parallel but resolvable: still an orthonormal frame.
    let fr = LightFrame::new(o, z, Vec3::new(1e-9, 1e-12, 1.0)).unwrap();
    let (ex, ey, ez) = (
        fr.right().to_f64(),
        fr.up().to_f64(),
        fr.direction().to_f64(),
    );
    for (a, b) in [(ex, ey), (ey, ez), (ez, ex)] {
        assert!(dot(a, b).abs() < 1e-15);
    }
    assert!((ey[0] - 1.0).abs() < 1e-6, "{ey:?}");
    // The axes as documented: z along the beam, y toward up, x = y x z.
    let fr = LightFrame::new(Vec3::new(1.0, 2.0, 3.0), Vec3::new(0.0, 0.0, -2.0), y).unwrap();
    assert_eq!(
        fr.to_light(Vec3::new(1.0, 2.0, 3.0)),
        Vec3::new(0.0, 0.0, 0.0)
    );
    assert_eq!(
        fr.to_light(Vec3::new(1.0, 2.0, 0.0)),
        Vec3::new(0.0, 0.0, 3.0)
    );
    assert_eq!(
        fr.to_light(Vec3::new(1.0, 3.0, 3.0)),
        Vec3::new(0.0, 1.0, 0.0)
    );
    assert_eq!(
        fr.to_light(Vec3::new(0.0, 2.0, 3.0)),
        Vec3::new(1.0, 0.0, 0.0)
    );
}
