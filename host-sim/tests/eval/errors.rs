//! Invalid input lines: non-finite numbers, missing, malformed and unknown parameters, broken
//! JSON, numbers beyond f32; each answered with a precise error, the run going on.

use super::*;

#[test]
fn non_finite_strings_are_refused() {
    let base = valid_cases();
    let mut lines = Vec::new();
    // One non-finite number in each kind of parameter.
    let mut l = base[0].clone();
    l["n"] = json!(["NaN", 0, 1]);
    lines.push((l, "n is not finite"));
    let mut l = base[4].clone();
    l["sigma"] = json!("Infinity");
    lines.push((l, "sigma is not finite"));
    let mut l = base[6].clone();
    l["radius"] = json!("-Infinity");
    lines.push((l, "radius is not finite"));
    let mut l = base[8].clone();
    l["verts"][2][1] = json!("NaN");
    lines.push((l, "verts is not finite"));
    let mut l = base[13].clone();
    l["p"] = json!([0, "Infinity", 0]);
    lines.push((l, "p is not finite"));
    let mut l = base[12].clone();
    l["m"] = json!("Infinity");
    lines.push((l, "m is not finite"));
    let mut l = base[14].clone();
    l["coeffs"][3][0] = json!("-Infinity");
    lines.push((l, "coeffs is not finite"));
    let mut l = base[3].clone();
    l["ground"] = json!([0, "NaN", 0]);
    lines.push((l, "ground is not finite"));
    let mut l = base[2].clone();
    l["c"] = json!("NaN");
    lines.push((l, "c is not finite"));
    let mut l = base[15].clone();
    l["alpha"] = json!("NaN");
    lines.push((l, "alpha is not finite"));
    let mut l = base[9].clone();
    l["r"] = json!([0, 0, "Infinity"]);
    lines.push((l, "r is not finite"));
    let input: Vec<Value> = lines.iter().map(|(l, _)| l.clone()).collect();
    for backend in ["f64", "f32", "f32-fast"] {
        let out = run(backend, &input);
        for ((line, want), got) in lines.iter().zip(&out) {
            assert_eq!(got["id"], line["id"]);
            assert!(
                error_of(got).contains(want),
                "{backend}: {got} should say {want:?}"
            );
        }
    }
}

#[test]
fn invalid_inputs_get_precise_errors() {
    let cases = [
        (
            json!({"id": 1, "model": "hemi_cos", "n": [0, 0, 0], "axis": [0, 0, 1]}),
            "n has zero length",
        ),
        (
            json!({"id": 2, "model": "hemi_cos", "n": [0, 0, 1], "axis": [0, 0, 0]}),
            "axis has zero length",
        ),
        (
            json!({"id": 3, "model": "phong_cap", "r": [0, 0, 0], "axis": [0, 0, 1], "sigma": 0.3, "m": 3}),
            "r has zero length",
        ),
        (
            json!({"id": 4, "model": "cap_lambert", "n": [0, 0, 1], "axis": [0, 0, 1], "sigma": 2.0}),
            "sigma is outside [0, pi/2]",
        ),
        // Just above pi/2 in f64 (it rounds to pi/2 in f32): refused by every backend.
        (
            json!({"id": 5, "model": "cap_lambert", "n": [0, 0, 1], "axis": [0, 0, 1], "sigma": 1.5707963267948968}),
            "sigma is outside [0, pi/2]",
        ),
        (
            json!({"id": 6, "model": "sh9_disc_irradiance", "n": [0, 0, 1], "axis": [0, 0, 1], "alpha": 3.2}),
            "alpha is outside [0, pi]",
        ),
        (
            json!({"id": 7, "model": "phong_hemi_const", "r": [0, 0, 1], "axis": [0, 0, 1], "m": 2.5}),
            "m must be a non-negative integer",
        ),
        (
            json!({"id": 8, "model": "phong_hemi_const", "r": [0, 0, 1], "axis": [0, 0, 1], "m": -1}),
            "m must be a non-negative integer",
        ),
        (
            json!({"id": 9, "model": "sphere_lambert", "p": [0, 0, 2.5], "n": [0, 0, 1],
                   "center": [0, 0, 3], "radius": 1}),
            "inside or on the sphere",
        ),
        (
            json!({"id": 10, "model": "sphere_lambert", "p": [0, 0, 0], "n": [0, 0, 1],
                   "center": [0, 0, 3], "radius": 0}),
            "radius is not > 0",
        ),
        (
            json!({"id": 11, "model": "polygon_lambert", "p": [0, 0, 0], "n": [0, 0, 1],
                   "verts": [[0, 0, 1], [1, 0, 1]]}),
            "fewer than 3 vertices",
        ),
        (
            json!({"id": 12, "model": "polygon_lambert", "p": [0, 0, 0], "n": [0, 0, 1],
                   "verts": [[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 2]]}),
            "not planar",
        ),
        (
            json!({"id": 13, "model": "polygon_lambert", "p": [0, 0, 0], "n": [0, 0, 1],
                   "verts": [[0, 0, 1], [2, 1, 1], [2, 0, 1], [0, 2, 1]]}),
            "not simple",
        ),
        (
            json!({"id": 14, "model": "phong_sphere", "p": [0, 0, 0], "r": [0, 0, 1],
                   "center": [0, 0, 3], "radius": 1, "m": 2_000_000}),
            "too large",
        ),
        (
            json!({"id": 15, "model": "hemi_cos", "n": [0, 1], "axis": [0, 0, 1]}),
            "n: expected an array of 3 numbers",
        ),
        (
            json!({"id": 16, "model": "hemi_cos", "n": [0, "x", 1], "axis": [0, 0, 1]}),
            "n: expected a number",
        ),
    ];
    // A regular 65-gon: more vertices than the protocol's capacity.
    let ring: Vec<Value> = (0..65)
        .map(|i| {
            let t = i as f64 * std::f64::consts::TAU / 65.0;
            json!([t.cos(), t.sin(), 2.0])
        })
        .collect();
    let mut cases = cases.to_vec();
    cases.push((
        json!({"id": 17, "model": "polygon_lambert", "p": [0, 0, 0], "n": [0, 0, 1], "verts": ring}),
        "more than 64 vertices",
    ));
    // Arvo's moments: one invalid input each.
    cases.extend([
        (
            json!({"id": 101, "model": "axial_moment", "p": [0, 0, 0], "verts": square(),
                   "w": [0, 0, 0], "m": 3}),
            "w has zero length",
        ),
        (
            json!({"id": 102, "model": "double_axis_moment", "p": [0, 0, 0], "verts": square(),
                   "w": [0, 0, 1], "v": [0, 0, 1], "m": 2_000_000}),
            "m is too large",
        ),
        (
            json!({"id": 103, "model": "directional_luminaire", "p": [0, 0, 0], "n": [0, 0, 1],
                   "verts": [[0, 0, 1], [1, 0, 1]], "axis": [0, 0, -1], "m": 1}),
            "fewer than 3 vertices",
        ),
        (
            json!({"id": 104, "model": "glossy_reflection", "p": [0, 0, 0], "n": [0, 0, 1],
                   "e": [0, 0, 0], "verts": square(), "m": 8}),
            "e has zero length",
        ),
        (
            json!({"id": 105, "model": "glossy_transmission", "p": [0, 0, 0], "n": [0, 0, 0],
                   "e": [0, 0, 1], "verts": square(), "m": 8}),
            "n has zero length",
        ),
        (
            json!({"id": 106, "model": "lune_normalization", "w": [0, 0, 1], "v": [0, 0, 0], "m": 5}),
            "v has zero length",
        ),
    ]);
    // Line and parallelogram lights: one invalid input each (and an invalid decay).
    cases.extend([
        (
            json!({"id": 201, "model": "line_lambert", "p": [0.25, 0, 2], "n": [0, 0, 1],
                   "a": [-1, 0, 2], "b": [1, 0, 2], "k": 2}),
            "shading point is on the segment",
        ),
        (
            json!({"id": 202, "model": "line_lambert", "p": [0, 0, 0], "n": [0, 0, 1],
                   "a": [-1, 0, 2], "b": [1, 0, 2], "k": 4}),
            "decay k is outside {0, 1, 2, 3}",
        ),
        (
            json!({"id": 203, "model": "line_phong_peak", "p": [0, 0, 0], "r": [0, 0, 1],
                   "a": [1, 0, 2], "b": [1, 0, 2], "m": 8}),
            "segment has zero length",
        ),
        (
            json!({"id": 204, "model": "rect_phong_peak", "p": [0, 0, 0], "r": [0, 0, 1],
                   "origin": [-1, -1, 2], "eu": [2, 0, 0], "ev": [-3, 0, 0], "m": 8}),
            "zero area",
        ),
    ]);
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
    // m = 3.0 is an integer, and 0 is allowed.
    for m in [json!(3.0), json!(0)] {
        let out = one(
            "f64",
            json!({"id": "m", "model": "phong_hemi_const", "r": [0, 0.2, 1], "axis": [0, 0, 1], "m": m}),
        );
        assert!(out["value"].as_f64().unwrap() > 0.0, "{out}");
    }
}

#[test]
fn bad_json_gets_null_id_and_the_run_goes_on() {
    let input = "not json\n{\"id\": \"x\", \"model\": \n[1, 2]\n{\"model\": \"hemi_const\", \"n\": [0,0,1], \"axis\": [0,0,1]}\n{\"id\":\"ok\",\"model\":\"hemi_const\",\"n\":[0,0,1],\"axis\":[0,0,1]}\n";
    let (out, code) = run_raw("f64", input);
    assert_eq!(code, 0);
    assert_eq!(out.len(), 5);
    for (k, l) in out[..4].iter().enumerate() {
        let v: Value = serde_json::from_str(l).unwrap();
        // The truncated line 2 still shows its id.
        let id = if k == 1 { json!("x") } else { Value::Null };
        assert_eq!(v["id"], id, "{l}");
        assert!(
            error_of(&v).starts_with(&format!("input line {}: ", k + 1)),
            "{l}"
        );
    }
    let v: Value = serde_json::from_str(&out[4]).unwrap();
    assert_eq!(v, json!({"id": "ok", "value": 1.0}));
}

#[test]
fn a_truncated_line_gives_its_line_number_and_id() {
    // Blank lines count: the truncated line is line 4 of the input.
    let input = "{\"id\":\"a\",\"model\":\"hemi_const\",\"n\":[0,0,1],\"axis\":[0,0,1]}\n\n   \n{\"id\":\"c\",\"model\":\"cap_lambert\",\"n\":[0,0,1]\n";
    let (out, code, stderr) = run_full("f64", input);
    assert_eq!(code, 0);
    assert_eq!(out.len(), 2);
    let v: Value = serde_json::from_str(&out[1]).unwrap();
    assert_eq!(
        v,
        json!({"id": "c", "error": "input line 4: invalid JSON: EOF while parsing an object at column 43"})
    );
    assert_eq!(
        stderr,
        "host-sim eval: 1 of 2 lines answered with an error (the first is input line 4); exit status 0\n"
    );
}

#[test]
fn failing_lines_keep_exit_status_0_and_print_one_summary_line() {
    // The protocol: "the run goes on with the next line and exits 0".
    let input = "{\"id\":1,\"model\":\"hemi_const\",\"n\":[0,0,1],\"axis\":[0,0,1]}\n\
                 {\"id\":2,\"model\":\"hemi_const\",\"n\":[0,0,0],\"axis\":[0,0,1]}\n\
                 {\"id\":3,\"model\":\"nope\"}\n\
                 {\"id\":4,\"model\":\"hemi_cos\",\"n\":[0,0,1],\"axis\":[0,0,1]}\n";
    let (out, code, stderr) = run_full("f32", input);
    assert_eq!(code, 0);
    assert_eq!(out.len(), 4);
    assert!(out[3].contains("\"value\""), "{}", out[3]);
    assert_eq!(
        stderr,
        "host-sim eval: 2 of 4 lines answered with an error (the first is input line 2); exit status 0\n"
    );
    // No error line: nothing on stderr.
    let (_, code, stderr) = run_full("f32", input.lines().next().unwrap());
    assert_eq!((code, stderr.as_str()), (0, ""));
}

#[test]
fn missing_parameter_echoes_the_id() {
    let out = run(
        "f64",
        &[
            json!({"id": "no-sigma", "model": "cap_lambert", "n": [0, 0, 1], "axis": [0, 0, 1]}),
            json!({"id": "no-model", "n": [0, 0, 1]}),
            json!({"id": 42, "model": "phong_polygon", "p": [0, 0, 0], "r": [0, 0, 1], "verts": square()}),
            json!({"id": 43, "model": "phong_polygon", "p": [0, 0, 0]}),
        ],
    );
    assert_eq!(out[0]["id"], "no-sigma");
    assert_eq!(
        error_of(&out[0]),
        "missing parameter: sigma (cap_lambert takes n, axis, sigma)"
    );
    assert_eq!(out[1]["id"], "no-model");
    assert_eq!(error_of(&out[1]), "missing parameter: model");
    assert_eq!(out[2]["id"], 42);
    assert_eq!(
        error_of(&out[2]),
        "missing parameter: m (phong_polygon takes p, r, verts, m)"
    );
    // All the missing ones at once.
    assert_eq!(
        error_of(&out[3]),
        "missing parameters: r, verts, m (phong_polygon takes p, r, verts, m)"
    );
}

#[test]
fn unknown_keys_are_answered_and_reported_on_stderr() {
    // The protocol does not forbid other keys: the value is answered as without them, and
    // standard error names them (with a suggestion); a misspelt parameter is missing, and
    // the error says what the unknown key may have meant.
    let lines = [
        json!({"id": 1, "model": "cap_lambert", "n": [0, 0, 1], "axis": [0, 0, 1], "sigma": 0.3, "sigmaa": 1}),
        json!({"id": 2, "model": "hemi_cos", "n": [0, 0, 1], "axis": [0, 0, 1], "comment": "x"}),
        json!({"id": 3, "model": "cap_lambert", "n": [0, 0, 1], "axis": [0, 0, 1], "sigmaa": 0.3}),
    ];
    let input: String = lines.iter().map(|l| format!("{l}\n")).collect();
    let (out, code, stderr) = run_full("f64", &input);
    assert_eq!(code, 0);
    let clean = run(
        "f64",
        &[
            json!({"id": 1, "model": "cap_lambert", "n": [0, 0, 1], "axis": [0, 0, 1], "sigma": 0.3}),
        ],
    );
    let first: serde_json::Value = serde_json::from_str(&out[0]).unwrap();
    assert_eq!(first["value"], clean[0]["value"]);
    let second: serde_json::Value = serde_json::from_str(&out[1]).unwrap();
    assert!(second["value"].is_number(), "{second}");
    let third: serde_json::Value = serde_json::from_str(&out[2]).unwrap();
    assert_eq!(
        third["error"],
        "missing parameter: sigma (cap_lambert takes n, axis, sigma); unknown: sigmaa (did you mean sigma?)"
    );
    let warnings: Vec<&str> = stderr.lines().filter(|l| l.contains("ignored")).collect();
    assert_eq!(
        warnings,
        [
            "host-sim eval: input line 1: unknown parameter for cap_lambert, ignored: sigmaa (did you mean sigma?); cap_lambert takes n, axis, sigma",
            "host-sim eval: input line 2: unknown parameter for hemi_cos, ignored: comment; hemi_cos takes n, axis",
        ]
    );
}

#[test]
fn finite_numbers_beyond_f32_do_not_fit_f32() {
    let line = json!({"id": "big", "model": "hemi_const", "n": [1e308, 0, 1], "axis": [0, 0, 1]});
    for backend in ["f32", "f32-fast"] {
        assert_eq!(
            error_of(&one(backend, line.clone())),
            "n: 1e308 does not fit f32 (largest finite f32: 3.4028235e38)"
        );
    }
    // f64 holds it (the normal, normalized, is +x: (1 + n.axis)/2 = 1/2).
    assert_eq!(one("f64", line)["value"], json!(0.5));
    // A non-finite input is still "not finite".
    let nan = json!({"id": "nan", "model": "hemi_cos", "n": ["NaN", 0, 1], "axis": [0, 0, 1]});
    assert!(error_of(&one("f32", nan)).contains("n is not finite"));
}
