//! Mesh generators that fill caller buffers: UV sphere, plane, box, torus.
//!
//! Each generator has a `_counts` function giving the buffer lengths it needs, writes into the
//! front of the caller's vertex and triangle slices and returns the counts written. Triangles
//! are counter-clockwise seen from outside (the front faces of [`super::Cull::Back`]); normals
//! are unit and outward. Nothing is written when a buffer is too small (the error says which
//! and how much is needed), so they never panic.
//!
//! Accuracy: positions and normals to the backend's `sin`/`cos`, of angles `2 pi k / n` (and
//! plane fractions `k / n`) rounded by the type's product and division, for every segment
//! count (in [`Fixed22`](crate::Fixed22) too, whose range ends at 512: the integers are scaled
//! by a power of two first, see `scaled_pair`; `tests/raster_fixed.rs` measures the vertices
//! against f64's at 600 segments). Cost: one `sin` and one `cos`
//! per ring and per segment (the inner loops multiply), a few multiply-adds per vertex.

use super::{RasterError, Vertex};
use crate::{Error, Real, Vec3};

/// How many vertices and triangles a mesh has (or a generator wrote).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct MeshCounts {
    /// Vertices.
    pub vertices: usize,
    /// Triangles.
    pub triangles: usize,
}

fn check_buffers<T>(
    need: MeshCounts,
    verts: &[Vertex<T>],
    tris: &[[u16; 3]],
) -> Result<(), RasterError> {
    if need.vertices > 1 << 16 {
        return Err(RasterError::TooManyVertices {
            needed: need.vertices,
        });
    }
    if verts.len() < need.vertices {
        return Err(RasterError::BufferTooSmall {
            what: "vertices",
            needed: need.vertices,
            got: verts.len(),
        });
    }
    if tris.len() < need.triangles {
        return Err(RasterError::BufferTooSmall {
            what: "triangles",
            needed: need.triangles,
            got: tris.len(),
        });
    }
    Ok(())
}

fn positive<T: Real>(x: T, name: &'static str) -> Result<T, RasterError> {
    if !x.is_finite() {
        return Err(Error::NotFinite(name).into());
    }
    if !(x > T::ZERO) {
        return Err(RasterError::BadParameter(name));
    }
    Ok(x)
}

/// `(k 2^-s, n 2^-s)` for `k <= n`, with the smallest `s >= 0` that brings `n 2^-s` below 64:
/// exact in every backend (at most 10 fractional bits), and small enough that
/// `2 pi k 2^-s` stays far inside [`Fixed22`](crate::Fixed22)'s range of +-512, where
/// `from_u32(n)` itself would saturate from `n = 512` (and `2 pi k` from `k = 82`). The floats'
/// products and quotients of these are those of `k` and `n` scaled by `2^-s` exactly: the same
/// bits as computing with `k` and `n`; for `n < 64` every backend computes with `k` and `n`.
#[inline]
fn scaled_pair<T: Real>(k: usize, n: u16) -> (T, T) {
    let bits = 16 - n.leading_zeros(); // n < 2^bits
    let s = bits.saturating_sub(6);
    let k = k.min(usize::from(n)) as i32;
    (T::from_fixed_i32(k, s), T::from_fixed_i32(i32::from(n), s))
}

/// `k / n` (`k <= n`, `n > 0`), rounded once by the type's division (see [`scaled_pair`]).
#[inline]
fn fraction<T: Real>(k: usize, n: u16) -> T {
    let (k, n) = scaled_pair::<T>(k, n);
    k / n
}

/// `(cos, sin)` of `2 pi k / n` (or `pi k / n` with `half`), `k <= n`.
#[inline]
fn angle<T: Real>(k: usize, n: u16, half: bool) -> (T, T) {
    let full = if half { T::PI } else { T::TAU };
    let (k, n) = scaled_pair::<T>(k, n);
    let a = full * k / n;
    (a.cos(), a.sin())
}

/// Buffer sizes of [`uv_sphere`]: `(stacks + 1)(slices + 1)` vertices (the seam and the poles
/// repeated, so each vertex has one normal) and `2 slices (stacks - 1)` triangles.
pub fn uv_sphere_counts(stacks: u16, slices: u16) -> MeshCounts {
    let (st, sl) = (stacks as usize, slices as usize);
    MeshCounts {
        vertices: (st + 1) * (sl + 1),
        triangles: 2 * sl * st.saturating_sub(1),
    }
}

/// A sphere of `radius` at the origin, poles on the y axis, `stacks` rings of latitude
/// (at least 2) and `slices` of longitude (at least 3).
///
/// # Errors
/// [`RasterError::BadParameter`] (`"stacks"`, `"slices"`, `"radius"`),
/// [`RasterError::Model`] for a non-finite radius, [`RasterError::TooManyVertices`],
/// [`RasterError::BufferTooSmall`].
pub fn uv_sphere<T: Real>(
    radius: T,
    stacks: u16,
    slices: u16,
    verts: &mut [Vertex<T>],
    tris: &mut [[u16; 3]],
) -> Result<MeshCounts, RasterError> {
    let radius = positive(radius, "radius")?;
    if stacks < 2 {
        return Err(RasterError::BadParameter("stacks"));
    }
    if slices < 3 {
        return Err(RasterError::BadParameter("slices"));
    }
    let need = uv_sphere_counts(stacks, slices);
    check_buffers(need, verts, tris)?;
    let row = slices as usize + 1;
    for i in 0..=stacks as usize {
        let (ct, st) = angle::<T>(i, stacks, true);
        for j in 0..row {
            let (cp, sp) = angle::<T>(j, slices, false);
            let n = Vec3::new(st * sp, ct, st * cp);
            verts[i * row + j] = Vertex::new(n * radius, n);
        }
    }
    let mut t = 0;
    for i in 0..stacks as usize {
        for j in 0..slices as usize {
            let a = (i * row + j) as u16;
            let b = ((i + 1) * row + j) as u16;
            let (c, d) = (b + 1, a + 1);
            if i != stacks as usize - 1 {
                tris[t] = [a, b, c];
                t += 1;
            }
            if i != 0 {
                tris[t] = [a, c, d];
                t += 1;
            }
        }
    }
    Ok(MeshCounts {
        vertices: need.vertices,
        triangles: t,
    })
}

/// A grid of `a` by `b` cells: `(a + 1)(b + 1)` vertices, `2 a b` triangles.
fn grid_counts(a: u16, b: u16) -> MeshCounts {
    let (a, b) = (a as usize, b as usize);
    MeshCounts {
        vertices: (a + 1) * (b + 1),
        triangles: 2 * a * b,
    }
}

/// Buffer sizes of [`plane`]: `(nx + 1)(nz + 1)` vertices, `2 nx nz` triangles.
pub fn plane_counts(nx: u16, nz: u16) -> MeshCounts {
    grid_counts(nx, nz)
}

/// A `size_x` by `size_z` rectangle in the plane `y = 0`, centred on the origin, facing +y,
/// divided into `nx` by `nz` cells (at least 1 each; more cells give Gouraud shading more
/// vertices to interpolate).
///
/// # Errors
/// [`RasterError::BadParameter`] (`"size_x"`, `"size_z"`, `"nx"`, `"nz"`),
/// [`RasterError::Model`] for a non-finite size, [`RasterError::TooManyVertices`],
/// [`RasterError::BufferTooSmall`].
pub fn plane<T: Real>(
    size_x: T,
    size_z: T,
    nx: u16,
    nz: u16,
    verts: &mut [Vertex<T>],
    tris: &mut [[u16; 3]],
) -> Result<MeshCounts, RasterError> {
    let size_x = positive(size_x, "size_x")?;
    let size_z = positive(size_z, "size_z")?;
    if nx == 0 {
        return Err(RasterError::BadParameter("nx"));
    }
    if nz == 0 {
        return Err(RasterError::BadParameter("nz"));
    }
    let need = plane_counts(nx, nz);
    check_buffers(need, verts, tris)?;
    let up = Vec3::new(T::ZERO, T::ONE, T::ZERO);
    let row = nz as usize + 1;
    for i in 0..=nx as usize {
        let x = size_x * (fraction::<T>(i, nx) - T::HALF);
        for j in 0..row {
            let z = size_z * (fraction::<T>(j, nz) - T::HALF);
            verts[i * row + j] = Vertex::new(Vec3::new(x, T::ZERO, z), up);
        }
    }
    let mut t = 0;
    for i in 0..nx as usize {
        for j in 0..nz as usize {
            let a = (i * row + j) as u16;
            let b = a + 1;
            let c = ((i + 1) * row + j + 1) as u16;
            let d = c - 1;
            tris[t] = [a, b, c];
            tris[t + 1] = [a, c, d];
            t += 2;
        }
    }
    Ok(MeshCounts {
        vertices: need.vertices,
        triangles: t,
    })
}

/// Buffer sizes of [`cuboid`]: 24 vertices (4 per face, for flat normals), 12 triangles.
pub const fn cuboid_counts() -> MeshCounts {
    MeshCounts {
        vertices: 24,
        triangles: 12,
    }
}

/// A box with half-extents `half` (all > 0), centred on the origin, axis-aligned.
///
/// # Errors
/// [`RasterError::BadParameter`] (`"half"`), [`RasterError::Model`] for a non-finite
/// extent, [`RasterError::BufferTooSmall`].
pub fn cuboid<T: Real>(
    half: Vec3<T>,
    verts: &mut [Vertex<T>],
    tris: &mut [[u16; 3]],
) -> Result<MeshCounts, RasterError> {
    for x in [half.x, half.y, half.z] {
        positive(x, "half")?;
    }
    let need = cuboid_counts();
    check_buffers(need, verts, tris)?;
    let (o, l) = (T::ZERO, T::ONE);
    let (x, y, z) = (Vec3::new(l, o, o), Vec3::new(o, l, o), Vec3::new(o, o, l));
    // (normal, u, v) with u x v = normal.
    let faces = [
        (x, y, z),
        (-x, z, y),
        (y, z, x),
        (-y, x, z),
        (z, x, y),
        (-z, y, x),
    ];
    let scale = |v: Vec3<T>| Vec3::new(v.x * half.x, v.y * half.y, v.z * half.z);
    for (f, &(n, u, v)) in faces.iter().enumerate() {
        let (c, u, v) = (scale(n), scale(u), scale(v));
        let b = 4 * f;
        verts[b] = Vertex::new(c - u - v, n);
        verts[b + 1] = Vertex::new(c + u - v, n);
        verts[b + 2] = Vertex::new(c + u + v, n);
        verts[b + 3] = Vertex::new(c - u + v, n);
        let b = b as u16;
        tris[2 * f] = [b, b + 1, b + 2];
        tris[2 * f + 1] = [b, b + 2, b + 3];
    }
    Ok(need)
}

/// Buffer sizes of [`torus`]: `(major + 1)(minor + 1)` vertices, `2 major minor` triangles.
pub fn torus_counts(major_segments: u16, minor_segments: u16) -> MeshCounts {
    grid_counts(major_segments, minor_segments)
}

/// A torus around the y axis: tube centre circle of radius `major`, tube radius `minor`
/// (`0 < minor < major`), `major_segments` around the axis and `minor_segments` around the
/// tube (at least 3 each).
///
/// # Errors
/// [`RasterError::BadParameter`] (`"major"`, `"minor"`, `"major_segments"`,
/// `"minor_segments"`), [`RasterError::Model`] for a non-finite radius,
/// [`RasterError::TooManyVertices`], [`RasterError::BufferTooSmall`].
pub fn torus<T: Real>(
    major: T,
    minor: T,
    major_segments: u16,
    minor_segments: u16,
    verts: &mut [Vertex<T>],
    tris: &mut [[u16; 3]],
) -> Result<MeshCounts, RasterError> {
    let major = positive(major, "major")?;
    let minor = positive(minor, "minor")?;
    if !(minor < major) {
        return Err(RasterError::BadParameter("minor"));
    }
    if major_segments < 3 {
        return Err(RasterError::BadParameter("major_segments"));
    }
    if minor_segments < 3 {
        return Err(RasterError::BadParameter("minor_segments"));
    }
    let need = torus_counts(major_segments, minor_segments);
    check_buffers(need, verts, tris)?;
    let row = minor_segments as usize + 1;
    for j in 0..=major_segments as usize {
        let (cp, sp) = angle::<T>(j, major_segments, false);
        let radial = Vec3::new(sp, T::ZERO, cp);
        for i in 0..row {
            let (ct, st) = angle::<T>(i, minor_segments, false);
            let n = radial * ct + Vec3::new(T::ZERO, st, T::ZERO);
            verts[j * row + i] = Vertex::new(radial * major + n * minor, n);
        }
    }
    let mut t = 0;
    for j in 0..major_segments as usize {
        for i in 0..minor_segments as usize {
            let a = (j * row + i) as u16;
            let b = ((j + 1) * row + i) as u16;
            let (c, d) = (b + 1, a + 1);
            tris[t] = [a, b, c];
            tris[t + 1] = [a, c, d];
            t += 2;
        }
    }
    Ok(MeshCounts {
        vertices: need.vertices,
        triangles: t,
    })
}
