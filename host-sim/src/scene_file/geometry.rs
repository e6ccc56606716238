//! The geometry of a scene file: meshes (with the budget's tessellation factor), their
//! transforms, and the camera, each built in the scalar type with its errors at its keys.

use super::*;
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

pub(super) fn build_mesh<T: Real>(
    m: &MeshDef,
    pos: usize,
    tess: f64,
) -> Result<scenes::MeshBuf<T>, Located> {
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
pub(super) fn transform<T: Real>(d: &MeshDef) -> Result<Affine<T>, Located> {
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

pub(super) fn build_camera<T: Real>(cam: &CameraDef, pos: usize) -> Result<Camera<T>, Located> {
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
