use super::*;

fn row(model: &str, ns: f64, err: f64) -> Row {
    Row {
        model: model.into(),
        backend: "f32".into(),
        host_ns: ns,
        m4f: None,
        m0: None,
        rv32: None,
        code: None,
        max_err: err,
        rms_err: err,
        kind: Kind::F32,
    }
}

#[test]
fn targets_are_the_readmes() {
    assert_eq!(target("cap_lambert", "f32"), Some(2e-6));
    assert_eq!(target("phong_cap", "f32"), Some(2e-6 + 16.0 / 16_777_216.0));
    assert_eq!(
        target("axial_moment", "f32"),
        Some(2e-6 + 4.0 / 16_777_216.0)
    );
    assert_eq!(target("cap_lambert", "f32-fast"), Some(1.0 / 1024.0));
    assert_eq!(target("polygon_lambert", "fixed"), Some(1.0 / 1024.0));
    assert_eq!(target("point_lambert", "f32"), None);
    let mut r = row("cap_lambert", 1.0, 2.5e-6);
    assert_eq!(missed_targets(std::slice::from_ref(&r)).len(), 1);
    r.max_err = 1.9e-6;
    assert!(missed_targets(std::slice::from_ref(&r)).is_empty());
    r.max_err = f64::NAN;
    assert_eq!(missed_targets(&[r]).len(), 1);
}

#[test]
fn pareto_keeps_only_undominated_rows_sorted_by_time() {
    let rows = [
        row("a", 10.0, 1e-3),
        row("b", 20.0, 1e-6),
        row("c", 30.0, 1e-3), // dominated by a
        row("d", 5.0, 1e-2),
        row("e", 20.0, 1e-5), // dominated by b
    ];
    assert_eq!(pareto(&rows), vec![3, 0, 1]);
}

#[test]
fn random_dirs_are_unit_and_deterministic() {
    let a = random_dirs(100, 7);
    assert_eq!(a, random_dirs(100, 7));
    for d in &a {
        let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        assert!((l - 1.0).abs() < 1e-12, "{l}");
    }
    // Spread over the sphere: the mean is near 0.
    let mean: f64 = a.iter().map(|d| d[2]).sum::<f64>() / 100.0;
    assert!(mean.abs() < 0.2, "{mean}");
}

#[test]
fn counts_csv_is_read_by_column_name() {
    let dir = std::env::temp_dir().join(format!("budget-counts-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("counts.csv");
    std::fs::write(
        &p,
        "target,backend,model,insns_min,insns_median,insns_max,code_bytes,max_err,x\n\
         m4f,f32,cap_lambert,147,153,383,1328,1.7e-8,16\n\
         rv32imc,fixed,cap_lambert,522,575,1602,6000,2.0e-4,16\n",
    )
    .unwrap();
    let c = read_counts(&p);
    assert_eq!(
        c.get(&("m4f".into(), "f32".into(), "cap_lambert".into())),
        Some(&(Some(153), Some(1328)))
    );
    // The RISC-V median goes to its own column; code bytes stay the ARM images'.
    let mut rows = vec![row("cap_lambert", 1.0, 0.0)];
    rows[0].backend = "fixed".into();
    rows[0].kind = Kind::Fixed;
    fill_counts(&mut rows, &c);
    assert_eq!(
        (rows[0].rv32, rows[0].m0, rows[0].code),
        (Some(575), None, None)
    );
    assert!(csv(&rows).lines().nth(1).unwrap().ends_with(",575"));
    assert!(read_counts(&dir.join("missing.csv")).is_empty());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn world_table_pairs_each_call_with_its_world_row() {
    let mut c = Counts::new();
    let mut put = |t: &str, b: &str, m: &str, n: u64| {
        c.insert((t.into(), b.into(), m.into()), (Some(n), None));
    };
    put("m4f", "f32", "polygon_lambert", 700);
    put("m4f", "f32", "polygon_lambert/world", 900);
    put("m0", "fixed", "sphere_lambert/world", 1400);
    let t = world_markdown(&c);
    assert_eq!(t.lines().count(), 2 + world_cases::WORLD_CASES.len());
    assert!(
        t.contains("| `polygon_lambert` | 700 | 900 |  |  |  |  |"),
        "{t}"
    );
    assert!(
        t.contains("| `sphere_lambert` |  |  |  | 1400 |  |  |"),
        "{t}"
    );
}

#[test]
fn unit_table_pairs_each_call_with_its_unit_row() {
    let mut c = Counts::new();
    let mut put = |t: &str, b: &str, m: &str, n: u64| {
        c.insert((t.into(), b.into(), m.into()), (Some(n), None));
    };
    put("m4f", "f32", "hemi_const", 52);
    put("m4f", "f32", "hemi_const/unit", 20);
    put("m0", "fixed", "hemi_const", 622);
    put("m0", "fixed", "hemi_const/unit", 170);
    put("rv32imc", "fixed", "polygon_lambert/unit", 5600);
    let t = unit_markdown(&c);
    assert_eq!(t.lines().count(), 2 + cases::UNIT_CASES.len());
    assert!(
        t.contains("| `hemi_const` | 52 | 20 | 622 | 170 |  |  |"),
        "{t}"
    );
    assert!(
        t.contains("| `polygon_lambert` |  |  |  |  |  | 5600 |"),
        "{t}"
    );
}

#[test]
fn the_budget_has_every_model_and_alternative_with_errors_in_range() {
    let args = BudgetArgs {
        out: std::env::temp_dir(),
        counts: "/nonexistent/counts.csv".into(),
        samples: 256,
        reps: 1,
        scene: None,
        chip: None,
        fps: None,
        max_error: None,
        check: None,
        emit_spec: None,
        calibrate: false,
    };
    let rows = budget(&args).unwrap();
    for m in MODELS {
        for b in ["f32", "f32-fast"] {
            let r = rows
                .iter()
                .find(|r| r.model == m && r.backend == b)
                .unwrap_or_else(|| panic!("{m} {b} missing"));
            // Within the README's targets: f32 2e-6 + m 2^-24, f32-fast 1/1024.
            let tol = target(m, b).unwrap();
            assert!(r.max_err <= tol, "{m} {b}: {} > {tol:e}", r.max_err);
            assert!(r.rms_err <= r.max_err);
        }
        // Fixed point: the models of its table, within 1/1024; no row for the others.
        let fixed = rows.iter().find(|r| r.model == m && r.backend == "fixed");
        match fixed {
            Some(r) => assert!(
                r.max_err <= target(m, "fixed").unwrap(),
                "{m} fixed: {}",
                r.max_err
            ),
            None => assert!(!cases::FIXED_MODELS.contains(&m), "{m} fixed missing"),
        }
    }
    // The alternatives: k = 1 of the cap is far off, k = 64 much closer.
    let cap = |b: &str| {
        rows.iter()
            .find(|r| r.model == "cap_lambert" && r.backend == b)
            .map(|r| r.max_err)
            .unwrap()
    };
    assert!(
        cap("f32-pts1") > 10.0 * cap("f32-pts64"),
        "{} {}",
        cap("f32-pts1"),
        cap("f32-pts64")
    );
    assert!(cap("f32-pts64") < 1e-2);
    assert!(
        missed_targets(&rows).is_empty(),
        "{:?}",
        missed_targets(&rows)
    );
    let text = csv(&rows);
    assert!(text.starts_with(HEADER));
    assert_eq!(text.lines().count(), rows.len() + 1);
    // No counts file: those columns are empty.
    assert!(text.lines().nth(1).unwrap().contains(",,,,"));
}
