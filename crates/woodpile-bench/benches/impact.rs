//! `cargo bench --manifest-path crates/woodpile-bench/Cargo.toml --bench impact`: one 20-rod resonant impact run (docs/physics.md §9 chain,
//! default striker, 2 ms) with the paper's RK4 at 0.1 µs, with RK4 at 0.5 µs and with DOPRI5 at
//! rtol = 1e-6 (both accurate to 1e-5 on the transmitted peak, see bench/README.md), each with
//! full 1 µs sampling and with peaks only.

// criterion_group! generates an undocumented entry point.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use woodpile::{
    simulate, CellModel, ChainBuilder, Excitation, Method, RunSettings, Striker,
    PAPER_OPTIMIZED_CHAIN_MM,
};

fn impact(c: &mut Criterion) {
    let chain = ChainBuilder::table1_rods(&PAPER_OPTIMIZED_CHAIN_MM, CellModel::Resonant)
        .expect("catalogue rods")
        .build()
        .expect("valid chain");
    let excitation = Excitation::Impact(Striker::paper());
    let mut group = c.benchmark_group("impact_20_rods_2ms");
    group.sample_size(20);
    let methods = [
        ("rk4_0.1us", Method::Rk4 { time_step_s: 1e-7 }),
        ("rk4_0.5us", Method::Rk4 { time_step_s: 5e-7 }),
        (
            "dopri5_1e-6",
            Method::Dopri5 {
                rtol: 1e-6,
                atol: 1e-12,
            },
        ),
    ];
    for (name, method) in methods {
        for (sampling, interval) in [("sampled_1us", 1e-6), ("peaks_only", 2e-3)] {
            let settings = RunSettings {
                method,
                sample_interval_s: interval,
                ..RunSettings::paper_impact()
            };
            group.bench_function(format!("{name}/{sampling}"), |b| {
                b.iter(|| simulate(&chain, &excitation, &settings, &mut ()).expect("run succeeds"))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, impact);
criterion_main!(benches);
