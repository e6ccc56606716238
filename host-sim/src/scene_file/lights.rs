//! The lights of a scene file: each `[[light]]` built in the scalar type, its errors at its
//! keys, its `SceneLight` twin, and the Hermite variant of caps and spheres.

use super::*;
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
    fn diffuse(&self, _p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        Rgb::splat(self.0.lambert_hermite(n))
    }
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        Illuminant::phong(&self.0, lobe, p, r)
    }
}

impl<T: Real> Illuminant<T> for Hermite<SphereLight<T>> {
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        Rgb::splat(self.0.lambert_hermite(p, n))
    }
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
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

pub(super) fn build_light<T: Real + 'static>(
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
