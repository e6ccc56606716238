//! `host-sim eval`: the eval protocol of `shared/spec/eval-protocol.md`.
//!
//! JSON Lines on standard input, one JSON line per input line on standard output, in the same
//! order. The model dispatch is written once, in [`eval_model`], generic over
//! [`arealight::Real`], and instantiated per backend.
//!
//! Behaviour the protocol leaves open, decided here:
//!
//! - a blank (empty or whitespace-only) input line is skipped: it gets no output line;
//! - a line without an `id` (or with `"id": null`) gets an error line with `"id": null`; any
//!   other JSON value of `id` is echoed back as given;
//! - a model id the spec lists but this build does not implement answers
//!   `"unsupported: <model> is not implemented yet"`; an id the spec does not list answers
//!   `"unknown model: <model>"` on every backend;
//! - range checks the backends must agree on (sigma, alpha, m) are made in f64, before the
//!   conversion to the backend's scalar type. A finite number too large for f32 (say 1e300)
//!   becomes infinity on the f32 backends and is refused there as not finite.

use std::io::{self, BufRead, Write};

use arealight::{
    CapLight, Fast32, Fixed22, HemisphereLight, OvercastSky, PhongLobe, PolygonLight, Real, Rgb,
    Sh9, SkyGround, SphereLight, Vec3,
};
use clap::{Args, ValueEnum};
use serde::Serialize;
use serde_json::{Map, Value};

/// The polygon capacity of the protocol (more vertices: the library's `TooManyVertices`).
pub const MAX_VERTICES: usize = 64;

/// The scalar backend the library is instantiated with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Backend {
    /// The reference: the library with `T = f64`.
    #[value(name = "f64")]
    F64,
    /// The firmware float path: `T = f32` (libm).
    #[value(name = "f32")]
    F32,
    /// `T = arealight::Fast32`: f32 with the library's cheap sqrt and atan2.
    #[value(name = "f32-fast")]
    F32Fast,
    /// The fixed-point path: `T = arealight::Fixed22` (I10F22), for the models of
    /// [`FIXED_SUPPORTED`]; the others answer "unsupported".
    #[value(name = "fixed")]
    Fixed,
}

/// Arguments of `host-sim eval`.
#[derive(Args, Debug)]
pub struct EvalArgs {
    /// Scalar backend to evaluate with.
    #[arg(long, value_enum, default_value = "f64")]
    pub backend: Backend,
}

/// The models the protocol defines that this build evaluates.
pub const SUPPORTED: &[&str] = &[
    "hemi_const",
    "hemi_cos",
    "sky_overcast",
    "sky_ground",
    "cap_lambert",
    "cap_lambert_hermite",
    "sphere_lambert",
    "sphere_lambert_hermite",
    "polygon_lambert",
    "phong_hemi_const",
    "phong_hemi_cos",
    "phong_cap",
    "phong_sphere",
    "phong_polygon",
    "sh9_irradiance",
    "sh9_disc_irradiance",
    "superellipse_shape",
    "distance_falloff",
    "axial_moment",
    "double_axis_moment",
    "directional_luminaire",
    "glossy_reflection",
    "glossy_transmission",
    "lune_normalization",
    "line_lambert",
    "line_phong_peak",
    "rect_phong_peak",
];

/// The models the protocol defines that are not implemented yet.
pub const NOT_YET: &[&str] = &[];

/// The answer of a model: a scalar or an RGB triple, already converted to f64.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Answer {
    /// `{"value": x}`.
    Value(f64),
    /// `{"rgb": [r, g, b]}`.
    Rgb([f64; 3]),
}

/// Why a line has no value: the text of its `error` field.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EvalError(pub String);

impl From<arealight::Error> for EvalError {
    fn from(e: arealight::Error) -> Self {
        EvalError(e.to_string())
    }
}
impl From<String> for EvalError {
    fn from(s: String) -> Self {
        EvalError(s)
    }
}
impl From<&str> for EvalError {
    fn from(s: &str) -> Self {
        EvalError(s.to_owned())
    }
}

type EvalResult<T> = Result<T, EvalError>;

/// The parameters of one input line (the line's JSON object), read by name.
pub struct Params<'a> {
    map: &'a Map<String, Value>,
}

/// A JSON number, or one of the strings that stand for the non-finite values.
fn number(v: &Value, name: &str) -> EvalResult<f64> {
    match v {
        Value::Number(x) => x
            .as_f64()
            .ok_or_else(|| EvalError(format!("{name}: number out of range"))),
        Value::String(s) => match s.as_str() {
            "NaN" => Ok(f64::NAN),
            "Infinity" => Ok(f64::INFINITY),
            "-Infinity" => Ok(f64::NEG_INFINITY),
            _ => Err(EvalError(format!(
                "{name}: expected a number (or \"NaN\", \"Infinity\", \"-Infinity\"), got the string {s:?}"
            ))),
        },
        other => Err(EvalError(format!(
            "{name}: expected a number, got {}",
            kind(other)
        ))),
    }
}

fn kind(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

fn triple(v: &Value, name: &str) -> EvalResult<[f64; 3]> {
    match v {
        Value::Array(a) if a.len() == 3 => Ok([
            number(&a[0], name)?,
            number(&a[1], name)?,
            number(&a[2], name)?,
        ]),
        Value::Array(a) => Err(EvalError(format!(
            "{name}: expected an array of 3 numbers, got {} elements",
            a.len()
        ))),
        other => Err(EvalError(format!(
            "{name}: expected an array of 3 numbers, got {}",
            kind(other)
        ))),
    }
}

impl<'a> Params<'a> {
    /// Parameters from a line's object.
    pub fn new(map: &'a Map<String, Value>) -> Self {
        Params { map }
    }

    fn get(&self, name: &str) -> EvalResult<&'a Value> {
        self.map
            .get(name)
            .ok_or_else(|| EvalError(format!("missing parameter: {name}")))
    }

    /// A scalar, in f64 (non-finite values pass: the library refuses them with its message).
    pub fn f64(&self, name: &str) -> EvalResult<f64> {
        number(self.get(name)?, name)
    }

    /// A vector (point or direction) converted to `T`.
    pub fn vec3<T: Real>(&self, name: &str) -> EvalResult<Vec3<T>> {
        Ok(Vec3::from_f64(triple(self.get(name)?, name)?))
    }

    /// A colour converted to `T`.
    pub fn rgb<T: Real>(&self, name: &str) -> EvalResult<Rgb<T>> {
        Ok(Rgb::from_f64(triple(self.get(name)?, name)?))
    }

    /// An array of vectors (any count: the library checks it).
    pub fn verts<T: Real>(&self, name: &str) -> EvalResult<Vec<Vec3<T>>> {
        match self.get(name)? {
            Value::Array(a) => a
                .iter()
                .map(|v| Ok(Vec3::from_f64(triple(v, name)?)))
                .collect(),
            other => Err(EvalError(format!(
                "{name}: expected an array of vectors, got {}",
                kind(other)
            ))),
        }
    }

    /// Nine colours.
    pub fn coeffs<T: Real>(&self, name: &str) -> EvalResult<[Rgb<T>; 9]> {
        match self.get(name)? {
            Value::Array(a) if a.len() == 9 => {
                let mut out = [Rgb::splat(T::ZERO); 9];
                for (o, v) in out.iter_mut().zip(a) {
                    *o = Rgb::from_f64(triple(v, name)?);
                }
                Ok(out)
            }
            Value::Array(a) => Err(EvalError(format!(
                "{name}: expected an array of 9 colours, got {} elements",
                a.len()
            ))),
            other => Err(EvalError(format!(
                "{name}: expected an array of 9 colours, got {}",
                kind(other)
            ))),
        }
    }

    /// A non-negative integer (3 and 3.0 alike). Values above `u32::MAX` saturate, so the
    /// library reports them as too large.
    pub fn uint(&self, name: &'static str) -> EvalResult<u32> {
        let x = self.f64(name)?;
        if !x.is_finite() {
            return Err(arealight::Error::NotFinite(name).into());
        }
        if x < 0.0 || x.fract() != 0.0 {
            return Err(EvalError(format!("{name} must be a non-negative integer")));
        }
        Ok(if x > u32::MAX as f64 {
            u32::MAX
        } else {
            x as u32
        })
    }

    /// A cap half-angle: range-checked in f64 (so every backend refuses the same inputs), then
    /// converted. A non-finite value passes to the library, which names it.
    pub fn sigma<T: Real>(&self, name: &str) -> EvalResult<T> {
        let x = self.f64(name)?;
        if x.is_finite() && !(0.0..=std::f64::consts::FRAC_PI_2).contains(&x) {
            return Err(arealight::Error::SigmaOutOfRange.into());
        }
        Ok(T::from_f64(x))
    }

    /// A disc half-angle in [0, pi], checked as [`Params::sigma`].
    pub fn alpha<T: Real>(&self, name: &str) -> EvalResult<T> {
        let x = self.f64(name)?;
        if x.is_finite() && !(0.0..=std::f64::consts::PI).contains(&x) {
            return Err(arealight::Error::AlphaOutOfRange.into());
        }
        Ok(T::from_f64(x))
    }
}

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

/// Evaluates `model` with the parameters `p` on backend `T`: the protocol's one dispatch.
///
/// # Errors
/// The text of the line's `error` field: a missing or malformed parameter, an invalid input
/// (the library's message), an unsupported or unknown model, or a non-finite result.
pub fn eval_model<T: Real>(model: &str, p: &Params) -> EvalResult<Answer> {
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
        "polygon_lambert" => {
            let (pt, n, verts) = (p.vec3::<T>("p")?, p.vec3::<T>("n")?, p.verts::<T>("verts")?);
            let poly = PolygonLight::<T, MAX_VERTICES>::new(&verts)?;
            scalar(poly.try_lambert(pt, n)?)
        }
        "phong_hemi_const" | "phong_hemi_cos" => {
            let (r, axis, m) = (p.vec3::<T>("r")?, p.vec3::<T>("axis")?, p.uint("m")?);
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
            let (sigma, m) = (p.sigma::<T>("sigma")?, p.uint("m")?);
            let cap = CapLight::new(axis, sigma)?;
            let lobe = PhongLobe::new(m)?;
            scalar(cap.phong(&lobe, check_dir(r, "r")?))
        }
        "phong_sphere" => {
            let (pt, r, center) = (p.vec3::<T>("p")?, p.vec3::<T>("r")?, p.vec3::<T>("center")?);
            let (radius, m) = (p.f64("radius")?, p.uint("m")?);
            let sphere = SphereLight::new(center, T::from_f64(radius))?;
            let lobe = PhongLobe::new(m)?;
            scalar(sphere.try_phong(&lobe, pt, r)?)
        }
        "phong_polygon" => {
            let (pt, r, verts) = (p.vec3::<T>("p")?, p.vec3::<T>("r")?, p.verts::<T>("verts")?);
            let m = p.uint("m")?;
            let poly = PolygonLight::<T, MAX_VERTICES>::new(&verts)?;
            let lobe = PhongLobe::new(m)?;
            scalar(poly.try_phong(&lobe, pt, r)?)
        }
        "axial_moment" => {
            let (pt, verts, w) = (p.vec3::<T>("p")?, p.verts::<T>("verts")?, p.vec3::<T>("w")?);
            let m = p.uint("m")?;
            let poly = PolygonLight::<T, MAX_VERTICES>::new(&verts)?;
            scalar(poly.try_axial_moment(pt, w, m)?)
        }
        "double_axis_moment" => {
            let (pt, verts) = (p.vec3::<T>("p")?, p.verts::<T>("verts")?);
            let (w, v, m) = (p.vec3::<T>("w")?, p.vec3::<T>("v")?, p.uint("m")?);
            let poly = PolygonLight::<T, MAX_VERTICES>::new(&verts)?;
            scalar(poly.try_double_axis_moment(pt, w, v, m)?)
        }
        "directional_luminaire" => {
            let (pt, n, verts) = (p.vec3::<T>("p")?, p.vec3::<T>("n")?, p.verts::<T>("verts")?);
            let (axis, m) = (p.vec3::<T>("axis")?, p.uint("m")?);
            let poly = PolygonLight::<T, MAX_VERTICES>::new(&verts)?;
            scalar(poly.try_directional_luminaire(pt, n, axis, m)?)
        }
        "glossy_reflection" | "glossy_transmission" => {
            let (pt, n, e) = (p.vec3::<T>("p")?, p.vec3::<T>("n")?, p.vec3::<T>("e")?);
            let (verts, m) = (p.verts::<T>("verts")?, p.uint("m")?);
            let poly = PolygonLight::<T, MAX_VERTICES>::new(&verts)?;
            scalar(if model == "glossy_reflection" {
                poly.try_glossy_reflection(pt, n, e, m)?
            } else {
                poly.try_glossy_transmission(pt, n, e, m)?
            })
        }
        "lune_normalization" => {
            let (w, v, m) = (p.vec3::<T>("w")?, p.vec3::<T>("v")?, p.uint("m")?);
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
            let (a, b, m) = (p.vec3::<T>("a")?, p.vec3::<T>("b")?, p.uint("m")?);
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
            let m = p.uint("m")?;
            // The constructor validates in f64 on every backend.
            let light = arealight::ParallelogramLight::new(origin, eu, ev)?;
            let lobe = PhongLobe::new(m)?;
            scalar(light.try_phong_peak(&lobe, pt, r)?)
        }
        m if NOT_YET.contains(&m) => {
            return Err(EvalError(format!(
                "unsupported: {m} is not implemented yet"
            )))
        }
        m => return Err(EvalError(format!("unknown model: {m}"))),
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

/// One output line; `id` comes first.
#[derive(Debug, Serialize)]
pub struct OutLine {
    id: Value,
    #[serde(skip_serializing_if = "Option::is_none")]
    value: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rgb: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    error: Option<String>,
}

impl OutLine {
    fn error(id: Value, msg: impl Into<String>) -> Self {
        OutLine {
            id,
            value: None,
            rgb: None,
            error: Some(msg.into()),
        }
    }
}

/// The models the fixed-point backend ([`Fixed22`]) answers (issue 3's scope, plus the
/// uberlight shaping factors); the library's list.
pub const FIXED_SUPPORTED: &[&str] = &arealight::real::fixed22::SUPPORTED_MODELS;

/// The fixed-point type cannot hold NaN, infinities or magnitudes of 512 and more: such an
/// input gets the error the float backends give for a non-finite value, or a range error,
/// instead of a silently saturated value. (Positions beyond the fixed path's coordinate limit
/// are refused by the library itself.) Integer parameters (`m`, `k`) are parsed as integers.
fn fixed_inputs_representable(map: &Map<String, Value>) -> EvalResult<()> {
    fn walk(v: &Value, name: &str) -> EvalResult<()> {
        match v {
            Value::Array(a) => a.iter().try_for_each(|x| walk(x, name)),
            Value::Number(_) | Value::String(_) => {
                let x = number(v, name)?;
                if !x.is_finite() {
                    Err(arealight::Error::NotFinite(static_name(name)).into())
                } else if x.abs() >= 512.0 {
                    Err(EvalError(format!(
                        "{name} is outside the range of the fixed-point backend (|x| < 512)"
                    )))
                } else {
                    Ok(())
                }
            }
            _ => Ok(()),
        }
    }
    for (k, v) in map {
        if !matches!(k.as_str(), "id" | "model" | "m" | "k") {
            walk(v, k)?;
        }
    }
    Ok(())
}

/// The library's errors name parameters with `&'static str`; the few names the protocol uses
/// are interned here (an unknown key keeps a generic name).
fn static_name(name: &str) -> &'static str {
    const NAMES: &[&str] = &[
        "n",
        "axis",
        "zenith",
        "c",
        "up",
        "sky",
        "ground",
        "sigma",
        "p",
        "center",
        "radius",
        "verts",
        "r",
        "coeffs",
        "alpha",
        "pos",
        "a",
        "b",
        "A",
        "B",
        "d",
        "z",
        "M",
        "d0",
        "znear",
        "zfar",
        "near_edge",
        "far_edge",
    ];
    NAMES
        .iter()
        .find(|&&x| x == name)
        .copied()
        .unwrap_or("a parameter")
}

/// Answers one non-blank input line.
pub fn process_line(line: &[u8], backend: Backend) -> OutLine {
    let parsed: Value = match serde_json::from_slice(line) {
        Ok(v) => v,
        Err(e) => return OutLine::error(Value::Null, format!("invalid JSON: {e}")),
    };
    let Value::Object(map) = parsed else {
        return OutLine::error(Value::Null, "invalid input: a line must be a JSON object");
    };
    let id = match map.get("id") {
        None | Some(Value::Null) => return OutLine::error(Value::Null, "missing parameter: id"),
        Some(id) => id.clone(),
    };
    let model = match map.get("model") {
        Some(Value::String(m)) => m.as_str(),
        Some(other) => {
            return OutLine::error(id, format!("model: expected a string, got {}", kind(other)))
        }
        None => return OutLine::error(id, "missing parameter: model"),
    };
    let params = Params::new(&map);
    let result = match backend {
        Backend::F64 => eval_model::<f64>(model, &params),
        Backend::F32 => eval_model::<f32>(model, &params),
        Backend::F32Fast => eval_model::<Fast32>(model, &params),
        Backend::Fixed => {
            if FIXED_SUPPORTED.contains(&model) {
                fixed_inputs_representable(&map)
                    .and_then(|()| eval_model::<Fixed22>(model, &params))
            } else if SUPPORTED.contains(&model) || NOT_YET.contains(&model) {
                Err(EvalError(format!(
                    "unsupported: the fixed-point backend does not implement {model}"
                )))
            } else {
                Err(EvalError(format!("unknown model: {model}")))
            }
        }
    };
    match result {
        Ok(Answer::Value(x)) => OutLine {
            id,
            value: Some(x),
            rgb: None,
            error: None,
        },
        Ok(Answer::Rgb(c)) => OutLine {
            id,
            value: None,
            rgb: Some(c),
            error: None,
        },
        Err(EvalError(msg)) => OutLine::error(id, msg),
    }
}

/// Runs the protocol from `input` to `output` until end of input. Blank lines are skipped.
///
/// # Errors
/// An I/O error reading the input or writing the output (a closed pipe among them).
pub fn run(input: impl BufRead, output: impl Write, backend: Backend) -> io::Result<()> {
    let mut input = input;
    let mut out = io::BufWriter::new(output);
    let mut buf = Vec::new();
    loop {
        buf.clear();
        if input.read_until(b'\n', &mut buf)? == 0 {
            break;
        }
        if buf.iter().all(u8::is_ascii_whitespace) {
            continue;
        }
        let line = process_line(&buf, backend);
        serde_json::to_writer(&mut out, &line).map_err(io::Error::from)?;
        out.write_all(b"\n")?;
    }
    out.flush()
}

/// `host-sim eval`: stdin to stdout. A closed output pipe ends the run quietly.
pub fn main(args: &EvalArgs) -> std::process::ExitCode {
    let stdin = io::stdin();
    let stdout = io::stdout();
    match run(stdin.lock(), stdout.lock(), args.backend) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("host-sim eval: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval(backend: Backend, line: &str) -> String {
        serde_json::to_string(&process_line(line.as_bytes(), backend)).unwrap()
    }

    #[test]
    fn id_comes_first_and_numbers_round_trip() {
        let s = eval(
            Backend::F64,
            r#"{"id":"a","model":"hemi_const","n":[0,0,1],"axis":[0,0,1]}"#,
        );
        assert_eq!(s, r#"{"id":"a","value":1.0}"#);
        let s = eval(Backend::F64, r#"{"model":"hemi_const"}"#);
        assert_eq!(s, r#"{"id":null,"error":"missing parameter: id"}"#);
    }

    #[test]
    fn exponent_parsing() {
        let m = |v: &str| {
            let map: Map<String, Value> = serde_json::from_str(&format!(r#"{{"m":{v}}}"#)).unwrap();
            Params::new(&map).uint("m")
        };
        assert_eq!(m("3"), Ok(3));
        assert_eq!(m("3.0"), Ok(3));
        assert_eq!(m("0"), Ok(0));
        assert_eq!(m("-0.0"), Ok(0));
        assert_eq!(m("1e30"), Ok(u32::MAX));
        let bad = Err(EvalError("m must be a non-negative integer".into()));
        assert_eq!(m("2.5"), bad);
        assert_eq!(m("-1"), bad);
        assert!(m(r#""NaN""#).unwrap_err().0.contains("not finite"));
        assert!(m(r#""Infinity""#).unwrap_err().0.contains("not finite"));
    }

    #[test]
    fn range_checks_agree_across_backends() {
        // Just above pi/2 in f64, but rounds to f32's pi/2.
        let line = r#"{"id":1,"model":"cap_lambert","n":[0,0,1],"axis":[0,0,1],"sigma":1.5707963267948968}"#;
        for b in [Backend::F64, Backend::F32, Backend::F32Fast] {
            assert!(eval(b, line).contains("sigma is outside"), "{b:?}");
        }
    }
}
