//! Scenes from TOML files (`host-sim render --scene FILE`): camera, lights, materials and
//! meshes, rendered in f32 with the crate's rasterizer. See `host-sim/scenes/example.toml`.
//!
//! Every error names the file, line and column: TOML syntax and unknown or mistyped keys (from
//! the parser), and the library's refusals (a zero-area polygon, a sphere radius <= 0, an
//! unknown material) at the entry that caused them.

use std::path::{Path, PathBuf};

use arealight::raster::{Affine, Camera, Material, Projection, RasterError, Shading};
use arealight::{
    Ambient, CapLight, DirectionalLight, Environment, HemisphereLight, Illuminant, LineLight,
    OvercastSky, ParallelogramLight, PointLight, PolygonLight, Rgb, Sh9, SkyGround, SphereLight,
    Tinted, Vec3,
};
use serde::Deserialize;
use toml::Spanned;

use crate::figure;
use crate::scenes::{self, Lights, Object, Scene, Surface};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    camera: Spanned<CameraDef>,
    #[serde(default)]
    light: Vec<Spanned<LightDef>>,
    #[serde(default)]
    material: Vec<Spanned<MaterialDef>>,
    #[serde(default)]
    mesh: Vec<Spanned<MeshDef>>,
}

fn default_up() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}
fn default_fov() -> f64 {
    40.0
}
fn white() -> [f64; 3] {
    [1.0, 1.0, 1.0]
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraDef {
    eye: [f64; 3],
    target: [f64; 3],
    #[serde(default = "default_up")]
    up: [f64; 3],
    #[serde(default = "default_fov")]
    fov_deg: f64,
    width: u16,
    height: u16,
    /// Omitted: 0.8 over the light's diffuse value at the origin with normal +y.
    exposure: Option<f64>,
    #[serde(default)]
    background: [u8; 3],
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LightDef {
    kind: String,
    #[serde(default = "white")]
    colour: [f64; 3],
    direction: Option<[f64; 3]>,
    position: Option<[f64; 3]>,
    #[serde(default)]
    inverse_square: bool,
    axis: Option<[f64; 3]>,
    sigma_deg: Option<f64>,
    center: Option<[f64; 3]>,
    radius: Option<f64>,
    vertices: Option<Vec<[f64; 3]>>,
    a: Option<[f64; 3]>,
    b: Option<[f64; 3]>,
    origin: Option<[f64; 3]>,
    eu: Option<[f64; 3]>,
    ev: Option<[f64; 3]>,
    sky: Option<[f64; 3]>,
    ground: Option<[f64; 3]>,
    environment: Option<String>,
}

fn default_exponent() -> u32 {
    1
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialDef {
    name: String,
    diffuse: [f64; 3],
    #[serde(default)]
    specular: [f64; 3],
    #[serde(default = "default_exponent")]
    exponent: u32,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MeshDef {
    kind: String,
    material: Spanned<String>,
    #[serde(default)]
    translate: [f64; 3],
    /// `[axis x, axis y, axis z, degrees]`.
    rotate: Option<[f64; 4]>,
    scale: Option<[f64; 3]>,
    #[serde(default)]
    gouraud: bool,
    #[serde(default)]
    two_sided: bool,
    radius: Option<f64>,
    stacks: Option<u16>,
    slices: Option<u16>,
    size: Option<[f64; 2]>,
    cells: Option<[u16; 2]>,
    half: Option<[f64; 3]>,
    major: Option<f64>,
    minor: Option<f64>,
    segments: Option<[u16; 2]>,
}

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

/// An error located at `at` in the file.
struct Located {
    at: usize,
    msg: String,
}

fn at<E: std::fmt::Display>(at: usize) -> impl Fn(E) -> Located {
    move |e| Located {
        at,
        msg: e.to_string(),
    }
}

fn need<T: Copy>(x: Option<T>, kind: &str, key: &str, pos: usize) -> Result<T, Located> {
    x.ok_or_else(|| Located {
        at: pos,
        msg: format!("a {kind} needs `{key}`"),
    })
}

fn v3(a: [f64; 3]) -> Vec3<f32> {
    Vec3::from_f64(a)
}

fn build_light(l: &LightDef, pos: usize) -> Result<Box<dyn Illuminant<f32>>, Located> {
    let k = l.kind.as_str();
    let e = at::<arealight::Error>(pos);
    let light: Box<dyn Illuminant<f32>> = match k {
        "directional" => Box::new(DirectionalLight::new(v3(need(l.direction, k, "direction", pos)?)).map_err(&e)?),
        "point" => {
            let p = v3(need(l.position, k, "position", pos)?);
            Box::new(if l.inverse_square {
                PointLight::inverse_square(p)
            } else {
                PointLight::new(p)
            }
            .map_err(&e)?)
        }
        "hemisphere" => Box::new(HemisphereLight::new(v3(need(l.axis, k, "axis", pos)?)).map_err(&e)?),
        "overcast" => Box::new(OvercastSky::new(v3(need(l.axis, k, "axis", pos)?), 1.0).map_err(&e)?),
        "sky_ground" => Box::new(
            SkyGround::new(
                v3(need(l.axis, k, "axis", pos)?),
                Rgb::from_f64(need(l.sky, k, "sky", pos)?),
                Rgb::from_f64(need(l.ground, k, "ground", pos)?),
            )
            .map_err(&e)?,
        ),
        "cap" => Box::new(
            CapLight::new(
                v3(need(l.axis, k, "axis", pos)?),
                (need(l.sigma_deg, k, "sigma_deg", pos)? as f32).to_radians(),
            )
            .map_err(&e)?,
        ),
        "sphere" => Box::new(
            SphereLight::new(v3(need(l.center, k, "center", pos)?), need(l.radius, k, "radius", pos)? as f32)
                .map_err(&e)?,
        ),
        "polygon" => {
            let vs: Vec<Vec3<f32>> = l
                .vertices
                .as_ref()
                .ok_or_else(|| Located {
                    at: pos,
                    msg: "a polygon needs `vertices`".into(),
                })?
                .iter()
                .map(|&p| v3(p))
                .collect();
            Box::new(PolygonLight::<f32, 16>::new(&vs).map_err(&e)?)
        }
        "line" => Box::new(
            LineLight::new(v3(need(l.a, k, "a", pos)?), v3(need(l.b, k, "b", pos)?)).map_err(&e)?,
        ),
        "parallelogram" => Box::new(
            ParallelogramLight::new(
                v3(need(l.origin, k, "origin", pos)?),
                v3(need(l.eu, k, "eu", pos)?),
                v3(need(l.ev, k, "ev", pos)?),
            )
            .map_err(&e)?,
        ),
        "sh9" => {
            let env = match l.environment.as_deref() {
                Some("grace_cathedral") | None => Environment::GraceCathedral,
                Some("eucalyptus_grove") => Environment::EucalyptusGrove,
                Some("st_peters_basilica") => Environment::StPetersBasilica,
                Some(other) => {
                    return Err(Located {
                        at: pos,
                        msg: format!(
                            "unknown environment {other:?} (grace_cathedral, eucalyptus_grove, st_peters_basilica)"
                        ),
                    })
                }
            };
            Box::new(Sh9::<f32>::environment(env).prepare())
        }
        "ambient" => Box::new(Ambient(Rgb::splat(1.0f32))),
        other => {
            return Err(Located {
                at: pos,
                msg: format!(
                    "unknown light kind {other:?} (directional, point, hemisphere, overcast, sky_ground, cap, sphere, polygon, line, parallelogram, sh9, ambient)"
                ),
            })
        }
    };
    Ok(Box::new(
        Tinted::new(Lights(vec![light]), Rgb::from_f64(l.colour)).map_err(&e)?,
    ))
}

fn build_mesh(m: &MeshDef, pos: usize) -> Result<scenes::MeshBuf<f32>, Located> {
    let k = m.kind.as_str();
    let e = at::<RasterError>(pos);
    match k {
        "sphere" => scenes::sphere(
            need(m.radius, k, "radius", pos)?,
            m.stacks.unwrap_or(16),
            m.slices.unwrap_or(32),
        )
        .map_err(e),
        "plane" => {
            let s = need(m.size, k, "size", pos)?;
            let c = m.cells.unwrap_or([1, 1]);
            scenes::plane(s[0], s[1], c[0], c[1]).map_err(e)
        }
        "box" => scenes::cuboid(need(m.half, k, "half", pos)?).map_err(e),
        "torus" => {
            let s = m.segments.unwrap_or([32, 16]);
            scenes::torus(
                need(m.major, k, "major", pos)?,
                need(m.minor, k, "minor", pos)?,
                s[0],
                s[1],
            )
            .map_err(e)
        }
        other => Err(Located {
            at: pos,
            msg: format!("unknown mesh kind {other:?} (sphere, plane, box, torus)"),
        }),
    }
}

fn build(file: &File) -> Result<Scene<f32>, Located> {
    let cam = file.camera.get_ref();
    let cam_at = file.camera.span().start;
    let camera = Camera::new(
        v3(cam.eye),
        v3(cam.target),
        v3(cam.up),
        Projection::Perspective {
            fov_y: (cam.fov_deg as f32).to_radians(),
        },
        cam.width,
        cam.height,
    )
    .map_err(at(cam_at))?;
    let mut lights = Vec::new();
    for l in &file.light {
        lights.push(build_light(l.get_ref(), l.span().start)?);
    }
    let lights = Lights(lights);
    let mut materials = Vec::new();
    for m in &file.material {
        let d = m.get_ref();
        let mat = Material::new(
            Rgb::from_f64(d.diffuse),
            Rgb::from_f64(d.specular),
            d.exponent,
        )
        .map_err(at(m.span().start))?;
        materials.push((d.name.clone(), mat));
    }
    let mut objects = Vec::new();
    for m in &file.mesh {
        let (d, pos) = (m.get_ref(), m.span().start);
        let name = d.material.get_ref();
        let Some((_, mat)) = materials.iter().find(|(n, _)| n == name) else {
            return Err(Located {
                at: d.material.span().start,
                msg: format!("no material named {name:?}"),
            });
        };
        let mut xf = Affine::identity();
        if let Some(s) = d.scale {
            xf = xf.then(&Affine::scale(v3(s)).map_err(at(pos))?);
        }
        if let Some(r) = d.rotate {
            xf = xf.then(
                &Affine::rotation(v3([r[0], r[1], r[2]]), (r[3] as f32).to_radians())
                    .map_err(at(pos))?,
            );
        }
        xf = xf.then(&Affine::translation(v3(d.translate)).map_err(at(pos))?);
        objects.push(Object {
            shading: if d.gouraud {
                Shading::Gouraud
            } else {
                Shading::PerPixel
            },
            two_sided: d.two_sided,
            ..Object::new(build_mesh(d, pos)?, xf, Surface::Lit(*mat))
        });
    }
    let exposure = match cam.exposure {
        Some(x) => x as f32,
        None => scenes::exposure_at(&lights, v3([0.0; 3]), v3([0.0, 1.0, 0.0])),
    };
    Ok(Scene {
        camera,
        objects,
        lights,
        exposure,
        background: cam.background,
        encoding: arealight::raster::Encoding::Srgb,
    })
}

/// Parses and builds the scene in `src` (named `name` in messages).
///
/// # Errors
/// `name:line:column: message` for a syntax error, an unknown or mistyped key, or a value the
/// library refuses.
pub fn parse(name: &str, src: &str) -> Result<Scene<f32>, String> {
    let located = |l: Located| {
        let (line, col) = line_col(src, l.at);
        format!("{name}:{line}:{col}: {}", l.msg)
    };
    let file: File = toml::from_str(src).map_err(|e| {
        let at = e.span().map_or(0, |s| s.start);
        located(Located {
            at,
            msg: e.message().trim().to_string(),
        })
    })?;
    build(&file).map_err(located)
}

/// Renders the scene file `path` into `out/<file stem>.png`.
///
/// # Errors
/// A message for an unreadable or bad file, or a PNG that cannot be written.
pub fn render_file(path: &Path, out: &Path) -> Result<PathBuf, String> {
    let src = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let scene = parse(&path.display().to_string(), &src)?;
    let stem = path
        .file_stem()
        .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
    let p = scenes::panel(&scene, &format!("{stem} (f32, per-pixel)"))
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let pix = figure::sheet(&format!("scene file {}", path.display()), &[p], 1, "");
    figure::save(&pix, out, &format!("{stem}.png"))
}

#[cfg(test)]
mod tests {
    use super::*;

    const EXAMPLE: &str = include_str!("../scenes/example.toml");

    #[test]
    fn the_example_scene_builds() {
        let s = parse("example.toml", EXAMPLE).unwrap();
        assert_eq!(s.objects.len(), 4);
        assert_eq!(s.lights.0.len(), 2);
        assert_eq!((s.camera.width(), s.camera.height()), (320, 240));
    }

    #[test]
    fn errors_name_line_and_column() {
        // A syntax error: the missing value on line 3.
        let err = |src: &str| parse("bad.toml", src).err().unwrap_or_default();
        let e = err("[camera]\neye = [0, 1, 5]\ntarget = \n");
        assert!(e.starts_with("bad.toml:3:"), "{e}");
        // An unknown key.
        let src =
            "[camera]\neye = [0, 1, 5]\ntarget = [0, 0, 0]\nwidth = 10\nheight = 10\nzoom = 2\n";
        let e = err(src);
        assert!(e.starts_with("bad.toml:6:1:") && e.contains("zoom"), "{e}");
        // A library refusal at its entry (the [[light]] header, line 7): radius 0.
        let src = "[camera]\neye = [0, 1, 5]\ntarget = [0, 0, 0]\nwidth = 10\nheight = 10\n\n[[light]]\nkind = \"sphere\"\ncenter = [0, 3, 0]\nradius = 0.0\n";
        let e = err(src);
        assert!(
            e.starts_with("bad.toml:7:1:") && e.contains("radius"),
            "{e}"
        );
        // A mesh naming a missing material: at the name.
        let src = "[camera]\neye = [0, 1, 5]\ntarget = [0, 0, 0]\nwidth = 10\nheight = 10\n\n[[mesh]]\nkind = \"box\"\nhalf = [1, 1, 1]\nmaterial = \"gold\"\n";
        let e = err(src);
        assert!(
            e.starts_with("bad.toml:10:12:") && e.contains("gold"),
            "{e}"
        );
    }

    #[test]
    fn line_col_counts_from_one() {
        assert_eq!(line_col("ab\ncd", 0), (1, 1));
        assert_eq!(line_col("ab\ncd", 4), (2, 2));
    }
}
