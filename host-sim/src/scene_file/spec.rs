//! A scene file as Rust source for the boards (`host-sim budget --scene FILE --emit-spec
//! OUT.rs`): the file's values, defaults resolved, as a `demo_scene::spec::SceneSpec` constant,
//! which `boards/demo-scene`'s `Player` builds and renders with the firmware's frame path (the
//! emulated checks of `host-sim budget`). The player mirrors this module's parent step for
//! step; `host-sim budget --check` requires the emulated frame's counts to equal the host's.

use std::fmt::Write;

use super::{
    parse_as, File, LightDef, MeshDef, DEFAULT_CELLS, DEFAULT_COLOUR, DEFAULT_EXPONENT,
    DEFAULT_FOV_DEG, DEFAULT_SEGMENTS, DEFAULT_SLICES, DEFAULT_STACKS, DEFAULT_UP, S,
};

/// The most vertices of a polygon light on the boards (`demo_scene::spec::POLYGON_VERTICES`).
const BOARD_POLYGON: usize = 8;
/// The most lights and meshes on the boards (`demo_scene::spec::MAX_LIGHTS`, `MAX_OBJECTS`).
const BOARD_LIGHTS: usize = 8;
const BOARD_OBJECTS: usize = 8;

/// An f64 as a Rust literal that reads back as the same value (`{:?}` round-trips).
fn lit(x: f64) -> String {
    let s = format!("{x:?}");
    if s.contains(['.', 'e', 'i', 'N']) {
        s
    } else {
        format!("{s}.0")
    }
}

fn arr<const K: usize>(a: [f64; K]) -> String {
    let items: Vec<String> = a.iter().map(|&x| lit(x)).collect();
    format!("[{}]", items.join(", "))
}

fn get<const K: usize>(x: &Option<S<[f64; K]>>) -> Option<[f64; K]> {
    x.as_ref().map(|s| *s.get_ref())
}

fn light(l: &LightDef) -> Result<String, String> {
    let k = l.kind.get_ref().as_str();
    let need3 = |x: &Option<S<[f64; 3]>>| get(x).map(arr).unwrap_or_default();
    Ok(match k {
        "ambient" => "LightKind::Ambient".into(),
        "directional" => format!("LightKind::Directional({})", need3(&l.direction)),
        "point" => format!(
            "LightKind::Point {{ position: {}, inverse_square: {} }}",
            need3(&l.position),
            l.inverse_square.as_ref().is_some_and(|s| *s.get_ref())
        ),
        "hemisphere" => format!("LightKind::Hemisphere({})", need3(&l.axis)),
        "overcast" => format!("LightKind::Overcast({})", need3(&l.axis)),
        "sky_ground" => format!(
            "LightKind::SkyGround {{ axis: {}, sky: {}, ground: {} }}",
            need3(&l.axis),
            need3(&l.sky),
            need3(&l.ground)
        ),
        "cap" => format!(
            "LightKind::Cap {{ axis: {}, sigma_deg: {} }}",
            need3(&l.axis),
            lit(l.sigma_deg.as_ref().map_or(0.0, |s| *s.get_ref()))
        ),
        "sphere" => format!(
            "LightKind::Sphere {{ center: {}, radius: {} }}",
            need3(&l.center),
            lit(l.radius.as_ref().map_or(0.0, |s| *s.get_ref()))
        ),
        "polygon" => {
            let vs = l
                .vertices
                .as_ref()
                .map(|s| s.get_ref().clone())
                .unwrap_or_default();
            if vs.len() > BOARD_POLYGON {
                return Err(format!(
                    "a polygon light of {} vertices: the boards' scenes hold at most {BOARD_POLYGON}",
                    vs.len()
                ));
            }
            let vs: Vec<String> = vs.into_iter().map(arr).collect();
            format!("LightKind::Polygon(&[{}])", vs.join(", "))
        }
        other => {
            return Err(format!(
                "a {other} light: the boards' scenes (arealight::Scene) have no {other} lights"
            ))
        }
    })
}

fn mesh(m: &MeshDef) -> String {
    let f = |x: &Option<S<f64>>| lit(x.as_ref().map_or(0.0, |s| *s.get_ref()));
    let n = |x: &Option<S<i64>>, d: u16| x.as_ref().map_or(d, |s| *s.get_ref() as u16);
    let n2 = |x: &Option<S<[i64; 2]>>, d: [u16; 2]| {
        x.as_ref().map_or(d, |s| s.get_ref().map(|v| v as u16))
    };
    match m.kind.get_ref().as_str() {
        "sphere" => format!(
            "MeshSpec::Sphere {{ radius: {}, stacks: {}, slices: {} }}",
            f(&m.radius),
            n(&m.stacks, DEFAULT_STACKS),
            n(&m.slices, DEFAULT_SLICES)
        ),
        "plane" => {
            let c = n2(&m.cells, DEFAULT_CELLS);
            format!(
                "MeshSpec::Plane {{ size: {}, cells: [{}, {}] }}",
                arr(get(&m.size).unwrap_or_default()),
                c[0],
                c[1]
            )
        }
        "box" => format!(
            "MeshSpec::Box {{ half: {} }}",
            arr(get(&m.half).unwrap_or_default())
        ),
        _ => {
            let s = n2(&m.segments, DEFAULT_SEGMENTS);
            format!(
                "MeshSpec::Torus {{ major: {}, minor: {}, segments: [{}, {}] }}",
                f(&m.major),
                f(&m.minor),
                s[0],
                s[1]
            )
        }
    }
}

fn option<const K: usize>(x: &Option<S<[f64; K]>>) -> String {
    get(x).map_or("None".into(), |a| format!("Some({})", arr(a)))
}

/// The Rust source of scene file `src` (named `name`: its stem names the constant's scene) as
/// a `demo_scene::spec::SceneSpec` constant `SCENE`, with `VERTICES` and `TRIANGLES`, the
/// buffers it needs.
///
/// # Errors
/// Whatever [`super::parse`] refuses, and what the boards' scenes cannot hold (line,
/// parallelogram and SH9 lights; more than 8 lights, meshes or polygon vertices).
pub fn emit_spec(name: &str, src: &str) -> Result<String, String> {
    // Validates everything, and resolves the exposure a file leaves out (in f64).
    let parsed = parse_as::<f64>(name, src)?;
    let file: File = toml::from_str(src).map_err(|e| format!("{name}: {e}"))?;
    let stem = std::path::Path::new(name)
        .file_stem()
        .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
    if file.light.len() > BOARD_LIGHTS || file.mesh.len() > BOARD_OBJECTS {
        return Err(format!(
            "{name}: {} lights and {} meshes: the boards' scenes hold at most {BOARD_LIGHTS} of each",
            file.light.len(),
            file.mesh.len()
        ));
    }
    let cam = file.camera.get_ref();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "//! `host-sim/scenes/{stem}.toml` for the boards, generated by\n//! `host-sim budget --scene host-sim/scenes/{stem}.toml --emit-spec <this file>`:\n//! do not edit (CI regenerates it and fails on a difference).\n"
    );
    let _ = writeln!(s, "use crate::spec::*;");
    let _ = writeln!(
        s,
        "#[allow(unused_imports)]\nuse arealight::raster::Encoding;\n"
    );
    let (v, t) = parsed
        .objects
        .iter()
        .fold((0, 0), |(v, t), o| (v + o.vertices, t + o.triangles));
    let _ = writeln!(s, "/// Vertices of the scene's meshes, in all.");
    let _ = writeln!(s, "pub const VERTICES: usize = {v};");
    let _ = writeln!(s, "/// Triangles of the scene's meshes, in all.");
    let _ = writeln!(s, "pub const TRIANGLES: usize = {t};\n");
    let _ = writeln!(s, "/// The scene.");
    let _ = writeln!(s, "pub const SCENE: SceneSpec = SceneSpec {{");
    let _ = writeln!(s, "    name: {stem:?},");
    let _ = writeln!(s, "    camera: CameraSpec {{");
    let _ = writeln!(s, "        eye: {},", arr(*cam.eye.get_ref()));
    let _ = writeln!(s, "        target: {},", arr(*cam.target.get_ref()));
    let _ = writeln!(
        s,
        "        up: {},",
        arr(get(&cam.up).unwrap_or(DEFAULT_UP))
    );
    let fov = cam
        .fov_deg
        .as_ref()
        .map_or(DEFAULT_FOV_DEG, |f| *f.get_ref());
    let _ = writeln!(s, "        fov_deg: {},", lit(fov));
    let _ = writeln!(s, "        width: {},", cam.width.get_ref());
    let _ = writeln!(s, "        height: {},", cam.height.get_ref());
    let _ = writeln!(s, "    }},");
    let _ = writeln!(s, "    exposure: {},", lit(parsed.scene.exposure));
    let bg = parsed.scene.background;
    let _ = writeln!(s, "    background: [{}, {}, {}],", bg[0], bg[1], bg[2]);
    let _ = writeln!(s, "    encoding: Encoding::{:?},", parsed.scene.encoding);
    let _ = writeln!(s, "    lights: &[");
    for l in &file.light {
        let l = l.get_ref();
        let colour = get(&l.colour).unwrap_or(DEFAULT_COLOUR);
        let kind = light(l).map_err(|e| format!("{name}: {e}"))?;
        let _ = writeln!(
            s,
            "        LightSpec {{ kind: {kind}, colour: {} }},",
            arr(colour)
        );
    }
    let _ = writeln!(s, "    ],");
    let _ = writeln!(s, "    objects: &[");
    for m in &file.mesh {
        let m = m.get_ref();
        let mat = file
            .material
            .iter()
            .map(|x| x.get_ref())
            .find(|x| x.name.get_ref() == m.material.get_ref())
            .ok_or_else(|| format!("{name}: no material {:?}", m.material.get_ref()))?;
        let surface = match get(&mat.emissive) {
            Some(e) => format!("SurfaceSpec::Emissive({})", arr(e)),
            None => format!(
                "SurfaceSpec::Lit {{ diffuse: {}, specular: {}, exponent: {} }}",
                arr(get(&mat.diffuse).unwrap_or_default()),
                arr(get(&mat.specular).unwrap_or_default()),
                mat.exponent
                    .as_ref()
                    .map_or(DEFAULT_EXPONENT, |x| *x.get_ref() as u32)
            ),
        };
        let flag = |x: &Option<S<bool>>| x.as_ref().is_some_and(|b| *b.get_ref());
        let _ = writeln!(s, "        ObjectSpec {{");
        let _ = writeln!(s, "            mesh: {},", mesh(m));
        let _ = writeln!(s, "            scale: {},", option(&m.scale));
        let _ = writeln!(s, "            rotate: {},", option(&m.rotate));
        let _ = writeln!(s, "            translate: {},", option(&m.translate));
        let _ = writeln!(s, "            surface: {surface},");
        let _ = writeln!(s, "            gouraud: {},", flag(&m.gouraud));
        let _ = writeln!(s, "            two_sided: {},", flag(&m.two_sided));
        let _ = writeln!(s, "        }},");
    }
    let _ = writeln!(s, "    ],");
    let _ = writeln!(s, "}};");
    Ok(s)
}
