//! Shaders in two parts, for lights that stand still on meshes that stand still.
//!
//! A Gouraud frame calls the shader at every visible vertex. Where some lights, the mesh, its
//! material and the camera do not change from one frame to the next (a lamp fixed to the
//! ceiling over a statue, seen by a fixed camera), those lights' terms at a vertex are the
//! same every frame. A [`SplitShader`] computes them apart ([`SplitShader::fixed_part`]: the
//! sums of the fixed lights' diffuse and Phong terms, a [`LightSums`]) from the colour that
//! finishes them ([`SplitShader::finish`]: the other lights added, times the material).
//! [`PreparedMesh::shade_split`](super::PreparedMesh::shade_split) keeps each vertex's fixed
//! part (in storage given by
//! [`PreparedMesh::with_fixed_sums`](super::PreparedMesh::with_fixed_sums)) and computes it
//! again only where it may have changed:
//!
//! - for a vertex transformed (or given screen data, on two cores) since it was kept: its
//!   position or normal may differ, and with them the view direction;
//! - for every vertex when the shader's [`SplitShader::fixed_version`] or the draw options'
//!   `two_sided` differ from the kept ones'. The version stands for what the mesh cannot see:
//!   the fixed lights and the material. **Change it whenever one of them changes.**
//!
//! The colours are those of the shader that computes both parts every time, bit for bit
//! ([`SplitLit`] and [`Lit`](super::Lit): the fixed lights are the scene's first ones, and the
//! sum over the lights goes on from the kept partial sums in the same order).
//!
//! Cost: per kept vertex 24 bytes of storage (`f32`, `Fixed22`; 48 with `f64`) and, per frame,
//! the load of its sums instead of the fixed lights' models. In the demo (the panel over the
//! sphere; `boards/rp2040-st7789`) this takes the polygon light's Lambert and Phong terms out
//! of the sphere's frames after the first: see the RP2040 README's frame table.

use super::shade::{reflect, Material, Shader};
use crate::illuminant::mul_rgb;
use crate::{Real, Rgb, Scene, UnitVec3, Vec3};

/// The partial sums of some lights' terms at a surface point: what a [`SplitShader`] keeps
/// per vertex. Storage for [`PreparedMesh::with_fixed_sums`](super::PreparedMesh::with_fixed_sums).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSums<T> {
    /// The sum of the diffuse (Lambert) terms, times the lights' colours.
    pub diffuse: Rgb<T>,
    /// The sum of the Phong terms, times the lights' colours (0 for a matte material).
    pub phong: Rgb<T>,
}

impl<T: Real> LightSums<T> {
    /// Zero sums (to fill storage arrays; all zero bits, so that a `static` of them costs no
    /// flash).
    pub const ZERO: Self = LightSums {
        diffuse: Rgb::new(T::ZERO, T::ZERO, T::ZERO),
        phong: Rgb::new(T::ZERO, T::ZERO, T::ZERO),
    };
}

impl<T: Real> Default for LightSums<T> {
    fn default() -> Self {
        Self::ZERO
    }
}

/// A shader whose colour is a part that stays the same from frame to frame, kept per vertex,
/// and a part that finishes it (see the module docs). `finish(fixed_part(p, n, v), p, n, v)`
/// is the colour, for `p`, `n`, `v` as [`Shader::shade`] takes them.
pub trait SplitShader<T: Real> {
    /// What the fixed part depends on besides the vertex and the camera (the fixed lights and
    /// the material), as a number the caller changes whenever that changes: a kept part with
    /// another version is computed again.
    fn fixed_version(&self) -> u32;
    /// The part that stays the same.
    fn fixed_part(&self, p: Vec3<T>, n: UnitVec3<T>, v: UnitVec3<T>) -> LightSums<T>;
    /// The colour, from the kept part. Should be finite (the renderer maps a non-finite
    /// channel to 0).
    fn finish(&self, fixed: &LightSums<T>, p: Vec3<T>, n: UnitVec3<T>, v: UnitVec3<T>) -> Rgb<T>;
}

/// [`Lit`](super::Lit) of a [`Scene`] whose first `fixed` lights (push order) stand still: a
/// [`SplitShader`] with the same colours as `Lit::new(scene, material)`, bit for bit, and a
/// [`Shader`] computing both parts at once (per-pixel shading draws with it as with `Lit`).
#[derive(Debug)]
pub struct SplitLit<'a, T, const L: usize, const N: usize> {
    scene: &'a Scene<T, L, N>,
    material: &'a Material<T>,
    fixed: usize,
    version: u32,
}

impl<'a, T: Real, const L: usize, const N: usize> SplitLit<'a, T, L, N> {
    /// `material` under `scene`, of which the first `fixed` lights (at most all) and the
    /// material are what `version` stands for ([`SplitShader::fixed_version`]): give another
    /// version when one of them changes.
    pub fn new(
        scene: &'a Scene<T, L, N>,
        material: &'a Material<T>,
        fixed: usize,
        version: u32,
    ) -> Self {
        SplitLit {
            scene,
            material,
            fixed,
            version,
        }
    }

    /// Whether the material has a specular term ([`Lit`](super::Lit)'s test: the Phong terms
    /// are skipped for a black specular colour).
    #[inline(always)]
    fn specular(&self) -> bool {
        let s = self.material.specular;
        s.r > T::ZERO || s.g > T::ZERO || s.b > T::ZERO
    }

    /// `acc` plus the terms of the lights `lights`, as `Lit` sums them.
    #[inline(always)]
    fn sums(
        &self,
        lights: core::ops::Range<usize>,
        acc: LightSums<T>,
        p: Vec3<T>,
        n: UnitVec3<T>,
        v: UnitVec3<T>,
    ) -> LightSums<T> {
        if self.specular() {
            let r = reflect(v, n);
            let (diffuse, phong) = self.scene.diffuse_and_phong_over(
                lights,
                (acc.diffuse, acc.phong),
                &self.material.lobe,
                p,
                n,
                r,
            );
            LightSums { diffuse, phong }
        } else {
            LightSums {
                diffuse: self.scene.diffuse_over(lights, acc.diffuse, p, n),
                phong: acc.phong,
            }
        }
    }
}

impl<T: Real, const L: usize, const N: usize> SplitShader<T> for SplitLit<'_, T, L, N> {
    fn fixed_version(&self) -> u32 {
        self.version
    }

    /// The first `fixed` lights' sums. Cost: their models' (as in [`Lit`](super::Lit)).
    #[inline]
    fn fixed_part(&self, p: Vec3<T>, n: UnitVec3<T>, v: UnitVec3<T>) -> LightSums<T> {
        self.sums(0..self.fixed, LightSums::ZERO, p, n, v)
    }

    /// The other lights added to `fixed`, times the material. Cost: their models' (as in
    /// [`Lit`](super::Lit)), a reflection (6 multiply-adds) and 6 multiply-adds.
    #[inline]
    fn finish(&self, fixed: &LightSums<T>, p: Vec3<T>, n: UnitVec3<T>, v: UnitVec3<T>) -> Rgb<T> {
        let m = self.material;
        let s = self.sums(self.fixed..usize::MAX, *fixed, p, n, v);
        let c = if self.specular() {
            mul_rgb(m.diffuse, s.diffuse).add(mul_rgb(m.specular, s.phong))
        } else {
            mul_rgb(m.diffuse, s.diffuse)
        };
        c.finite_or_zero()
    }
}

impl<T: Real, const L: usize, const N: usize> Shader<T> for SplitLit<'_, T, L, N> {
    /// Both parts at once (for per-pixel shading, or a mesh without fixed sums): the colour
    /// of `Lit::new(scene, material)`, bit for bit. Cost: `Lit`'s.
    #[inline]
    fn shade(&self, p: Vec3<T>, n: UnitVec3<T>, v: UnitVec3<T>) -> Rgb<T> {
        self.finish(&self.fixed_part(p, n, v), p, n, v)
    }
}
