//! The boundary sums of Arvo's moments along a clipped ring: its arcs ([`Arc`], on a polygon
//! edge or on a clipping plane's great circle), their accumulation for order `n`
//! ([`MomentSum`]), and the second clipping plane of the double-axis moments ([`SecondClip`]).
//! See the module docs of [`crate::moments`].

use crate::polygon::{arc_axis_form, cos_power_sums};
use crate::{Real, UnitVec3, Vec3};

/// Which great circle an arc of a clipped ring lies on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Circle {
    /// A polygon edge (its circle from the edge itself).
    Edge,
    /// The first clipping plane (normal `k1`).
    First,
    /// The second clipping plane (normal `k2`).
    Second,
}

/// An arc of a (clipped) ring seen from `p`: unnormalized endpoints, `d = ub - ua` from the
/// polygon's own edge vector where there is one, and its great circle.
#[derive(Clone, Copy, Debug)]
pub(super) struct Arc<T> {
    pub(super) ua: Vec3<T>,
    pub(super) ub: Vec3<T>,
    pub(super) d: Vec3<T>,
    pub(super) circle: Circle,
}

/// The accumulator of the boundary sums of the module docs for order `n`, axes `w`, `v`:
/// `Q = (w.v) ([n odd] Omega + sum (w.g) S) + sum (v.g) T(n)`, `Omega` from the fan
/// (added by the caller).
pub(super) struct MomentSum<T> {
    pub(super) n: u32,
    pub(super) w: Vec3<T>,
    pub(super) v: Vec3<T>,
    pub(super) wv: T,
    pub(super) k1: Vec3<T>,
    pub(super) k2: Vec3<T>,
    /// Early termination: the per-arc budget (0: never stop early).
    pub(super) budget: T,
    pub(super) sum: T,
}

impl<T: Real> MomentSum<T> {
    pub(super) fn add(&mut self, arc: &Arc<T>) {
        // The arc's unit pole g (ua x ub direction) and (cos l, sin l) up to a common factor.
        let cr = arc.ua.cross(arc.d);
        let (g, glen) = match arc.circle {
            Circle::Edge => match cr.normalize_with_length() {
                Some(x) => x,
                None => return, // Seen end-on: zero length, no contribution.
            },
            Circle::First | Circle::Second => {
                let k = if arc.circle == Circle::First {
                    self.k1
                } else {
                    self.k2
                };
                let gk = cr.dot(k);
                if !(gk.abs() > T::ZERO) {
                    return;
                }
                (if gk < T::ZERO { -k } else { k }, gk.abs())
            }
        };
        let Some(s) = arc.ua.normalize() else {
            return;
        };
        let dot = arc.ua.dot(arc.ub);
        let x = glen.atan2(dot);
        let scale = dot.abs().max(glen);
        if !(scale > T::ZERO) || !scale.is_finite() {
            return;
        }
        // (Not `phong_edge_terms`' normalized pair: measured, that moved the f32 and f64
        // maxima of the tests by an ULP or so either way, glossy transmission's f32 worst from
        // 2.4e-7 to 2.8e-7.)
        let (cd, sd) = (dot / scale, glen / scale);
        let inv = T::ONE / (cd * cd + sd * sd).sqrt();
        let (cos_x, sin_x) = ((cd * inv).clamp(-T::ONE, T::ONE), (sd * inv).clamp01());
        let w = self.w;
        let wg = w.dot(g);
        let vg = self.v.dot(g);
        let a = w.dot(s);
        // b, and c^2 = f = 1 - (w.g)^2. All three are unit vectors: every caller of
        // raw_moment_sum / clipped_moment_sum normalizes w and v, g is a normalized pole or
        // +-k1, +-k2 (which are w and v), s is normalized above.
        let unit = UnitVec3::new_unchecked;
        let (b, f) = arc_axis_form(unit(w), unit(g), unit(s), wg, a);
        let alpha = self.wv * wg;
        let stop = if self.budget > T::ZERO {
            let awg = wg.abs();
            let half_n = T::from_u32(self.n / 2 + 1);
            let geo = if awg * awg * half_n >= T::ONE {
                T::ONE / awg
            } else {
                awg * half_n
            };
            Some((x * (self.wv.abs() * geo + vg.abs()), self.budget))
        } else {
            None
        };
        let (sum, last) = cos_power_sums(self.n, x, cos_x, sin_x, a, b, f, stop);
        self.sum += alpha * sum + vg * last;
    }
}

/// The second streaming clip stage: arcs of a ring (already clipped to the first plane) in,
/// arcs of the ring clipped to `u.k >= 0` out, in ring order up to a rotation.
pub(super) struct SecondClip<T> {
    pub(super) k: Vec3<T>,
    /// The first plane's normal and the unit direction of the planes' intersection line
    /// (`None` when the planes coincide).
    pub(super) k1: Vec3<T>,
    pub(super) line: Option<Vec3<T>>,
    pub(super) exit: Option<Vec3<T>>,
    pub(super) first_entry: Option<Vec3<T>>,
}

impl<T: Real> SecondClip<T> {
    /// Where the arc `e` crosses the second plane, and the pieces' edge vectors
    /// `(x - ua, ub - x)`. An arc on the first plane crosses it exactly at `+-line`: its chord
    /// passes within about `h` of `p` when it spans nearly pi (a polygon seen edge-on from
    /// height `h`), where a point interpolated on the chord would lose its direction.
    pub(super) fn crossing(&self, e: &Arc<T>, da: T, db: T) -> (Vec3<T>, Vec3<T>, Vec3<T>) {
        if e.circle == Circle::First {
            if let Some(l) = self.line {
                let pole = e.ua.cross(e.d).dot(self.k1);
                let y = if e.ua.cross(l).dot(self.k1) * pole >= T::ZERO {
                    l
                } else {
                    -l
                };
                let y = y * e.ua.max_abs();
                return (y, y - e.ua, e.ub - y);
            }
        }
        let t = (da / (da - db)).clamp01();
        (e.ua + e.d * t, e.d * t, e.d * (T::ONE - t))
    }

    pub(super) fn push<F: FnMut(&Arc<T>)>(&mut self, e: Arc<T>, f: &mut F) {
        if e.circle == Circle::First && self.line.is_none() {
            // The planes coincide (the caller handles opposite ones): an arc of the first
            // plane lies on the second; only rounding could put it below.
            f(&e);
            return;
        }
        let (da, db) = (e.ua.dot(self.k), e.ub.dot(self.k));
        match (da < T::ZERO, db < T::ZERO) {
            (false, false) => f(&e),
            (false, true) => {
                let (x, d1, _) = self.crossing(&e, da, db);
                f(&Arc { ub: x, d: d1, ..e });
                self.exit = Some(x);
            }
            (true, false) => {
                let (x, _, d2) = self.crossing(&e, da, db);
                match self.exit.take() {
                    Some(ex) => f(&Arc {
                        ua: ex,
                        ub: x,
                        d: x - ex,
                        circle: Circle::Second,
                    }),
                    None => {
                        if self.first_entry.is_none() {
                            self.first_entry = Some(x);
                        }
                    }
                }
                f(&Arc { ua: x, d: d2, ..e });
            }
            (true, true) => {}
        }
    }

    pub(super) fn finish<F: FnMut(&Arc<T>)>(&mut self, f: &mut F) {
        if let (Some(ex), Some(en)) = (self.exit.take(), self.first_entry.take()) {
            f(&Arc {
                ua: ex,
                ub: en,
                d: en - ex,
                circle: Circle::Second,
            });
        }
    }
}
