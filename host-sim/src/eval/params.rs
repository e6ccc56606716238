//! Reading one input line's parameters by name ([`Params`]): numbers, points, directions,
//! polygons and integers, checked against the protocol's ranges in f64 before the conversion
//! to the backend's scalar type.

use super::*;

/// The parameters of one input line (the line's JSON object), read by name: only names the
/// model declares in [`MODELS`] (checked in debug builds).
pub struct Params<'a> {
    map: &'a Map<String, Value>,
    def: &'static ModelDef,
}

/// A JSON number, or one of the strings that stand for the non-finite values.
pub(super) fn number(v: &Value, name: &str) -> EvalResult<f64> {
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

pub(super) fn kind(v: &Value) -> &'static str {
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
    /// The parameters of model `def` from a line's object.
    pub fn new(map: &'a Map<String, Value>, def: &'static ModelDef) -> Self {
        Params { map, def }
    }

    fn get(&self, name: &str) -> EvalResult<&'a Value> {
        debug_assert!(
            self.def.param(name).is_some(),
            "{} reads {name}, which MODELS does not declare",
            self.def.id
        );
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

    /// A point in world coordinates (`arealight::world`: I32F32, |x| < 2^30).
    pub fn point(&self, name: &'static str) -> EvalResult<WorldPoint> {
        Ok(WorldPoint::from_f64(triple(self.get(name)?, name)?, name)?)
    }

    /// An array of points in world coordinates.
    pub fn points(&self, name: &'static str) -> EvalResult<Vec<WorldPoint>> {
        match self.get(name)? {
            Value::Array(a) => a
                .iter()
                .map(|v| Ok(WorldPoint::from_f64(triple(v, name)?, name)?))
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

    /// A Phong or moment exponent: a non-negative integer up to the backend's limit
    /// (`T::MAX_PHONG_EXPONENT`: 1048576, 255 for the fixed-point type), which the message
    /// states.
    pub fn exponent<T: Real>(&self, name: &'static str) -> EvalResult<u32> {
        let m = self.uint(name)?;
        let limit = T::MAX_PHONG_EXPONENT.min(arealight::phong::MAX_EXPONENT);
        if m > limit {
            let x = self.f64(name)?;
            return Err(EvalError(format!(
                "Phong exponent {name} is too large: {x} > {limit}, the largest this backend accepts"
            )));
        }
        Ok(m)
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
