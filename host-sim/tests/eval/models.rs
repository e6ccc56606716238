//! The model ids: every id of the protocol with its parameters (`--list-models`, the docs),
//! unknown and unsupported ids, and the fixed-point backend's list.

use super::*;

/// Every model id of the protocol and its parameters, in the protocol's order (from the
/// protocol's table).
pub(super) const PROTOCOL: &[(&str, &[&str])] = &[
    ("hemi_const", &["n", "axis"]),
    ("hemi_cos", &["n", "axis"]),
    ("sky_overcast", &["n", "zenith", "c"]),
    ("sky_ground", &["n", "up", "sky", "ground"]),
    ("cap_lambert", &["n", "axis", "sigma"]),
    ("cap_lambert_hermite", &["n", "axis", "sigma"]),
    ("sphere_lambert", &["p", "n", "center", "radius"]),
    ("sphere_lambert_hermite", &["p", "n", "center", "radius"]),
    ("polygon_lambert", &["p", "n", "verts"]),
    ("line_lambert", &["p", "n", "a", "b", "k"]),
    ("phong_hemi_const", &["r", "axis", "m"]),
    ("phong_hemi_cos", &["r", "axis", "m"]),
    ("phong_cap", &["r", "axis", "sigma", "m"]),
    ("phong_sphere", &["p", "r", "center", "radius", "m"]),
    ("phong_polygon", &["p", "r", "verts", "m"]),
    ("line_phong_peak", &["p", "r", "a", "b", "m"]),
    ("rect_phong_peak", &["p", "r", "origin", "eu", "ev", "m"]),
    ("axial_moment", &["p", "verts", "w", "m"]),
    ("double_axis_moment", &["p", "verts", "w", "v", "m"]),
    ("directional_luminaire", &["p", "n", "verts", "axis", "m"]),
    ("glossy_reflection", &["p", "n", "e", "verts", "m"]),
    ("glossy_transmission", &["p", "n", "e", "verts", "m"]),
    ("lune_normalization", &["w", "v", "m"]),
    ("sh9_irradiance", &["n", "coeffs"]),
    ("sh9_disc_irradiance", &["n", "axis", "alpha"]),
    ("superellipse_shape", &["pos", "a", "b", "A", "B", "d"]),
    (
        "distance_falloff",
        &[
            "z",
            "M",
            "d0",
            "alpha",
            "znear",
            "zfar",
            "near_edge",
            "far_edge",
        ],
    ),
];

pub(super) fn list_models() -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["eval", "--list-models"])
        .stdin(Stdio::null())
        .output()
        .unwrap();
    assert!(out.status.success());
    assert!(out.stderr.is_empty());
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn list_models_covers_every_protocol_id_with_its_parameters() {
    let text = list_models();
    let rows: Vec<&str> = text
        .lines()
        .filter(|l| l.contains(": "))
        .filter(|l| {
            PROTOCOL
                .iter()
                .any(|(id, _)| l.starts_with(&format!("{id} ")))
        })
        .collect();
    assert_eq!(rows.len(), PROTOCOL.len(), "{text}");
    for (id, params) in PROTOCOL {
        let row = rows
            .iter()
            .find(|l| l.split_whitespace().next() == Some(id))
            .unwrap_or_else(|| panic!("{id} missing from --list-models:\n{text}"));
        // The parameters, in order, as `name: type`.
        const TYPES: &[&str] = &[
            "point",
            "direction",
            "vector",
            "rgb",
            "polygon",
            "sh9",
            "number",
            "integer",
        ];
        let names: Vec<&str> = row
            .split(", ")
            .filter_map(|chunk| {
                let (name, ty) = chunk.split_once(": ")?;
                let ty = ty.split([' ', ',']).next()?;
                TYPES
                    .contains(&ty)
                    .then(|| name.rsplit(' ').next().unwrap())
            })
            .collect();
        assert_eq!(&names, params, "{row}");
        let rgb = matches!(*id, "sky_ground" | "sh9_irradiance");
        assert_eq!(
            row.split_whitespace().nth(1),
            Some(if rgb { "rgb" } else { "value" })
        );
        let fixed = FIXED_MODELS.contains(id);
        assert_eq!(
            row.split_whitespace().nth(2),
            Some(if fixed { "yes" } else { "no" })
        );
    }
    // Every line the valid cases use answers: the table and the dispatch agree.
    let ids: Vec<String> = valid_cases()
        .iter()
        .map(|c| c["model"].as_str().unwrap().to_owned())
        .collect();
    for (id, _) in PROTOCOL {
        assert!(ids.iter().any(|i| i == id), "{id} has no valid case");
    }
}

#[test]
fn the_docs_cover_every_model() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/");
    for doc in ["models.md", "eval-protocol.md"] {
        let text = std::fs::read_to_string(format!("{root}{doc}")).unwrap();
        for (id, params) in PROTOCOL {
            assert!(
                text.contains(&format!("`{id}`")),
                "{doc} does not name {id}"
            );
            if doc == "models.md" {
                for p in *params {
                    assert!(text.contains(&format!("`{p}`")), "{doc}: {id}'s {p}");
                }
            }
        }
        assert!(
            !text.contains("shared/spec"),
            "{doc} points outside the repository"
        );
    }
}

#[test]
fn unknown_models_suggest_the_nearest_id() {
    for backend in ["f64", "fixed"] {
        let out = one(
            backend,
            json!({"id": "u", "model": "cap_lambrt", "n": [0, 0, 1]}),
        );
        assert_eq!(
            error_of(&out),
            "unknown model: cap_lambrt (did you mean cap_lambert?); `host-sim eval --list-models` lists them"
        );
    }
    let out = one("f64", json!({"id": "u", "model": "sphere_lambert_hermit"}));
    assert!(
        error_of(&out).contains("did you mean sphere_lambert_hermite?"),
        "{out}"
    );
}

#[test]
fn help_has_no_rustdoc_syntax() {
    for args in [&["eval", "--help"][..], &["--help"], &["render", "--help"]] {
        let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
            .args(args)
            .output()
            .unwrap();
        assert!(out.status.success());
        let text = String::from_utf8(out.stdout).unwrap();
        assert!(!text.contains("[`"), "{args:?}: {text}");
        assert!(!text.contains("shared/spec"), "{args:?}: {text}");
    }
}

pub(super) const NOT_YET: [&str; 0] = [];

#[test]
fn unsupported_and_unknown_models() {
    let mut lines: Vec<Value> = NOT_YET
        .iter()
        .map(|m| json!({"id": m, "model": m}))
        .collect();
    lines.push(json!({"id": "u", "model": "no_such_model", "n": [0, 0, 1]}));
    for backend in ["f64", "f32", "f32-fast"] {
        let out = run(backend, &lines);
        for (m, got) in NOT_YET.iter().zip(&out) {
            assert_eq!(got["id"], *m);
            assert_eq!(
                error_of(got),
                format!("unsupported: {m} is not implemented yet")
            );
        }
        let last = out.last().unwrap();
        assert_eq!(last["id"], "u");
        assert!(error_of(last).contains("no_such_model"), "{last}");
        assert!(!error_of(last).starts_with("unsupported"), "{last}");
    }
}

/// The fixed-point backend's models (issue 3's scope and the shaping factors) and, from
/// issue 13, those it answers beyond the library's list (host-sim's `FIXED_SUPPORTED_MORE`:
/// within 1/1024 in tests/fixed_line.rs and tests/fixed_moments.rs).
pub(super) const FIXED_MODELS: &[&str] = &[
    "hemi_const",
    "hemi_cos",
    "sky_overcast",
    "sky_ground",
    "cap_lambert",
    "cap_lambert_hermite",
    "sphere_lambert",
    "sphere_lambert_hermite",
    "polygon_lambert",
    "phong_hemi_const",
    "phong_hemi_cos",
    "phong_cap",
    "phong_sphere",
    "phong_polygon",
    "sh9_irradiance",
    "sh9_disc_irradiance",
    "superellipse_shape",
    "distance_falloff",
    "rect_phong_peak",
    "axial_moment",
    "double_axis_moment",
    "lune_normalization",
];

/// The library's list is the first 18 of [`FIXED_MODELS`].
#[test]
fn fixed_models_extend_the_library_list() {
    assert_eq!(
        &FIXED_MODELS[..18],
        &arealight::real::fixed22::SUPPORTED_MODELS[..]
    );
}
