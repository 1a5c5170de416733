//! The static solve of a lattice under gravity and a preload (docs/physics.md §16, "Gravity and a
//! preload"): the benchmark's 10-layer × 5-rod lattice of 100 mm fused-quartz rods (5 mm, pitch
//! 20 mm, a support under every bottom rod's centre), g = 9.81 m/s² and a 10 N preload on the 25
//! top-layer crossings, left at rest. Builds the equations (`LatticeOde::build`, which solves for
//! the equilibrium) `REPEATS` times and prints the median CPU time of this thread and wall time,
//! the solve's residual |∇Π| / |f|, the supports' Σ F_s against M g + F_p, and the largest static
//! force. The time of the build without the static load (gravity and preload zero, a striker:
//! the same modes and contacts) is printed beside it, so that the solve's share is the difference.
//!
//! Run: `cargo run --release -p woodpile --example lattice_static`
//! (`ELEMENTS=8`: elements per half rod, default 16; `LATTICE=4x3`: the claims' 3 × 3-rod,
//! 4-layer lattice of 80 mm rods; `REPEATS=1`, default 3; `SAVE=path`: write the equilibrium's
//! modal coordinates and contact forces, one number a line; `COMPARE=path`: read such a file and
//! print the largest difference of coordinates and forces, relative to the largest of each;
//! `DRIVE=displacement`: the preload through a displacement actuator's tips on the same
//! crossings instead, the actuator's height solved with the lattice, its tips' shares printed)

use woodpile::model::{
    Lattice, LatticeBuilder, LatticeExcitation, LatticeLab, LayerSpec, LoadPoints, Preload,
};
use woodpile::ode::LatticeOde;
use woodpile::{Drive, DriveQuantity, Material, Signal, Striker, Wall};

fn lattice(elements: usize) -> woodpile::Result<Lattice> {
    let (layers, rods, length_m) = match std::env::var("LATTICE").as_deref() {
        Ok("4x3") => (4, 3, 80e-3),
        _ => (10, 5, 100e-3),
    };
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

/// The excitation the preload comes with: none (left at rest, the preload F_p/N on each
/// top-layer crossing) or, with `DRIVE=displacement`, a displacement actuator's tip on each
/// (the paper's sensor), held still.
fn excitation() -> LatticeExcitation {
    let points = LoadPoints::TopCrossings;
    if std::env::var("DRIVE").as_deref() != Ok("displacement") {
        return LatticeExcitation::Rest { points };
    }
    let drive = Drive {
        quantity: DriveQuantity::Displacement {
            tip: Wall::paper_sensor(),
        },
        signal: Signal::Harmonic {
            amplitude: 1e-7,
            frequency_hz: 1e3,
        },
        ramp_s: 1e-3,
    };
    LatticeExcitation::Drive { drive, points }
}

/// The tips' shares of the preload: (smallest, largest, sum) \[N\], under an actuator.
fn tip_shares(ode: &LatticeOde) -> Option<(f64, f64, f64)> {
    ode.has_actuator().then(|| {
        let (forces, _) = ode.static_forces_n();
        forces[ode.incident_contacts()]
            .iter()
            .fold((f64::INFINITY, 0.0_f64, 0.0), |(l, h, s), &f| {
                (l.min(f), h.max(f), s + f)
            })
    })
}

/// This thread's CPU time \[s\] (utime + stime of /proc/thread-self/stat, 10 ms ticks).
fn cpu_s() -> f64 {
    let stat = std::fs::read_to_string("/proc/thread-self/stat").unwrap_or_default();
    let fields: Vec<&str> = stat
        .rsplit(')')
        .next()
        .unwrap_or("")
        .split_whitespace()
        .collect();
    let tick = |i: usize| fields.get(i).and_then(|v| v.parse::<f64>().ok());
    match (tick(11), tick(12)) {
        (Some(u), Some(s)) => (u + s) / 100.0,
        _ => f64::NAN,
    }
}

/// (mean CPU s, median wall s) of `repeats` calls of `f` (the mean of CPU times, whose sum is
/// exact to a tick, rather than their median), and its last result.
fn timed<T>(repeats: usize, mut f: impl FnMut() -> T) -> ((f64, f64), T) {
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..repeats {
        let (c0, w0) = (cpu_s(), std::time::Instant::now());
        last = Some(f());
        times.push((cpu_s() - c0, w0.elapsed().as_secs_f64()));
    }
    let cpu = times.iter().map(|t| t.0).sum::<f64>() / repeats as f64;
    let mut wall: Vec<f64> = times.iter().map(|t| t.1).collect();
    wall.sort_by(f64::total_cmp);
    (
        (cpu, wall[wall.len() / 2]),
        last.expect("at least one repeat"),
    )
}

fn main() -> woodpile::Result<()> {
    let env = |k: &str, d: usize| {
        std::env::var(k)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(d)
    };
    let (elements, repeats) = (env("ELEMENTS", 16), env("REPEATS", 3).max(1));
    let (g, fp) = (9.81, 10.0);
    let lattice = lattice(elements)?;
    let lab = LatticeLab {
        preload: Preload {
            force_n: fp,
            gravity_m_s2: g,
        },
        ..LatticeLab::default()
    };
    let rest = excitation();
    let (unloaded, _) = timed(repeats, || {
        LatticeOde::new(&lattice, &Striker::paper(), [0.0, 0.0]).map(|o| o.coordinates())
    });
    let (loaded, ode) = timed(repeats, || LatticeOde::build(&lattice, &rest, &lab));
    let ode = ode?;
    let (forces, residual) = ode.static_forces_n();
    let supports: f64 = (0..ode.contacts())
        .filter(|&c| ode.is_support(c))
        .map(|c| forces[c])
        .sum();
    let weight = lattice.mass_kg() * g;
    let largest = forces.iter().fold(0.0_f64, |m, &f| m.max(f));
    println!(
        "{} layers × {} rods, {elements} elements per half rod: {} modal coordinates, {} contacts",
        lattice.layers,
        lattice.rods.len() / lattice.layers,
        ode.coordinates(),
        ode.contacts()
    );
    println!(
        "build with the static solve: {:.3} s CPU ({:.3} s wall); without a static load: {:.3} s CPU ({:.3} s wall); {repeats} builds (CPU: mean, wall: median)",
        loaded.0, loaded.1, unloaded.0, unloaded.1
    );
    println!(
        "residual |∇Π|/|f| {residual:.2e}; supports {supports:.9} N against M g + F_p {:.9} N ({:.2e}); largest static force {largest:.6} N",
        weight + fp,
        (supports - weight - fp).abs() / (weight + fp)
    );
    if let Some((low, high, sum)) = tip_shares(&ode) {
        println!("actuator's tips: {low:.6} to {high:.6} N, {sum:.12} N in all");
    }
    let q0 = &ode.initial_state()[..ode.coordinates()];
    let values: Vec<f64> = q0.iter().chain(forces).copied().collect();
    if let Ok(path) = std::env::var("SAVE") {
        let text: String = values.iter().map(|v| format!("{v:e}\n")).collect();
        std::fs::write(&path, text).expect("SAVE: a writable path");
    }
    if let Ok(path) = std::env::var("COMPARE") {
        let text = std::fs::read_to_string(&path).expect("COMPARE: a file written by SAVE");
        let other: Vec<f64> = text.lines().map(|l| l.parse().expect("a number")).collect();
        assert_eq!(other.len(), values.len(), "COMPARE: another lattice");
        let n = q0.len();
        let worst = |a: &[f64], b: &[f64]| {
            let scale = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            a.iter()
                .zip(b)
                .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
                / scale
        };
        // The rigid modes (ω = 0) apart: the lattice may tip about its supports' line at no
        // cost (docs/physics.md §16), so only the elastic modes and the forces are unique.
        let omega2: Vec<f64> = lattice
            .rods
            .iter()
            .flat_map(|r| r.modes.omega_rad_s.iter().map(|w| w * w))
            .collect();
        let part = |rigid: bool, v: &[f64]| -> Vec<f64> {
            v.iter()
                .zip(&omega2)
                .map(|(x, &w2)| if (w2 == 0.0) == rigid { *x } else { 0.0 })
                .collect()
        };
        println!(
            "against {path}: max |Δq| / max |q| {:.2e} (elastic modes {:.2e}, rigid modes {:.2e}); max |ΔF| / max F {:.2e}",
            worst(&values[..n], &other[..n]),
            worst(&part(false, &values[..n]), &part(false, &other[..n])),
            worst(&part(true, &values[..n]), &part(true, &other[..n])),
            worst(&values[n..], &other[n..])
        );
    }
    Ok(())
}
