//! Validation of a polygon light's vertices, in f64 for every backend: planarity, area and
//! simplicity (no two edges cross or touch).

use super::PLANAR_TOL;
use crate::{Error, Real, Vec3};

/// Validates a polygon in f64; returns its unit normal (Newell's method).
///
/// Works on the vertices relative to vertex 0 scaled by a power of two (exact) that brings
/// their largest coordinate into [1, 2), so a polygon is accepted or refused alike at every
/// scale the type represents (the squares below would otherwise underflow or overflow f64
/// beyond about `2^+-500`).
///
/// Planarity: every vertex within `PLANAR_TOL` of the size of the plane of the largest fan
/// triangle `(v0, v_i, v_i+1)` (the spec's `1e-6`), plus, for a type whose rounding is absolute
/// (fixed point, [`Real::RESOLUTION`] `r > 0`), what rounding the vertices of a planar polygon
/// to the type can do: each vertex moves by up to `e = sqrt(3) r/2`, so a rounded vertex is off
/// the plane through the rounded `v0` by `2e`, and the fitted plane tilts by up to
/// `4 e size/|c|` (`c` the fan triangle's cross product), which moves a vertex at `size` from
/// `v0` by `4 e size^2/|c|`: `sqrt(3) r (1 + 2 size^2/|c|)`, taken with a margin of 1.5 for the
/// second-order terms. Floats add nothing: the spec's tolerance stands.
pub(super) fn validate_polygon<T: Real>(verts: &[Vec3<T>]) -> Result<[f64; 3], Error> {
    // One copy of the validation for every backend (it runs in f64 anyway).
    // (`get`: no bounds check; every index asked for is below `verts.len()`, and a NaN vertex
    // would be refused.)
    let vert = |i: usize| verts.get(i).map_or([f64::NAN; 3], |v| v.to_f64());
    validate_polygon_f64(verts.len(), &vert, T::RESOLUTION.to_f64())
}

/// [`validate_polygon`] on the `n` vertices `vert(i)` (in f64) of a backend of resolution `res`.
pub(crate) fn validate_polygon_f64(
    n: usize,
    vert: &dyn Fn(usize) -> [f64; 3],
    res: f64,
) -> Result<[f64; 3], Error> {
    type V = Vec3<f64>;
    let at = |i: usize| -> V { Vec3::from_f64(vert(i % n)) };
    let o = at(0);
    // The power of two: 2^-e with 2^e <= the largest coordinate of v_i - v0 < 2^(e+1), as two
    // factors (each within f64's range).
    let big = (1..n).fold(0.0f64, |m, i| m.max((at(i) - o).max_abs()));
    if !(big > 0.0) || !big.is_finite() {
        return Err(Error::ZeroArea);
    }
    let e = libm::ilogb(big);
    let scale = (libm::ldexp(1.0, -e / 2), libm::ldexp(1.0, -e - (-e / 2)));
    // Vertex i relative to vertex 0, scaled.
    let v = |i: usize| -> V { (at(i) - o) * scale.0 * scale.1 };
    // Size: the largest distance from vertex 0 (within a factor 2 of the diameter).
    let size = (1..n).fold(0.0f64, |m, i| m.max(v(i).length()));
    if !(size > 0.0) || !size.is_finite() {
        return Err(Error::ZeroArea);
    }
    let rel = |i: usize| -> V {
        let d = v(i);
        Vec3::new(d.x / size, d.y / size, d.z / size)
    };
    // A plane first: the largest of the fan cross products (v_i - v0) x (v_i+1 - v0). (Newell's
    // normal cannot serve here: a crossed "bowtie" has a zero Newell normal but is not simple.)
    let mut plane = Vec3::new(0.0, 0.0, 0.0);
    let mut best = 0.0f64;
    for i in 1..n - 1 {
        let c = rel(i).cross(rel(i + 1));
        let l = c.dot(c);
        if l > best {
            best = l;
            plane = c;
        }
    }
    // All vertices collinear (to f64 precision): zero area.
    if !(best > 1e-28) {
        return Err(Error::ZeroArea);
    }
    let root = libm::sqrt(best);
    let plane = Vec3::new(plane.x / root, plane.y / root, plane.z / root);
    // The rounding of the vertices (fixed point; see above), in the scaled coordinates.
    let res = res * scale.0 * scale.1;
    let tol = PLANAR_TOL * size + 1.5 * libm::sqrt(3.0) * res * (1.0 + 2.0 / root);
    for i in 1..n {
        if libm::fabs(plane.dot(v(i))) > tol {
            return Err(Error::NotPlanar);
        }
    }
    let unit = plane.to_f64();
    // Simplicity in the plane: drop the dominant axis of the normal.
    let ax = unit.map(libm::fabs);
    let (ia, ib) = if ax[0] >= ax[1] && ax[0] >= ax[2] {
        (1, 2)
    } else if ax[1] >= ax[2] {
        (2, 0)
    } else {
        (0, 1)
    };
    let p2 = |i: usize| {
        let d = v(i).to_f64();
        // Indices in [0, 3) by construction (`get`: no panic path compiled).
        let c = |k: usize| d.get(k).copied().unwrap_or(0.0);
        [c(ia) / size, c(ib) / size]
    };
    for i in 0..n {
        let (a0, a1) = (p2(i), p2(i + 1));
        for j in (i + 1)..n {
            let adjacent = j == i + 1 || (i == 0 && j == n - 1);
            let (b0, b1) = (p2(j), p2(j + 1));
            if adjacent {
                // Two consecutive edges must not fold back onto each other.
                let (shared, x, y) = if j == i + 1 {
                    (a1, a0, b1)
                } else {
                    (a0, a1, b0)
                };
                let e1 = [x[0] - shared[0], x[1] - shared[1]];
                let e2 = [y[0] - shared[0], y[1] - shared[1]];
                let cross = e1[0] * e2[1] - e1[1] * e2[0];
                let dotp = e1[0] * e2[0] + e1[1] * e2[1];
                let l1 = libm::hypot(e1[0], e1[1]);
                let l2 = libm::hypot(e2[0], e2[1]);
                if l1 == 0.0 || l2 == 0.0 || (libm::fabs(cross) <= 1e-12 * l1 * l2 && dotp > 0.0) {
                    return Err(Error::NotSimple);
                }
            } else if segments_touch(a0, a1, b0, b1) {
                return Err(Error::NotSimple);
            }
        }
    }
    // Newell's normal (twice the area vector, over size^2) for the area and the orientation.
    let mut nn = Vec3::new(0.0f64, 0.0, 0.0);
    for i in 0..n {
        let (a, b) = (rel(i), rel(i + 1));
        nn.x += (a.y - b.y) * (a.z + b.z);
        nn.y += (a.z - b.z) * (a.x + b.x);
        nn.z += (a.x - b.x) * (a.y + b.y);
    }
    let len = nn.length();
    // A simple polygon of relative area below 1e-14 is zero area to f64.
    if !(len > 1e-14) {
        return Err(Error::ZeroArea);
    }
    Ok(nn.to_f64().map(|x| x / len))
}

fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

fn on_segment(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> bool {
    c[0] >= a[0].min(b[0])
        && c[0] <= a[0].max(b[0])
        && c[1] >= a[1].min(b[1])
        && c[1] <= a[1].max(b[1])
}

/// Closed segments `a0a1` and `b0b1` intersect (cross or touch).
fn segments_touch(a0: [f64; 2], a1: [f64; 2], b0: [f64; 2], b1: [f64; 2]) -> bool {
    let eps = 1e-12;
    let d1 = orient(b0, b1, a0);
    let d2 = orient(b0, b1, a1);
    let d3 = orient(a0, a1, b0);
    let d4 = orient(a0, a1, b1);
    if ((d1 > eps && d2 < -eps) || (d1 < -eps && d2 > eps))
        && ((d3 > eps && d4 < -eps) || (d3 < -eps && d4 > eps))
    {
        return true;
    }
    (libm::fabs(d1) <= eps && on_segment(b0, b1, a0))
        || (libm::fabs(d2) <= eps && on_segment(b0, b1, a1))
        || (libm::fabs(d3) <= eps && on_segment(a0, a1, b0))
        || (libm::fabs(d4) <= eps && on_segment(a0, a1, b1))
}
