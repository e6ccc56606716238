//! The rasterizer as a fuzzing family: a prepared mesh drawn into bands from arbitrary bytes
//! ([`Family::Raster`]), and the integer geometry on arbitrary sub-pixel coordinates
//! ([`raster_edges`]).

use super::*;

std::thread_local! {
    /// Encoding tables per backend and encoding (4097 encodes each: built once per thread).
    static TABLES: std::cell::RefCell<Vec<(&'static str, Encoding, EncodeTable)>> =
        const { std::cell::RefCell::new(Vec::new()) };
}

pub(super) fn table<T: Real>(e: Encoding) -> EncodeTable {
    let name = std::any::type_name::<T>();
    TABLES.with(|t| {
        let mut t = t.borrow_mut();
        if let Some((_, _, tab)) = t.iter().find(|x| x.0 == name && x.1 == e) {
            return tab.clone();
        }
        let tab = EncodeTable::new::<T>(e);
        t.push((name, e, tab.clone()));
        tab
    })
}

/// The rasterizer's integer geometry on arbitrary sub-pixel coordinates (any `i32`): the edge
/// function, the top-left rule, pixel centres, the triangle setup and its queries (over a
/// small window of arbitrary rows).
pub fn raster_edges(inp: &mut Input<'_>) {
    let fp = |inp: &mut Input<'_>| FixedPoint::new(inp.u32() as i32, inp.u32() as i32);
    let (a, b, c) = (fp(inp), fp(inp), fp(inp));
    let _ = edge_function(a, b, c);
    let _ = is_top_left(a, b);
    let _ = FixedPoint::pixel_centre(inp.u32() as i32, inp.u32() as i32);
    let cull = if inp.below(2) == 0 {
        Cull::None
    } else {
        Cull::Back
    };
    if let Some(t) = EdgeTriangle::new([a, b, c], cull) {
        let _ = (t.area2(), t.swapped(), t.vertices());
        let _ = t.weights_at(c);
        let _ = t.covers(fp(inp));
        let (w, r0) = (1 + inp.below(64) as i32, inp.u32() as i32);
        let r1 = r0.saturating_add(1 + inp.below(16) as i32);
        let _ = t.pixel_bounds(w, r0, r1);
        // Any window for the bounds alone (no loop over it).
        let _ = t.pixel_bounds(inp.u32() as i32, inp.u32() as i32, inp.u32() as i32);
        t.for_each_covered(w, r0, r1, |_, _, _| {});
        t.for_each_span(w, r0, r1, |_, _, _| {});
    }
}

/// `Real::to_fixed_i32` of the float backends overflows (a panic in debug builds) below
/// `i32::MIN`, which the prepared path reaches with a vertex colour times exposure below -128
/// (tests/fuzz_bits.rs, `to_fixed_i32_saturates`, ignored until src/real.rs is fixed). Until
/// then the raster family draws with non-negative colours and exposure; set this to `false`
/// with the fix.
pub const NEGATIVE_COLOURS_OVERFLOW: bool = false;

/// The rasterizer on arbitrary input: a camera, a mesh (indices possibly out of range), a
/// transform, a material and options, drawn through bands of arbitrary height (a band as wide
/// as the viewport, or not), by `draw` and by the prepared path; then the integer triangle
/// setup on coordinates within the rasterizer's range ([`MAX_COORD`]).
pub(super) fn raster<T: Real>(s: &mut Src<'_, '_>) {
    let cull = if s.inp.below(2) == 0 {
        Cull::None
    } else {
        Cull::Back
    };
    // A camera.
    let (eye, target, up) = (s.p::<T>(), s.p::<T>(), s.v::<T>());
    let projection = if s.inp.below(2) == 0 {
        Projection::Perspective { fov_y: s.s::<T>() }
    } else {
        Projection::Orthographic {
            half_height: s.ps::<T>(),
        }
    };
    let size = |inp: &mut Input<'_>| match inp.below(16) {
        0 => 0,
        1 => 5000,
        _ => 1 + inp.below(40) as u16,
    };
    let (width, height) = (size(s.inp), size(s.inp));
    let camera = Camera::new(eye, target, up, projection, width, height);
    let camera = match (camera, s.inp.below(4)) {
        (Ok(cam), 0) => cam.with_depth_range(s.s::<T>(), s.s::<T>()),
        (c, _) => c,
    };
    // A mesh: 3 to 6 vertices, 1 to 4 triangles, an index out of range now and then.
    let nv = 3 + s.inp.below(4) as usize;
    let verts: Vec<Vertex<T>> = (0..nv)
        .map(|_| Vertex::new(s.p::<T>(), s.v::<T>()))
        .collect();
    let nt = 1 + s.inp.below(4) as usize;
    let tris: Vec<[u16; 3]> = (0..nt)
        .map(|_| core::array::from_fn(|_| s.inp.below(nv as u32 + 1) as u16))
        .collect();
    let transform = match s.inp.below(4) {
        0 => Affine::translation(s.p::<T>()),
        1 => Affine::scale(s.v::<T>()),
        2 => Affine::rotation(s.v::<T>(), s.s::<T>()),
        _ => Ok(Affine::identity()),
    }
    .unwrap_or_else(|_| Affine::identity());
    let light = HemisphereLight::new(s.v::<T>())
        .unwrap_or_else(|_| HemisphereLight::new(Vec3::new(T::ZERO, T::ONE, T::ZERO)).unwrap());
    let (mut kd, mut ks, m) = (s.c::<T>(), s.c::<T>(), s.m::<T>());
    let mut exposure = s.s::<T>();
    if NEGATIVE_COLOURS_OVERFLOW {
        // Until `Real::to_fixed_i32` saturates (see the constant): colours and exposure >= 0.
        kd = Rgb::new(kd.r.abs(), kd.g.abs(), kd.b.abs());
        ks = Rgb::new(ks.r.abs(), ks.g.abs(), ks.b.abs());
        exposure = exposure.abs();
    }
    let material = Material::new(kd, ks, m).or_else(|_| Material::matte(kd));
    let mut opts = DrawOptions::new(if s.inp.below(2) == 0 {
        Shading::Gouraud
    } else {
        Shading::PerPixel
    });
    opts.cull = cull;
    opts.two_sided = s.inp.below(2) == 0;
    opts.exposure = exposure;
    opts.encoding = [Encoding::Linear, Encoding::Gamma2, Encoding::Srgb][s.inp.below(3) as usize];
    let rows = 1 + s.inp.below(8) as u16;
    let band_width = if s.inp.below(8) == 0 {
        1 + s.inp.below(50) as u16
    } else {
        width.max(1)
    };
    let with_depth = s.inp.below(4) != 0;
    let (Ok(camera), Ok(mesh), Ok(material)) = (camera, Mesh::new(&verts, &tris), material) else {
        return;
    };
    if band_width as u32 * rows as u32 > 1 << 16 {
        return;
    }
    let n = band_width as usize * rows as usize;
    let (mut px, mut depth) = (vec![Rgb565(0); n], vec![0u16; n]);
    let Ok(mut band) = Band::new(
        &mut px,
        if with_depth { Some(&mut depth) } else { None },
        band_width,
        0,
    ) else {
        return;
    };
    let shader = Lit::new(&light, &material);
    let mut storage = vec![PreparedVertex::<T>::EMPTY; nv];
    let mut prepared = PreparedMesh::new(mesh, &mut storage).ok();
    if let Some(p) = prepared.as_mut() {
        p.transform(&camera, &transform);
        let _ = p.shade(&camera, &shader, &opts);
        let _ = p.rows();
    }
    // Two cores sharing the frame: each transforms and shades half the vertices, and takes the
    // other half's screen data and colours.
    let (mut st0, mut st1) = (
        vec![PreparedVertex::<T>::EMPTY; nv],
        vec![PreparedVertex::<T>::EMPTY; nv],
    );
    let mut shared = PreparedMesh::new(mesh, &mut st0)
        .ok()
        .zip(PreparedMesh::new(mesh, &mut st1).ok());
    if let Some((a, b)) = shared.as_mut() {
        a.transform_some(&camera, &transform, true, |i| i % 2 == 0);
        b.transform_some(&camera, &transform, true, |i| i % 2 == 1);
        let (sa, sb): (Vec<_>, Vec<_>) = (a.screen().collect(), b.screen().collect());
        a.set_screen(&camera, sb, |i| i % 2 == 1);
        b.set_screen(&camera, sa, |i| i % 2 == 0);
        let _ = a.shade_some(&camera, &shader, &opts, |i| i % 2 == 0);
        let _ = b.shade_some(&camera, &shader, &opts, |i| i % 2 == 1);
        let (ca, cb): (Vec<_>, Vec<_>) = (a.colours().collect(), b.colours().collect());
        a.set_colours(cb, |i| i % 2 == 1);
        b.set_colours(ca, |i| i % 2 == 0);
    }
    let tab = table::<T>(opts.encoding);
    let mut y0 = 0u16;
    while y0 < camera.height() {
        band.move_to(y0);
        band.clear(Rgb565(0));
        let _ = draw(&camera, &mut band, &mesh, &transform, &shader, &opts);
        if let Some(p) = &prepared {
            let _ = p.draw(&camera, &mut band, &shader, &opts, &tab);
        }
        if let Some((a, b)) = &shared {
            let _ = a.draw(&camera, &mut band, &shader, &opts, &tab);
            let _ = b.draw(&camera, &mut band, &shader, &opts, &tab);
        }
        y0 = y0.saturating_add(rows);
    }
    // The triangle setup within the rasterizer's range, at any rows.
    let fp = |inp: &mut Input<'_>| {
        let c = |x: u32| (x % (2 * MAX_COORD as u32 + 1)) as i32 - MAX_COORD;
        FixedPoint::new(c(inp.u32()), c(inp.u32()))
    };
    if let Some(t) = EdgeTriangle::new([fp(s.inp), fp(s.inp), fp(s.inp)], cull) {
        let w = 1 + s.inp.below(64) as i32;
        let r0 = s.inp.u32() as i32 % (MAX_COORD / 16);
        let r1 = r0 + 1 + s.inp.below(16) as i32;
        t.for_each_covered(w, r0, r1, |_, _, _| {});
        t.for_each_span(w, r0, r1, |_, _, _| {});
    }
}
