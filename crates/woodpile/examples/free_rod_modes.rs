//! A single free rod struck at a quarter of its length (docs/physics.md §16): how the energy the
//! striker leaves in the rod is shared by rigid translation, rocking and the bending modes.
//!
//! The 80 mm fused-quartz rod (5 mm) floats free (no supports, no gravity) and is struck at
//! s₀ = L/4 by the paper's striker (10 mm soda-lime glass, 0.2 m drop). For a linear rod driven by
//! a point force F(t) at s₀ and at rest before, mode j (mass-normalised, ω_j, deflection r_j at
//! s₀) holds E_j = ½ r_j² |F̂(ω_j)|² once the contact has opened, F̂(ω) = ∫ F(t) e^{−iωt} dt. The
//! example runs the lattice model's finite-element rod (RKN 6(4), rtol 1e-10), integrates F̂
//! from the run's force history, and compares every mode's energy at the end of the run
//!
//! 1. with ½ r_j² |F̂(ω_j)|² of the same finite-element mode (the run obeys its own modes), and
//! 2. with ½ W_j(s₀)² |F̂(Ω_j)|² of the analytic Timoshenko free–free mode j (its frequency Ω_j
//!    and shape W_j, `Rod::free_free_modes`; rigid modes: 1/√m and s₀/√J),
//!
//! for 2 to 32 elements per half rod; then the same struck rod with `rod = { modes = l }`
//! (analytic modes, l = 1..20) against the finite-element rod at 32 elements: the striker's
//! peak force and the rod's energy held by bending modes.
//!
//! Run: `cargo run --release -p woodpile --example free_rod_modes`

use woodpile::integrate::{Integrator, OdeSystem};
use woodpile::model::{FreeRodModes, Lattice, LatticeBuilder, LayerSpec, Supports};
use woodpile::ode::LatticeOde;
use woodpile::{Material, Method, Rod, Striker};

const LENGTH_M: f64 = 0.08;
const S0_M: f64 = 0.25 * LENGTH_M;
const DURATION_S: f64 = 80e-6;
const MODES: usize = 8;

fn lattice(fe_elements: usize, bending: Option<usize>) -> Lattice {
    let layer = LayerSpec {
        rods: 1,
        pitch_m: 0.0,
        length_m: LENGTH_M,
        diameter_m: 5e-3,
        material: Material::fused_quartz(),
        angle_deg: 90.0,
    };
    let mut b = LatticeBuilder::new(vec![layer], fe_elements);
    b.supports = Supports::Points(Vec::new());
    b.bending_modes = bending;
    b.build().expect("a valid rod")
}

/// One struck-rod run: the rod's modal energies at the end, F̂ at the given frequencies, the
/// striker's peak force, (P − m v₀)/(m v₀) and H/(m v₀ L).
struct Struck {
    energies_j: Vec<f64>,
    spectrum: Vec<f64>,
    peak_n: f64,
    momentum: f64,
    moment: f64,
}

fn struck(lattice: &Lattice, omegas: &[f64]) -> Struck {
    let striker = Striker::paper();
    let mut ode = LatticeOde::new(lattice, &striker, [S0_M, 0.0]).expect("on the rod");
    let modes: &FreeRodModes = &lattice.rods[0].modes;
    let row = modes.modal_row(S0_M);
    let beta = ode.contact_betas()[0];
    let q = ode.coordinates();
    let ms = striker.mass_kg();
    let force = |y: &[f64]| {
        let d = y[0] / ms.sqrt() - row.iter().zip(&y[1..q]).map(|(r, x)| r * x).sum::<f64>();
        beta * d.max(0.0).powf(1.5)
    };
    let y0 = ode.initial_state();
    let units = ode.tolerance_units();
    let method = Method::Rkn64 {
        rtol: 1e-10,
        atol: 1e-16,
    };
    let mut integrator = Integrator::new(method, &mut ode, 0.0, y0, &units, DURATION_S);
    let dt = 2e-9;
    let (mut re, mut im) = (vec![0.0; omegas.len()], vec![0.0; omegas.len()]);
    let mut y = vec![0.0; ode.dimension()];
    let (mut k, mut peak) = (1usize, 0.0_f64);
    while integrator.t() < DURATION_S {
        integrator.step(&mut ode, DURATION_S).expect("a good run");
        while (k as f64) * dt <= integrator.t() {
            let t = k as f64 * dt;
            integrator.interpolate(t, &mut y);
            let f = force(&y);
            peak = peak.max(f);
            for (i, w) in omegas.iter().enumerate() {
                re[i] += f * (w * t).cos() * dt;
                im[i] -= f * (w * t).sin() * dt;
            }
            k += 1;
        }
    }
    let y = integrator.y();
    let energies_j = (0..modes.omega_rad_s.len())
        .map(|j| {
            let (x, v) = (y[1 + j], y[q + 3 + 1 + j]);
            0.5 * (v * v + (modes.omega_rad_s[j] * x).powi(2))
        })
        .collect();
    let (p, h, _, _) = ode.momentum_audit(y);
    let p0 = ms * striker.velocity_m_s;
    Struck {
        energies_j,
        spectrum: re.iter().zip(&im).map(|(a, b)| a * a + b * b).collect(),
        peak_n: peak,
        momentum: (p - p0) / p0,
        moment: (h[0].abs() + h[1].abs()) / (p0 * LENGTH_M),
    }
}

fn main() {
    let rod = Rod::new(LENGTH_M, 5e-3, 0.0, Material::fused_quartz()).expect("a rod");
    let analytic = rod.free_free_modes(MODES).expect("below the cutoff");
    let mass = rod.mass_kg();
    let inertia = mass * LENGTH_M.powi(2) / 12.0
        + rod.material.density_kg_m3 * rod.second_moment_m4() * LENGTH_M;
    let mut exact_rows = vec![1.0 / mass.sqrt(), S0_M / inertia.sqrt()];
    exact_rows.extend(analytic.iter().map(|m| m.deflection(S0_M)));
    let mut exact_omegas = vec![0.0, 0.0];
    exact_omegas.extend(analytic.iter().map(|m| m.omega_rad_s));
    println!("Analytic free–free Timoshenko modes of the 80 mm rod:");
    for (j, m) in analytic.iter().enumerate() {
        println!(
            "  mode {}: {:9.1} Hz  {}  W(L/4) = {:+.4} kg^-1/2",
            j + 1,
            m.omega_rad_s / (2.0 * std::f64::consts::PI),
            if m.symmetric {
                "symmetric    "
            } else {
                "antisymmetric"
            },
            m.deflection(S0_M)
        );
    }
    println!(
        "\nModal energies at the end of the run, share of the rod's energy (finite-element rod):"
    );
    println!("elements | translation rocking | bending 1..{MODES} | max |E_FE − FE modes' prediction|/E_rod | max |E_FE − analytic|/E_j, modes ≥ 0.1 % | P, H audit");
    for n in [2usize, 4, 8, 16, 32] {
        let lat = lattice(n, None);
        let modes = &lat.rods[0].modes;
        let count = (2 + MODES).min(modes.omega_rad_s.len());
        let mut omegas: Vec<f64> = modes.omega_rad_s[..count].to_vec();
        omegas.extend_from_slice(&exact_omegas[..count]);
        let run = struck(&lat, &omegas);
        let total: f64 = run.energies_j.iter().sum();
        let fe_row = modes.modal_row(S0_M);
        let own = (0..count)
            .map(|j| (run.energies_j[j] - 0.5 * fe_row[j].powi(2) * run.spectrum[j]).abs() / total)
            .fold(0.0, f64::max);
        let vs_exact = (0..count)
            .filter(|&j| run.energies_j[j] > 1e-3 * total)
            .map(|j| {
                let e = 0.5 * exact_rows[j].powi(2) * run.spectrum[count + j];
                (run.energies_j[j] - e).abs() / e
            })
            .fold(0.0, f64::max);
        let shares: Vec<String> = run.energies_j[..count]
            .iter()
            .map(|e| format!("{:.4}", e / total))
            .collect();
        println!(
            "{n:>8} | {} | {own:.1e} | {vs_exact:.1e} | {:.1e}, {:.1e}",
            shares.join(" "),
            run.momentum,
            run.moment
        );
    }
    println!("\nrod = {{ modes = l }} (analytic modes) against the finite-element rod at 32 elements per half rod:");
    let reference = struck(&lattice(32, None), &[]);
    let ref_total: f64 = reference.energies_j.iter().sum();
    let ref_bending = ref_total - reference.energies_j[0] - reference.energies_j[1];
    println!(
        "   l | striker peak [N] | rel. to FE | bending energy share | rel. to FE    (FE-32: {:.2} N, {:.4})",
        reference.peak_n,
        ref_bending / ref_total
    );
    for l in [1, 2, 3, 4, 6, 8, 12, 16, 20] {
        let run = struck(&lattice(1, Some(l)), &[]);
        let total: f64 = run.energies_j.iter().sum();
        let bending = (total - run.energies_j[0] - run.energies_j[1]) / total;
        println!(
            "{l:>4} | {:16.3} | {:+.1e} | {bending:20.4} | {:+.1e}",
            run.peak_n,
            run.peak_n / reference.peak_n - 1.0,
            bending / (ref_bending / ref_total) - 1.0
        );
    }
}
