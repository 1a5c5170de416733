//! Steps set by the contacts under loads (docs/physics.md §8, "Exact linear vibrations"): five
//! 80 mm quartz rods as finite-element beams (16 elements per half rod) for 0.5 ms, samples
//! every 1 µs, under the paper's blast; a 10 N, 5 kHz harmonic force drive (its default ramp);
//! that drive over a 20 N preload under gravity; a 0.2 µm, 5 kHz displacement drive (0.1 ms ramp)
//! through the paper's sensor as the actuator's tip over a 20 N preload under gravity; the
//! paper's impact under a 5 N preload and gravity; the column at rest under that preload; the
//! impact with on-site damping (τ = 0.2 ms); the blast over a 5 N preload under gravity with that
//! damping; the impact with resonator damping (ζ = 1 %); the preloaded blast with both. For
//! each: DOPRI5 with events at rtol 1e-11 (converged), then `peak_tolerance` 1e-4, 1e-5, 1e-6
//! as woodpile resolves them (the exact modal method), DOPRI5 with events at the rtol
//! `peak_tolerance = 1e-5` gave it before, and the exact method at each rtol given as an
//! argument: steps, median wall time of 5 runs, the worst relative error of any contact peak
//! above 1 % of the largest, the energy error.
//!
//! Run: `cargo run --release -p woodpile --example exact_loads -- 1e-6 1e-7 1e-8 1e-9`
//! (`ONLY=blast`: the cases whose name starts so)

use woodpile::excitation::DriveQuantity;
use woodpile::model::{Damping, Preload, Wall};
use woodpile::{
    simulate, BlastProfile, CellModel, Chain, ChainBuilder, Drive, Element, Excitation, Material,
    Method, Rod, RunSettings, RunSummary, Signal, Striker, UnitCell,
};

fn fe_chain(force_n: f64, gravity_m_s2: f64) -> woodpile::Result<Chain> {
    damped_fe_chain(force_n, gravity_m_s2, None, 0.0)
}

fn damped_fe_chain(
    force_n: f64,
    gravity_m_s2: f64,
    on_site_time_s: Option<f64>,
    resonator_ratio: f64,
) -> woodpile::Result<Chain> {
    let rod = Rod::new(80e-3, 5e-3, 0.0, Material::fused_quartz())?;
    let cell = UnitCell::from_rod_fe(&rod, 16)?;
    let mut list = Vec::new();
    for _ in 0..5 {
        let mut e = Element::table1_rod(80, CellModel::Resonant)?;
        e.cell = cell.clone();
        list.push(e);
    }
    let preload = Preload {
        force_n,
        gravity_m_s2,
    };
    let damping = Damping {
        on_site_time_s,
        resonator_ratio,
        ..Damping::default()
    };
    ChainBuilder::new(list)
        .preload(preload)
        .damping(damping)
        .build()
}

fn run(chain: &Chain, excitation: &Excitation, method: Method) -> woodpile::Result<RunSummary> {
    let settings = RunSettings {
        duration_s: 5e-4,
        method,
        sample_interval_s: 1e-6,
    };
    simulate(chain, excitation, &settings, &mut ())
}

fn median_run(
    chain: &Chain,
    excitation: &Excitation,
    method: Method,
) -> woodpile::Result<RunSummary> {
    let mut runs: Vec<RunSummary> = (0..5)
        .map(|_| run(chain, excitation, method))
        .collect::<woodpile::Result<_>>()?;
    runs.sort_by(|a, b| a.wall_time_s.total_cmp(&b.wall_time_s));
    Ok(runs.swap_remove(2))
}

/// The worst relative error of a contact peak above 1 % of the largest.
fn worst(a: &RunSummary, reference: &RunSummary) -> f64 {
    let largest = reference
        .contact_peak_forces_n
        .iter()
        .fold(0.0_f64, |m, &f| m.max(f));
    a.contact_peak_forces_n
        .iter()
        .zip(&reference.contact_peak_forces_n)
        .filter(|(_, &r)| r > 0.01 * largest)
        .map(|(x, r)| (x / r - 1.0).abs())
        .fold(0.0, f64::max)
}

fn cases() -> woodpile::Result<Vec<(&'static str, Chain, Excitation)>> {
    let harmonic = Signal::Harmonic {
        amplitude: 10.0,
        frequency_hz: 5e3,
    };
    let displacement = Drive {
        quantity: DriveQuantity::Displacement {
            tip: Wall::paper_sensor(),
        },
        ramp_s: 1e-4,
        signal: Signal::Harmonic {
            amplitude: 2e-7,
            frequency_hz: 5e3,
        },
    };
    Ok(vec![
        (
            "blast",
            fe_chain(0.0, 0.0)?,
            Excitation::Blast(BlastProfile::paper()),
        ),
        (
            "force drive",
            fe_chain(0.0, 0.0)?,
            Excitation::Drive(Drive::force(harmonic.clone())),
        ),
        (
            "preloaded force drive",
            fe_chain(20.0, 9.81)?,
            Excitation::Drive(Drive::force(harmonic)),
        ),
        (
            "preloaded displacement drive",
            fe_chain(20.0, 9.81)?,
            Excitation::Drive(displacement),
        ),
        (
            "preloaded impact",
            fe_chain(5.0, 9.81)?,
            Excitation::Impact(Striker::paper()),
        ),
        (
            "preloaded column at rest",
            fe_chain(5.0, 9.81)?,
            Excitation::Rest,
        ),
        (
            "damped impact",
            damped_fe_chain(0.0, 0.0, Some(2e-4), 0.0)?,
            Excitation::Impact(Striker::paper()),
        ),
        (
            "damped preloaded blast",
            damped_fe_chain(5.0, 9.81, Some(2e-4), 0.0)?,
            Excitation::Blast(BlastProfile::paper()),
        ),
        (
            "resonator-damped impact",
            damped_fe_chain(0.0, 0.0, None, 0.01)?,
            Excitation::Impact(Striker::paper()),
        ),
        (
            "resonator-damped preloaded blast",
            damped_fe_chain(5.0, 9.81, Some(2e-4), 0.01)?,
            Excitation::Blast(BlastProfile::paper()),
        ),
    ])
}

fn main() -> woodpile::Result<()> {
    let only = std::env::var("ONLY").ok();
    let rtols: Vec<f64> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    for (name, chain, excitation) in cases()? {
        if only.as_ref().is_some_and(|o| !name.starts_with(o.as_str())) {
            continue;
        }
        let reference = run(
            &chain,
            &excitation,
            Method::Dopri5Events {
                rtol: 1e-11,
                atol: 1e-17,
            },
        )?;
        println!(
            "{name}: converged energy error {:.1e}",
            reference.energy.max_relative_error
        );
        let mut methods: Vec<(String, Method)> = [1e-4, 1e-5, 1e-6]
            .map(|t| {
                (
                    format!("peak_tolerance {t:e}"),
                    Method::PeakTolerance { peak_tolerance: t },
                )
            })
            .to_vec();
        let before = Method::PeakTolerance {
            peak_tolerance: 1e-5,
        }
        .resolve(false);
        methods.push((
            "dopri5 with events as peak_tolerance 1e-5 chose it before".into(),
            before,
        ));
        for &r in &rtols {
            methods.push((
                format!("exact-modes rtol {r:e}"),
                Method::ExactModes {
                    rtol: r,
                    atol: r * 1e-6,
                },
            ));
        }
        for (label, method) in methods {
            let s = median_run(&chain, &excitation, method)?;
            println!(
                "  {label}: {} steps ({} rejected), {:.3} ms, worst peak {:.2e}, energy {:.1e}",
                s.stats.steps,
                s.stats.rejected_steps,
                s.wall_time_s * 1e3,
                worst(&s, &reference),
                s.energy.max_relative_error
            );
        }
    }
    Ok(())
}
