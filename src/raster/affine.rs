//! Model transforms ([`Affine`]: object to world space) and their normal matrices
//! ([`NormalMatrix`]), which [`PreparedMesh`](super::PreparedMesh) keeps to compute a vertex's
//! unit normal where it is first needed.

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
    /// `point_small` and the normal matrix's rows without saturation tests, 20 000 cases; and
    /// a scale beyond 2 is not small. (The camera's `clip_within`: `camera`'s tests.)
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
    }
}
