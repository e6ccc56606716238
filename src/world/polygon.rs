//! [`WorldPolygonLight`]: a polygon light in world coordinates.

use super::{magnitudes, origin, q60_shift, q60_vec3_scaled, WorldPoint};
use crate::polygon::validate_polygon_f64;
use crate::unit::Direction;
#[cfg(feature = "phong")]
use crate::PhongLobe;
use crate::{Error, PolygonLight, Real, Vec3};
use heapless::Vec;

/// A planar, simple polygon light of unit radiance with at most `N` vertices, in world
/// coordinates (see [the module](super)): its models computed in `T` on the polygon as seen
/// from each `p`, translated and scaled by a power of two into the kernels' range. The same
/// models, errors and fallbacks as [`PolygonLight`], with no range limit below `2^30` units on
/// any backend.
#[derive(Clone, Debug, PartialEq)]
pub struct WorldPolygonLight<T, const N: usize = 8> {
    verts: Vec<WorldPoint, N>,
    normal: Vec3<T>,
    /// A ball around the polygon for the Phong terms' proof of a negligible term
    /// (`polygon/negligible.rs`): its centre and its radius in raw units (`2^-32`), raised.
    /// `None` without the `phong` feature.
    ball: Option<(WorldPoint, i64)>,
}

impl<T: Real, const N: usize> WorldPolygonLight<T, N> {
    /// A polygon light from its vertices in order (either winding), validated in f64 as
    /// [`PolygonLight::new`] (with the world format's resolution, `2^-32`, in place of the
    /// backend's). Cost: O(k^2) for k vertices, once.
    ///
    /// # Errors
    /// [`Error::TooFewVertices`], [`Error::TooManyVertices`], [`Error::ZeroArea`],
    /// [`Error::NotPlanar`], [`Error::NotSimple`].
    pub fn new(verts: &[WorldPoint]) -> Result<Self, Error> {
        if verts.len() < 3 {
            return Err(Error::TooFewVertices);
        }
        if verts.len() > N {
            return Err(Error::TooManyVertices { capacity: N });
        }
        let vert = |i: usize| verts.get(i).map_or([f64::NAN; 3], |v| v.to_f64());
        let normal = validate_polygon_f64(verts.len(), &vert, WorldPoint::RESOLUTION)?;
        let mut v = Vec::new();
        for &x in verts {
            // Cannot fail: the length was checked against N above.
            let _ = v.push(x);
        }
        Ok(WorldPolygonLight {
            ball: if cfg!(feature = "phong") {
                world_ball(&v)
            } else {
                None
            },
            verts: v,
            normal: Vec3::from_f64(normal),
        })
    }

    /// The vertices.
    pub fn vertices(&self) -> &[WorldPoint] {
        &self.verts
    }

    /// The unit normal of the polygon's plane (oriented by the winding, right-handed).
    pub fn normal(&self) -> Vec3<T> {
        self.normal
    }

    /// The polygon as seen from `p`, in `T`: each vertex minus `p`, all scaled by the power of
    /// two that puts the largest coordinate in `[2, 4]`. Its models at the origin are this
    /// light's models at `p`.
    pub fn local(&self, p: WorldPoint) -> PolygonLight<T, N> {
        let mut light = PolygonLight::empty_with_normal(self.normal);
        self.fill_local(p, &mut light);
        light
    }

    /// Pushes [`WorldPolygonLight::local`]'s vertices onto `light` (built empty, with this
    /// polygon's normal, by the caller: the models then run on it where it was built, with no
    /// copy of it; see [`PolygonLight::empty_with_normal`]) and returns the shift that scaled
    /// them (see `scale_to_q60`). Two passes over the differences (three 64-bit subtractions a
    /// vertex each) instead of a copy of them: the shift from their magnitudes, then each
    /// converted already scaled (no 64-bit shift; the same values as `scale_to_q60` and
    /// `q60_vec3`).
    #[inline(always)]
    fn fill_local(&self, p: WorldPoint, light: &mut PolygonLight<T, N>) -> i32 {
        let m = self
            .verts
            .iter()
            .fold(0u64, |m, v| m | magnitudes(v.minus(p)));
        let shift = q60_shift(m);
        for v in self.verts.iter() {
            light.push_local(q60_vec3_scaled(v.minus(p), shift));
        }
        shift
    }

    /// [`WorldPolygonLight::fill_local`] with the polygon's ball carried over (scaled as the
    /// vertices, its radius raised by `2^-18` for the conversions to `T`, which round each
    /// coordinate of the centre and of the vertices by at most half a unit in the last
    /// place: below `2^-22` at the local scale of 2 to 4), for the Phong terms. No ball where
    /// the radius would not fit the local format (`8`).
    #[cfg(feature = "phong")]
    #[inline(always)]
    fn fill_local_with_ball(&self, p: WorldPoint, light: &mut PolygonLight<T, N>) {
        let shift = self.fill_local(p, light);
        let Some((c, r)) = self.ball else {
            return;
        };
        // The centre lies within the vertices' range, so its offset scales as theirs did.
        let [x, y, z] = c.minus(p);
        // Converted already scaled, as the vertices (no 64-bit or 128-bit shift; the same
        // values), where the scaled values stay within an i64 (a halving always does).
        let fits = |v: u64| shift < 0 || v.leading_zeros() > shift as u32;
        if fits(magnitudes([x, y, z])) && fits((r + 1).unsigned_abs()) {
            let rho = super::q60_scaled::<T>(r + 1, shift) + T::from_fixed_i32(1, 18);
            light.set_ball(q60_vec3_scaled([x, y, z], shift), rho);
        }
    }

    /// `[polygon_lambert]` with precise errors: see [`PolygonLight::try_lambert`] (no range
    /// error: a [`WorldPoint`] is always in range).
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::ZeroLength`] for `n`, [`Error::Unresolved`] for a
    /// fixed-point `p` the kernel cannot resolve after scaling: within its rounding of the
    /// plane over the face or near the edges, or within `2^-9` of a vertex or of an edge
    /// beside it (README, "Fixed point").
    pub fn try_lambert(&self, p: WorldPoint, n: impl Direction<T>) -> Result<T, Error> {
        let mut light = PolygonLight::empty_with_normal(self.normal);
        self.fill_local(p, &mut light);
        // (`PolygonLight::try_lambert` less its range check of `p`, the origin here.)
        let o = origin();
        light.lambert_at(o, n, light.in_plane(o))
    }

    /// `[polygon_lambert]` at `p`: [`PolygonLight::lambert`] of [`WorldPolygonLight::local`].
    /// Fallback: 0 for a zero or non-finite `n` and for `p` in the polygon's plane.
    /// Accuracy and cost: [the module docs](super) (measured by `tests/world.rs`).
    #[inline]
    pub fn lambert(&self, p: WorldPoint, n: impl Direction<T>) -> T {
        self.try_lambert(p, n).unwrap_or(T::ZERO)
    }

    /// `[phong_polygon]` with precise errors: see [`PolygonLight::try_phong`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::ZeroLength`] for `r`, [`Error::Unresolved`] as
    /// [`WorldPolygonLight::try_lambert`].
    #[cfg(feature = "phong")]
    pub fn try_phong(
        &self,
        lobe: &PhongLobe<T>,
        p: WorldPoint,
        r: impl Direction<T>,
    ) -> Result<T, Error> {
        let mut light = PolygonLight::empty_with_normal(self.normal);
        self.fill_local_with_ball(p, &mut light);
        // (`PolygonLight::try_phong` less its range check of `p`, the origin here.)
        let o = origin();
        light.phong_at(lobe, o, r, light.in_plane(o))
    }

    /// `[phong_polygon]` at `p`: [`PolygonLight::phong`] of [`WorldPolygonLight::local`].
    /// Fallback: as [`WorldPolygonLight::lambert`].
    /// Accuracy and cost: [the module docs](super) (measured by `tests/world.rs`).
    #[cfg(feature = "phong")]
    #[inline]
    pub fn phong(&self, lobe: &PhongLobe<T>, p: WorldPoint, r: impl Direction<T>) -> T {
        self.try_phong(lobe, p, r).unwrap_or(T::ZERO)
    }
}

/// The ball of [`WorldPolygonLight`]: the centre the mean of the vertices (floored, in raw
/// units), the radius the largest distance to a vertex (in f64 from the exact raw
/// differences, raised by `1e-9` of itself and 4 raw units, far above f64's rounding).
/// `None` for a radius of `2^62` raw units or more.
fn world_ball(verts: &[WorldPoint]) -> Option<(WorldPoint, i64)> {
    let n = i128::try_from(verts.len().max(1)).ok()?;
    let mut sum = [0i128; 3];
    for v in verts {
        for (s, r) in sum.iter_mut().zip(v.raw) {
            *s += i128::from(r);
        }
    }
    let c = WorldPoint::from_bits(sum.map(|s| s.div_euclid(n) as i64)).ok()?;
    let mut r2 = 0.0f64;
    for v in verts {
        let d = v.minus(c).map(|x| x as f64);
        r2 = r2.max(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }
    let r = libm::sqrt(r2) * (1.0 + 1e-9) + 4.0;
    (r < (1u64 << 62) as f64).then_some((c, r as i64))
}

#[cfg(all(test, feature = "phong", feature = "fixed"))]
mod tests {
    use super::*;
    use crate::test_rng::uniform;
    use crate::Fixed22;

    /// The scaled ball of [`WorldPolygonLight::local_with_ball`] holds every vertex of the
    /// local polygon as the backend rounds it (checked in f64 on the converted values), for
    /// polygons from 0.01 to 100 units across, up to 10^6 units from the origin, seen from
    /// points from 1e-3 to 1e3 sizes away; and every Phong term the local polygon proves
    /// negligible with it (`phong_negligible`, which `try_phong` answers 0) is below `2^-24`
    /// in f64.
    fn ball_holds<T: Real>() -> (u32, u32) {
        let mut rnd = uniform(0x5DEE_CE66);
        let (mut cases, mut proven) = (0u32, 0u32);
        for i in 0..4000u32 {
            let far = [0.0, 1e3, 1e6][i as usize % 3];
            let size = libm::pow(10.0, rnd() * 4.0 - 2.0);
            let mut c = || far + (rnd() - 0.5) * 100.0;
            let centre = [c(), c(), c()];
            let quad = [(-1.0, -0.7), (1.0, -0.6), (0.8, 0.9), (-0.9, 0.7)];
            let tilt = rnd();
            let corners: [WorldPoint; 4] = core::array::from_fn(|k| {
                let (x, y) = quad[k];
                let v = [
                    centre[0] + x * size,
                    centre[1] + y * size * tilt,
                    centre[2] + y * size * (1.0 - tilt),
                ];
                WorldPoint::from_f64(v, "v").unwrap_or(WorldPoint::ORIGIN)
            });
            let Ok(light) = WorldPolygonLight::<T, 4>::new(&corners) else {
                continue;
            };
            let Ok(exact) = WorldPolygonLight::<f64, 4>::new(&corners) else {
                continue;
            };
            let away = size * libm::pow(10.0, rnd() * 6.0 - 3.0);
            let dir = [rnd() - 0.5, rnd() - 0.5, rnd() - 0.5];
            let p = [
                centre[0] + dir[0] * away,
                centre[1] + dir[1] * away,
                centre[2] + dir[2] * away,
            ];
            let Ok(p) = WorldPoint::from_f64(p, "p") else {
                continue;
            };
            let mut local = PolygonLight::empty_with_normal(light.normal());
            light.fill_local_with_ball(p, &mut local);
            let Some((bc, rho)) = local.ball() else {
                continue;
            };
            cases += 1;
            let bc = bc.to_f64();
            for v in local.vertices() {
                let v = v.to_f64();
                let d = [v[0] - bc[0], v[1] - bc[1], v[2] - bc[2]];
                let dist = libm::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                assert!(dist <= rho.to_f64(), "case {i}: {dist} > {}", rho.to_f64());
            }
            // r towards the centre, turned away by a random angle.
            let to = [
                centre[0] - p.to_f64()[0],
                centre[1] - p.to_f64()[1],
                centre[2] - p.to_f64()[2],
            ];
            let turn = [rnd() - 0.5, rnd() - 0.5, rnd() - 0.5];
            let k = rnd() * 3.0;
            let len = |a: [f64; 3]| libm::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
            let (lt, lu) = (len(to), len(turn));
            if !(lt > 0.0 && lu > 0.0) {
                continue;
            }
            let rd: [f64; 3] = core::array::from_fn(|j| to[j] / lt + k * turn[j] / lu);
            let Some(ru) = Vec3::<T>::from_f64(rd).to_unit() else {
                continue;
            };
            let m = [11, 20, 48, 128, 255][i as usize % 5];
            let (Ok(lobe), Ok(lobe64)) = (PhongLobe::<T>::new(m), PhongLobe::<f64>::new(m)) else {
                continue;
            };
            let r_min = crate::polygon::near_limit::<T>(crate::polygon::phong_near_log2(m));
            let (verts, ball) = (local.vertices(), local.ball());
            if crate::polygon::phong_negligible_with(
                verts,
                ball,
                origin(),
                ru,
                &lobe,
                r_min,
                &mut crate::polygon::Uncached,
                (&mut [T::ZERO; crate::polygon::NEGLIGIBLE_HEIGHTS], &mut 0),
            ) {
                let r64 = Vec3::<f64>::from_f64(ru.into_inner().to_f64());
                let term = exact.phong(&lobe64, p, r64);
                if term > 0.0 {
                    proven += 1;
                }
                assert!(
                    term < 1.0 / 16_777_216.0,
                    "case {i}: m = {m}, term {term:e}"
                );
            }
        }
        (cases, proven)
    }

    #[test]
    fn the_scaled_ball_holds_the_local_polygon() {
        for (cases, proven) in [ball_holds::<Fixed22>(), ball_holds::<f32>()] {
            assert!(
                cases > 3_000 && proven > 50,
                "{cases} cases, {proven} nonzero terms proven"
            );
        }
    }
}
