//! Independent references for the segment and parallelogram models (`tests/line/`): plain
//! `std` f64 that never calls the library and never uses a closed form.
//!
//! - [`line_lambert`]: the defining integral of `[line_lambert]` along the segment by global
//!   adaptive Gauss-Kronrod (G10/K21, QUADPACK's `qk21` rule): the panel with the largest
//!   error estimate `|K21 - G10|` is bisected until the estimates sum to `TOL` of
//!   `max(1, |I|)`. The variable is the segment parameter measured from the point of the
//!   segment closest to `p` (so nodes near the peak of the integrand keep full relative
//!   resolution when `p` is within 1e-12 of the segment); the kink where `L.n` changes sign
//!   (the horizon crossing) and that closest point are breakpoints, and the mesh is graded
//!   toward the closest point from the width of the peak there (`dist/len`) up by factors of 4,
//!   since an adaptive rule all of whose nodes miss a feature that narrow would accept a panel
//!   without it. `|K21 - G10|` is the error of the 10-point rule, far larger than that of the
//!   21-point value returned, so the estimate is an upper bound in practice. The rule's
//!   constants are checked by [`check_rule`] (exactness on monomials, Legendre roots). The
//!   quadrature is as exact as the f64 geometry: with `p` within `h` of a segment of length
//!   `len` in a general orientation, the rounding of `a - p` moves the perpendicular by about
//!   `1e-16 len`, a relative `1e-16 len/h` (checked against 50-digit arithmetic: 2.5e-10 at
//!   `h = 1e-6 len`).
//! - [`line_max_cos`], [`rect_max_cos`]: the largest `cos(angle(q - p, r))` over the points `q`
//!   of a segment / parallelogram by dense sampling plus golden-section refinement (no use of
//!   the closest-angular-point formula or of the ray test).
// The rule's constants are QUADPACK's, digit for digit.
#![allow(
    dead_code,
    clippy::neg_cmp_op_on_partial_ord,
    clippy::excessive_precision
)]

pub type V3 = [f64; 3];

fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn norm(a: V3) -> f64 {
    // Scaled, so tiny vectors do not underflow.
    let m = a[0].abs().max(a[1].abs()).max(a[2].abs());
    if m == 0.0 {
        return 0.0;
    }
    let s = scale(a, 1.0 / m);
    m * dot(s, s).sqrt()
}
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn unit(a: V3) -> V3 {
    scale(a, 1.0 / norm(a))
}

// ---------------------------------------------------------------------------------------------
// Gauss-Kronrod 10/21
// ---------------------------------------------------------------------------------------------

/// Kronrod abscissae on [0, 1] (positive half, descending; odd indices are the Gauss nodes).
const XGK: [f64; 11] = [
    0.995_657_163_025_808_080_735_527_280_689_003,
    0.973_906_528_517_171_720_077_964_012_084_452,
    0.930_157_491_355_708_226_001_207_180_059_508,
    0.865_063_366_688_984_510_732_096_688_423_493,
    0.780_817_726_586_416_897_063_717_578_345_042,
    0.679_409_568_299_024_406_234_327_365_114_874,
    0.562_757_134_668_604_683_339_000_099_272_694,
    0.433_395_394_129_247_190_799_265_943_165_784,
    0.294_392_862_701_460_198_131_126_603_103_866,
    0.148_874_338_981_631_210_884_826_001_129_720,
    0.0,
];
/// Kronrod weights.
const WGK: [f64; 11] = [
    0.011_694_638_867_371_874_278_064_396_062_192,
    0.032_558_162_307_964_727_478_818_972_459_390,
    0.054_755_896_574_351_996_031_381_300_244_580,
    0.075_039_674_810_919_952_767_043_140_916_190,
    0.093_125_454_583_697_605_535_065_465_083_366,
    0.109_387_158_802_297_641_899_210_590_325_805,
    0.123_491_976_262_065_851_077_208_067_198_014,
    0.134_709_217_311_473_325_928_054_001_771_707,
    0.142_775_938_577_060_080_797_094_273_138_717,
    0.147_739_104_901_338_491_374_841_515_972_068,
    0.149_445_554_002_916_905_664_936_468_389_821,
];
/// Gauss weights of the nodes XGK[1], XGK[3], ..., XGK[9].
const WG: [f64; 5] = [
    0.066_671_344_308_688_137_593_568_809_893_332,
    0.149_451_349_150_580_593_145_776_339_657_697,
    0.219_086_362_515_982_043_995_534_934_228_163,
    0.269_266_719_309_996_355_091_226_921_569_469,
    0.295_524_224_714_752_870_173_892_994_651_338,
];

/// (K21, |K21 - G10|) on [a, b].
fn qk21<F: FnMut(f64) -> f64>(f: &mut F, a: f64, b: f64) -> (f64, f64) {
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let fc = f(c);
    let mut k = WGK[10] * fc;
    let mut g = 0.0;
    for i in 0..10 {
        let x = h * XGK[i];
        let s = f(c - x) + f(c + x);
        k += WGK[i] * s;
        if i % 2 == 1 {
            g += WG[i / 2] * s;
        }
    }
    (k * h, ((k - g) * h).abs())
}

/// Checks the rule's constants: the Gauss nodes are roots of P10, G10 integrates x^j exactly
/// for j <= 19 and K21 for j <= 31 (on [-1, 1]). Returns the largest deviation.
pub fn check_rule() -> f64 {
    let mut worst = 0.0f64;
    for j in 0..32u32 {
        let exact = if j % 2 == 1 {
            0.0
        } else {
            2.0 / (j as f64 + 1.0)
        };
        let mut f = |x: f64| x.powi(j as i32);
        let (k, err) = qk21(&mut f, -1.0, 1.0);
        worst = worst.max((k - exact).abs());
        if j <= 19 {
            // |K - G| is the G10 error: exact polynomials give 0 up to rounding.
            worst = worst.max(err);
        }
    }
    for i in (1..10).step_by(2) {
        let x = XGK[i];
        let (mut p0, mut p1) = (1.0f64, x);
        for n in 2..=10 {
            let nf = n as f64;
            let p2 = ((2.0 * nf - 1.0) * x * p1 - (nf - 1.0) * p0) / nf;
            p0 = p1;
            p1 = p2;
        }
        worst = worst.max(p1.abs());
    }
    worst
}

/// A panel of the global adaptive rule, ordered by its error estimate.
struct Panel {
    a: f64,
    b: f64,
    value: f64,
    err: f64,
}
impl PartialEq for Panel {
    fn eq(&self, o: &Self) -> bool {
        self.err.total_cmp(&o.err).is_eq()
    }
}
impl Eq for Panel {}
impl PartialOrd for Panel {
    fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Panel {
    fn cmp(&self, o: &Self) -> std::cmp::Ordering {
        self.err.total_cmp(&o.err)
    }
}

/// Global adaptive G10/K21 over the pieces between consecutive `breaks`: bisects the panel
/// with the largest error estimate until the estimates sum to `tol * max(1, |I|)` (or
/// `max_panels`). Returns `(I, estimate)`.
pub fn integrate<F: FnMut(f64) -> f64>(
    mut f: F,
    breaks: &[f64],
    tol: f64,
    max_panels: usize,
) -> (f64, f64) {
    let mut heap = std::collections::BinaryHeap::new();
    for w in breaks.windows(2) {
        if w[1] > w[0] {
            let (value, err) = qk21(&mut f, w[0], w[1]);
            heap.push(Panel {
                a: w[0],
                b: w[1],
                value,
                err,
            });
        }
    }
    let sums = |h: &std::collections::BinaryHeap<Panel>| {
        h.iter()
            .fold((0.0, 0.0), |(v, e), p| (v + p.value, e + p.err))
    };
    let (mut total, mut err) = sums(&heap);
    loop {
        if err <= tol * total.abs().max(1.0) || heap.len() >= max_panels {
            // Re-add from scratch (no drift from the running updates).
            let (t, e) = sums(&heap);
            if e <= tol * t.abs().max(1.0) || heap.len() >= max_panels {
                return (t, e);
            }
            total = t;
            err = e;
        }
        let Some(p) = heap.pop() else {
            return (0.0, 0.0);
        };
        let m = 0.5 * (p.a + p.b);
        total -= p.value;
        err -= p.err;
        if !(m > p.a && m < p.b) {
            // Cannot split further (a panel one ULP wide): accept it as it is.
            total += p.value;
            heap.push(Panel { err: 0.0, ..p });
            continue;
        }
        for (a, b) in [(p.a, m), (m, p.b)] {
            let (value, e) = qk21(&mut f, a, b);
            total += value;
            err += e;
            heap.push(Panel {
                a,
                b,
                value,
                err: e,
            });
        }
    }
}

/// Target of [`line_lambert`]: the error estimates sum to this fraction of `max(1, |I|)`.
pub const TOL: f64 = 1e-14;

/// `[line_lambert]` by quadrature: `integral over t in [0, 1] of (L.n)+ / |L|^(k+1)`,
/// `L = (a - p) + t (b - a)`, `n` normalized. Returns `(I, error estimate)`.
pub fn line_lambert(a: V3, b: V3, p: V3, n: V3, k: u32) -> (f64, f64) {
    let n = unit(n);
    let (l0, l1, d) = (sub(a, p), sub(b, p), sub(b, a));
    let e = unit(d);
    let len = norm(d);
    // The integration variable tau is the segment parameter measured from the point c of the
    // segment closest to p: L = lc + tau d. When p is close to the segment the integrand
    // peaks there with width dist/len; nodes near it then have full relative resolution (in
    // t they would be quantized to the ULPs of t_c, coarse when p is within 1e-12 of the
    // segment), L has no cancellation there, and in an axis-aligned frame lc and the ends are
    // exact. The far end is one parameter unit from the near one.
    let (s0, s1) = (dot(l0, e), dot(l1, e));
    let (lc, tau0, tau1) = if s0 < 0.0 && s1 > 0.0 {
        // The foot of the perpendicular, e x (L0 x e), inside the segment.
        let lc = cross(e, cross(l0, e));
        if s0.abs() <= s1.abs() {
            (lc, s0 / len, s0 / len + 1.0)
        } else {
            (lc, s1 / len - 1.0, s1 / len)
        }
    } else if norm(l0) <= norm(l1) {
        (l0, 0.0, 1.0)
    } else {
        (l1, -1.0, 0.0)
    };
    let f = |tau: f64| {
        let l = add(lc, scale(d, tau));
        let c = dot(l, n);
        if c <= 0.0 {
            0.0
        } else {
            c / norm(l).powi(k as i32 + 1)
        }
    };
    let mut breaks = vec![tau0, tau1];
    let dn = dot(d, n);
    if dn != 0.0 {
        // The horizon crossing, where L.n changes sign (a kink).
        let t = -dot(lc, n) / dn;
        if t > tau0 && t < tau1 {
            breaks.push(t);
        }
    }
    // A mesh graded toward the closest point (tau = 0), from the width of the peak there
    // (dist/len) up: an adaptive rule whose nodes all miss a feature that narrow would accept
    // a panel without it.
    let w = norm(lc) / len;
    if tau0 < 0.0 && tau1 > 0.0 {
        breaks.push(0.0);
    }
    let mut x = w;
    while x < 1.0 {
        for t in [-x, x] {
            if t > tau0 && t < tau1 {
                breaks.push(t);
            }
        }
        x *= 4.0;
    }
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    integrate(f, &breaks, TOL, 50_000)
}

// ---------------------------------------------------------------------------------------------
// Brute-force peaks
// ---------------------------------------------------------------------------------------------

const GOLD: f64 = 0.618_033_988_749_894_9;

/// Golden-section search for the maximum of `f` on [lo, hi] (unimodal there).
fn golden_max<F: FnMut(f64) -> f64>(mut f: F, mut lo: f64, mut hi: f64) -> (f64, f64) {
    let mut x1 = hi - GOLD * (hi - lo);
    let mut x2 = lo + GOLD * (hi - lo);
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..120 {
        if f1 < f2 {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + GOLD * (hi - lo);
            f2 = f(x2);
        } else {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - GOLD * (hi - lo);
            f1 = f(x1);
        }
        if !(hi - lo > 1e-17 * (1.0 + lo.abs())) {
            break;
        }
    }
    if f1 >= f2 {
        (x1, f1)
    } else {
        (x2, f2)
    }
}

/// `cos(angle(q - p, r))`, computed as `(q - p).r / |q - p|`.
fn cos_to(q_minus_p: V3, r: V3) -> f64 {
    let l = norm(q_minus_p);
    if l == 0.0 {
        return -1.0;
    }
    dot(q_minus_p, r) / l
}

/// The largest cosine between `r` and the directions from `p` to the segment `a -> b`: 4097
/// samples, then golden section between the neighbours of the best (the cosine is unimodal
/// along the arc of directions).
pub fn line_max_cos(a: V3, b: V3, p: V3, r: V3) -> f64 {
    let r = unit(r);
    let l0 = sub(a, p);
    let d = sub(b, a);
    let f = |t: f64| cos_to(add(l0, scale(d, t)), r);
    let n = 4096;
    let (mut bi, mut bv) = (0usize, f64::NEG_INFINITY);
    for i in 0..=n {
        let v = f(i as f64 / n as f64);
        if v > bv {
            bv = v;
            bi = i;
        }
    }
    let lo = (bi.saturating_sub(1)) as f64 / n as f64;
    let hi = ((bi + 1).min(n)) as f64 / n as f64;
    let (_, gv) = golden_max(f, lo, hi);
    bv.max(gv).max(f(0.0)).max(f(1.0))
}

/// The largest cosine between `r` and the directions from `p` to the parallelogram
/// `o + s eu + t ev`: the four edges as [`line_max_cos`], a 201 x 201 grid, nested golden
/// sections around the grid's best point and over the whole square (the cosine is
/// quasi-concave where positive). Every candidate is a point of the light, so the maximum of
/// the candidates never overestimates.
pub fn rect_max_cos(o: V3, eu: V3, ev: V3, p: V3, r: V3) -> f64 {
    let r = unit(r);
    let q0 = sub(o, p);
    let f = |s: f64, t: f64| cos_to(add(q0, add(scale(eu, s), scale(ev, t))), r);
    let corners = [o, add(o, eu), add(add(o, eu), ev), add(o, ev)];
    let mut best = f64::NEG_INFINITY;
    for i in 0..4 {
        best = best.max(line_max_cos(corners[i], corners[(i + 1) % 4], p, r));
    }
    let n = 200;
    let (mut bi, mut bj) = (0usize, 0usize);
    let mut gv = f64::NEG_INFINITY;
    for i in 0..=n {
        for j in 0..=n {
            let v = f(i as f64 / n as f64, j as f64 / n as f64);
            if v > gv {
                gv = v;
                bi = i;
                bj = j;
            }
        }
    }
    best = best.max(gv);
    let nested = |slo: f64, shi: f64, tlo: f64, thi: f64| {
        golden_max(|s| golden_max(|t| f(s, t), tlo, thi).1, slo, shi).1
    };
    let h = 4.0 / n as f64;
    let (s0, t0) = (bi as f64 / n as f64, bj as f64 / n as f64);
    best = best.max(nested(
        (s0 - h).max(0.0),
        (s0 + h).min(1.0),
        (t0 - h).max(0.0),
        (t0 + h).min(1.0),
    ));
    best.max(nested(0.0, 1.0, 0.0, 1.0))
}

/// `((c)+)^m` with the spec's `m = 0` convention (1 where `c > 0`, else 0).
pub fn lobe(c: f64, m: u32) -> f64 {
    if c > 0.0 {
        c.powi(m as i32)
    } else {
        0.0
    }
}
