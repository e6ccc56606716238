//! Exact coverage of the edge functions: shared edges cover every pixel once (exhaustive on
//! small grids, jittered meshes), and the top-left rule on pixel centres.

use super::*;

/// Counts, per pixel of `[x0, x1) x [y0, y1)`, the triangles that cover it.
pub(super) fn coverage(tris: &[[FixedPoint; 3]], x0: i32, y0: i32, x1: i32, y1: i32) -> Vec<u32> {
    let (w, h) = ((x1 - x0) as usize, (y1 - y0) as usize);
    let mut count = vec![0u32; w * h];
    for t in tris {
        // Shift so the window starts at pixel (0, 0).
        let s = |p: FixedPoint| FixedPoint::new(p.x - x0 * SUBPIXEL, p.y - y0 * SUBPIXEL);
        if let Some(e) = EdgeTriangle::new([s(t[0]), s(t[1]), s(t[2])], Cull::None) {
            e.for_each_covered(w as i32, 0, h as i32, |x, y, _| {
                count[y as usize * w + x as usize] += 1;
            });
        }
    }
    count
}

/// Strictly inside the triangle (either orientation).
pub(super) fn strictly_inside(t: &[FixedPoint; 3], p: FixedPoint) -> bool {
    let e = [
        edge_function(t[0], t[1], p),
        edge_function(t[1], t[2], p),
        edge_function(t[2], t[0], p),
    ];
    e.iter().all(|&v| v > 0) || e.iter().all(|&v| v < 0)
}

#[test]
fn shared_edges_cover_every_pixel_once_exhaustive() {
    // Every ordered pair of distinct points of a quarter-pixel lattice over 3x3 pixels (the
    // lattice contains the pixel centres, so many edges pass exactly through them), with far
    // apexes on both sides: the two triangles share the edge a-b.
    let pts: Vec<FixedPoint> = (0..13)
        .flat_map(|i| (0..13).map(move |j| FixedPoint::new(4 * i, 4 * j)))
        .collect();
    let mut on_edge_pixels = 0u64;
    for &a in &pts {
        for &b in &pts {
            if a == b {
                continue;
            }
            let perp = (-(b.y - a.y), b.x - a.x);
            let l = FixedPoint::new(a.x + 16 * perp.0, a.y + 16 * perp.1);
            let r = FixedPoint::new(a.x - 16 * perp.0, a.y - 16 * perp.1);
            let tris = [[a, b, l], [b, a, r]];
            let cov = coverage(&tris, -1, -1, 4, 4);
            for py in -1..4 {
                for px in -1..4 {
                    let c = cov[((py + 1) * 5 + px + 1) as usize];
                    assert!(
                        c <= 1,
                        "pixel ({px},{py}) drawn {c} times, edge {a:?}-{b:?}"
                    );
                    let p = FixedPoint::pixel_centre(px, py);
                    let along = i64::from(p.x - a.x) * i64::from(p.x - b.x)
                        + i64::from(p.y - a.y) * i64::from(p.y - b.y);
                    let on_shared = edge_function(a, b, p) == 0 && along < 0;
                    if on_shared {
                        on_edge_pixels += 1;
                    }
                    if on_shared || strictly_inside(&tris[0], p) || strictly_inside(&tris[1], p) {
                        assert_eq!(c, 1, "pixel ({px},{py}) missed, edge {a:?}-{b:?}");
                    }
                }
            }
        }
    }
    // The exhaustive set really exercised the tie-breaking rule.
    assert!(on_edge_pixels > 1_000, "{on_edge_pixels}");
}

#[test]
fn jittered_meshes_cover_the_window_exactly_once() {
    // A 6x6 grid of quads over [-2, 10] pixels, each vertex jittered by up to a quarter cell
    // (on a 4-step lattice for half the seeds, so edges and vertices hit pixel centres), quads
    // split along a random diagonal, either winding: every pixel of the 8x8 window exactly
    // once. Seeds whose jitter folds a triangle over (the mesh overlaps itself) are skipped.
    let mut used = 0;
    for seed in 0..400u64 {
        let mut rng = Lcg(seed);
        let n = 6;
        let step = 2 * SUBPIXEL;
        let coarse = seed % 2 == 0;
        let grid: Vec<FixedPoint> = (0..=n)
            .flat_map(|i| (0..=n).map(move |j| (i, j)))
            .map(|(i, j)| {
                let inner = i > 0 && i < n && j > 0 && j < n;
                let (mut dx, mut dy) = (0, 0);
                if inner {
                    dx = rng.range(step / 2) - step / 4;
                    dy = rng.range(step / 2) - step / 4;
                    if coarse {
                        dx -= dx.rem_euclid(4);
                        dy -= dy.rem_euclid(4);
                    }
                }
                FixedPoint::new(-2 * SUBPIXEL + i * step + dx, -2 * SUBPIXEL + j * step + dy)
            })
            .collect();
        let at = |i: i32, j: i32| grid[(i * (n + 1) + j) as usize];
        let mut tris = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                let (t1, t2) = if rng.next() % 2 == 0 {
                    ([a, b, c], [a, c, d])
                } else {
                    ([a, b, d], [b, c, d])
                };
                if seed % 3 == 0 {
                    tris.push([t1[0], t1[2], t1[1]]);
                    tris.push([t2[0], t2[2], t2[1]]);
                } else {
                    tris.push(t1);
                    tris.push(t2);
                }
            }
        }
        let sign = |t: &[FixedPoint; 3]| edge_function(t[0], t[1], t[2]).signum();
        if tris.iter().any(|t| sign(t) != sign(&tris[0])) {
            continue;
        }
        used += 1;
        let cov = coverage(&tris, 0, 0, 8, 8);
        assert!(cov.iter().all(|&c| c == 1), "seed {seed}: {cov:?}");
    }
    assert!(used > 300, "{used}");
}

#[test]
fn top_left_rule_on_pixel_centres() {
    // A square whose edges run through pixel centres (8, 8) to (40, 40): the top and left
    // edges are in, the bottom and right ones out, so exactly pixels (0..2, 0..2).
    let (a, b, c, d) = (
        FixedPoint::new(8, 8),
        FixedPoint::new(40, 8),
        FixedPoint::new(40, 40),
        FixedPoint::new(8, 40),
    );
    let cov = coverage(&[[a, b, c], [a, c, d]], 0, 0, 4, 4);
    let expect: Vec<u32> = (0..16).map(|i| u32::from(i % 4 < 2 && i / 4 < 2)).collect();
    assert_eq!(cov, expect);
    // The square from (0, 0) to (64, 64): all 16 pixel centres strictly inside.
    let (a, b, c, d) = (
        FixedPoint::new(0, 0),
        FixedPoint::new(64, 0),
        FixedPoint::new(64, 64),
        FixedPoint::new(0, 64),
    );
    assert_eq!(coverage(&[[a, b, c], [a, c, d]], 0, 0, 4, 4), vec![1; 16]);
    // Zero area and culling.
    assert!(EdgeTriangle::new([a, b, FixedPoint::new(128, 0)], Cull::None).is_none());
    // (a, b, c) is clockwise on the y-down grid: a back face in the mesh convention.
    assert!(EdgeTriangle::new([a, b, c], Cull::Back).is_none());
    assert!(EdgeTriangle::new([a, c, b], Cull::Back).is_some());
}
