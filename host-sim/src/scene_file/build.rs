//! A whole scene file built: the camera, the lights, the materials and the meshes, in file
//! order, with what the budget needs of each.

use super::*;
/// A built scene with what the budget needs of its file.
type Built<T> = (
    Scene<T>,
    Vec<LightInfo>,
    Vec<ObjectInfo>,
    Vec<Option<SceneLight<T, MAX_POLYGON>>>,
);

pub(super) fn build<T: Real + 'static>(
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
