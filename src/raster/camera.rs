//! Projections and the [`Camera`]: world to clip space, clip to screen. (The model transforms,
//! object to world space, are [`Affine`]'s.)

use super::*;

/// `width / height` from both sides scaled by `2^-12` (at most 1 for sides up to
/// [`MAX_VIEWPORT`]): the floats' quotient is the same (power-of-two scaling is exact), and
/// fixed point never materializes a side of 512 or more (which would saturate).
fn aspect<T: Real>(width: u16, height: u16) -> T {
    const SIDE_SHIFT: u32 = 12;
    T::from_fixed_i32(i32::from(width), SIDE_SHIFT)
        / T::from_fixed_i32(i32::from(height), SIDE_SHIFT)
}

/// The camera's projection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection<T> {
    /// Perspective with vertical field of view `fov_y` (radians, in (0, pi)).
    Perspective {
        /// Vertical field of view, radians.
        fov_y: T,
    },
    /// Orthographic, showing `half_height` world units above and below the centre.
    Orthographic {
        /// Half the visible height, world units.
        half_height: T,
    },
}

/// A camera: position, orientation, projection and viewport size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera<T> {
    pub(super) eye: Vec3<T>,
    pub(super) right: Vec3<T>,
    pub(super) up: Vec3<T>,
    pub(super) forward: Vec3<T>,
    pub(super) perspective: bool,
    pub(super) sx: T,
    pub(super) sy: T,
    pub(super) width: u16,
    pub(super) height: u16,
    pub(super) near: T,
    pub(super) far: T,
}

impl<T: Real> Camera<T> {
    /// A camera at `eye` looking at `target`, with `up` (any length, not parallel to the view)
    /// giving the roll, for a `width` x `height` viewport. The depth range is
    /// `[d/64, 16 d]`, `d = |target - eye|`; see [`Camera::with_depth_range`].
    ///
    /// # Errors
    /// [`RasterError::Model`] for a non-finite or zero vector, `up` parallel to the view
    /// ([`Error::Parallel`]), a non-finite projection parameter;
    /// [`RasterError::BadParameter`] (`"fov_y"`, `"half_height"`) for one out of range;
    /// [`RasterError::BadSize`] (`"viewport"`) for a side of 0 or above [`MAX_VIEWPORT`];
    /// [`RasterError::Model`] with [`Error::OutOfRange`] (`"eye"`, `"target"`) for a
    /// coordinate beyond [`Real::COORDINATE_LIMIT`] (fixed point only: the view vectors and
    /// clip coordinates would leave the type's range, and the lights refuse such points).
    pub fn new(
        eye: Vec3<T>,
        target: Vec3<T>,
        up: Vec3<T>,
        projection: Projection<T>,
        width: u16,
        height: u16,
    ) -> Result<Self, RasterError> {
        if width == 0 || height == 0 || width > MAX_VIEWPORT || height > MAX_VIEWPORT {
            return Err(RasterError::BadSize("viewport"));
        }
        eye.check_position("eye")?;
        target.check_position("target")?;
        let (forward, dist) = (target - eye)
            .normalize_with_length()
            .ok_or(Error::ZeroLength("target - eye"))?;
        let up = up.try_normalize("up")?;
        let parallel = Error::Parallel {
            a: "up",
            b: "target - eye",
        };
        let side = forward.cross(up);
        if !(side.length() > T::from_f64(1e-6)) {
            return Err(parallel.into());
        }
        let right = side.normalize().ok_or(parallel)?;
        let up = right.cross(forward);
        let aspect = aspect::<T>(width, height);
        let (perspective, sy) = match projection {
            Projection::Perspective { fov_y } => {
                if !fov_y.is_finite() {
                    return Err(Error::NotFinite("fov_y").into());
                }
                if !(fov_y > T::ZERO && fov_y < T::PI) {
                    return Err(RasterError::BadParameter("fov_y"));
                }
                let half = fov_y * T::HALF;
                (true, half.cos() / half.sin())
            }
            Projection::Orthographic { half_height } => {
                if !half_height.is_finite() {
                    return Err(Error::NotFinite("half_height").into());
                }
                if !(half_height > T::ZERO) {
                    return Err(RasterError::BadParameter("half_height"));
                }
                (false, T::ONE / half_height)
            }
        };
        Ok(Camera {
            eye,
            right,
            up,
            forward,
            perspective,
            sx: sy / aspect,
            sy,
            width,
            height,
            near: dist * T::from_f64(1.0 / 64.0),
            far: dist * T::from_f64(16.0),
        })
    }

    /// The same camera with the depth range `[near, far]` (view distances along the view
    /// direction; geometry outside is clipped; the 16-bit depth is linear in it).
    ///
    /// # Errors
    /// [`RasterError::BadParameter`] (`"near"`, `"far"`) unless `0 < near < far`, finite.
    pub fn with_depth_range(mut self, near: T, far: T) -> Result<Self, RasterError> {
        if !(near > T::ZERO) || !near.is_finite() {
            return Err(RasterError::BadParameter("near"));
        }
        if !(far > near) || !far.is_finite() {
            return Err(RasterError::BadParameter("far"));
        }
        self.near = near;
        self.far = far;
        Ok(self)
    }

    /// The same camera (eye, orientation, vertical field of view or height) for a `width` x
    /// `height` viewport: for supersampling, `k` times each side.
    ///
    /// # Errors
    /// [`RasterError::BadSize`] (`"viewport"`) for a side of 0 or above [`MAX_VIEWPORT`].
    pub fn with_viewport(mut self, width: u16, height: u16) -> Result<Self, RasterError> {
        if width == 0 || height == 0 || width > MAX_VIEWPORT || height > MAX_VIEWPORT {
            return Err(RasterError::BadSize("viewport"));
        }
        self.sx = self.sy / aspect::<T>(width, height);
        self.width = width;
        self.height = height;
        Ok(self)
    }

    /// The viewport width in pixels.
    pub fn width(&self) -> u16 {
        self.width
    }
    /// The viewport height in pixels.
    pub fn height(&self) -> u16 {
        self.height
    }
    /// The eye position.
    pub fn eye(&self) -> Vec3<T> {
        self.eye
    }
    /// The unit view direction.
    pub fn forward(&self) -> Vec3<T> {
        self.forward
    }

    /// Clip coordinates `(x, y, z, w)` of a world point (`z` the view depth): within
    /// [`Real::COORDINATE_LIMIT`], [`Camera::clip_within`]'s bits; beyond it (fixed point
    /// only) the saturating dot products and scalings, rounded down.
    #[inline]
    pub(super) fn clip(&self, p: Vec3<T>) -> [T; 4] {
        if T::COORDINATE_LIMIT == f64::MAX || T::within_coordinate_limit([p.x, p.y, p.z]) {
            return self.clip_within(p);
        }
        let d = p - self.eye;
        let z = d.dot(self.forward);
        self.clip_of(d.dot(self.right) * self.sx, d.dot(self.up) * self.sy, z)
    }

    /// [`Camera::clip`] of a point within [`Real::COORDINATE_LIMIT`] (checked by the caller,
    /// as the eye is by the constructors): the offset from the eye (at most 8 on fixed point)
    /// dotted with the camera's unit axes, then scaled, without fixed point's saturation
    /// tests. Accuracy: the floats round as `Vec3::dot` and `*` do; fixed point rounds each
    /// dot product once, to within 7/8 of a unit of `2^-22` of the exact value of its
    /// quantized inputs, and each scaling to nearest (three floors a dot product and one a
    /// scaling before: up to 4 units, which took [`Camera::project`] to 7.3e-4 pixels from
    /// f64 at 800 x 480 at one point, now 6.7e-5 there; the test's worst, 5.6e-4, is now
    /// 3.75e-4: `tests/raster_fixed.rs`). Cost: once a vertex.
    #[inline]
    pub(super) fn clip_within(&self, p: Vec3<T>) -> [T; 4] {
        let d = p - self.eye;
        let d = [d.x, d.y, d.z];
        let axis = |v: Vec3<T>| T::dot3_axis(d, [v.x, v.y, v.z]);
        let (x, y) = (axis(self.right), axis(self.up));
        let z = axis(self.forward);
        self.clip_of(T::mul_nearest(x, self.sx), T::mul_nearest(y, self.sy), z)
    }

    /// The clip coordinates from the scaled offsets `x`, `y` and the view depth `z`.
    #[inline(always)]
    fn clip_of(&self, x: T, y: T, z: T) -> [T; 4] {
        [x, y, z, if self.perspective { z } else { T::ONE }]
    }

    /// The unit direction from `p` toward the eye (the view direction itself for an
    /// orthographic camera, and at the eye). Cost: 1 normalization (perspective).
    #[inline]
    pub fn view_dir(&self, p: Vec3<T>) -> UnitVec3<T> {
        // `forward` is normalized by the constructors.
        let back = UnitVec3::new_unchecked(-self.forward);
        if self.perspective {
            (self.eye - p).to_unit().unwrap_or(back)
        } else {
            back
        }
    }

    /// The pixel coordinates `(x, y)` (`y` down, pixel centres at `i + 0.5`) of a world point
    /// in front of the camera, or `None` behind the near plane or where a coordinate does not
    /// fit the type (never for the float types; [`Fixed22`](crate::Fixed22): at 512 pixels
    /// and beyond, or below -512: its range; and for `p` beyond [`Real::COORDINATE_LIMIT`]).
    /// Accuracy: `x_ndc = x / w` and `y_ndc` by one division each (correctly rounded on every
    /// backend); the float types round `(x_ndc + 1) width / 2` once; fixed point is exact from
    /// its normalized device coordinates, measured within 3.75e-4 pixels of f64 at 800 x 480
    /// (2 000 random points within the coordinate limit, `tests/raster_fixed.rs`). Cost: a
    /// clip transform, two divisions, two `f64` products (fixed point: and a range test of
    /// `p`).
    pub fn project(&self, p: Vec3<T>) -> Option<(T, T)> {
        p.check_position("p").ok()?;
        let c = self.clip_within(p);
        if !(c[2] >= self.near) {
            return None;
        }
        // (ndc + 1) and w/2 are exact in f64, their product is rounded once (to the type by
        // `from_f64`), as the type's own product would round it. The ratios by one division
        // each (one rounding, where `c * (1/w)` rounds `1/w` first and multiplies its error
        // by `c`: in fixed point up to 4 units of `2^-22` in `ndc` for a point 8 away).
        let x = (c[0] / c[3] + T::ONE).to_f64() * (f64::from(self.width) * 0.5);
        let y = (T::ONE - c[1] / c[3]).to_f64() * (f64::from(self.height) * 0.5);
        let (xt, yt) = (T::from_f64(x), T::from_f64(y));
        if T::RESOLUTION > T::ZERO && (xt.to_f64() != x || yt.to_f64() != y) {
            // A fixed-point type rounds such a product exactly unless it saturated.
            return None;
        }
        Some((xt, yt))
    }

    /// The snapped screen position (sub-pixel units, `y` down) of clip coordinates `c` with
    /// `w > 0`, `1/w`, and whether the normalized device coordinates are finite. The viewport
    /// transform runs in sub-pixel integers ([`Real::mul_u32_to_fixed_i32`]): no value of the
    /// type exceeds the normalized device coordinates (`|x| <= 4 w` in the guard band), so
    /// fixed point draws any viewport up to [`MAX_VIEWPORT`] exactly from them, while the
    /// float types give the same bits as `((x_ndc + 1) width / 2)` snapped. Beyond the guard
    /// band (the band test's unclipped vertices) the coordinates saturate monotonically.
    #[inline]
    pub(super) fn screen_fixed(&self, c: &[T; 4]) -> (FixedPoint, T, bool) {
        let iw = T::ONE / c[3];
        let (nx, ny) = (c[0] * iw, c[1] * iw);
        // round(16 (n + 1) w / 2) = round(8 (n + 1) w).
        let half = super::edge::SUBPIXEL_BITS - 1;
        let x = (nx + T::ONE).mul_u32_to_fixed_i32(u32::from(self.width), half);
        let y = (T::ONE - ny).mul_u32_to_fixed_i32(u32::from(self.height), half);
        (FixedPoint::new(x, y), iw, nx.is_finite() && ny.is_finite())
    }
}

#[cfg(all(test, feature = "fixed"))]
mod tests {
    use super::*;
    use crate::test_rng::uniform;
    use crate::Fixed22;

    /// The camera's clip transform in `Fixed22` against the exact values of its own quantized
    /// inputs (the offset from the eye, the axes and scales, in f64): each dot product
    /// within 7/8 of a unit of `2^-22`, each scaled coordinate within `7/8 s + 1/2` units;
    /// `clip` is `clip_within` inside the coordinate limit. Random cameras and points
    /// within the limit, 20 000 cases; the worst errors seen are printed.
    #[test]
    fn clip_within_rounds_to_nearest() {
        extern crate std;
        let mut rnd = uniform(0x5EED_CA3E);
        let mut c = |s: f64| Fixed22::from_f64((rnd() * 2.0 - 1.0) * s);
        let v = |c: &mut dyn FnMut(f64) -> Fixed22, s: f64| Vec3::new(c(s), c(s), c(s));
        let f = |v: Vec3<Fixed22>| [v.x.to_f64(), v.y.to_f64(), v.z.to_f64()];
        let unit = 2f64.powi(-22);
        let (mut cases, mut worst_dot, mut worst_scaled) = (0, 0.0f64, 0.0f64);
        for _ in 0..20_000 {
            let (eye, target, up) = (v(&mut c, 4.0), v(&mut c, 4.0), v(&mut c, 1.0));
            let Ok(cam) = Camera::new(
                eye,
                target,
                up,
                Projection::Perspective {
                    fov_y: Fixed22::from_f64(0.9),
                },
                240,
                240,
            ) else {
                continue;
            };
            let p = v(&mut c, 4.0);
            let got = cam.clip_within(p);
            assert_eq!(got, cam.clip(p), "{p:?}");
            let (pe, e) = (f(p), f(cam.eye));
            let d = [pe[0] - e[0], pe[1] - e[1], pe[2] - e[2]];
            let dot = |a: Vec3<Fixed22>| {
                let a = f(a);
                d[0] * a[0] + d[1] * a[1] + d[2] * a[2]
            };
            let z = (got[2].to_f64() - dot(cam.forward)) / unit;
            assert!(z > -0.875 && z <= 0.5, "z off by {z} units: {p:?}");
            for (k, axis, s) in [(0, cam.right, cam.sx), (1, cam.up, cam.sy)] {
                let s = s.to_f64();
                let e = (got[k].to_f64() - dot(axis) * s) / unit;
                assert!(e.abs() <= 0.875 * s + 0.5, "{k}: off by {e} units: {p:?}");
                worst_scaled = worst_scaled.max(e.abs());
            }
            worst_dot = worst_dot.max(z.abs());
            cases += 1;
        }
        std::println!(
            "clip_within: {cases} cases, dot within {worst_dot:.3} units, scaled {worst_scaled:.3}"
        );
        assert!(cases > 15_000, "{cases}");
    }
}
