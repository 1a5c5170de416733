//! Evaluations per second of the breeder GA on the paper's 20-rod impact problem (resonant
//! model, 2 ms of RK4 at 0.1 µs), with 1 and 2 worker threads. One iteration is
//! `BreederGa::initialize` with a population of 8 and the cache off: 8 simulations through the
//! GA's own thread pool; criterion reports the throughput in elements (= evaluations) per second.
//! Run: `cargo bench --manifest-path crates/woodpile-bench/Cargo.toml --bench optimize` (about a minute).

// criterion_group! generates an undocumented entry point.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::time::Duration;
use woodpile::optimize::{BreederGa, DesignSpace, GaSettings, StandardObjective};
use woodpile::CellModel;

const DESIGNS: usize = 8;

fn evaluations(c: &mut Criterion) {
    let mut group = c.benchmark_group("optimize/paper-impact-20-rods");
    group.throughput(Throughput::Elements(DESIGNS as u64));
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(10));
    for threads in [1, 2] {
        let ga = BreederGa::new(
            DesignSpace::paper_impact(CellModel::Resonant),
            Box::new(StandardObjective::TransmittedForce),
            GaSettings {
                population: DESIGNS,
                threads,
                cache: false,
                ..GaSettings::default()
            },
        )
        .unwrap();
        group.bench_function(format!("{threads}-threads"), |b| {
            b.iter(|| ga.initialize().unwrap().ledger.evaluations)
        });
    }
    group.finish();
}

criterion_group!(benches, evaluations);
criterion_main!(benches);
