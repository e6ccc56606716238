//! `host-sim eval` end to end: the binary, fed on stdin, read back from stdout.

use std::io::Write;
use std::process::{Command, Stdio};

use serde_json::{json, Value};

mod errors;
mod models;
use models::FIXED_MODELS;

/// Runs `host-sim eval --backend <backend>` on `input`; returns stdout's lines, the exit code
/// and stderr.
fn run_full(backend: &str, input: &str) -> (Vec<String>, i32, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["eval", "--backend", backend])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn host-sim");
    let mut stdin = child.stdin.take().unwrap();
    let input = input.to_owned();
    let writer = std::thread::spawn(move || {
        stdin.write_all(input.as_bytes()).unwrap();
    });
    let out = child.wait_with_output().unwrap();
    writer.join().unwrap();
    let stdout = String::from_utf8(out.stdout).unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    (
        stdout.lines().map(str::to_owned).collect(),
        out.status.code().unwrap_or(-1),
        stderr,
    )
}

/// [`run_full`], asserting that stderr is empty or the one summary line of a run with error
/// lines.
fn run_raw(backend: &str, input: &str) -> (Vec<String>, i32) {
    let (out, code, stderr) = run_full(backend, input);
    let errors = out.iter().filter(|l| l.contains("\"error\":")).count();
    if errors == 0 {
        assert!(stderr.is_empty(), "stderr: {stderr}");
    } else {
        assert_eq!(stderr.lines().count(), 1, "stderr: {stderr}");
        assert!(
            stderr.starts_with(&format!("host-sim eval: {errors} of {} lines", out.len())),
            "stderr: {stderr}"
        );
    }
    (out, code)
}

/// Runs the lines (as JSON values) and parses the answers; asserts exit code 0.
fn run(backend: &str, lines: &[Value]) -> Vec<Value> {
    let input: String = lines.iter().map(|l| format!("{l}\n")).collect();
    let (out, code) = run_raw(backend, &input);
    assert_eq!(code, 0);
    assert_eq!(out.len(), lines.len(), "one output line per input line");
    out.iter()
        .map(|l| serde_json::from_str(l).expect("output is JSON"))
        .collect()
}

fn one(backend: &str, line: Value) -> Value {
    run(backend, &[line]).pop().unwrap()
}

fn error_of(v: &Value) -> &str {
    v["error"]
        .as_str()
        .unwrap_or_else(|| panic!("expected an error, got {v}"))
}

const GRACE: [[f64; 3]; 9] = arealight::sh9::GRACE_CATHEDRAL;

fn square() -> Value {
    json!([[-1, -1, 2], [1, -1, 2], [1, 1, 2], [-1, 1, 2]])
}

/// A simple valid case for every supported model.
fn valid_cases() -> Vec<Value> {
    vec![
        json!({"id": "hemi_const", "model": "hemi_const", "n": [0, 0.6, 0.8], "axis": [0, 0, 1]}),
        json!({"id": "hemi_cos", "model": "hemi_cos", "n": [0.3, 0.6, 0.5], "axis": [0, 0, 1]}),
        json!({"id": "sky_overcast", "model": "sky_overcast", "n": [0, 0.6, 0.8], "zenith": [0, 0, 2], "c": 1.5}),
        json!({"id": "sky_ground", "model": "sky_ground", "n": [0, 1, 1], "up": [0, 1, 0],
               "sky": [0.6, 0.7, 1.0], "ground": [0.3, 0.2, 0.1]}),
        json!({"id": "cap_lambert", "model": "cap_lambert", "n": [1, 0, 0.2], "axis": [0, 0, 1], "sigma": 0.5}),
        json!({"id": "cap_lambert_hermite", "model": "cap_lambert_hermite", "n": [1, 0, 0.2],
               "axis": [0, 0, 1], "sigma": 0.5}),
        json!({"id": "sphere_lambert", "model": "sphere_lambert", "p": [0, 0, 0], "n": [0, 0.3, 1],
               "center": [0, 0, 3], "radius": 1}),
        json!({"id": "sphere_lambert_hermite", "model": "sphere_lambert_hermite", "p": [0, 0, 0],
               "n": [0, 0.3, 1], "center": [0, 0, 3], "radius": 1}),
        json!({"id": "polygon_lambert", "model": "polygon_lambert", "p": [0, 0, 0], "n": [0, 0.5, 1],
               "verts": square()}),
        json!({"id": "phong_hemi_const", "model": "phong_hemi_const", "r": [0, 0.5, 1], "axis": [0, 0, 1], "m": 8}),
        json!({"id": "phong_hemi_cos", "model": "phong_hemi_cos", "r": [0, 0.5, 1], "axis": [0, 0, 1], "m": 7}),
        json!({"id": "phong_cap", "model": "phong_cap", "r": [0, 0.3, 1], "axis": [0, 0, 1], "sigma": 0.4, "m": 9}),
        json!({"id": "phong_sphere", "model": "phong_sphere", "p": [0, 0, 0], "r": [0, 0.2, 1],
               "center": [0, 0, 3], "radius": 1, "m": 16}),
        json!({"id": "phong_polygon", "model": "phong_polygon", "p": [0, 0, 0], "r": [0, 0.3, 1],
               "verts": square(), "m": 16}),
        json!({"id": "sh9_irradiance", "model": "sh9_irradiance", "n": [0.2, 0.3, 1], "coeffs": GRACE}),
        json!({"id": "sh9_disc_irradiance", "model": "sh9_disc_irradiance", "n": [0, 0.2, 1],
               "axis": [0, 0, 1], "alpha": 0.6}),
        json!({"id": "superellipse_shape", "model": "superellipse_shape", "pos": [0.05, 0.3, 1],
               "a": 0.2, "b": 0.3, "A": 0.3, "B": 0.4, "d": 0.8}),
        json!({"id": "distance_falloff", "model": "distance_falloff", "z": 0.7, "M": 2, "d0": 1,
               "alpha": 1, "znear": 1, "zfar": 2, "near_edge": 0.4, "far_edge": 0.8}),
        json!({"id": "axial_moment", "model": "axial_moment", "p": [0, 0, 0], "verts": square(),
               "w": [0, 0.2, 1], "m": 3}),
        json!({"id": "double_axis_moment", "model": "double_axis_moment", "p": [0, 0, 0],
               "verts": square(), "w": [0, 0.2, 1], "v": [0.1, 0, 1], "m": 2}),
        json!({"id": "directional_luminaire", "model": "directional_luminaire", "p": [0, 0, 0],
               "n": [0, 0.3, 1], "verts": square(), "axis": [0, 0, -1], "m": 4}),
        json!({"id": "glossy_reflection", "model": "glossy_reflection", "p": [0, 0, 0], "n": [0, 0, 1],
               "e": [0, 0.3, 1], "verts": square(), "m": 8}),
        json!({"id": "glossy_transmission", "model": "glossy_transmission", "p": [0, 0, 0],
               "n": [0, 0, -1], "e": [0, 0.2, -1], "verts": square(), "m": 8}),
        json!({"id": "lune_normalization", "model": "lune_normalization", "w": [0, 0, 1],
               "v": [0, 1, 1], "m": 5}),
        json!({"id": "line_lambert", "model": "line_lambert", "p": [0, 0, 0], "n": [0, 0.3, 1],
               "a": [-1, 0.5, 2], "b": [1.5, -0.2, 2.5], "k": 2}),
        json!({"id": "line_phong_peak", "model": "line_phong_peak", "p": [0, 0, 0], "r": [0.2, 0.1, 1],
               "a": [-1, 0.5, 2], "b": [1.5, -0.2, 2.5], "m": 16}),
        json!({"id": "rect_phong_peak", "model": "rect_phong_peak", "p": [0, 0, 0], "r": [0.6, 0.1, 1],
               "origin": [-1, -1, 2], "eu": [2, 0, 0], "ev": [0, 2, 0], "m": 16}),
    ]
}

/// The answer's numbers (one for "value", three for "rgb").
fn numbers(v: &Value) -> Vec<f64> {
    if let Some(x) = v.get("value") {
        vec![x.as_f64().unwrap()]
    } else if let Some(c) = v.get("rgb") {
        c.as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    } else {
        panic!("no value in {v}")
    }
}

#[test]
fn every_supported_model_answers_on_every_float_backend() {
    let cases = valid_cases();
    let reference = run("f64", &cases);
    let f32s = run("f32", &cases);
    let fast = run("f32-fast", &cases);
    for (((case, r), a), b) in cases.iter().zip(&reference).zip(&f32s).zip(&fast) {
        let id = &case["id"];
        for out in [r, a, b] {
            assert_eq!(&out["id"], id, "{out}");
            assert!(out.get("error").is_none(), "{out}");
        }
        let want_rgb = matches!(id.as_str(), Some("sky_ground" | "sh9_irradiance"));
        assert_eq!(r.get("rgb").is_some(), want_rgb, "{r}");
        let (r, a, b) = (numbers(r), numbers(a), numbers(b));
        for k in 0..r.len() {
            assert!(r[k].is_finite() && a[k].is_finite() && b[k].is_finite());
            assert!(r[k] > 0.0, "{id}: a lit case should be positive: {}", r[k]);
            assert!(
                (r[k] - a[k]).abs() <= 1e-5,
                "{id}: f32 {} vs f64 {}",
                a[k],
                r[k]
            );
            assert!(
                (r[k] - b[k]).abs() <= r[k].abs().max(1.0) / 1024.0,
                "{id}: f32-fast {} vs f64 {}",
                b[k],
                r[k]
            );
        }
    }
}

#[test]
fn numbers_round_trip() {
    use arealight::{HemisphereLight, PhongLobe, PolygonLight, Vec3};
    let out = run(
        "f64",
        &[
            json!({"id": "one", "model": "hemi_const", "n": [0, 0, 1], "axis": [0, 0, 1]}),
            json!({"id": "cos", "model": "hemi_cos", "n": [0.3, 0.6, 0.5], "axis": [0, 0, 1]}),
            json!({"id": "poly", "model": "phong_polygon", "p": [0, 0, 0], "r": [0, 0.3, 1],
                   "verts": square(), "m": 16}),
        ],
    );
    assert_eq!(out[0]["value"].as_f64(), Some(1.0));
    // Bit-exact against the library called directly.
    let hemi = HemisphereLight::<f64>::new(Vec3::new(0.0, 0.0, 1.0)).unwrap();
    let want = hemi.lambert_cos(Vec3::new(0.3, 0.6, 0.5));
    assert_eq!(out[1]["value"].as_f64().unwrap().to_bits(), want.to_bits());
    let verts = [
        Vec3::new(-1.0, -1.0, 2.0),
        Vec3::new(1.0, -1.0, 2.0),
        Vec3::new(1.0, 1.0, 2.0),
        Vec3::new(-1.0, 1.0, 2.0),
    ];
    let poly = PolygonLight::<f64, 4>::new(&verts).unwrap();
    let want = poly.phong(
        &PhongLobe::new(16).unwrap(),
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.0, 0.3, 1.0),
    );
    assert_eq!(out[2]["value"].as_f64().unwrap().to_bits(), want.to_bits());
    // The f32 backend prints the f32 result exactly (as f64).
    let out = one(
        "f32",
        json!({"id": "c", "model": "hemi_cos", "n": [0.3, 0.6, 0.5], "axis": [0, 0, 1]}),
    );
    let hemi = HemisphereLight::<f32>::new(Vec3::new(0.0, 0.0, 1.0)).unwrap();
    let want = hemi.lambert_cos(Vec3::new(0.3, 0.6, 0.5)) as f64;
    assert_eq!(out["value"].as_f64().unwrap().to_bits(), want.to_bits());
}

#[test]
fn exact_output_text() {
    let (out, code) = run_raw(
        "f64",
        "{\"id\":\"a\",\"model\":\"hemi_const\",\"n\":[0,0,1],\"axis\":[0,0,1]}\n",
    );
    assert_eq!(code, 0);
    assert_eq!(out, vec![r#"{"id":"a","value":1.0}"#.to_owned()]);
}

#[test]
fn fixed_backend_answers_its_models_within_1_1024_and_refuses_the_others() {
    let cases = valid_cases();
    let reference = run("f64", &cases);
    let out = run("fixed", &cases);
    for ((case, r), got) in cases.iter().zip(&reference).zip(&out) {
        assert_eq!(got["id"], case["id"]);
        let model = case["model"].as_str().unwrap();
        if FIXED_MODELS.contains(&model) {
            assert!(got.get("error").is_none(), "{got}");
            for (a, b) in numbers(got).iter().zip(numbers(r)) {
                assert!(
                    (a - b).abs() <= 1.0 / 1024.0,
                    "{model}: fixed {a} vs f64 {b}"
                );
            }
        } else {
            assert_eq!(
                error_of(got),
                format!("unsupported: the fixed-point backend does not implement {model}")
            );
        }
    }
    // What the format cannot hold is refused, never saturated silently.
    let bad = [
        (json!({"id": 1, "model": "hemi_const", "n": ["NaN", 0, 1], "axis": [0, 0, 1]}),
         "n is not finite (NaN or infinity)"),
        (json!({"id": 2, "model": "hemi_const", "n": [0, 0, 1e6], "axis": [0, 0, 1]}),
         "n is outside the range of the fixed-point backend (|x| < 512)"),
        (json!({"id": 3, "model": "polygon_lambert", "p": [0, 0, 0], "n": [0, 0, 1],
                "verts": [[-1, -1, 2e9], [1, -1, 2e9], [1, 1, 2e9]]}),
         "verts is outside the coordinate range (|x| <= 4 for the fixed-point type's own coordinates, |x| < 2^30 for world coordinates)"),
        (json!({"id": 4, "model": "phong_cap", "r": [0, 0, 1], "axis": [0, 0, 1], "sigma": 0.3, "m": 256}),
         "Phong exponent m is too large: 256 > 255, the largest this backend accepts"),
    ];
    for (line, want) in bad {
        assert_eq!(error_of(&one("fixed", line)), want);
    }
}

/// The positional models on the fixed backend take world coordinates: random scenes with
/// positions up to 1000 units (the kind modelled in metres) are all answered, within 1/1024 of
/// f64 (before, positions beyond 4 were refused: 28 of 40 `phong_sphere` cases of such a set).
#[test]
fn fixed_backend_answers_scenes_in_world_units() {
    // splitmix64: a small deterministic source.
    let mut state = 0x5eed_u64;
    let mut next = move || {
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut point = |scale: f64| -> [f64; 3] { [0, 1, 2].map(|_| (2.0 * next() - 1.0) * scale) };
    let mut lines = Vec::new();
    for i in 0..200 {
        let c = point(1000.0);
        let r = 0.5 + 50.0 * point(1.0)[0].abs();
        // A point outside the sphere: along a direction from the centre, 1.5 to 20 radii away.
        let dir = point(1.0);
        let len = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2])
            .sqrt()
            .max(1e-3);
        let k = r * (1.5 + 18.5 * point(1.0)[0].abs()) / len;
        let p = [c[0] + dir[0] * k, c[1] + dir[1] * k, c[2] + dir[2] * k];
        let n = point(1.0);
        let m = (i * 37) % 256;
        for model in ["sphere_lambert", "sphere_lambert_hermite"] {
            lines.push(json!({"id": lines.len(), "model": model, "p": p, "n": n, "center": c, "radius": r}));
        }
        lines.push(json!({"id": lines.len(), "model": "phong_sphere", "p": p, "r": n, "center": c, "radius": r, "m": m}));
        // A square of side 2s centred at q (axis-aligned plane), seen from a point off it.
        let q = point(1000.0);
        let s = 1.0 + 100.0 * point(1.0)[0].abs();
        let verts = [[-s, -s], [s, -s], [s, s], [-s, s]].map(|[a, b]| [q[0] + a, q[1] + b, q[2]]);
        let off = point(1000.0);
        let p = [
            off[0],
            off[1],
            q[2] + if off[2] >= 0.0 { 1.0 } else { -1.0 } + off[2],
        ];
        lines.push(
            json!({"id": lines.len(), "model": "polygon_lambert", "p": p, "n": n, "verts": verts}),
        );
        lines.push(json!({"id": lines.len(), "model": "phong_polygon", "p": p, "r": n, "verts": verts, "m": m}));
    }
    let want = run("f64", &lines);
    let got = run("fixed", &lines);
    let mut worst = 0.0f64;
    for ((line, w), g) in lines.iter().zip(&want).zip(&got) {
        assert!(g.get("error").is_none(), "{line} -> {g}");
        let (a, b) = (numbers(g)[0], numbers(w)[0]);
        worst = worst.max((a - b).abs());
        assert!(
            (a - b).abs() <= 1.0 / 1024.0,
            "{line}: fixed {a} vs f64 {b}"
        );
    }
    println!(
        "world units: {} cases, fixed within {worst:.2e} of f64",
        lines.len()
    );
}

#[test]
fn order_is_preserved_and_blank_lines_are_skipped() {
    let mut input = String::new();
    let mut ids = Vec::new();
    for i in 0..200 {
        let line = match i % 4 {
            0 => {
                json!({"id": format!("L{i}"), "model": "hemi_const", "n": [0, i, 1], "axis": [0, 0, 1]})
            }
            1 => {
                json!({"id": format!("L{i}"), "model": "cap_lambert", "n": [0, 0, 1], "axis": [0, 0, 1]})
            }
            2 => json!({"id": format!("L{i}"), "model": "line_lambert"}),
            _ => {
                json!({"id": format!("L{i}"), "model": "sh9_irradiance", "n": [1, 0, i], "coeffs": GRACE})
            }
        };
        input.push_str(&format!("{line}\n"));
        if i % 7 == 0 {
            input.push_str("\n   \r\n");
        }
        ids.push(format!("L{i}"));
    }
    // A last line without a newline still counts.
    input.push_str(r#"{"id":"end","model":"hemi_const","n":[0,0,1],"axis":[0,0,1]}"#);
    ids.push("end".to_owned());
    let (out, code) = run_raw("f32", &input);
    assert_eq!(code, 0);
    assert_eq!(out.len(), ids.len());
    for (line, id) in out.iter().zip(&ids) {
        let v: Value = serde_json::from_str(line).unwrap();
        assert_eq!(v["id"], *id);
    }
}

#[test]
fn closed_stdout_does_not_panic() {
    // Lots of output to a reader that goes away after the first line.
    let line = r#"{"id":"a","model":"hemi_const","n":[0,0,1],"axis":[0,0,1]}"#;
    let input: String = std::iter::repeat_n(format!("{line}\n"), 200_000).collect();
    let mut child = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["eval", "--backend", "f64"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdin = child.stdin.take().unwrap();
    let writer = std::thread::spawn(move || {
        // The child may exit before reading everything: ignore the broken pipe here.
        let _ = stdin.write_all(input.as_bytes());
    });
    let mut stdout = child.stdout.take().unwrap();
    let mut first = [0u8; 16];
    std::io::Read::read_exact(&mut stdout, &mut first).unwrap();
    drop(stdout);
    let out = child.wait_with_output().unwrap();
    writer.join().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.code(), Some(0), "{stderr}");
}

/// June's figure 20-17 shape with `pos`, and one parameter replaced.
fn shape_line(id: u32, pos: Value, key: &str, val: Value) -> Value {
    let mut l = json!({"id": id, "model": "superellipse_shape", "pos": pos,
                       "a": 0.2, "b": 0.3, "A": 0.3, "B": 0.4, "d": 0.8});
    l[key] = val;
    l
}

/// June's listing falloff (zones 0.6..1 and 2..2.8) at `z`, and one parameter replaced.
fn falloff_line(id: u32, z: Value, key: &str, val: Value) -> Value {
    let mut l = json!({"id": id, "model": "distance_falloff", "z": z, "M": 2, "d0": 1, "alpha": 1,
                       "znear": 1, "zfar": 2, "near_edge": 0.4, "far_edge": 0.8});
    l[key] = val;
    l
}

#[test]
fn shaping_models_validate() {
    let on_axis = json!([0, 0, 1]);
    let cases = [
        (
            shape_line(1, on_axis.clone(), "a", json!(0)),
            "a is not > 0",
        ),
        (
            shape_line(2, on_axis.clone(), "d", json!(-1)),
            "d is not > 0",
        ),
        (
            shape_line(3, on_axis.clone(), "a", json!(0.3)),
            "a is not < A",
        ),
        (
            shape_line(4, on_axis.clone(), "b", json!(0.5)),
            "b is not < B",
        ),
        (
            shape_line(5, on_axis.clone(), "A", json!("Infinity")),
            "A is not finite",
        ),
        (
            shape_line(6, json!([0, "NaN", 1]), "d", json!(0.8)),
            "pos is not finite",
        ),
        (
            shape_line(7, on_axis.clone(), "B", json!(-0.4)),
            "B is not > 0",
        ),
        (
            falloff_line(8, json!(1.5), "M", json!(1)),
            "falloff peak M is not > 1",
        ),
        (falloff_line(9, json!(1.5), "d0", json!(0)), "d0 is not > 0"),
        (
            falloff_line(10, json!(1.5), "alpha", json!(-1)),
            "alpha is negative",
        ),
        (
            falloff_line(11, json!(1.5), "near_edge", json!(0)),
            "near_edge is not > 0",
        ),
        (
            falloff_line(12, json!(1.5), "far_edge", json!(-1)),
            "far_edge is not > 0",
        ),
        (
            falloff_line(13, json!(1.5), "znear", json!(2)),
            "znear is not < zfar",
        ),
        (falloff_line(14, json!(-1), "M", json!(2)), "z is negative"),
        // Rounds to -0 in f32: refused on every backend all the same.
        (
            falloff_line(15, json!(-1e-50), "M", json!(2)),
            "z is negative",
        ),
        (
            falloff_line(16, json!("NaN"), "M", json!(2)),
            "z is not finite",
        ),
        (
            falloff_line(17, json!(1.5), "d0", json!("-Infinity")),
            "d0 is not finite",
        ),
    ];
    let input: Vec<Value> = cases.iter().map(|(l, _)| l.clone()).collect();
    for backend in ["f64", "f32", "f32-fast"] {
        let out = run(backend, &input);
        for ((line, want), got) in cases.iter().zip(&out) {
            assert_eq!(got["id"], line["id"]);
            assert!(
                error_of(got).contains(want),
                "{backend}: {got} should say {want:?}"
            );
        }
    }
    let mut missing = shape_line(18, on_axis.clone(), "d", json!(1));
    missing.as_object_mut().unwrap().remove("d");
    assert_eq!(
        error_of(&one("f64", missing)),
        "missing parameter: d (superellipse_shape takes pos, a, b, A, B, d)"
    );

    // Values the spec pins down exactly.
    let open = |id: u32, z: f64| {
        let mut l = falloff_line(id, json!(z), "znear", json!(0));
        l["zfar"] = json!(10);
        l
    };
    let lines = [
        (shape_line(20, on_axis.clone(), "d", json!(0.8)), 1.0), // X = Y = 0
        (shape_line(21, json!([0.1, 0.1, 0]), "d", json!(0.8)), 0.0), // z <= 0
        (shape_line(22, json!([0.1, 0.1, -1]), "d", json!(0.8)), 0.0),
        (shape_line(23, json!([1, 0, 1]), "d", json!(0.8)), 0.0), // outside A
        (shape_line(24, json!([0.1, 0.1, 1]), "d", json!(1)), 1.0), // inside a, b
        (open(25, 1.0), 1.0),                                     // z = d0
        (open(26, 0.0), 2.0),                                     // z = 0: the peak M
        (open(27, 2.0), 0.5),                                     // (d0/z)^alpha
        (falloff_line(28, json!(0.5), "M", json!(2)), 0.0),       // before the cut-on
        (falloff_line(29, json!(3), "M", json!(2)), 0.0),         // after the cut-off
    ];
    let input: Vec<Value> = lines.iter().map(|(l, _)| l.clone()).collect();
    for backend in ["f64", "f32", "f32-fast"] {
        let out = run(backend, &input);
        for ((line, want), got) in lines.iter().zip(&out) {
            let x = got["value"]
                .as_f64()
                .unwrap_or_else(|| panic!("{backend}: {got}"));
            assert!(
                (x - want).abs() <= 1e-6,
                "{backend}: {} gave {x}, want {want}",
                line["id"]
            );
        }
    }
}
