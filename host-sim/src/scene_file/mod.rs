//! Scenes from TOML files (`host-sim render --scene FILE`): camera, lights, materials and
//! meshes, rendered in f32 with the crate's rasterizer. The format (every key, its type, unit,
//! default and range) is described in `docs/scene-format.md`; `host-sim/scenes/example.toml`
//! is a complete example.
//!
//! Every error names the file, line and column, and uses the file's own key names: TOML
//! syntax, unknown keys (with a suggestion when one is a near miss) and mistyped values (from
//! the parser); values out of range (at the key, with the allowed range); and the library's
//! refusals (a zero-area polygon, a zero direction) at the key that caused them. A Phong
//! exponent above 1000 is accepted with a warning (the cost of a specular sample grows
//! linearly with it).

use std::ops::Range;
use std::path::{Path, PathBuf};

use arealight::raster::{Affine, Camera, Encoding, Material, Projection, RasterError, Shading};
use arealight::{
    Ambient, CapLight, DirectionalLight, Environment, HemisphereLight, Illuminant, LineLight,
    OvercastSky, ParallelogramLight, PhongLobe, PointLight, PolygonLight, Real, Rgb, SceneLight,
    Sh9, SkyGround, SphereLight, Tinted, Vec3,
};
use serde::Deserialize;
use toml::Spanned;

use crate::eval::{closest, did_you_mean};
use crate::figure;
use crate::scenes::{self, Lights, Object, Scene, Surface};

/// The largest viewport side (the rasterizer's).
const MAX_SIDE: i64 = arealight::raster::MAX_VIEWPORT as i64;
/// The largest Phong exponent (the library's).
const MAX_EXPONENT: i64 = arealight::phong::MAX_EXPONENT as i64;
/// Above this exponent a scene renders, with a warning: every specular sample costs O(m).
const SLOW_EXPONENT: i64 = 1000;
/// The vertex capacity of a polygon light in a scene file.
pub const MAX_POLYGON: usize = 16;
/// The most vertices a mesh may have (16-bit indices).
const MAX_MESH_VERTICES: i64 = 1 << 16;

/// Defaults of the keys a file may leave out (`docs/scene-format.md` lists them).
const DEFAULT_UP: [f64; 3] = [0.0, 1.0, 0.0];
const DEFAULT_FOV_DEG: f64 = 40.0;
const DEFAULT_STACKS: u16 = 16;
const DEFAULT_SLICES: u16 = 32;
const DEFAULT_CELLS: [u16; 2] = [1, 1];
const DEFAULT_SEGMENTS: [u16; 2] = [32, 16];
const DEFAULT_EXPONENT: u32 = 1;
const DEFAULT_COLOUR: [f64; 3] = [1.0; 3];

mod spec;
pub use spec::emit_spec;

type S<T> = Spanned<T>;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    camera: S<CameraDef>,
    #[serde(default)]
    light: Vec<S<LightDef>>,
    #[serde(default)]
    material: Vec<S<MaterialDef>>,
    #[serde(default)]
    mesh: Vec<S<MeshDef>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraDef {
    eye: S<[f64; 3]>,
    target: S<[f64; 3]>,
    up: Option<S<[f64; 3]>>,
    fov_deg: Option<S<f64>>,
    width: S<i64>,
    height: S<i64>,
    /// Omitted: 0.8 over the lights' diffuse value at the origin with normal +y.
    exposure: Option<S<f64>>,
    background: Option<S<[i64; 3]>>,
    /// `"srgb"` (default), `"gamma2"` or `"linear"`.
    encoding: Option<S<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LightDef {
    kind: S<String>,
    colour: Option<S<[f64; 3]>>,
    direction: Option<S<[f64; 3]>>,
    position: Option<S<[f64; 3]>>,
    inverse_square: Option<S<bool>>,
    axis: Option<S<[f64; 3]>>,
    sigma_deg: Option<S<f64>>,
    center: Option<S<[f64; 3]>>,
    radius: Option<S<f64>>,
    vertices: Option<S<Vec<[f64; 3]>>>,
    a: Option<S<[f64; 3]>>,
    b: Option<S<[f64; 3]>>,
    origin: Option<S<[f64; 3]>>,
    eu: Option<S<[f64; 3]>>,
    ev: Option<S<[f64; 3]>>,
    sky: Option<S<[f64; 3]>>,
    ground: Option<S<[f64; 3]>>,
    environment: Option<S<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialDef {
    name: S<String>,
    diffuse: Option<S<[f64; 3]>>,
    /// Constant radiance instead of diffuse and specular reflection (a visible lamp).
    emissive: Option<S<[f64; 3]>>,
    specular: Option<S<[f64; 3]>>,
    exponent: Option<S<i64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MeshDef {
    kind: S<String>,
    material: S<String>,
    translate: Option<S<[f64; 3]>>,
    /// `[axis x, axis y, axis z, degrees]`.
    rotate: Option<S<[f64; 4]>>,
    scale: Option<S<[f64; 3]>>,
    gouraud: Option<S<bool>>,
    two_sided: Option<S<bool>>,
    radius: Option<S<f64>>,
    stacks: Option<S<i64>>,
    slices: Option<S<i64>>,
    size: Option<S<[f64; 2]>>,
    cells: Option<S<[i64; 2]>>,
    half: Option<S<[f64; 3]>>,
    major: Option<S<f64>>,
    minor: Option<S<f64>>,
    segments: Option<S<[i64; 2]>>,
}

/// The light kinds and the keys each takes besides `kind` and `colour` (required ones first;
/// `docs/scene-format.md` has the same table).
const LIGHT_KINDS: &[(&str, &[&str])] = &[
    ("directional", &["direction"]),
    ("point", &["position", "inverse_square"]),
    ("hemisphere", &["axis"]),
    ("overcast", &["axis"]),
    ("sky_ground", &["axis", "sky", "ground"]),
    ("cap", &["axis", "sigma_deg"]),
    ("sphere", &["center", "radius"]),
    ("polygon", &["vertices"]),
    ("line", &["a", "b"]),
    ("parallelogram", &["origin", "eu", "ev"]),
    ("sh9", &["environment"]),
    ("ambient", &[]),
];

/// The mesh kinds and the keys each takes besides the common ones.
const MESH_KINDS: &[(&str, &[&str])] = &[
    ("sphere", &["radius", "stacks", "slices"]),
    ("plane", &["size", "cells"]),
    ("box", &["half"]),
    ("torus", &["major", "minor", "segments"]),
];

/// The keys every mesh takes.
const MESH_COMMON: &[&str] = &[
    "kind",
    "material",
    "translate",
    "rotate",
    "scale",
    "gouraud",
    "two_sided",
];

/// The SH9 environments, by file name.
const ENVIRONMENTS: &[(&str, Environment)] = &[
    ("grace_cathedral", Environment::GraceCathedral),
    ("eucalyptus_grove", Environment::EucalyptusGrove),
    ("st_peters_basilica", Environment::StPetersBasilica),
];

/// `line:column` (1-based) of byte offset `at` in `src`.
pub fn line_col(src: &str, at: usize) -> (usize, usize) {
    let before = &src[..at.min(src.len())];
    let line = before.matches('\n').count() + 1;
    let col = before
        .rfind('\n')
        .map_or(before.len(), |i| before.len() - i - 1)
        + 1;
    (line, col)
}

/// The start of the key whose value starts at `value` (`width = 0`: the `w`), found by
/// walking back over `=` and the key; `value` itself if the text is not `key = value`.
fn key_start(src: &str, value: usize) -> usize {
    let b = src.as_bytes();
    let mut i = value.min(b.len());
    let ws = |c: u8| c == b' ' || c == b'\t';
    while i > 0 && ws(b[i - 1]) {
        i -= 1;
    }
    if i == 0 || b[i - 1] != b'=' {
        return value;
    }
    i -= 1;
    while i > 0 && ws(b[i - 1]) {
        i -= 1;
    }
    let end = i;
    while i > 0 && (b[i - 1].is_ascii_alphanumeric() || matches!(b[i - 1], b'_' | b'-' | b'"')) {
        i -= 1;
    }
    if i == end {
        value
    } else {
        i
    }
}

/// An error located at byte `at` of the file, or at the key of the value at `at`.
struct Located {
    at: usize,
    key: bool,
    msg: String,
}

/// An error at the key of the value spanning `span`.
fn at_key(span: Range<usize>, msg: impl Into<String>) -> Located {
    Located {
        at: span.start,
        key: true,
        msg: msg.into(),
    }
}

/// An error at byte `at` itself (a table header, a value).
fn at(at: usize, msg: impl Into<String>) -> Located {
    Located {
        at,
        key: false,
        msg: msg.into(),
    }
}

/// The byte offset of a located error in `src`.
fn resolve(src: &str, l: &Located) -> usize {
    if l.key {
        key_start(src, l.at)
    } else {
        l.at
    }
}

/// Formats a number as written in a file (`0.5`, `-1`, `1e300`).
fn show(x: f64) -> String {
    if x.is_nan() {
        "nan".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf" } else { "-inf" }.into()
    } else if x != 0.0 && (x.abs() >= 1e9 || x.abs() < 1e-6) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// `key` must be finite (TOML allows `nan` and `inf`).
fn finite<const K: usize>(key: &str, v: &S<[f64; K]>) -> Result<[f64; K], Located> {
    if v.get_ref().iter().all(|x| x.is_finite()) {
        Ok(*v.get_ref())
    } else {
        Err(at_key(
            v.span(),
            format!("`{key}` has a non-finite number (nan or inf)"),
        ))
    }
}

/// A number in `ok`, else `key = x is out of range: <range>`.
fn in_range(key: &str, v: &S<f64>, ok: impl Fn(f64) -> bool, range: &str) -> Result<f64, Located> {
    let x = *v.get_ref();
    if x.is_finite() && ok(x) {
        Ok(x)
    } else {
        Err(at_key(
            v.span(),
            format!("`{key}` = {} is out of range: {range}", show(x)),
        ))
    }
}

/// An integer in `lo..=hi`.
fn int_in(key: &str, v: &S<i64>, lo: i64, hi: i64, unit: &str) -> Result<u16, Located> {
    let x = *v.get_ref();
    if (lo..=hi).contains(&x) {
        Ok(x as u16)
    } else {
        Err(at_key(
            v.span(),
            format!("`{key}` = {x} is out of range: {lo} to {hi}{unit}"),
        ))
    }
}

/// A required key of a light or mesh kind.
fn need<'a, T>(
    x: &'a Option<S<T>>,
    what: &str,
    key: &str,
    pos: usize,
) -> Result<&'a S<T>, Located> {
    x.as_ref()
        .ok_or_else(|| at(pos, format!("a {what} needs `{key}`")))
}

fn v3<T: Real>(a: [f64; 3]) -> Vec3<T> {
    Vec3::from_f64(a)
}

/// Refuses keys that the kind does not take, at the key.
fn only_keys(
    present: &[(&'static str, Option<Range<usize>>)],
    allowed: &[&str],
    what: &str,
) -> Result<(), Located> {
    for (key, span) in present {
        if let Some(span) = span {
            if !allowed.contains(key) {
                return Err(at_key(
                    span.clone(),
                    format!(
                        "`{key}` is not a key of a {what} (its keys: {})",
                        allowed.join(", ")
                    ),
                ));
            }
        }
    }
    Ok(())
}

fn span_of<T>(x: &Option<S<T>>) -> Option<Range<usize>> {
    x.as_ref().map(|s| s.span())
}

impl LightDef {
    fn present(&self) -> [(&'static str, Option<Range<usize>>); 17] {
        [
            ("colour", span_of(&self.colour)),
            ("direction", span_of(&self.direction)),
            ("position", span_of(&self.position)),
            ("inverse_square", span_of(&self.inverse_square)),
            ("axis", span_of(&self.axis)),
            ("sigma_deg", span_of(&self.sigma_deg)),
            ("center", span_of(&self.center)),
            ("radius", span_of(&self.radius)),
            ("vertices", span_of(&self.vertices)),
            ("a", span_of(&self.a)),
            ("b", span_of(&self.b)),
            ("origin", span_of(&self.origin)),
            ("eu", span_of(&self.eu)),
            ("ev", span_of(&self.ev)),
            ("sky", span_of(&self.sky)),
            ("ground", span_of(&self.ground)),
            ("environment", span_of(&self.environment)),
        ]
    }

    /// The span of the file key `key`.
    fn span(&self, key: &str) -> Option<Range<usize>> {
        self.present()
            .into_iter()
            .find(|(k, _)| *k == key)
            .and_then(|(_, s)| s)
    }
}

/// A library refusal of a light, at the file key it concerns, in the file's names.
fn light_error(l: &LightDef, pos: usize, e: arealight::Error) -> Located {
    use arealight::Error as E;
    let file_key = |p: &'static str| -> &'static str {
        match p {
            "to_light" => "direction",
            "zenith" | "up" => "axis",
            "verts" => "vertices",
            "sigma" => "sigma_deg",
            other => other,
        }
    };
    let (key, msg) = match e {
        E::NotFinite(p) => {
            let k = file_key(p);
            (k, format!("`{k}` is not finite (nan or inf, or beyond f32's range)"))
        }
        E::ZeroLength("segment") => ("b", "`a` and `b` are the same point".to_owned()),
        E::ZeroLength(p) => {
            let k = file_key(p);
            (k, format!("`{k}` has zero length (a direction must be non-zero)"))
        }
        E::TooManyVertices { .. } => (
            "vertices",
            format!("`vertices`: more than {MAX_POLYGON} (a scene's polygon light has at most {MAX_POLYGON})"),
        ),
        E::TooFewVertices | E::NotPlanar | E::NotSimple => ("vertices", format!("`vertices`: {e}")),
        E::ZeroArea if l.kind.get_ref() == "parallelogram" => {
            ("ev", "`eu` and `ev` are parallel (the parallelogram has zero area)".to_owned())
        }
        E::ZeroArea => ("vertices", format!("`vertices`: {e}")),
        E::RadiusNotPositive => ("radius", "`radius` is out of range: > 0".to_owned()),
        E::SigmaOutOfRange => ("sigma_deg", "`sigma_deg` is out of range: 0 to 90 degrees".to_owned()),
        other => ("", other.to_string()),
    };
    match l.span(key) {
        Some(span) => at_key(span, msg),
        None => at(pos, msg),
    }
}

/// A cap or sphere light whose diffuse term is Snyder's two-segment Hermite approximation
/// (`lambert_hermite`) instead of the exact one (`host-sim budget`'s "Hermite" option); its
/// Phong term is the exact one's.
struct Hermite<L>(L);

impl<T: Real> Illuminant<T> for Hermite<CapLight<T>> {
    fn diffuse(&self, _p: Vec3<T>, n: Vec3<T>) -> Rgb<T> {
        Rgb::splat(self.0.lambert_hermite(n))
    }
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: Vec3<T>) -> Rgb<T> {
        Illuminant::phong(&self.0, lobe, p, r)
    }
}

impl<T: Real> Illuminant<T> for Hermite<SphereLight<T>> {
    fn diffuse(&self, p: Vec3<T>, n: Vec3<T>) -> Rgb<T> {
        Rgb::splat(self.0.lambert_hermite(p, n))
    }
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: Vec3<T>) -> Rgb<T> {
        Illuminant::phong(&self.0, lobe, p, r)
    }
}

/// A light of the file: the boxed light the host renders with, what the budget needs of it,
/// and the same light as a [`SceneLight`] (the boards' light type: `Scene::prepare`'s culling),
/// for the kinds a `Scene` holds.
type BuiltLight<T> = (
    Box<dyn Illuminant<T>>,
    LightInfo,
    Option<SceneLight<T, MAX_POLYGON>>,
);

fn build_light<T: Real + 'static>(
    l: &LightDef,
    pos: usize,
    hermite: bool,
) -> Result<BuiltLight<T>, Located> {
    let k = l.kind.get_ref().as_str();
    let Some((_, keys)) = LIGHT_KINDS.iter().find(|(n, _)| *n == k) else {
        let names: Vec<&str> = LIGHT_KINDS.iter().map(|(n, _)| *n).collect();
        return Err(at_key(
            l.kind.span(),
            format!(
                "unknown light kind {k:?}{}; kinds: {}",
                did_you_mean(k, names.iter().copied()),
                names.join(", ")
            ),
        ));
    };
    let mut allowed = vec!["colour"];
    allowed.extend_from_slice(keys);
    only_keys(&l.present(), &allowed, &format!("{k} light"))?;
    let what = format!("{k} light");
    let vec = |x: &Option<S<[f64; 3]>>, key: &str| -> Result<Vec3<T>, Located> {
        Ok(v3(finite(key, need(x, &what, key, pos)?)?))
    };
    let rgb = |x: &Option<S<[f64; 3]>>, key: &str| -> Result<Rgb<T>, Located> {
        Ok(Rgb::from_f64(finite(key, need(x, &what, key, pos)?)?))
    };
    let e = |e: arealight::Error| light_error(l, pos, e);
    let mut vertices = 0;
    // Boxed, with its `SceneLight` twin where a `Scene` holds the kind.
    fn both<T: Real + 'static, L: Illuminant<T> + Clone + 'static>(
        l: L,
        scene: impl FnOnce(L) -> SceneLight<T, MAX_POLYGON>,
    ) -> (Box<dyn Illuminant<T>>, Option<SceneLight<T, MAX_POLYGON>>) {
        (Box::new(l.clone()), Some(scene(l)))
    }
    let (light, scene_light): (Box<dyn Illuminant<T>>, _) = match k {
        "directional" => both(
            DirectionalLight::new(vec(&l.direction, "direction")?).map_err(e)?,
            SceneLight::Directional,
        ),
        "point" => {
            let p = vec(&l.position, "position")?;
            let inverse_square = l.inverse_square.as_ref().is_some_and(|s| *s.get_ref());
            both(
                if inverse_square {
                    PointLight::inverse_square(p)
                } else {
                    PointLight::new(p)
                }
                .map_err(e)?,
                SceneLight::Point,
            )
        }
        "hemisphere" => both(
            HemisphereLight::new(vec(&l.axis, "axis")?).map_err(e)?,
            SceneLight::Hemisphere,
        ),
        "overcast" => both(
            OvercastSky::new(vec(&l.axis, "axis")?, T::ONE).map_err(e)?,
            SceneLight::Overcast,
        ),
        "sky_ground" => both(
            SkyGround::new(
                vec(&l.axis, "axis")?,
                rgb(&l.sky, "sky")?,
                rgb(&l.ground, "ground")?,
            )
            .map_err(e)?,
            SceneLight::SkyGround,
        ),
        "cap" => {
            let axis = vec(&l.axis, "axis")?;
            let s = need(&l.sigma_deg, &what, "sigma_deg", pos)?;
            let sigma = in_range(
                "sigma_deg",
                s,
                |x| (0.0..=90.0).contains(&x),
                "0 to 90 degrees",
            )?;
            let cap = CapLight::new(
                axis,
                T::from_f64(sigma.to_radians().min(core::f64::consts::FRAC_PI_2)),
            )
            .map_err(e)?;
            if hermite {
                (Box::new(Hermite(cap)), Some(SceneLight::Cap(cap)))
            } else {
                both(cap, SceneLight::Cap)
            }
        }
        "sphere" => {
            let center = vec(&l.center, "center")?;
            let r = need(&l.radius, &what, "radius", pos)?;
            let r = in_range("radius", r, |x| x > 0.0, "> 0")?;
            let sphere = SphereLight::new(center, T::from_f64(r)).map_err(e)?;
            if hermite {
                (Box::new(Hermite(sphere)), Some(SceneLight::Sphere(sphere)))
            } else {
                both(sphere, SceneLight::Sphere)
            }
        }
        "polygon" => {
            let vs = need(&l.vertices, &what, "vertices", pos)?;
            if vs.get_ref().iter().flatten().any(|x| !x.is_finite()) {
                return Err(at_key(
                    vs.span(),
                    "`vertices` has a non-finite number (nan or inf)",
                ));
            }
            if !(3..=MAX_POLYGON).contains(&vs.get_ref().len()) {
                return Err(at_key(
                    vs.span(),
                    format!(
                        "`vertices` has {} vertices: a polygon light has 3 to {MAX_POLYGON}",
                        vs.get_ref().len()
                    ),
                ));
            }
            let vs: Vec<Vec3<T>> = vs.get_ref().iter().map(|&p| v3(p)).collect();
            vertices = vs.len();
            both(
                PolygonLight::<T, MAX_POLYGON>::new(&vs).map_err(e)?,
                SceneLight::Polygon,
            )
        }
        "line" => (
            Box::new(LineLight::new(vec(&l.a, "a")?, vec(&l.b, "b")?).map_err(e)?),
            None,
        ),
        "parallelogram" => (
            Box::new(
                ParallelogramLight::new(
                    vec(&l.origin, "origin")?,
                    vec(&l.eu, "eu")?,
                    vec(&l.ev, "ev")?,
                )
                .map_err(e)?,
            ),
            None,
        ),
        "sh9" => {
            let env = match &l.environment {
                None => Environment::GraceCathedral,
                Some(name) => {
                    let n = name.get_ref().as_str();
                    match ENVIRONMENTS.iter().find(|(k, _)| *k == n) {
                        Some((_, env)) => *env,
                        None => {
                            let names: Vec<&str> = ENVIRONMENTS.iter().map(|(k, _)| *k).collect();
                            return Err(at_key(
                                name.span(),
                                format!(
                                    "unknown environment {n:?}{}; environments: {}",
                                    did_you_mean(n, names.iter().copied()),
                                    names.join(", ")
                                ),
                            ));
                        }
                    }
                }
            };
            both(Sh9::<T>::environment(env).prepare(), SceneLight::Sh9)
        }
        _ => both(Ambient(Rgb::splat(T::ONE)), SceneLight::Ambient),
    };
    let colour = match &l.colour {
        Some(c) => finite("colour", c)?,
        None => DEFAULT_COLOUR,
    };
    let kind = match (k, hermite) {
        ("cap", true) => "cap_hermite",
        ("sphere", true) => "sphere_hermite",
        _ => LIGHT_KINDS
            .iter()
            .find(|(n, _)| *n == k)
            .map_or("ambient", |(n, _)| *n),
    };
    let info = LightInfo {
        kind,
        vertices,
        line: 0,
        colour,
    };
    Ok((
        Box::new(Tinted::new(Lights(vec![light]), Rgb::from_f64(colour)).map_err(e)?),
        info,
        scene_light,
    ))
}

impl MeshDef {
    fn present(&self) -> [(&'static str, Option<Range<usize>>); 14] {
        [
            ("translate", span_of(&self.translate)),
            ("rotate", span_of(&self.rotate)),
            ("scale", span_of(&self.scale)),
            ("gouraud", span_of(&self.gouraud)),
            ("two_sided", span_of(&self.two_sided)),
            ("radius", span_of(&self.radius)),
            ("stacks", span_of(&self.stacks)),
            ("slices", span_of(&self.slices)),
            ("size", span_of(&self.size)),
            ("cells", span_of(&self.cells)),
            ("half", span_of(&self.half)),
            ("major", span_of(&self.major)),
            ("minor", span_of(&self.minor)),
            ("segments", span_of(&self.segments)),
        ]
    }
}

/// A mesh's vertex count `(a + 1)(b + 1)` within 16-bit indices, else an error at `span`.
fn grid_fits(a: u16, b: u16, keys: &str, span: Range<usize>) -> Result<(), Located> {
    let n = (a as i64 + 1) * (b as i64 + 1);
    if n > MAX_MESH_VERTICES {
        Err(at_key(
            span,
            format!("{keys} give {n} vertices: a mesh has at most {MAX_MESH_VERTICES}"),
        ))
    } else {
        Ok(())
    }
}

/// `n` segments times the tessellation factor `tess`, rounded, at least `min` (what a budget
/// tries; 1 keeps the file's values).
fn tessellate(n: u16, tess: f64, min: u16) -> u16 {
    if tess == 1.0 {
        return n;
    }
    ((f64::from(n) * tess).round().clamp(f64::from(min), 4096.0) as u16).max(min)
}

fn build_mesh<T: Real>(m: &MeshDef, pos: usize, tess: f64) -> Result<scenes::MeshBuf<T>, Located> {
    let k = m.kind.get_ref().as_str();
    let Some((_, keys)) = MESH_KINDS.iter().find(|(n, _)| *n == k) else {
        let names: Vec<&str> = MESH_KINDS.iter().map(|(n, _)| *n).collect();
        return Err(at_key(
            m.kind.span(),
            format!(
                "unknown mesh kind {k:?}{}; kinds: {}",
                did_you_mean(k, names.iter().copied()),
                names.join(", ")
            ),
        ));
    };
    let mut allowed = MESH_COMMON.to_vec();
    allowed.extend_from_slice(keys);
    only_keys(&m.present(), &allowed, &format!("{k} mesh"))?;
    let what = format!("{k} mesh");
    let positive = |key: &str, x: &Option<S<f64>>| -> Result<f64, Located> {
        in_range(key, need(x, &what, key, pos)?, |x| x > 0.0, "> 0")
    };
    let e = |e: RasterError| at(pos, e.to_string());
    match k {
        "sphere" => {
            let r = positive("radius", &m.radius)?;
            let stacks = match &m.stacks {
                Some(s) => int_in("stacks", s, 2, 4096, "")?,
                None => DEFAULT_STACKS,
            };
            let slices = match &m.slices {
                Some(s) => int_in("slices", s, 3, 4096, "")?,
                None => DEFAULT_SLICES,
            };
            let span = span_of(&m.stacks)
                .or(span_of(&m.slices))
                .unwrap_or(pos..pos);
            grid_fits(stacks, slices, "`stacks` and `slices`", span)?;
            let (stacks, slices) = (tessellate(stacks, tess, 2), tessellate(slices, tess, 3));
            grid_fits(
                stacks,
                slices,
                "`stacks` and `slices`",
                span_of(&m.stacks).unwrap_or(pos..pos),
            )?;
            scenes::sphere(r, stacks, slices).map_err(e)
        }
        "plane" => {
            let s = need(&m.size, &what, "size", pos)?;
            let size = finite("size", s)?;
            if !size.iter().all(|&x| x > 0.0) {
                return Err(at_key(
                    s.span(),
                    format!(
                        "`size` = [{}, {}] is out of range: both > 0",
                        show(size[0]),
                        show(size[1])
                    ),
                ));
            }
            let c = match &m.cells {
                Some(c) => {
                    let [a, b] = *c.get_ref();
                    let ok = |x: i64| (1..=4096).contains(&x);
                    if !(ok(a) && ok(b)) {
                        return Err(at_key(
                            c.span(),
                            format!("`cells` = [{a}, {b}] is out of range: 1 to 4096 each"),
                        ));
                    }
                    grid_fits(a as u16, b as u16, "`cells`", c.span())?;
                    [a as u16, b as u16]
                }
                None => DEFAULT_CELLS,
            };
            let c = c.map(|n| tessellate(n, tess, 1));
            grid_fits(c[0], c[1], "`cells`", span_of(&m.cells).unwrap_or(pos..pos))?;
            scenes::plane(size[0], size[1], c[0], c[1]).map_err(e)
        }
        "box" => {
            let h = need(&m.half, &what, "half", pos)?;
            let half = finite("half", h)?;
            if !half.iter().all(|&x| x > 0.0) {
                return Err(at_key(
                    h.span(),
                    format!(
                        "`half` = [{}, {}, {}] is out of range: all three > 0",
                        show(half[0]),
                        show(half[1]),
                        show(half[2])
                    ),
                ));
            }
            scenes::cuboid(half).map_err(e)
        }
        _ => {
            let major = positive("major", &m.major)?;
            let minor = need(&m.minor, &what, "minor", pos)?;
            let minor = in_range(
                "minor",
                minor,
                |x| x > 0.0 && x < major,
                &format!("> 0 and < `major` ({})", show(major)),
            )?;
            let s = match &m.segments {
                Some(s) => {
                    let [a, b] = *s.get_ref();
                    let ok = |x: i64| (3..=4096).contains(&x);
                    if !(ok(a) && ok(b)) {
                        return Err(at_key(
                            s.span(),
                            format!("`segments` = [{a}, {b}] is out of range: 3 to 4096 each"),
                        ));
                    }
                    grid_fits(a as u16, b as u16, "`segments`", s.span())?;
                    [a as u16, b as u16]
                }
                None => DEFAULT_SEGMENTS,
            };
            let s = s.map(|n| tessellate(n, tess, 3));
            grid_fits(
                s[0],
                s[1],
                "`segments`",
                span_of(&m.segments).unwrap_or(pos..pos),
            )?;
            scenes::torus(major, minor, s[0], s[1]).map_err(e)
        }
    }
}

/// The mesh's transform: scale, then rotate, then translate.
fn transform<T: Real>(d: &MeshDef) -> Result<Affine<T>, Located> {
    let mut xf = Affine::identity();
    if let Some(s) = &d.scale {
        let v = finite("scale", s)?;
        if v.contains(&0.0) {
            return Err(at_key(
                s.span(),
                "`scale` has a zero component: each must be non-zero (negative mirrors)",
            ));
        }
        xf = xf.then(&Affine::scale(v3(v)).map_err(|e| at_key(s.span(), format!("`scale`: {e}")))?);
    }
    if let Some(r) = &d.rotate {
        let [x, y, z, deg] = finite("rotate", r)?;
        if [x, y, z] == [0.0; 3] {
            return Err(at_key(
                r.span(),
                "`rotate` has a zero axis: [axis x, axis y, axis z, degrees] needs a non-zero axis",
            ));
        }
        xf = xf.then(
            &Affine::rotation(v3([x, y, z]), T::from_f64(deg.to_radians()))
                .map_err(|e| at_key(r.span(), format!("`rotate`: {e}")))?,
        );
    }
    if let Some(t) = &d.translate {
        let v = finite("translate", t)?;
        xf = xf.then(
            &Affine::translation(v3(v))
                .map_err(|e| at_key(t.span(), format!("`translate`: {e}")))?,
        );
    }
    Ok(xf)
}

fn build_camera<T: Real>(cam: &CameraDef, pos: usize) -> Result<Camera<T>, Located> {
    let eye = finite("eye", &cam.eye)?;
    let target = finite("target", &cam.target)?;
    let up = match &cam.up {
        Some(u) => finite("up", u)?,
        None => DEFAULT_UP,
    };
    let fov = match &cam.fov_deg {
        Some(f) => in_range(
            "fov_deg",
            f,
            |x| x > 0.0 && x < 180.0,
            "more than 0 and less than 180 degrees",
        )?,
        None => DEFAULT_FOV_DEG,
    };
    let px = " pixels";
    let width = int_in("width", &cam.width, 1, MAX_SIDE, px)?;
    let height = int_in("height", &cam.height, 1, MAX_SIDE, px)?;
    if eye == target {
        return Err(at_key(
            cam.target.span(),
            "`target` is the same point as `eye` (the camera looks from eye to target)",
        ));
    }
    Camera::new(
        v3(eye),
        v3(target),
        v3(up),
        Projection::Perspective {
            fov_y: T::from_f64(fov.to_radians()),
        },
        width,
        height,
    )
    .map_err(|e| {
        use arealight::Error as E;
        let up_span = cam.up.as_ref().map(|u| u.span());
        match e {
            RasterError::Model(E::ZeroLength("up")) => match up_span {
                Some(s) => at_key(s, "`up` has zero length (it gives the camera's roll)"),
                None => at(pos, e.to_string()),
            },
            RasterError::Model(E::Parallel { .. }) => {
                let msg = "`up` is parallel to the view direction (target - eye): it cannot give the roll";
                match up_span {
                    Some(s) => at_key(s, msg),
                    None => at_key(cam.target.span(), format!("{msg} (the default up is [0, 1, 0])")),
                }
            }
            RasterError::Model(E::ZeroLength(_)) => at_key(
                cam.target.span(),
                "`target` is too close to `eye` (the camera looks from eye to target)",
            ),
            other => at(pos, other.to_string()),
        }
    })
}

/// A built scene with what the budget needs of its file.
type Built<T> = (
    Scene<T>,
    Vec<LightInfo>,
    Vec<ObjectInfo>,
    Vec<Option<SceneLight<T, MAX_POLYGON>>>,
);

fn build<T: Real + 'static>(
    file: &File,
    src: &str,
    tess: f64,
    hermite: bool,
    warnings: &mut Vec<Located>,
) -> Result<Built<T>, Located> {
    let cam = file.camera.get_ref();
    let camera = build_camera(cam, file.camera.span().start)?;
    let mut lights = Vec::new();
    let mut light_info = Vec::new();
    let mut scene_lights = Vec::new();
    for l in &file.light {
        let (light, mut info, scene_light) = build_light(l.get_ref(), l.span().start, hermite)?;
        info.line = line_col(src, l.span().start).0;
        lights.push(light);
        light_info.push(info);
        scene_lights.push(scene_light);
    }
    let lights = Lights(lights);
    let mut materials: Vec<(String, Finish<T>)> = Vec::new();
    for m in &file.material {
        let d = m.get_ref();
        let name = d.name.get_ref();
        if materials.iter().any(|(n, _)| n == name) {
            return Err(at_key(
                d.name.span(),
                format!("a second material named {name:?} (names must be unique)"),
            ));
        }
        if let Some(e) = &d.emissive {
            let emitted = finite("emissive", e)?;
            if emitted.iter().any(|&c| c < 0.0) {
                return Err(at_key(
                    e.span(),
                    "`emissive` has a negative channel: each must be >= 0",
                ));
            }
            let other = [
                ("diffuse", span_of(&d.diffuse)),
                ("specular", span_of(&d.specular)),
                ("exponent", span_of(&d.exponent)),
            ];
            if let Some((key, Some(span))) = other.into_iter().find(|(_, s)| s.is_some()) {
                return Err(at_key(
                    span,
                    format!("`{key}` in an emissive material: an `emissive` material shines with its own colour and takes no `diffuse`, `specular` or `exponent`"),
                ));
            }
            materials.push((name.clone(), Finish::Emissive(Rgb::from_f64(emitted))));
            continue;
        }
        let Some(diffuse) = &d.diffuse else {
            return Err(at(
                m.span().start,
                "missing key `diffuse` in [[material]] (or `emissive` for a light's own glow)",
            ));
        };
        let diffuse = finite("diffuse", diffuse)?;
        let specular = match &d.specular {
            Some(s) => finite("specular", s)?,
            None => [0.0; 3],
        };
        let exponent = match &d.exponent {
            Some(x) => {
                let m = *x.get_ref();
                if !(0..=MAX_EXPONENT).contains(&m) {
                    return Err(at_key(
                        x.span(),
                        format!(
                            "`exponent` = {m} is out of range: 0 to {MAX_EXPONENT} (the library's largest Phong exponent; a specular sample costs O(exponent))"
                        ),
                    ));
                }
                if m > SLOW_EXPONENT {
                    warnings.push(at_key(
                        x.span(),
                        format!(
                            "`exponent` = {m} makes rendering slow: a specular sample costs O(exponent), about {} times the cost at {SLOW_EXPONENT} (the library accepts up to {MAX_EXPONENT})",
                            m / SLOW_EXPONENT),
                    ));
                }
                m as u32
            }
            None => DEFAULT_EXPONENT,
        };
        let mat = Material::new(Rgb::from_f64(diffuse), Rgb::from_f64(specular), exponent)
            .map_err(|e| at(m.span().start, e.to_string()))?;
        materials.push((name.clone(), Finish::Lit(mat)));
    }
    let mut objects = Vec::new();
    let mut object_info = Vec::new();
    for m in &file.mesh {
        let (d, pos) = (m.get_ref(), m.span().start);
        let name = d.material.get_ref();
        let Some((_, mat)) = materials.iter().find(|(n, _)| n == name) else {
            let names: Vec<&str> = materials.iter().map(|(n, _)| n.as_str()).collect();
            let hint = closest(name, names.iter().copied())
                .map_or(String::new(), |c| format!(" (did you mean {c:?}?)"));
            return Err(at_key(
                d.material.span(),
                format!(
                    "no material named {name:?}{hint}; the file's materials: {}",
                    if names.is_empty() {
                        "none (add a [[material]])".to_owned()
                    } else {
                        names.join(", ")
                    }
                ),
            ));
        };
        let mesh = build_mesh(d, pos, tess)?;
        let xf = transform(d)?;
        object_info.push(ObjectInfo {
            kind: MESH_KINDS
                .iter()
                .find(|(n, _)| *n == d.kind.get_ref().as_str())
                .map_or("mesh", |(n, _)| *n),
            line: line_col(src, pos).0,
            material: name.clone(),
            vertices: mesh.verts.len(),
            triangles: mesh.tris.len(),
        });
        let surface = match mat {
            Finish::Lit(m) => Surface::Lit(*m),
            Finish::Emissive(c) => Surface::Emissive(*c),
        };
        objects.push(Object {
            shading: if d.gouraud.as_ref().is_some_and(|g| *g.get_ref()) {
                Shading::Gouraud
            } else {
                Shading::PerPixel
            },
            two_sided: d.two_sided.as_ref().is_some_and(|t| *t.get_ref()),
            ..Object::new(mesh, xf, surface)
        });
    }
    let exposure = match &cam.exposure {
        Some(x) => T::from_f64(in_range("exposure", x, |x| x > 0.0, "> 0")?),
        None => scenes::exposure_at(&lights, v3([0.0; 3]), v3([0.0, 1.0, 0.0])),
    };
    let background = match &cam.background {
        Some(b) => {
            let [r, g, bl] = *b.get_ref();
            if ![r, g, bl].iter().all(|c| (0..=255).contains(c)) {
                return Err(at_key(
                    b.span(),
                    format!(
                        "`background` = [{r}, {g}, {bl}] is out of range: 0 to 255 each (sRGB)"
                    ),
                ));
            }
            [r as u8, g as u8, bl as u8]
        }
        None => [0; 3],
    };
    let encoding = match &cam.encoding {
        None => Encoding::Srgb,
        Some(e) => match e.get_ref().as_str() {
            "srgb" => Encoding::Srgb,
            "gamma2" => Encoding::Gamma2,
            "linear" => Encoding::Linear,
            other => {
                return Err(at_key(
                    e.span(),
                    format!(
                        "unknown encoding {other:?}{}; encodings: srgb, gamma2, linear",
                        did_you_mean(other, ["srgb", "gamma2", "linear"].into_iter())
                    ),
                ))
            }
        },
    };
    Ok((
        Scene {
            camera,
            objects,
            lights,
            exposure,
            background,
            encoding,
        },
        light_info,
        object_info,
        scene_lights,
    ))
}

/// A material as the file gives it: lit by the scene's lights, or glowing on its own.
enum Finish<T> {
    Lit(Material<T>),
    Emissive(Rgb<T>),
}

/// What a scene file's light is, for budgets (`host-sim budget --scene`).
#[derive(Clone, Debug, PartialEq)]
pub struct LightInfo {
    /// Its `kind` (`"polygon"`, `"sphere"`, ...).
    pub kind: &'static str,
    /// A polygon light's vertex count (0 for other kinds).
    pub vertices: usize,
    /// The line of its `[[light]]` header.
    pub line: usize,
    /// Its colour (the file's, or white).
    pub colour: [f64; 3],
}

/// What a scene file's mesh is, for budgets (`host-sim budget --scene`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ObjectInfo {
    /// Its `kind` (`"sphere"`, `"torus"`, ...).
    pub kind: &'static str,
    /// The line of its `[[mesh]]` header.
    pub line: usize,
    /// Its material's name.
    pub material: String,
    /// Vertices of its mesh.
    pub vertices: usize,
    /// Triangles of its mesh.
    pub triangles: usize,
}

/// A TOML error's message with a suggestion for an unknown key: serde's "unknown field `x`,
/// expected one of `a`, `b`" gains "(did you mean `a`?)".
fn toml_message(msg: &str) -> String {
    let msg = msg.trim();
    let Some(rest) = msg.strip_prefix("unknown field `") else {
        return msg.to_owned();
    };
    let Some((field, expected)) = rest.split_once('`') else {
        return msg.to_owned();
    };
    let candidates: Vec<&str> = expected.split('`').skip(1).step_by(2).collect();
    match closest(field, candidates.iter().copied()) {
        Some(c) => format!("unknown key `{field}` (did you mean `{c}`?){expected}"),
        None => format!("unknown key `{field}`{expected}"),
    }
}

/// A parsed scene and its warnings (`name:line:column: warning: ...`).
pub struct Parsed<T = f32> {
    /// The scene.
    pub scene: Scene<T>,
    /// Warnings (the scene renders, perhaps slowly).
    pub warnings: Vec<String>,
    /// The lights, in file order (the scene's lights are in the same order).
    pub lights: Vec<LightInfo>,
    /// The meshes, in file order (the scene's objects are in the same order).
    pub objects: Vec<ObjectInfo>,
    /// Each light as a [`SceneLight`] (`None` for the kinds a `Scene` does not hold: line,
    /// parallelogram), in file order: what `host-sim budget`'s light culling tests.
    pub scene_lights: Vec<Option<SceneLight<T, MAX_POLYGON>>>,
}

/// Parses and builds the scene in `src` (named `name` in messages).
///
/// # Errors
/// `name:line:column: message` for a syntax error, an unknown or mistyped key, a value out of
/// range, or a value the library refuses.
pub fn parse(name: &str, src: &str) -> Result<Parsed, String> {
    parse_as::<f32>(name, src)
}

/// [`parse`] in any scalar type `T` (the lights, meshes, camera and materials built in `T`,
/// from the file's decimal values): what `host-sim budget --scene` renders each backend with.
///
/// # Errors
/// As [`parse`]; also a value the library refuses in `T` (for example a coordinate beyond
/// the fixed-point range).
pub fn parse_as<T: Real + 'static>(name: &str, src: &str) -> Result<Parsed<T>, String> {
    parse_tessellated(name, src, 1.0)
}

/// [`parse_as`] with every mesh's segment counts (a sphere's `stacks` and `slices`, a
/// torus's `segments`, a plane's `cells`; not a box) times `tess`, rounded, at least their
/// minimum: what `host-sim budget --scene` tries besides the file's own tessellation.
///
/// # Errors
/// As [`parse_as`].
pub fn parse_tessellated<T: Real + 'static>(
    name: &str,
    src: &str,
    tess: f64,
) -> Result<Parsed<T>, String> {
    parse_variant(name, src, tess, false)
}

/// [`parse_tessellated`], and with `hermite` every cap and sphere light's diffuse term
/// replaced by Snyder's Hermite approximation (`lambert_hermite`; their kinds become
/// `cap_hermite` and `sphere_hermite`): `host-sim budget --scene`'s "Hermite" option.
///
/// # Errors
/// As [`parse_as`].
pub fn parse_variant<T: Real + 'static>(
    name: &str,
    src: &str,
    tess: f64,
    hermite: bool,
) -> Result<Parsed<T>, String> {
    let located = |l: Located| {
        let (line, col) = line_col(src, resolve(src, &l));
        format!("{name}:{line}:{col}: {}", l.msg)
    };
    let file: File = toml::from_str(src).map_err(|e| {
        let at = e.span().map_or(0, |s| s.start);
        located(Located {
            at,
            key: false,
            msg: toml_message(e.message()),
        })
    })?;
    let mut warnings = Vec::new();
    let (scene, lights, objects, scene_lights) =
        build(&file, src, tess, hermite, &mut warnings).map_err(located)?;
    let warnings = warnings
        .into_iter()
        .map(|w| {
            let (line, col) = line_col(src, resolve(src, &w));
            format!("{name}:{line}:{col}: warning: {}", w.msg)
        })
        .collect();
    Ok(Parsed {
        scene,
        warnings,
        lights,
        objects,
        scene_lights,
    })
}

/// Renders the scene file `path` into `out/<file stem>.png`; warnings go to standard error.
///
/// # Errors
/// A message for an unreadable or bad file, or a PNG that cannot be written.
pub fn render_file(path: &Path, out: &Path) -> Result<PathBuf, String> {
    let src = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let Parsed {
        scene, warnings, ..
    } = parse(&path.display().to_string(), &src)?;
    for w in &warnings {
        eprintln!("{w}");
    }
    let stem = path
        .file_stem()
        .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
    let gouraud = scene
        .objects
        .iter()
        .filter(|o| o.shading == Shading::Gouraud)
        .count();
    let shading = match gouraud {
        0 => "per pixel",
        g if g == scene.objects.len() => "Gouraud",
        _ => "per pixel and Gouraud",
    };
    let p = scenes::panel(&scene, &format!("{stem} (f32, {shading})"))
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let pix = figure::sheet(&format!("scene file {}", path.display()), &[p], 1, "");
    figure::save(&pix, out, &format!("{stem}.png"))
}

#[cfg(test)]
mod tests;
