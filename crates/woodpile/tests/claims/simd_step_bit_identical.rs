//! Claim: the run-time-selected SIMD build of the integrator step (AVX2 where the CPU has it)
//! gives bit for bit the results of the portable step: the same state after 2000 RK4 steps and
//! after 300 adaptive Dormand–Prince steps of the paper's 20-rod impact, and every modal
//! amplitude and rate after 300 steps of the exact modal method on five finite-element rods
//! (whose passes over the modes run four modes per vector there), and the whole state after 300
//! steps of the exact modal method on the 3 × 3-rod, 4-layer lattice of two-element half rods,
//! struck (undamped modes) and under a blast with every mode damped (the damped kernels, the
//! load points, the work and dissipation integrals); and the energy, dashpot power and damping
//! acceleration of finite-element cells with resonator dashpots mid-run (eight resonators summed
//! at once, four per vector there). Tolerance: none; the
//! SIMD build is compiled without FMA contraction, so every operation rounds the same way. (On a
//! CPU without AVX2 both paths are the portable one and the claim holds trivially.)

use woodpile::ode::ChainOde;
use woodpile::{CellModel, ChainBuilder, Excitation, Integrator, Method, Striker};

fn states(method: Method, steps: usize) -> (Vec<f64>, Vec<f64>) {
    let chain = ChainBuilder::table1_rods(&woodpile::PAPER_OPTIMIZED_CHAIN_MM, CellModel::Resonant)
        .unwrap()
        .build()
        .unwrap();
    let excitation = Excitation::Impact(Striker::paper());
    let run = |portable: bool| {
        let mut ode = ChainOde::new(&chain, &excitation).unwrap();
        let units = ode.tolerance_units();
        let y0 = ode.initial_state();
        let mut integ = Integrator::new(method, &mut ode, 0.0, y0, &units, 1e-6);
        for _ in 0..steps {
            if portable {
                integ.step_portable(&mut ode, 1.0).unwrap();
            } else {
                integ.step(&mut ode, 1.0).unwrap();
            }
        }
        integ.y().to_vec()
    };
    (run(false), run(true))
}

#[test]
fn fixed_step_is_bit_identical() {
    let (simd, portable) = states(Method::Rk4 { time_step_s: 1e-7 }, 2000);
    assert_bits_equal(&simd, &portable);
    assert!(simd.iter().any(|&x| x != 0.0), "the wave moved something");
}

#[test]
fn adaptive_step_is_bit_identical() {
    let (simd, portable) = states(
        Method::Dopri5 {
            rtol: 1e-9,
            atol: 1e-15,
        },
        300,
    );
    assert_bits_equal(&simd, &portable);
}

#[test]
fn exact_modal_step_is_bit_identical() {
    let rod = woodpile::Rod::new(80e-3, 5e-3, 0.0, woodpile::Material::fused_quartz()).unwrap();
    let cell = woodpile::UnitCell::from_rod_fe(&rod, 16).unwrap();
    let elements = (0..5)
        .map(|_| {
            let mut e = woodpile::Element::table1_rod(80, CellModel::Resonant).unwrap();
            e.cell = cell.clone();
            e
        })
        .collect();
    let chain = ChainBuilder::new(elements).build().unwrap();
    let ode = ChainOde::new(&chain, &Excitation::Impact(Striker::paper())).unwrap();
    let run = |portable| {
        woodpile::integrate::exact_modes_state(&ode, (1e-6, 1e-15, 1e-8), 300, portable).unwrap()
    };
    let (simd, portable) = (run(false), run(true));
    assert_bits_equal(&simd, &portable);
    assert!(simd.iter().any(|&x| x != 0.0), "the wave moved something");
}

#[test]
fn exact_modal_lattice_step_is_bit_identical() {
    use woodpile::model::{Damping, LatticeExcitation, LatticeLab, LoadPoints};
    let lattice = super::lattice_common::three_by_four(2);
    let struck = woodpile::ode::LatticeOde::new(&lattice, &Striker::paper(), [13e-3, 0.0]).unwrap();
    let lab = LatticeLab {
        damping: Damping {
            on_site_time_s: Some(1e-3),
            ..Damping::default()
        },
        modal_ratio: 0.02,
        ..LatticeLab::default()
    };
    let blast = LatticeExcitation::Blast {
        profile: woodpile::BlastProfile::Friedlander {
            peak_force_n: 200.0,
            duration_s: 1e-4,
            decay: 1.0,
        },
        points: LoadPoints::TopCrossings,
    };
    let blasted = woodpile::ode::LatticeOde::build(&lattice, &blast, &lab).unwrap();
    for ode in [struck, blasted] {
        let run = |portable| {
            woodpile::integrate::exact_modes_lattice_state(&ode, (1e-8, 1e-14), 5e-4, 300, portable)
                .unwrap()
        };
        let (simd, portable) = (run(false), run(true));
        assert_bits_equal(&simd, &portable);
        let q = ode.coordinates();
        assert!(
            simd[..q].iter().any(|&x| x != 0.0),
            "the load moved the modes"
        );
    }
}

#[test]
fn damped_cell_energy_is_bit_identical() {
    use woodpile::model::Damping;
    // Three rods as finite-element beams with resonator damping (ζ = 1 %) and on-site damping,
    // struck, at a state 200 DOPRI5 steps in (every mode moving).
    let damping = Damping {
        on_site_time_s: Some(2e-4),
        resonator_ratio: 0.01,
        ..Damping::default()
    };
    let chain = ChainBuilder::new(super::lattice_common::fe_rod_elements(
        &[80.0, 40.0, 20.0],
        8,
    ))
    .damping(damping)
    .build()
    .unwrap();
    let mut ode = ChainOde::new(&chain, &Excitation::Impact(Striker::paper())).unwrap();
    let units = ode.tolerance_units();
    let y0 = ode.initial_state();
    let method = Method::Dopri5 {
        rtol: 1e-8,
        atol: 1e-14,
    };
    let mut integ = Integrator::new(method, &mut ode, 0.0, y0, &units, 1e-8);
    for _ in 0..200 {
        integ.step_portable(&mut ode, 1.0).unwrap();
    }
    let cells = woodpile::ode::damped_cell_energies(&ode, integ.y()).unwrap();
    assert_eq!(cells.len(), 3);
    for [(e, p, a), (e0, p0, a0)] in &cells {
        assert_bits_equal(&[*e, *p, *a], &[*e0, *p0, *a0]);
    }
    let (energy, power, _) = cells[0][0];
    assert!(energy > 0.0 && power > 0.0, "the struck cell moves");
}

/// Both states bit for bit equal.
fn assert_bits_equal(simd: &[f64], portable: &[f64]) {
    assert_eq!(simd.len(), portable.len());
    assert!(simd
        .iter()
        .zip(portable)
        .all(|(a, b)| a.to_bits() == b.to_bits()));
}
