//! The protocol's one dispatch ([`eval_model`]): a model id and its parameters to the
//! library's call on backend `T`, the positional models through world coordinates in fixed
//! point ([`WORLD_MODELS`]).

use super::*;

/// A per-sample direction must be finite and non-zero (the library's per-sample functions
/// would silently answer 0). Returns it unchanged: the library normalizes it itself.
fn check_dir<T: Real>(d: Vec3<T>, name: &'static str) -> EvalResult<Vec3<T>> {
    d.try_normalize(name)?;
    Ok(d)
}

fn scalar<T: Real>(x: T) -> Answer {
    Answer::Value(x.to_f64())
}

fn colour<T: Real>(c: Rgb<T>) -> Answer {
    Answer::Rgb(c.to_f64())
}

/// The models the fixed-point backend takes through world coordinates (`arealight::world`):
/// their positions (`p`, `center`, `radius`, `verts`) in I32F32, `|x| < 2^30`, with no limit of
/// the fixed-point format's own; the floats take the plain models.
pub const WORLD_MODELS: [&str; 5] = [
    "sphere_lambert",
    "sphere_lambert_hermite",
    "phong_sphere",
    "polygon_lambert",
    "phong_polygon",
];

/// The parameters of [`WORLD_MODELS`] read as world coordinates.
pub(super) const WORLD_PARAMS: [&str; 4] = ["p", "center", "radius", "verts"];

/// `true` for the backends that take [`WORLD_MODELS`] through world coordinates: those with a
/// coordinate limit (fixed point).
fn in_world<T: Real>() -> bool {
    T::COORDINATE_LIMIT < f64::MAX
}

/// Evaluates model `def` with the parameters `p` on backend `T`: the protocol's one dispatch.
///
/// # Errors
/// The text of the line's `error` field: a missing or malformed parameter, an invalid input
/// (the library's message), or a non-finite result.
pub fn eval_model<T: Real>(def: &'static ModelDef, p: &Params) -> EvalResult<Answer> {
    let model = def.id;
    let answer = match model {
        "hemi_const" | "hemi_cos" => {
            let (n, axis) = (p.vec3::<T>("n")?, p.vec3::<T>("axis")?);
            let light = HemisphereLight::new(axis)?;
            let n = check_dir(n, "n")?;
            scalar(if model == "hemi_const" {
                light.lambert_const(n)
            } else {
                light.lambert_cos(n)
            })
        }
        "sky_overcast" => {
            let (n, zenith, c) = (p.vec3::<T>("n")?, p.vec3::<T>("zenith")?, p.f64("c")?);
            let sky = OvercastSky::new(zenith, T::from_f64(c))?;
            scalar(sky.lambert(check_dir(n, "n")?))
        }
        "sky_ground" => {
            let (n, up) = (p.vec3::<T>("n")?, p.vec3::<T>("up")?);
            let (sky, ground) = (p.rgb::<T>("sky")?, p.rgb::<T>("ground")?);
            let light = SkyGround::new(up, sky, ground)?;
            colour(light.irradiance(check_dir(n, "n")?))
        }
        "cap_lambert" | "cap_lambert_hermite" => {
            let (n, axis, sigma) = (
                p.vec3::<T>("n")?,
                p.vec3::<T>("axis")?,
                p.sigma::<T>("sigma")?,
            );
            let cap = CapLight::new(axis, sigma)?;
            let n = check_dir(n, "n")?;
            scalar(if model == "cap_lambert" {
                cap.lambert(n)
            } else {
                cap.lambert_hermite(n)
            })
        }
        "sphere_lambert" | "sphere_lambert_hermite" if in_world::<T>() => {
            let (pt, n) = (p.point("p")?, p.vec3::<T>("n")?);
            let (center, radius) = (p.point("center")?, p.f64("radius")?);
            let sphere = WorldSphereLight::<T>::new(center, radius)?;
            scalar(if model == "sphere_lambert" {
                sphere.try_lambert(pt, n)?
            } else {
                sphere.try_lambert_hermite(pt, n)?
            })
        }
        "sphere_lambert" | "sphere_lambert_hermite" => {
            let (pt, n) = (p.vec3::<T>("p")?, p.vec3::<T>("n")?);
            let (center, radius) = (p.vec3::<T>("center")?, p.f64("radius")?);
            let sphere = SphereLight::new(center, T::from_f64(radius))?;
            scalar(if model == "sphere_lambert" {
                sphere.try_lambert(pt, n)?
            } else {
                sphere.try_lambert_hermite(pt, n)?
            })
        }
        "polygon_lambert" if in_world::<T>() => {
            let (pt, n, verts) = (p.point("p")?, p.vec3::<T>("n")?, p.points("verts")?);
            let poly = WorldPolygonLight::<T, MAX_VERTICES>::new(&verts)?;
            scalar(poly.try_lambert(pt, n)?)
        }
        "polygon_lambert" => {
            let (pt, n, verts) = (p.vec3::<T>("p")?, p.vec3::<T>("n")?, p.verts::<T>("verts")?);
            let poly = PolygonLight::<T, MAX_VERTICES>::new(&verts)?;
            scalar(poly.try_lambert(pt, n)?)
        }
        "phong_hemi_const" | "phong_hemi_cos" => {
            let (r, axis, m) = (
                p.vec3::<T>("r")?,
                p.vec3::<T>("axis")?,
                p.exponent::<T>("m")?,
            );
            let light = HemisphereLight::new(axis)?;
            let lobe = PhongLobe::new(m)?;
            let r = check_dir(r, "r")?;
            scalar(if model == "phong_hemi_const" {
                light.phong_const(&lobe, r)
            } else {
                light.phong_cos(&lobe, r)
            })
        }
        "phong_cap" => {
            let (r, axis) = (p.vec3::<T>("r")?, p.vec3::<T>("axis")?);
            let (sigma, m) = (p.sigma::<T>("sigma")?, p.exponent::<T>("m")?);
            let cap = CapLight::new(axis, sigma)?;
            let lobe = PhongLobe::new(m)?;
            scalar(cap.phong(&lobe, check_dir(r, "r")?))
        }
        "phong_sphere" if in_world::<T>() => {
            let (pt, r, center) = (p.point("p")?, p.vec3::<T>("r")?, p.point("center")?);
            let (radius, m) = (p.f64("radius")?, p.exponent::<T>("m")?);
            let sphere = WorldSphereLight::<T>::new(center, radius)?;
            let lobe = PhongLobe::new(m)?;
            scalar(sphere.try_phong(&lobe, pt, r)?)
        }
        "phong_sphere" => {
            let (pt, r, center) = (p.vec3::<T>("p")?, p.vec3::<T>("r")?, p.vec3::<T>("center")?);
            let (radius, m) = (p.f64("radius")?, p.exponent::<T>("m")?);
            let sphere = SphereLight::new(center, T::from_f64(radius))?;
            let lobe = PhongLobe::new(m)?;
            scalar(sphere.try_phong(&lobe, pt, r)?)
        }
        "phong_polygon" if in_world::<T>() => {
            let (pt, r, verts) = (p.point("p")?, p.vec3::<T>("r")?, p.points("verts")?);
            let m = p.exponent::<T>("m")?;
            let poly = WorldPolygonLight::<T, MAX_VERTICES>::new(&verts)?;
            let lobe = PhongLobe::new(m)?;
            scalar(poly.try_phong(&lobe, pt, r)?)
        }
        "phong_polygon" => {
            let (pt, r, verts) = (p.vec3::<T>("p")?, p.vec3::<T>("r")?, p.verts::<T>("verts")?);
            let m = p.exponent::<T>("m")?;
            let poly = PolygonLight::<T, MAX_VERTICES>::new(&verts)?;
            let lobe = PhongLobe::new(m)?;
            scalar(poly.try_phong(&lobe, pt, r)?)
        }
        "axial_moment" => {
            let (pt, verts, w) = (p.vec3::<T>("p")?, p.verts::<T>("verts")?, p.vec3::<T>("w")?);
            let m = p.exponent::<T>("m")?;
            let poly = PolygonLight::<T, MAX_VERTICES>::new(&verts)?;
            scalar(poly.try_axial_moment(pt, w, m)?)
        }
        "double_axis_moment" => {
            let (pt, verts) = (p.vec3::<T>("p")?, p.verts::<T>("verts")?);
            let (w, v, m) = (p.vec3::<T>("w")?, p.vec3::<T>("v")?, p.exponent::<T>("m")?);
            let poly = PolygonLight::<T, MAX_VERTICES>::new(&verts)?;
            scalar(poly.try_double_axis_moment(pt, w, v, m)?)
        }
        "directional_luminaire" => {
            let (pt, n, verts) = (p.vec3::<T>("p")?, p.vec3::<T>("n")?, p.verts::<T>("verts")?);
            let (axis, m) = (p.vec3::<T>("axis")?, p.exponent::<T>("m")?);
            let poly = PolygonLight::<T, MAX_VERTICES>::new(&verts)?;
            scalar(poly.try_directional_luminaire(pt, n, axis, m)?)
        }
        "glossy_reflection" | "glossy_transmission" => {
            let (pt, n, e) = (p.vec3::<T>("p")?, p.vec3::<T>("n")?, p.vec3::<T>("e")?);
            let (verts, m) = (p.verts::<T>("verts")?, p.exponent::<T>("m")?);
            let poly = PolygonLight::<T, MAX_VERTICES>::new(&verts)?;
            scalar(if model == "glossy_reflection" {
                poly.try_glossy_reflection(pt, n, e, m)?
            } else {
                poly.try_glossy_transmission(pt, n, e, m)?
            })
        }
        "lune_normalization" => {
            let (w, v, m) = (p.vec3::<T>("w")?, p.vec3::<T>("v")?, p.exponent::<T>("m")?);
            scalar(arealight::try_lune_normalization(w, v, m)?)
        }
        "sh9_irradiance" => {
            let (n, coeffs) = (p.vec3::<T>("n")?, p.coeffs::<T>("coeffs")?);
            let env = Sh9::new(coeffs)?.prepare();
            colour(env.irradiance(check_dir(n, "n")?))
        }
        "sh9_disc_irradiance" => {
            let (n, axis, alpha) = (
                p.vec3::<T>("n")?,
                p.vec3::<T>("axis")?,
                p.alpha::<T>("alpha")?,
            );
            let env = Sh9::disc(axis, alpha, Rgb::splat(T::ONE))?.prepare();
            scalar(env.irradiance(check_dir(n, "n")?).r)
        }
        "superellipse_shape" => {
            let pos = p.vec3::<T>("pos")?;
            let s = [
                p.f64("a")?,
                p.f64("b")?,
                p.f64("A")?,
                p.f64("B")?,
                p.f64("d")?,
            ];
            // Validated in f64 first, so every backend refuses the same parameters.
            arealight::Superellipse::<f64>::new(s[0], s[1], s[2], s[3], s[4])?;
            let s = s.map(T::from_f64);
            let shape = arealight::Superellipse::new(s[0], s[1], s[2], s[3], s[4])?;
            scalar(shape.try_shape(pos)?)
        }
        "distance_falloff" => {
            let z = p.f64("z")?;
            let f = [
                p.f64("M")?,
                p.f64("d0")?,
                p.f64("alpha")?,
                p.f64("znear")?,
                p.f64("zfar")?,
                p.f64("near_edge")?,
                p.f64("far_edge")?,
            ];
            // Validated in f64 first (z too: a tiny negative z would round to -0 in f32), so
            // every backend refuses the same inputs.
            arealight::DistanceFalloff::<f64>::new(f[0], f[1], f[2], f[3], f[4], f[5], f[6])?
                .try_falloff(z)?;
            let f = f.map(T::from_f64);
            let light = arealight::DistanceFalloff::new(f[0], f[1], f[2], f[3], f[4], f[5], f[6])?;
            scalar(light.try_falloff(T::from_f64(z))?)
        }
        "line_lambert" => {
            let (pt, n) = (p.vec3::<T>("p")?, p.vec3::<T>("n")?);
            let (a, b, k) = (p.vec3::<T>("a")?, p.vec3::<T>("b")?, p.uint("k")?);
            let light = arealight::LineLight::new(a, b)?;
            scalar(light.try_lambert(pt, n, arealight::Decay::new(k)?)?)
        }
        "line_phong_peak" => {
            let (pt, r) = (p.vec3::<T>("p")?, p.vec3::<T>("r")?);
            let (a, b, m) = (p.vec3::<T>("a")?, p.vec3::<T>("b")?, p.exponent::<T>("m")?);
            let light = arealight::LineLight::new(a, b)?;
            let lobe = PhongLobe::new(m)?;
            scalar(light.try_phong_peak(&lobe, pt, r)?)
        }
        "rect_phong_peak" => {
            let (pt, r) = (p.vec3::<T>("p")?, p.vec3::<T>("r")?);
            let (origin, eu, ev) = (
                p.vec3::<T>("origin")?,
                p.vec3::<T>("eu")?,
                p.vec3::<T>("ev")?,
            );
            let m = p.exponent::<T>("m")?;
            // The constructor validates in f64 on every backend.
            let light = arealight::ParallelogramLight::new(origin, eu, ev)?;
            let lobe = PhongLobe::new(m)?;
            scalar(light.try_phong_peak(&lobe, pt, r)?)
        }
        m => {
            return Err(EvalError(format!(
                "internal: {m} is in MODELS but not dispatched"
            )))
        }
    };
    let finite = match answer {
        Answer::Value(x) => x.is_finite(),
        Answer::Rgb(c) => c.iter().all(|x| x.is_finite()),
    };
    if finite {
        Ok(answer)
    } else {
        Err(EvalError(format!(
            "internal: {model} gave a non-finite result"
        )))
    }
}
