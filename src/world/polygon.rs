//! [`WorldPolygonLight`]: a polygon light in world coordinates.

use super::{origin, q60_vec3, scale_to_q60, WorldPoint};
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
        let mut d = [[0i64; 3]; N];
        for (di, v) in d.iter_mut().zip(self.verts.iter()) {
            *di = v.minus(p);
        }
        scale_to_q60(d.as_flattened_mut());
        let mut verts = Vec::new();
        for &di in d.iter().take(self.verts.len()) {
            // Cannot fail: at most N vertices.
            let _ = verts.push(q60_vec3(di));
        }
        PolygonLight::from_parts(verts, self.normal)
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
        self.local(p).try_lambert(origin(), n)
    }

    /// `[polygon_lambert]` at `p`: [`PolygonLight::lambert`] of [`WorldPolygonLight::local`].
    /// Fallback: 0 for a zero or non-finite `n` and for `p` in the polygon's plane.
    /// Accuracy and cost: [the module docs](super) (measured by `tests/world.rs`).
    #[inline]
    pub fn lambert(&self, p: WorldPoint, n: impl Direction<T>) -> T {
        self.local(p).lambert(origin(), n)
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
        self.local(p).try_phong(lobe, origin(), r)
    }

    /// `[phong_polygon]` at `p`: [`PolygonLight::phong`] of [`WorldPolygonLight::local`].
    /// Fallback: as [`WorldPolygonLight::lambert`].
    /// Accuracy and cost: [the module docs](super) (measured by `tests/world.rs`).
    #[cfg(feature = "phong")]
    #[inline]
    pub fn phong(&self, lobe: &PhongLobe<T>, p: WorldPoint, r: impl Direction<T>) -> T {
        self.local(p).phong(lobe, origin(), r)
    }
}
