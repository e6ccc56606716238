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
    Sh9, SkyGround, SphereLight, Tinted, UnitVec3, Vec3,
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

mod build;
mod geometry;
mod lights;
mod spec;
use build::build;
use geometry::{build_camera, build_mesh, transform};
use lights::build_light;
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
