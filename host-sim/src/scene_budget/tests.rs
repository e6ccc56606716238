//! The scene budget's unit tests: costs by hand, the options, the Pareto front, the demo's
//! counts against the board's own frame.
use super::costs::{call_cost, calls_cost, predict, Costs, Finish, LightCost, CHIPS};
use super::work::{LightCalls, ObjectWork, Work};
use super::*;

use super::demo_scene;

const DEMO: &str = include_str!("../../scenes/demo.toml");

/// A cost table in the committed file's format: every item one chip needs.
fn synthetic() -> Costs {
    let mut csv = String::from("chip,backend,item,cost,source\n");
    for (item, c) in [
        ("lit_matte", 10.0),
        ("lit_specular", 20.0),
        ("diffuse:polygon", 1000.0),
        ("phong8:polygon", 2000.0),
        ("phong32:polygon", 4400.0),
        ("diffuse:ambient", 1.0),
        ("phong8:ambient", 0.0),
        ("phong32:ambient", 0.0),
        ("vertex_lit", 300.0),
        ("vertex_unlit", 200.0),
        ("shade_vertex", 50.0),
        ("shade_vertex_flat", 30.0),
        ("diffuse:polygon:lit", 1500.0),
        ("diffuse:polygon:dark", 200.0),
        ("phong8:polygon:lit", 3000.0),
        ("phong8:polygon:dark", 100.0),
        ("band_clear", 7000.0),
        ("triangle", 2000.0),
        ("pixel", 80.0),
        ("pixel_shaded", 90.0),
        ("flush_byte", 1.5),
    ] {
        csv.push_str(&format!("chip,f32,{item},{c},calibrate\n"));
    }
    Costs::parse(&csv, "chip").unwrap()
}

#[test]
fn a_shader_call_costs_the_material_and_each_light_with_phong_linear_in_m() {
    let c = synthetic();
    let lights = [
        LightCost {
            kind: "polygon".into(),
            vertices: 8,
        },
        LightCost {
            kind: "ambient".into(),
            vertices: 0,
        },
    ];
    // m = 20: halfway between 8 and 32 on the polygon's phong: 3200; an octagon is twice
    // a quad.
    let got = call_cost(
        &c,
        "f32",
        &lights,
        Finish::Lit {
            specular: true,
            m: 20,
        },
    )
    .unwrap();
    assert_eq!(got, 20.0 + 2.0 * (1000.0 + 3200.0) + 1.0);
    let matte = call_cost(
        &c,
        "f32",
        &lights,
        Finish::Lit {
            specular: false,
            m: 20,
        },
    )
    .unwrap();
    assert_eq!(matte, 10.0 + 2.0 * 1000.0 + 1.0);
    assert_eq!(
        call_cost(&c, "f32", &lights, Finish::Emissive).unwrap(),
        0.0
    );
    let unknown = [LightCost {
        kind: "line".into(),
        vertices: 0,
    }];
    let e = call_cost(
        &c,
        "f32",
        &unknown,
        Finish::Lit {
            specular: false,
            m: 1,
        },
    )
    .unwrap_err();
    assert!(e.contains("diffuse:line"), "{e}");
}

#[test]
fn lit_and_dark_calls_take_their_own_costs_where_measured() {
    let c = synthetic();
    let lights = [
        LightCost {
            kind: "polygon".into(),
            vertices: 4,
        },
        LightCost {
            kind: "ambient".into(),
            vertices: 0,
        },
    ];
    let per_light = [
        LightCalls {
            diffuse: [3, 2],
            phong: [1, 4],
        },
        LightCalls {
            diffuse: [5, 0],
            phong: [0, 5],
        },
    ];
    let matte = Finish::Lit {
        specular: false,
        m: 8,
    };
    // The material's own 10 per call; the polygon's split costs; the ambient light has no
    // split: its cost over all points (1), lit or dark.
    assert_eq!(
        calls_cost(&c, "f32", &lights, matte, 5, &per_light).unwrap(),
        5.0 * 10.0 + 3.0 * 1500.0 + 2.0 * 200.0 + 5.0 * 1.0
    );
    // Phong at m = 8: the polygon's split phong8; phong32 has no split (4000 for both),
    // and at m = 8 only phong8 counts.
    let shiny = Finish::Lit {
        specular: true,
        m: 8,
    };
    assert_eq!(
        calls_cost(&c, "f32", &lights, shiny, 5, &per_light).unwrap(),
        5.0 * 20.0 + 3.0 * 1500.0 + 2.0 * 200.0 + 5.0 + 3000.0 + 4.0 * 100.0
    );
    // Without per-light counts: every call at call_cost.
    assert_eq!(
        calls_cost(&c, "f32", &lights, matte, 5, &[]).unwrap(),
        5.0 * call_cost(&c, "f32", &lights, matte).unwrap()
    );
    assert_eq!(
        calls_cost(&c, "f32", &lights, Finish::Emissive, 5, &per_light).unwrap(),
        0.0
    );
}

#[test]
fn a_frame_is_its_counted_work_times_the_unit_costs() {
    let c = synthetic();
    let chip = CHIPS.iter().find(|c| c.name == "stm32f411").unwrap();
    let work = Work {
        objects: vec![
            ObjectWork {
                vertices_lit: 100,
                vertex_calls: 40,
                pixels: 1000,
                setups: 30,
                ..ObjectWork::default()
            },
            ObjectWork {
                vertices_unlit: 10,
                vertex_calls: 5,
                pixel_calls: 0,
                pixels: 200,
                setups: 4,
                ..ObjectWork::default()
            },
        ],
        bands: 15,
        bytes: 115_200,
    };
    let lights = [LightCost {
        kind: "polygon".into(),
        vertices: 4,
    }];
    let finishes = [
        Finish::Lit {
            specular: false,
            m: 1,
        },
        Finish::Emissive,
    ];
    let p = predict(chip, &c, "f32", &work, &finishes, &lights).unwrap();
    assert_eq!(p.transform, 100.0 * 300.0 + 10.0 * 200.0);
    // The emissive object's vertices at the flat shader's cost.
    assert_eq!(p.shade, 40.0 * (50.0 + 10.0 + 1000.0) + 5.0 * 30.0);
    assert_eq!(p.raster, 15.0 * 7000.0 + 34.0 * 2000.0 + 1200.0 * 80.0);
    assert_eq!(p.flush, 115_200.0 * 1.5);
    // Two cores halve shade and raster; core 0's flush is the single core's (measured).
    let dual = CHIPS.iter().find(|c| c.name == "rp2040-dual").unwrap();
    let d = predict(dual, &c, "f32", &work, &finishes, &lights).unwrap();
    assert_eq!(
        (d.shade, d.raster, d.flush),
        (p.shade / 2.0, p.raster / 2.0, p.flush)
    );
}

#[test]
fn the_pareto_front_and_the_recommendation() {
    let row = |ms: f64, e: f64| Row {
        backend: "f32",
        shading: format!("{ms} {e}"),
        tessellation: 1.0,
        variant: Variant::AsWritten,
        predicted: Prediction::default(),
        ms,
        max_err: e,
        mean_err: e,
        derived: false,
        pareto: false,
        work: Work::default(),
    };
    let mut rows = vec![
        row(10.0, 3.0),
        row(20.0, 1.0),
        row(30.0, 2.0),
        row(40.0, 0.0),
    ];
    mark_pareto(&mut rows);
    let front: Vec<bool> = rows.iter().map(|r| r.pareto).collect();
    assert_eq!(front, [true, true, false, true]);
    assert_eq!(recommend(&rows, Some(60.0), None).unwrap().ms, 10.0);
    assert_eq!(recommend(&rows, Some(40.0), Some(1.5)).unwrap().ms, 20.0);
    assert!(recommend(&rows, Some(100.0), Some(1.5)).is_none());
}

/// The scene file of the demo is the firmware's frame: the host's counts of the scene
/// file equal `boards/demo-scene`'s own frame 0 (the board code, rendered here), in f32
/// with its 16-row bands.
#[test]
fn the_demo_scene_file_counts_what_the_board_demo_draws() {
    use arealight::raster::{Band, Rgb565};
    let mut buffers = Box::new(demo_scene::MeshBuffers::<f32>::new());
    let mut table = Box::new(arealight::raster::EncodeTable::zeroed());
    let mut demo = demo_scene::Demo::new(&mut buffers, &mut table, Shading::Gouraud).unwrap();
    let (mut px, mut depth) = (
        vec![Rgb565(0); demo_scene::BAND_PIXELS],
        vec![0u16; demo_scene::BAND_PIXELS],
    );
    let mut band = Band::new(&mut px, Some(&mut depth), demo_scene::WIDTH, 0).unwrap();
    let report = demo
        .render_frame(0, &mut band, &mut || 0, |_| Ok::<(), ()>(()))
        .unwrap();
    let parsed = scene_file::parse_as::<f32>("demo.toml", DEMO).unwrap();
    let shading = vec![Shading::Gouraud; parsed.scene.objects.len()];
    let (_, work) = work::render(&parsed.scene, &shading, demo_scene::BAND_ROWS).unwrap();
    let s = report.stats;
    assert_eq!(
        [
            work.total(|o| o.vertex_calls + o.pixel_calls),
            work.total(|o| o.pixels),
            work.total(|o| o.setups)
        ],
        [
            u64::from(s.shaded),
            u64::from(s.pixels),
            u64::from(s.rasterized)
        ]
    );
    assert_eq!(work.total(|o| o.vertices_lit), 231 + 275);
    assert_eq!(work.total(|o| o.vertices_unlit), 77);
    assert_eq!(work.bands, 15);
}

/// Every scene of host-sim/scenes on every chip: rows for the chip's first backend (the
/// firmware's), finite positive times, and the f32 per-pixel frame within a level of the
/// f64 one (the same path in another precision).
#[test]
fn every_scene_budgets_on_every_chip() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    scenes.sort();
    assert!(scenes.len() >= 3, "{scenes:?}");
    for scene in &scenes {
        for chip in CHIPS {
            let b = budget(scene, chip.name).unwrap();
            let first = chip.backends[0];
            assert!(
                b.rows.iter().any(|r| r.backend == first)
                    || b.skipped.iter().any(|s| s.backend == first),
                "{} {}",
                scene.display(),
                chip.name
            );
            for r in &b.rows {
                assert!(r.ms.is_finite() && r.ms > 0.0, "{r:?}");
                assert!((0.0..=255.0).contains(&r.max_err), "{r:?}");
            }
            if let Some(r) = b
                .rows
                .iter()
                .find(|r| r.backend == "f32" && r.shading == "per pixel" && r.tessellation == 1.0)
            {
                assert!(r.max_err <= 1.0, "{} {}: {r:?}", scene.display(), chip.name);
            }
            assert!(b.rows.iter().any(|r| r.pareto));
        }
    }
}
