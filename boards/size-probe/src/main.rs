//! The size probe: a minimal firmware that calls the models of the enabled arealight family
//! (f32, or `Fixed22` with the `fixed` feature) on inputs the compiler cannot see, so the
//! linker keeps exactly the code a firmware using that family would carry. `measure.sh`
//! builds it once per family and target and reports `.text` minus the empty probe's.
//!
//! Inputs and results pass through `core::hint::black_box`, so nothing is constant-folded
//! away; every model of the family is called once.
#![no_std]
#![no_main]
#![forbid(unsafe_code)]
// The empty probe (no family enabled) uses none of the helpers below.
#![allow(unused_imports, unused_variables, unused_mut, dead_code)]

use arealight::{Real, Rgb, Vec3};
use core::hint::black_box;
use cortex_m_rt::entry;

#[cfg(feature = "fixed")]
type T = arealight::Fixed22;
#[cfg(not(feature = "fixed"))]
type T = f32;

/// An input the compiler cannot see through.
fn input(i: usize) -> T {
    black_box(T::from_f64(0.25 * i as f64))
}

/// An integer input the compiler cannot see through.
fn int(i: u32) -> u32 {
    black_box(i)
}

fn vec(i: usize) -> Vec3<T> {
    Vec3::new(input(i), input(i + 1), input(i + 2))
}

fn sink(x: T) {
    black_box(x);
}

#[entry]
fn main() -> ! {
    let (p, n, r) = (vec(0), vec(3), vec(5));
    #[cfg(feature = "hemisphere")]
    {
        if let Ok(h) = arealight::HemisphereLight::new(vec(1)) {
            sink(h.lambert_const(n) + h.lambert_cos(n));
        }
        if let Ok(s) = arealight::OvercastSky::new(vec(2), input(4)) {
            sink(s.lambert(n));
        }
        if let Ok(s) = arealight::SkyGround::new(vec(2), Rgb::splat(input(1)), Rgb::splat(input(2))) {
            sink(s.irradiance(n).r);
        }
    }
    #[cfg(feature = "cap")]
    {
        if let Ok(c) = arealight::CapLight::new(vec(1), input(4)) {
            sink(c.lambert(n) + c.lambert_hermite(n));
        }
        if let Ok(s) = arealight::SphereLight::new(vec(2), input(4)) {
            sink(s.lambert(p, n) + s.lambert_hermite(p, n));
        }
    }
    #[cfg(feature = "polygon")]
    {
        let verts = [vec(0), vec(1), vec(2), vec(3)];
        if let Ok(l) = arealight::PolygonLight::<T, 8>::new(&verts) {
            sink(l.lambert(p, n));
        }
    }
    #[cfg(feature = "phong")]
    {
        if let Ok(lobe) = arealight::PhongLobe::new(int(16)) {
            if let Ok(h) = arealight::HemisphereLight::new(vec(1)) {
                sink(h.phong_const(&lobe, r) + h.phong_cos(&lobe, r));
            }
            if let Ok(c) = arealight::CapLight::new(vec(1), input(4)) {
                sink(c.phong(&lobe, r));
            }
            if let Ok(s) = arealight::SphereLight::new(vec(2), input(4)) {
                sink(s.phong(&lobe, p, r));
            }
            let verts = [vec(0), vec(1), vec(2), vec(3)];
            if let Ok(l) = arealight::PolygonLight::<T, 8>::new(&verts) {
                sink(l.phong(&lobe, p, r));
            }
        }
    }
    #[cfg(feature = "sh9")]
    {
        let coeffs: [Rgb<T>; 9] = core::array::from_fn(|i| Rgb::splat(input(i)));
        if let Ok(s) = arealight::Sh9::new(coeffs) {
            sink(s.prepare().irradiance(n).g);
        }
        if let Ok(s) = arealight::Sh9::disc(vec(1), input(2), Rgb::splat(input(3))) {
            sink(s.prepare().irradiance(n).b);
        }
    }
    #[cfg(feature = "line")]
    {
        if let (Ok(k), Ok(l)) = (
            arealight::Decay::new(int(2)),
            arealight::LineLight::new(vec(1), vec(2)),
        ) {
            sink(l.lambert(p, n, k));
        }
    }
    #[cfg(feature = "moments")]
    {
        let verts = [vec(0), vec(1), vec(2), vec(3)];
        if let Ok(l) = arealight::PolygonLight::<T, 8>::new(&verts) {
            let m = int(16);
            sink(l.axial_moment(p, n, m) + l.double_axis_moment(p, n, r, m));
        }
    }
    #[cfg(feature = "shaping")]
    {
        if let Ok(s) = arealight::Superellipse::new(input(0), input(1), input(2), input(3), input(4)) {
            sink(s.shape(p));
        }
        if let Ok(f) = arealight::DistanceFalloff::new(input(0), input(1), input(2), input(3), input(4), input(5), input(6)) {
            sink(f.falloff(input(7)));
        }
    }
    loop {
        core::hint::spin_loop();
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {
        core::hint::spin_loop();
    }
}
