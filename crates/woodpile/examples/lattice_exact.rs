//! Steps set by the contacts on a lattice (docs/physics.md §8 "Exact linear vibrations", §16):
//! the 3 × 3-rod, 4-layer quartz lattice of the lattice claims (80 mm rods, pitch 20 mm, the
//! paper's striker off the centre at (13, 0) mm, 0.5 ms, samples every 1 µs), its rods
//! finite-element beams of E elements per half rod. For each E: the exact modal method at rtol
//! 1e-12 against RKN 6(4) at 1e-12 (both converged), then `peak_tolerance = 1e-5` as woodpile
//! resolves it (the exact modal method for these rods), RKN 6(4) at the rtol that tolerance
//! gives it, and the exact method at each rtol given as an argument: steps (rejected),
//! evaluations (contact forces at one node), median wall time of 5 runs, the worst relative
//! error of any contact peak above 1 % of the largest against the converged RKN 6(4) run, the
//! energy error.
//!
//! Run: `cargo run --release -p woodpile --example lattice_exact -- 1e-6 1e-7`
//! (`ELEMENTS=4,8`: the element counts, default 4, 8, 16; `LATTICE=10x5`: the benchmark's
//! 10-layer × 5-rod lattice of 100 mm rods struck at the centre, 2 ms, samples every 10 µs;
//! `REFERENCE_RTOL=1e-10`: the converged runs' rtol, default 1e-12; `LOAD=damped`: the impact
//! with every rod mode damped (modal ratio ζ = 2 %, on-site time τ = 1 ms), `LOAD=blast`: a
//! Friedlander blast (F0 = 200 N, Td = 0.1 ms) on the top crossings with that damping,
//! `LOAD=drive`: a 20 N, 5 kHz harmonic force drive on the top crossings (its default ramp) with
//! that damping, `LOAD=preloaded`: the damped impact under gravity (9.81 m/s²) and a 5 N
//! preload on the top crossings, from their static equilibrium; with a `LOAD` the converged run is DOPRI5 at REFERENCE_RTOL (default 1e-11)
//! and the peak tolerance's other method is DOPRI5 with events, as woodpile resolved it before)

use woodpile::model::{
    Damping, Lattice, LatticeBuilder, LatticeExcitation, LatticeLab, LayerSpec, LoadPoints, Preload,
};
use woodpile::ode::LatticeOde;
use woodpile::simulate::{simulate_lattice, LatticeRun};
use woodpile::{BlastProfile, Drive, Material, Method, RunSettings, Signal, Striker};

/// The `LOAD` option: the excitation and the lab physics (None: the lossless impact).
fn load() -> Option<(LatticeExcitation, LatticeLab)> {
    let kind = std::env::var("LOAD").ok()?;
    let lab = LatticeLab {
        damping: Damping {
            on_site_time_s: Some(1e-3),
            ..Damping::default()
        },
        modal_ratio: 0.02,
        ..LatticeLab::default()
    };
    let excitation = match kind.as_str() {
        "damped" => LatticeExcitation::Impact {
            striker: Striker::paper(),
            at_m: shape().3,
        },
        "preloaded" => {
            let lab = LatticeLab {
                preload: Preload {
                    force_n: 5.0,
                    gravity_m_s2: 9.81,
                },
                ..lab
            };
            let striker = Striker::paper();
            let at_m = shape().3;
            return Some((LatticeExcitation::Impact { striker, at_m }, lab));
        }
        "blast" => LatticeExcitation::Blast {
            profile: BlastProfile::Friedlander {
                peak_force_n: 200.0,
                duration_s: 1e-4,
                decay: 1.0,
            },
            points: LoadPoints::TopCrossings,
        },
        "drive" => LatticeExcitation::Drive {
            drive: Drive::force(Signal::Harmonic {
                amplitude: 20.0,
                frequency_hz: 5e3,
            }),
            points: LoadPoints::TopCrossings,
        },
        other => panic!("LOAD={other}: damped, preloaded, blast or drive"),
    };
    Some((excitation, lab))
}

fn build(lattice: &Lattice) -> woodpile::Result<LatticeOde> {
    match load() {
        Some((excitation, lab)) => LatticeOde::build(lattice, &excitation, &lab),
        None => LatticeOde::new(lattice, &Striker::paper(), shape().3),
    }
}

/// (layers, rods, rod length \[m\], impact point \[m\], duration \[s\], sample interval \[s\]).
type Shape = (usize, usize, f64, [f64; 2], f64, f64);

fn shape() -> Shape {
    match std::env::var("LATTICE").as_deref() {
        Ok("10x5") => (10, 5, 100e-3, [0.0, 0.0], 2e-3, 1e-5),
        _ => (4, 3, 80e-3, [13e-3, 0.0], 5e-4, 1e-6),
    }
}

fn lattice(elements: usize) -> woodpile::Result<Lattice> {
    let (layers, rods, length_m, ..) = shape();
    let layer = LayerSpec {
        rods,
        pitch_m: 20e-3,
        length_m,
        diameter_m: 5e-3,
        material: Material::fused_quartz(),
        angle_deg: 90.0,
    };
    LatticeBuilder::new(vec![layer; layers], elements).build()
}

/// A run and its wall time [s].
fn run(lattice: &Lattice, method: Method) -> woodpile::Result<(LatticeRun, f64)> {
    let (.., duration_s, sample_interval_s) = shape();
    let mut ode = build(lattice)?;
    let settings = RunSettings {
        duration_s,
        method,
        sample_interval_s,
    };
    let started = std::time::Instant::now();
    let run = simulate_lattice(&mut ode, &settings)?;
    Ok((run, started.elapsed().as_secs_f64()))
}

fn worst(a: &LatticeRun, b: &LatticeRun) -> f64 {
    worst_contact(a, b).0
}

/// The worst relative peak error over the peaks above 1 % of the largest, its contact and that
/// peak as a fraction of the largest.
fn worst_contact(a: &LatticeRun, b: &LatticeRun) -> (f64, usize, f64) {
    let largest = b
        .contact_peak_forces_n
        .iter()
        .fold(0.0, |m: f64, &f| m.max(f));
    a.contact_peak_forces_n
        .iter()
        .zip(&b.contact_peak_forces_n)
        .enumerate()
        .filter(|(_, (_, &y))| y > 0.01 * largest)
        .map(|(c, (x, y))| ((x / y - 1.0).abs(), c, y / largest))
        .fold((0.0, 0, 0.0), |m, e| if e.0 > m.0 { e } else { m })
}

fn median_run(lattice: &Lattice, method: Method) -> woodpile::Result<(LatticeRun, f64)> {
    let mut runs: Vec<(LatticeRun, f64)> = (0..5)
        .map(|_| run(lattice, method))
        .collect::<woodpile::Result<_>>()?;
    runs.sort_by(|a, b| a.1.total_cmp(&b.1));
    Ok(runs.swap_remove(2))
}

fn main() -> woodpile::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let rtols: Vec<f64> = args.iter().skip(1).filter_map(|a| a.parse().ok()).collect();
    let elements: Vec<usize> = std::env::var("ELEMENTS")
        .ok()
        .map(|s| s.split(',').filter_map(|e| e.parse().ok()).collect())
        .unwrap_or_else(|| vec![4, 8, 16]);
    let reference_rtol: f64 = std::env::var("REFERENCE_RTOL")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(if load().is_some() { 1e-11 } else { 1e-12 });
    let tolerance = Method::PeakTolerance {
        peak_tolerance: 1e-5,
    };
    for e in elements {
        let lattice = lattice(e)?;
        let ode = build(&lattice)?;
        println!(
            "striker's Hertz contact time {:.2} µs, stiffest mode {:.2} MHz",
            ode.striker_contact_time_s() * 1e6,
            ode.stiffest_mode_rad_s() / std::f64::consts::TAU / 1e6
        );
        let converged = if load().is_some() {
            Method::Dopri5 {
                rtol: reference_rtol,
                atol: reference_rtol * 1e-6,
            }
        } else {
            Method::Rkn64 {
                rtol: reference_rtol,
                atol: reference_rtol * 1e-6,
            }
        };
        let (reference, _) = run(&lattice, converged)?;
        let (exact_ref, _) = run(
            &lattice,
            Method::ExactModes {
                rtol: reference_rtol,
                atol: reference_rtol * 1e-6,
            },
        )?;
        println!(
            "{e} elements per half rod, {} contacts: exact-modes against {converged:?}, both at rtol {reference_rtol:e}: worst peak {:.2e} ({} against {} steps)",
            reference.contacts,
            worst(&exact_ref, &reference),
            exact_ref.stats.steps,
            reference.stats.steps
        );
        let mut methods = vec![
            ("peak_tolerance 1e-5".to_string(), tolerance),
            (
                "the other method at peak_tolerance 1e-5's rtol".to_string(),
                tolerance.resolve(load().is_none()),
            ),
        ];
        for &r in &rtols {
            let exact = Method::ExactModes {
                rtol: r,
                atol: r * 1e-6,
            };
            methods.push((format!("exact-modes rtol {r:e}"), exact));
        }
        for (label, method) in methods {
            let (s, wall_s) = median_run(&lattice, method)?;
            println!(
                "  {label} ({:?}): {} steps ({} rejected), {} evaluations, {:.2} ms, worst peak {:.2e} (contact {}, {:.3} of the largest), energy {:.1e}, D {:.4e} J, W {:.4e} J",
                s.method,
                s.stats.steps,
                s.stats.rejected_steps,
                s.stats.rhs_evaluations,
                wall_s * 1e3,
                worst(&s, &reference),
                worst_contact(&s, &reference).1,
                worst_contact(&s, &reference).2,
                s.energy.max_relative_error,
                s.energy.dissipated_j,
                s.energy.input_work_j
            );
        }
    }
    Ok(())
}
