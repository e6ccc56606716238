//! Tests of scene files: errors at their keys, the examples build.
use super::*;

const EXAMPLE: &str = include_str!("../../scenes/example.toml");

/// The camera lines 1 to 5 of every test file.
const CAMERA: &str = "[camera]\neye = [0, 1, 5]\ntarget = [0, 0, 0]\nwidth = 10\nheight = 10\n";

fn err(src: &str) -> String {
    parse("bad.toml", src).err().unwrap_or_default()
}

#[test]
fn the_example_scene_builds() {
    let s = parse("example.toml", EXAMPLE).unwrap();
    assert!(s.warnings.is_empty());
    let s = s.scene;
    assert_eq!(s.objects.len(), 4);
    assert_eq!(s.lights.0.len(), 2);
    assert_eq!((s.camera.width(), s.camera.height()), (320, 240));
}

#[test]
fn the_documented_example_builds() {
    let doc = include_str!("../../../docs/scene-format.md");
    let start = doc.find("```toml\n").expect("a toml block") + 8;
    let end = start + doc[start..].find("```").unwrap();
    let s = parse("scene-format.md", &doc[start..end]).unwrap();
    assert!(s.warnings.is_empty());
    assert!(!s.scene.objects.is_empty());
}

#[test]
fn errors_name_line_and_column() {
    // A syntax error: the missing value on line 3.
    let e = err("[camera]\neye = [0, 1, 5]\ntarget = \n");
    assert!(e.starts_with("bad.toml:3:"), "{e}");
    // An unknown key, with a suggestion.
    let e = err(&format!("{CAMERA}fov = 2\n"));
    assert!(
        e.starts_with("bad.toml:6:1:") && e.contains("did you mean `fov_deg`?"),
        "{e}"
    );
    // A library refusal at its key: radius 0 on line 10.
    let e = err(&format!(
        "{CAMERA}\n[[light]]\nkind = \"sphere\"\ncenter = [0, 3, 0]\nradius = -1.0\n"
    ));
    assert_eq!(e, "bad.toml:10:1: `radius` = -1 is out of range: > 0");
    // A mesh naming a missing material: at the name, with a suggestion.
    let e = err(&format!(
        "{CAMERA}\n[[material]]\nname = \"gold\"\ndiffuse = [1, 1, 0]\n\n[[mesh]]\nkind = \"box\"\nhalf = [1, 1, 1]\nmaterial = \"glod\"\n"
    ));
    assert!(
        e.starts_with("bad.toml:14:1:") && e.contains("did you mean \"gold\"?"),
        "{e}"
    );
}

#[test]
fn camera_errors_are_at_their_keys_with_the_range() {
    let e = err("[camera]\neye = [0, 1, 5]\ntarget = [0, 0, 0]\nwidth = 0\nheight = 10\n");
    assert_eq!(
        e,
        "bad.toml:4:1: `width` = 0 is out of range: 1 to 4096 pixels"
    );
    let e = err("[camera]\neye = [0, 1, 5]\ntarget = [0, 0, 0]\nwidth = 65535\nheight = 65535\n");
    assert_eq!(
        e,
        "bad.toml:4:1: `width` = 65535 is out of range: 1 to 4096 pixels"
    );
    let e = err(&format!("{CAMERA}fov_deg = 180\n"));
    assert_eq!(
        e,
        "bad.toml:6:1: `fov_deg` = 180 is out of range: more than 0 and less than 180 degrees"
    );
    let e = err(&format!("{CAMERA}up = [0, 2, 10]\n"));
    assert!(e.starts_with("bad.toml:6:1: `up` is parallel"), "{e}");
    let e = err(&format!("{CAMERA}background = [0, 300, 0]\n"));
    assert!(e.starts_with("bad.toml:6:1: `background`"), "{e}");
}

#[test]
fn light_and_mesh_errors_are_at_their_keys() {
    let light = |body: &str| err(&format!("{CAMERA}\n[[light]]\n{body}"));
    let e = light("kind = \"sphre\"\n");
    assert!(
        e.starts_with("bad.toml:8:1: unknown light kind \"sphre\" (did you mean sphere?)"),
        "{e}"
    );
    let e = light("kind = \"cap\"\naxis = [0, 1, 0]\nsigma_deg = 95\n");
    assert_eq!(
        e,
        "bad.toml:10:1: `sigma_deg` = 95 is out of range: 0 to 90 degrees"
    );
    let e = light("kind = \"directional\"\ndirection = [0, 0, 0]\n");
    assert!(
        e.starts_with("bad.toml:9:1: `direction` has zero length"),
        "{e}"
    );
    let e = light("kind = \"polygon\"\nvertices = [[0, 1, 0], [1, 1, 0], [2, 1, 0]]\n");
    assert!(
        e.starts_with("bad.toml:9:1: `vertices`: polygon has zero area"),
        "{e}"
    );
    let e = light("kind = \"polygon\"\nradius = 2\nvertices = [[0, 1, 0], [1, 1, 0], [1, 1, 1]]\n");
    assert!(
        e.starts_with("bad.toml:9:1: `radius` is not a key of a polygon light"),
        "{e}"
    );
    let mesh = |body: &str| {
        err(&format!(
            "{CAMERA}\n[[material]]\nname = \"m\"\ndiffuse = [1, 1, 1]\n\n[[mesh]]\nmaterial = \"m\"\n{body}"
        ))
    };
    let e = mesh("kind = \"torus\"\nmajor = 1\nminor = 2\n");
    assert_eq!(
        e,
        "bad.toml:15:1: `minor` = 2 is out of range: > 0 and < `major` (1)"
    );
    let e = mesh("kind = \"sphere\"\nradius = 1\nstacks = 1\n");
    assert_eq!(e, "bad.toml:15:1: `stacks` = 1 is out of range: 2 to 4096");
    let e = mesh("kind = \"sphere\"\nradius = 1\nstacks = 400\nslices = 400\n");
    assert!(
        e.starts_with("bad.toml:15:1: `stacks` and `slices` give 160801 vertices"),
        "{e}"
    );
}

#[test]
fn exponents_state_the_limit_and_warn_when_slow() {
    let mat = |m: &str| {
        parse(
            "x.toml",
            &format!("{CAMERA}\n[[material]]\nname = \"m\"\ndiffuse = [1, 1, 1]\nexponent = {m}\n"),
        )
    };
    let e = mat("2000000").err().unwrap();
    assert!(
        e.starts_with("x.toml:10:1: `exponent` = 2000000 is out of range: 0 to 1048576"),
        "{e}"
    );
    let w = mat("100000").ok().unwrap().warnings;
    assert_eq!(w.len(), 1);
    assert!(
        w[0].starts_with("x.toml:10:1: warning: `exponent` = 100000"),
        "{w:?}"
    );
    assert!(mat("1000").ok().unwrap().warnings.is_empty());
}

#[test]
fn line_col_counts_from_one() {
    assert_eq!(line_col("ab\ncd", 0), (1, 1));
    assert_eq!(line_col("ab\ncd", 4), (2, 2));
    let src = "[camera]\n  width =   0\n";
    assert_eq!(key_start(src, src.find('0').unwrap()), 11);
}
