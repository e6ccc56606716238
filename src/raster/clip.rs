//! Clipping in clip space: a triangle against the near and far planes and the guard band,
//! into a convex polygon of at most [`MAX_CLIPPED`] vertices.

use super::*;

/// The guard band: triangles are clipped to `|x|, |y| <= GUARD w` in clip space (four times
/// the viewport), far inside the edge functions' exact range.
pub(super) const GUARD: f64 = 4.0;

/// A vertex in clip space with its interpolated attributes.
#[derive(Clone, Copy, Debug)]
pub(super) struct ClipVert<T> {
    pub(super) c: [T; 4],
    pub(super) p: Vec3<T>,
    pub(super) n: Vec3<T>,
    pub(super) col: Rgb<T>,
}

impl<T: Real> ClipVert<T> {
    pub(super) fn lerp(&self, o: &Self, t: T) -> Self {
        let l = |a: T, b: T| a + (b - a) * t;
        ClipVert {
            c: core::array::from_fn(|i| l(self.c[i], o.c[i])),
            p: self.p + (o.p - self.p) * t,
            n: self.n + (o.n - self.n) * t,
            col: Rgb::new(
                l(self.col.r, o.col.r),
                l(self.col.g, o.col.g),
                l(self.col.b, o.col.b),
            ),
        }
    }
}

pub(super) const MAX_CLIPPED: usize = 9;

/// Signed distances to the six clip planes (inside >= 0): near, far, and the guard band.
#[inline]
pub(super) fn plane_distances<T: Real>(c: &[T; 4], near: T, far: T) -> [T; 6] {
    let g = T::from_f64(GUARD) * c[3];
    [
        c[2] - near,
        far - c[2],
        g - c[0],
        g + c[0],
        g - c[1],
        g + c[1],
    ]
}

/// Sutherland-Hodgman against the six planes; returns the number of vertices written.
pub(super) fn clip_polygon<T: Real>(
    tri: [ClipVert<T>; 3],
    near: T,
    far: T,
    out: &mut [ClipVert<T>; MAX_CLIPPED],
) -> usize {
    let mut a = [tri[0]; MAX_CLIPPED];
    a[..3].copy_from_slice(&tri);
    let mut na = 3;
    let mut b = [tri[0]; MAX_CLIPPED];
    for plane in 0..6 {
        let mut nb = 0;
        // Appends to `b` while it has room (iterators and `get_mut`: no index to check, no
        // division for the ring's wrap).
        let mut push = |v: ClipVert<T>| {
            if let Some(slot) = b.get_mut(nb) {
                *slot = v;
                nb += 1;
            }
        };
        let ring = a.iter().take(na);
        let next = a.iter().take(na).skip(1).chain(a.first());
        for (&p, &q) in ring.zip(next) {
            let dp = plane_distances(&p.c, near, far)[plane];
            let dq = plane_distances(&q.c, near, far)[plane];
            let (pin, qin) = (dp >= T::ZERO, dq >= T::ZERO);
            if pin {
                push(p);
            }
            if pin != qin {
                // From the inside vertex toward the outside one: the same point for both
                // triangles that share this edge.
                let (i_v, o_v, di, dout) = if pin { (p, q, dp, dq) } else { (q, p, dq, dp) };
                let t = (di / (di - dout)).clamp01();
                push(i_v.lerp(&o_v, t));
            }
        }
        a = b;
        na = nb;
        if na < 3 {
            return 0;
        }
    }
    for (o, v) in out.iter_mut().zip(a.iter().take(na)) {
        *o = *v;
    }
    na
}
