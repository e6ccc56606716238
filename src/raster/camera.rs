//! Model transforms ([`Affine`]), projections and the [`Camera`]: world to clip space, clip to
//! screen.

use super::*;

/// An affine model transform `p -> M p + t`; normals go through the cofactor matrix of `M`
/// (the inverse transpose up to a positive scale), so they stay perpendicular to surfaces
/// under any invertible `M`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Affine<T> {
    /// Rows of `M`.
    pub(super) m: [Vec3<T>; 3],
    pub(super) t: Vec3<T>,
    /// Rows of `sign(det M) cof(M)`.
    pub(super) nm: [Vec3<T>; 3],
}

impl<T: Real> Affine<T> {
    pub(super) fn from_parts(m: [Vec3<T>; 3], t: Vec3<T>) -> Self {
        let c = [m[1].cross(m[2]), m[2].cross(m[0]), m[0].cross(m[1])];
        let det = m[0].dot(c[0]);
        // M^-1 has the columns c[i]/det, so M^-T (the normal matrix) has them as rows. The
        // sign by negation, not a product by -1 or 1: the same bits on every backend (fixed
        // point's product by -1 saturates as its negation does), nine products fewer.
        let nm = if det < T::ZERO {
            [-c[0], -c[1], -c[2]]
        } else {
            c
        };
        Affine { m, t, nm }
    }

    /// The identity. (Its cofactor matrix is itself, as `from_parts` would compute it: the
    /// same bits, zeros included.)
    pub fn identity() -> Self {
        let (o, l) = (T::ZERO, T::ONE);
        let m = [Vec3::new(l, o, o), Vec3::new(o, l, o), Vec3::new(o, o, l)];
        Affine {
            m,
            t: Vec3::new(o, o, o),
            nm: m,
        }
    }

    /// A translation by `t`.
    ///
    /// # Errors
    /// [`RasterError::Model`] with [`Error::NotFinite`] (`"t"`), or [`Error::OutOfRange`]
    /// (`"t"`) for a component beyond [`Real::COORDINATE_LIMIT`] (fixed point only: a
    /// translated scene would leave the positions' range). Not checked: a composition
    /// ([`Affine::then`]) or a mesh whose transformed vertices leave the range; the lights
    /// then shade points beyond it (fixed point: finite, not meaningful).
    pub fn translation(t: Vec3<T>) -> Result<Self, RasterError> {
        t.check_position("t")?;
        let mut a = Self::identity();
        a.t = t;
        Ok(a)
    }

    /// A scale by `s` per axis (non-zero, finite).
    ///
    /// # Errors
    /// [`RasterError::Model`] with [`Error::NotFinite`] (`"scale"`) or
    /// [`RasterError::BadParameter`] (`"scale"`) for a zero component.
    pub fn scale(s: Vec3<T>) -> Result<Self, RasterError> {
        if !s.is_finite() {
            return Err(Error::NotFinite("scale").into());
        }
        if s.x == T::ZERO || s.y == T::ZERO || s.z == T::ZERO {
            return Err(RasterError::BadParameter("scale"));
        }
        let o = T::ZERO;
        Ok(Self::from_parts(
            [
                Vec3::new(s.x, o, o),
                Vec3::new(o, s.y, o),
                Vec3::new(o, o, s.z),
            ],
            Vec3::new(o, o, o),
        ))
    }

    /// A rotation by `angle` (radians, right-handed) about the unit axis `axis` (any length).
    ///
    /// # Errors
    /// [`RasterError::Model`] with [`Error::NotFinite`] / [`Error::ZeroLength`] (`"axis"`) or
    /// [`Error::NotFinite`] (`"angle"`).
    pub fn rotation(axis: Vec3<T>, angle: T) -> Result<Self, RasterError> {
        let a = axis.try_normalize("axis")?;
        if !angle.is_finite() {
            return Err(Error::NotFinite("angle").into());
        }
        let (s, c) = (angle.sin(), angle.cos());
        let k = T::ONE - c;
        let m = [
            Vec3::new(
                c + a.x * a.x * k,
                a.x * a.y * k - a.z * s,
                a.x * a.z * k + a.y * s,
            ),
            Vec3::new(
                a.y * a.x * k + a.z * s,
                c + a.y * a.y * k,
                a.y * a.z * k - a.x * s,
            ),
            Vec3::new(
                a.z * a.x * k - a.y * s,
                a.z * a.y * k + a.x * s,
                c + a.z * a.z * k,
            ),
        ];
        Ok(Self::from_parts(m, Vec3::new(T::ZERO, T::ZERO, T::ZERO)))
    }

    /// `self` followed by `next` (`next(self(p))`).
    pub fn then(&self, next: &Self) -> Self {
        let col = |j: usize| {
            let pick = |v: Vec3<T>| match j {
                0 => v.x,
                1 => v.y,
                _ => v.z,
            };
            Vec3::new(pick(self.m[0]), pick(self.m[1]), pick(self.m[2]))
        };
        let (c0, c1, c2) = (col(0), col(1), col(2));
        let m = core::array::from_fn(|i| {
            let r = next.m[i];
            Vec3::new(r.dot(c0), r.dot(c1), r.dot(c2))
        });
        let t = next.point(self.t);
        Self::from_parts(m, t)
    }

    /// `self` followed by a translation by `t`: [`Affine::then`] of [`Affine::translation`]`(t)`
    /// without its matrix product and cofactors (the matrix and the normal matrix are
    /// `self`'s; the translation is `self`'s plus `t`). The same transform: bit for bit in
    /// fixed point, equal values in floating point (where `then` may turn a zero's sign).
    /// Cost: three additions, where `then` takes 27 products and `translation` the identity's
    /// (on the Cortex-M0 in `Fixed22`, `then` and `from_parts` took about 3 000 cycles).
    ///
    /// # Errors
    /// As [`Affine::translation`]: [`RasterError::Model`] with [`Error::NotFinite`] or
    /// [`Error::OutOfRange`] (`"t"`).
    pub fn then_translation(&self, t: Vec3<T>) -> Result<Self, RasterError> {
        t.check_position("t")?;
        Ok(Affine {
            m: self.m,
            t: self.t + t,
            nm: self.nm,
        })
    }

    /// The transformed point `M p + t`. Cost: 9 multiply-adds.
    #[inline]
    pub fn point(&self, p: Vec3<T>) -> Vec3<T> {
        Vec3::new(self.m[0].dot(p), self.m[1].dot(p), self.m[2].dot(p)) + self.t
    }

    /// The transformed normal direction (not normalized). Cost: 9 multiply-adds.
    #[inline]
    pub fn normal(&self, n: Vec3<T>) -> Vec3<T> {
        Vec3::new(self.nm[0].dot(n), self.nm[1].dot(n), self.nm[2].dot(n))
    }

    /// Whether every entry of `M` is at most 2 in magnitude (rotations, and scales up to 2:
    /// every transform of the board demo): then [`Affine::point`] of a point with coordinates
    /// below 8 and [`Affine::normal`] of a normal with coordinates below 2 have products of
    /// at most 16 (the cofactors are at most 8) and sums of at most 48, which fixed point
    /// forms without its saturation tests ([`Affine::point_small`], [`NormalMatrix::unit_normal`]:
    /// the same bits).
    #[inline]
    pub(super) fn is_small(&self) -> bool {
        self.m.iter().all(|r| !(r.max_abs() > T::TWO))
    }

    /// [`Affine::point`] for a small transform ([`Affine::is_small`]) and `p` with
    /// coordinates below 8: the same bits, each row's products without fixed point's
    /// saturation tests (about 90 fewer Cortex-M0 instructions).
    #[inline]
    pub(super) fn point_small(&self, p: Vec3<T>) -> Vec3<T> {
        rows_times_small(&self.m, p) + self.t
    }

    /// The normal matrix alone, for the unit normals of a mesh's vertices
    /// ([`NormalMatrix::unit_normal`]); `small`: [`Affine::is_small`] (fixed point only).
    #[inline]
    pub(super) fn normal_matrix(&self, small: bool) -> NormalMatrix<T> {
        NormalMatrix { nm: self.nm, small }
    }
}

/// An [`Affine`]'s normal matrix, for the unit normals of a mesh's vertices: what
/// `PreparedMesh` keeps to compute them where first needed.
#[derive(Clone, Copy, Debug)]
pub(super) struct NormalMatrix<T> {
    nm: [Vec3<T>; 3],
    /// The transform is small ([`Affine::is_small`]) and fixed point: the products of a
    /// normal within 2 need no saturation tests (the same bits as [`Affine::normal`]'s).
    small: bool,
}

impl<T: Real> NormalMatrix<T> {
    /// Kept as `T` keeps it (`Sealed::keep_normals`: the floats keep nothing).
    #[inline(always)]
    pub(super) fn keep(&self) -> T::KeptNormals {
        T::keep_normals(self.nm, self.small)
    }

    /// What [`NormalMatrix::keep`] kept (`None` for the floats).
    #[inline(always)]
    pub(super) fn kept(kept: &T::KeptNormals) -> Option<Self> {
        T::kept_normals(kept).map(|(nm, small)| NormalMatrix { nm, small })
    }

    /// The unit transformed normal of the mesh normal `n` (zero where it has no direction):
    /// [`Affine::normal`] (without the saturation tests where `small` allows: the same bits),
    /// then a normalization.
    #[inline(always)]
    pub(super) fn unit_normal(&self, n: Vec3<T>) -> Vec3<T> {
        let zero = Vec3::new(T::ZERO, T::ZERO, T::ZERO);
        let m = if self.small && T::all_within([n.x, n.y, n.z], T::TWO) {
            rows_times_small(&self.nm, n)
        } else {
            Vec3::new(self.nm[0].dot(n), self.nm[1].dot(n), self.nm[2].dot(n))
        };
        m.normalize().unwrap_or(zero)
    }
}

/// The matrix of rows `rows` times `v`, each row's dot product the sealed `dot3_small` (its
/// bounds are the callers': [`Affine::point_small`], [`NormalMatrix::unit_normal`]).
#[inline(always)]
fn rows_times_small<T: Real>(rows: &[Vec3<T>; 3], v: Vec3<T>) -> Vec3<T> {
    let a = [v.x, v.y, v.z];
    let row = |r: Vec3<T>| T::dot3_small([r.x, r.y, r.z], a);
    Vec3::new(row(rows[0]), row(rows[1]), row(rows[2]))
}

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

    /// Clip coordinates `(x, y, z, w)` of a world point (`z` the view depth).
    #[inline]
    pub(super) fn clip(&self, p: Vec3<T>) -> [T; 4] {
        let d = p - self.eye;
        self.clip_offset(d.dot(self.right), d.dot(self.up), d.dot(self.forward))
    }

    /// [`Camera::clip`] of a point within [`Real::COORDINATE_LIMIT`] (checked by the caller,
    /// as the eye is by the constructors): the same bits, the offset from the eye (at most 8
    /// on fixed point) dotted with the camera's unit axes without fixed point's saturation
    /// tests (about 90 fewer Cortex-M0 instructions).
    #[inline]
    pub(super) fn clip_within(&self, p: Vec3<T>) -> [T; 4] {
        let d = p - self.eye;
        let d = [d.x, d.y, d.z];
        let axis = |v: Vec3<T>| T::dot3_small(d, [v.x, v.y, v.z]);
        self.clip_offset(axis(self.right), axis(self.up), axis(self.forward))
    }

    /// The clip coordinates from the eye offset's components along the camera's axes.
    #[inline(always)]
    fn clip_offset(&self, x: T, y: T, z: T) -> [T; 4] {
        [
            x * self.sx,
            y * self.sy,
            z,
            if self.perspective { z } else { T::ONE },
        ]
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
    /// Accuracy: the float types round
    /// `(x_ndc + 1) width / 2` once (as before); fixed point is exact from its normalized device
    /// coordinates. Cost: a clip transform, a reciprocal, two `f64` products (fixed point: and a
    /// range test of `p`).
    pub fn project(&self, p: Vec3<T>) -> Option<(T, T)> {
        p.check_position("p").ok()?;
        let c = self.clip_within(p);
        if !(c[2] >= self.near) {
            return None;
        }
        let iw = T::ONE / c[3];
        // (ndc + 1) and w/2 are exact in f64, their product is rounded once (to the type by
        // `from_f64`), as the type's own product would round it.
        let x = (c[0] * iw + T::ONE).to_f64() * (f64::from(self.width) * 0.5);
        let y = (T::ONE - c[1] * iw).to_f64() * (f64::from(self.height) * 0.5);
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

    /// `from_parts`' normal matrix is the cofactor matrix times the determinant's sign, as a
    /// product by -1 or 1 (the definition) gives it, bit for bit; `then_translation` is
    /// `then` of a translation; and `identity` is `from_parts` of the unit matrix: random
    /// matrices and translations (entries up to 4, a third of their
    /// rows' entries zero, about half the determinants negative) in `T`.
    fn normal_matrix_as_defined<T: Real>(seed: u32) {
        let mut rnd = uniform(seed);
        let mut e = |s: f64| {
            let r = rnd();
            T::from_f64(if r < 1.0 / 3.0 {
                0.0
            } else {
                (rnd() * 2.0 - 1.0) * s
            })
        };
        let mut negative = 0;
        for _ in 0..20_000 {
            let m: [Vec3<T>; 3] = core::array::from_fn(|_| Vec3::new(e(4.0), e(4.0), e(4.0)));
            let t0 = Vec3::new(e(2.0), e(2.0), e(2.0));
            let a = Affine::from_parts(m, t0);
            // `then_translation` is `then` of the translation: equal values (bits in fixed
            // point, which has one zero).
            let t = Vec3::new(e(2.0), e(2.0), e(2.0));
            let (Ok(got), Ok(tr)) = (a.then_translation(t), Affine::translation(t)) else {
                panic!("{t:?}");
            };
            let want = a.then(&tr);
            for (g, w) in got
                .m
                .iter()
                .chain(&got.nm)
                .chain([&got.t])
                .zip(want.m.iter().chain(&want.nm).chain([&want.t]))
            {
                for (g, w) in [(g.x, w.x), (g.y, w.y), (g.z, w.z)] {
                    assert_eq!(g.to_f64(), w.to_f64(), "{m:?} {t0:?} {t:?}");
                }
            }
            let c = [m[1].cross(m[2]), m[2].cross(m[0]), m[0].cross(m[1])];
            let det = m[0].dot(c[0]);
            negative += usize::from(det < T::ZERO);
            let s = if det < T::ZERO { -T::ONE } else { T::ONE };
            let want = [c[0] * s, c[1] * s, c[2] * s];
            for (got, want) in a.nm.iter().zip(&want) {
                for (g, w) in [(got.x, want.x), (got.y, want.y), (got.z, want.z)] {
                    assert_eq!(g.to_f64().to_bits(), w.to_f64().to_bits(), "{m:?}");
                }
            }
        }
        assert!((5_000..10_000).contains(&negative), "{negative}");
        let (o, l) = (T::ZERO, T::ONE);
        let unit = [Vec3::new(l, o, o), Vec3::new(o, l, o), Vec3::new(o, o, l)];
        let want = Affine::from_parts(unit, Vec3::new(o, o, o));
        let got = Affine::<T>::identity();
        for (g, w) in got
            .m
            .iter()
            .chain(&got.nm)
            .zip(want.m.iter().chain(&want.nm))
        {
            for (g, w) in [(g.x, w.x), (g.y, w.y), (g.z, w.z)] {
                assert_eq!(g.to_f64().to_bits(), w.to_f64().to_bits());
            }
        }
    }

    #[test]
    fn normal_matrix_is_the_signed_cofactor_matrix() {
        normal_matrix_as_defined::<f32>(0xC0FA_C702);
        normal_matrix_as_defined::<f64>(0xC0FA_C703);
        normal_matrix_as_defined::<Fixed22>(0xC0FA_C704);
    }

    /// The transform's small paths are the general ones bit for bit (`Fixed22`): random
    /// rotations times scales up to 2, points below 8 and normals below 2 through
    /// `point_small` and the normal matrix's rows without saturation tests, and random points within the coordinate limit through
    /// `clip_within`, for 20 000 cases each; and a scale beyond 2 is not small.
    #[test]
    fn small_paths_are_bit_identical() {
        let mut rnd = uniform(0x5EED_CAFE);
        let mut c = |s: f64| Fixed22::from_f64((rnd() * 2.0 - 1.0) * s);
        let v = |c: &mut dyn FnMut(f64) -> Fixed22, s: f64| Vec3::new(c(s), c(s), c(s));
        let (mut small, mut cases) = (0, 0);
        for _ in 0..20_000 {
            let axis = v(&mut c, 1.0);
            let Ok(rot) = Affine::rotation(axis, c(3.0)) else {
                continue;
            };
            let scale = Vec3::new(c(2.0), c(2.0), c(2.0));
            let Ok(sc) = Affine::scale(scale) else {
                continue;
            };
            let Ok(t) = Affine::translation(v(&mut c, 4.0)) else {
                continue;
            };
            let a = sc.then(&rot).then(&t);
            cases += 1;
            if !a.is_small() {
                continue;
            }
            small += 1;
            let (p, n) = (v(&mut c, 7.99), v(&mut c, 1.99));
            assert_eq!(a.point_small(p), a.point(p), "{a:?} {p:?}");
            assert_eq!(rows_times_small(&a.nm, n), a.normal(n), "{a:?} {n:?}");
        }
        assert!(small > cases / 2, "{small} of {cases}");
        let big = Affine::<Fixed22>::scale(Vec3::new(
            Fixed22::from_f64(2.5),
            Fixed22::ONE,
            Fixed22::ONE,
        ));
        assert!(!big.unwrap().is_small());
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
            assert_eq!(cam.clip_within(p), cam.clip(p), "{p:?}");
        }
    }
}
