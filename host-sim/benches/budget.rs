//! Host cost of the budget's cases (criterion): every kernel of the QEMU harness
//! (`boards/qemu-budget/src/cases.rs`) per backend, and the point-light / k-sample
//! alternatives (`points.rs`), over the harness's 16 inputs.
//!
//! `cargo bench -p host-sim --bench budget` (add `-- NAME` to filter, e.g. `-- pts16`). One
//! iteration is a sweep of the 16 inputs (16 calls); criterion's throughput line gives calls
//! per second. `host-sim budget` times the same kernels itself (median of runs) for
//! its table; this bench gives criterion's statistics for them.

#[allow(dead_code)]
#[path = "../../boards/qemu-budget/src/cases.rs"]
mod cases;
#[allow(dead_code)]
#[path = "../../boards/qemu-budget/src/points.rs"]
mod points;

use std::hint::black_box;
use std::time::Duration;

use arealight::{Fast32, Fixed22};
use cases::{Backend, Dirs, Lights, Meter, MODELS, RING};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};

/// Calls each kernel once per input; criterion does the timing around the whole sweep.
struct Once;

impl Meter for Once {
    fn call<R>(&mut self, f: impl Fn() -> R) -> (R, u32) {
        (black_box(f()), 0)
    }
}

fn ring() -> Dirs<'static> {
    Dirs {
        count: RING,
        get: &cases::ring,
    }
}

fn bench_backend<T: Backend>(c: &mut Criterion) {
    let Ok(lights) = Lights::<T>::new(|x| x) else {
        return;
    };
    let mut g = c.benchmark_group(format!("budget/{}", T::NAME));
    g.throughput(Throughput::Elements(RING as u64));
    for (m, model) in MODELS.iter().enumerate() {
        if !cases::supports(T::NAME, model) {
            continue;
        }
        g.bench_function(*model, |b| {
            b.iter(|| {
                let mut acc = 0.0;
                cases::run_model(black_box(&lights), m, ring(), |x| x, &mut Once, &mut |s| {
                    acc += s.value[0]
                });
                acc / RING as f64
            })
        });
    }
    g.finish();
}

fn bench_points(c: &mut Criterion) {
    let mut g = c.benchmark_group("budget/alternatives");
    g.throughput(Throughput::Elements(RING as u64));
    for k in points::KS {
        let l = points::Sampled::<f32>::new(k, cases::PHONG_M);
        for (alt, (name, _)) in points::ALTERNATIVES.iter().enumerate() {
            if name.starts_with("point_") && k != 1 {
                continue;
            }
            g.bench_function(format!("{name}/pts{k}"), |b| {
                b.iter(|| {
                    let mut acc = 0.0;
                    points::run_alt(black_box(&l), alt, ring(), |x| x, &mut Once, &mut |s| {
                        acc += s.value[0]
                    });
                    acc / RING as f64
                })
            });
        }
    }
    g.finish();
}

fn benches(c: &mut Criterion) {
    bench_backend::<f32>(c);
    bench_backend::<Fast32>(c);
    bench_backend::<Fixed22>(c);
    bench_points(c);
}

criterion_group! {
    name = budget;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(200))
        .measurement_time(Duration::from_millis(500));
    targets = benches
}
criterion_main!(budget);
