//! Claim: a displacement drive's actuator is rigid, so at rest under a preload F_p its tips carry
//! the shares of the static equilibrium, not F_p/N each (docs/physics.md §16, "Blasts and
//! drives"). Everything is checked from public data: the tips' static forces
//! (`contact_static_forces_n`), their β, the rods' modes at the points and the static state q*.
//!
//! (1) A seesaw: one 80 mm quartz rod on a single support under its centre, pressed at
//! s₁ = −10 mm and s₂ = +25 mm by the actuator (the paper's sensor as tip, F_p = 2 N). The rod's
//! rigid modes are in equilibrium only if the tips' moment about the support vanishes, so the
//! shares are the lever rule's, F₁ = F_p s₂ / (s₂ − s₁) = 1.43 N and F₂ = 0.57 N, whatever the
//! rod's and the contacts' flexibility (a rod's net force and moment are the gradient of Π along
//! its rigid modes, exact in the modal model). Equal shares would leave the moment
//! (F_p/2)(s₁ + s₂) ≠ 0 on the rod: no equilibrium. Tolerance 1e-10 of F_p: the static solve
//! stops at |∇Π| ≤ 1e-12 |f| (|f| = F_p, on the actuator), and the rocking mode's gradient is the
//! moment about the support over √I (m L²/12 of a 3.46 g rod: √I = 1.4e-3 kg^½ m), so the moment
//! left is at most 1e-12 F_p √I, a share error of about 4e-14 of F_p at the 35 mm lever; the
//! rest of the bound is margin for rounding (measured 1.9e-15).
//!
//! (2) The 3 × 3-rod, 4-layer lattice pressed at three points of its three top rods, at
//! s = +5, −15 and +18 mm from their centres (within the crossings below, at 0 and ±20 mm, beyond which a rod would tip over) (statically indeterminate: the shares follow from
//! the lattice's and the tips' compliance), F_p = 3 N:
//! - the tips' static forces sum to F_p within 1e-12 of F_p (the actuator's own equation,
//!   ∂Π/∂u = F_p − Σ F_i, is one component of the gradient the solve drives below 1e-12 |f|);
//! - every tip stands at the one actuator height u* (`LatticeOde::actuator_rest_m`): its
//!   overlap (F_i/β_i)^{2/3} plus its point's static deflection w_i(q*) equals u* within 1e-12
//!   of u* (rounding of the deflection's modal sum and of the 2/3 power; no shims);
//! - the shares differ: the largest exceeds the smallest by more than 10 % of F_p/N (the rule
//!   F_p/N each, in force before, fails this claim);
//! - held still for 1 ms (a displacement table that is 0 over the whole run; DOPRI5 at rtol
//!   1e-10), every tip's force stays at its static value within 1e-7 of F_p — the bound of
//!   claim `lattice_static_equilibrium` for a state that should not move (the integrator's error
//!   on it; the equilibrium itself is exact to 1e-12 |f|).
//!
//! (3) The same points on the lattice as built, its bottom rods each on one support under its
//! centre (all on the line y = 0): the bottom rods are seesaws, and two combinations of rigid
//! modes cost nothing — the lattice tipping about that line and twisting (each seesaw tipped in
//! proportion to its x) — so any equilibrium has Σ F_i y_i = 0 and Σ F_i x_i y_i = 0. With
//! the points at y = −20, 0, +20 mm and x = 5, −15, 18 mm that forces the outer tips' forces to 0
//! and the middle one's to F_p (both within 1e-12 of F_p, the solve's residual); with F_p/N on
//! each point (a force drive) there is no equilibrium, refused naming `preload`.
//!
//! (4) An actuator pressing a top rod at one point only, beyond its last crossing, tips it
//! over: no equilibrium, refused naming `preload` with the solve's residual. (A rigid actuator
//! with other points would rest on them, its tip there at no force.)
//!
//! (5) Without a preload, under gravity alone (the lattice of (2), the same points): the
//! actuator rests on the highest of its points at no force. Every tip's static force is 0, the
//! actuator's height u* is the smallest of the points' static deflections w_i(q*) (downward)
//! within 1e-12 of it (rounding of the modal sums: the highest tip touches, δ = u* − w = 0), and
//! the other tips are open, below it by more than 1e-6 of u* (gravity bends the lattice
//! differently under points 5, 15 and 18 mm from the rods' centres).

use super::lattice_common::{quartz_layer, three_by_four, three_rod_layer};
use woodpile::model::{
    Lattice, LatticeBuilder, LatticeExcitation, LatticeLab, LoadPoints, RodPoint, Supports,
};
use woodpile::ode::LatticeOde;
use woodpile::simulate::simulate_lattice;
use woodpile::{Drive, DriveQuantity, Method, Preload, RunSettings, Signal, Wall};

/// A displacement drive held at 0 up to `hold_s` (a table that only moves after it).
fn held_drive(hold_s: f64) -> Drive {
    Drive {
        quantity: DriveQuantity::Displacement {
            tip: Wall::paper_sensor(),
        },
        signal: Signal::Table {
            times_s: vec![0.0, hold_s, 2.0 * hold_s],
            values: vec![0.0, 0.0, 1e-7],
        },
        ramp_s: 0.0,
    }
}

/// The lattice under the actuator on the points at axial coordinates `s_mm` of the top rods
/// `rods`, preloaded with `preload_n`: the ODE and the points.
fn pressed(
    lattice: &Lattice,
    rods: &[usize],
    s_mm: &[f64],
    preload_n: f64,
    hold_s: f64,
) -> (LatticeOde, Vec<RodPoint>) {
    let preload = Preload {
        force_n: preload_n,
        gravity_m_s2: 0.0,
    };
    pressed_under(lattice, (rods, s_mm), preload, hold_s)
}

/// [`pressed`] under any static load.
fn pressed_under(
    lattice: &Lattice,
    (rods, s_mm): (&[usize], &[f64]),
    preload: Preload,
    hold_s: f64,
) -> (LatticeOde, Vec<RodPoint>) {
    let points_m: Vec<[f64; 2]> = rods
        .iter()
        .zip(s_mm)
        .map(|(&r, &s)| lattice.rods[r].point_m(s * 1e-3))
        .collect();
    let load = LoadPoints::Points(points_m);
    let points = load.on(lattice).unwrap();
    let excitation = LatticeExcitation::Drive {
        drive: held_drive(hold_s),
        points: load,
    };
    let lab = LatticeLab {
        preload,
        ..LatticeLab::default()
    };
    let ode = LatticeOde::build(lattice, &excitation, &lab).unwrap();
    assert!(ode.has_actuator());
    (ode, points)
}

/// The actuator height each tip implies: its static overlap (F/β)^{2/3} plus its point's
/// deflection w(q*) (state layout: the rods' modes in the lattice's order).
fn tip_heights_m(ode: &LatticeOde, lattice: &Lattice, points: &[RodPoint]) -> Vec<f64> {
    let q = ode.initial_state();
    let offsets: Vec<usize> = lattice
        .rods
        .iter()
        .scan(0, |offset, rod| {
            let first = *offset;
            *offset += rod.modes.modal_row(0.0).len();
            Some(first)
        })
        .collect();
    let (forces, _) = ode.static_forces_n();
    points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let row = lattice.rods[p.rod].modes.modal_row(p.s_m);
            let w: f64 = row
                .iter()
                .zip(&q[offsets[p.rod]..])
                .map(|(r, x)| r * x)
                .sum();
            (forces[i] / ode.contact_betas()[i]).powf(2.0 / 3.0) + w
        })
        .collect()
}

#[test]
fn a_seesaw_pressed_at_two_points_takes_the_lever_rule_shares() {
    let lattice = LatticeBuilder::new(vec![quartz_layer(1, 80e-3)], 4)
        .build()
        .unwrap();
    let (fp, s1, s2) = (2.0, -10.0, 25.0);
    let (ode, points) = pressed(&lattice, &[0, 0], &[s1, s2], fp, 1e-4);
    let (forces, residual) = ode.static_forces_n();
    let expected = [fp * s2 / (s2 - s1), fp * -s1 / (s2 - s1)];
    let worst = (0..2)
        .map(|i| (forces[i] - expected[i]).abs() / fp)
        .fold(0.0_f64, f64::max);
    eprintln!(
        "seesaw: tips {:.15} N, {:.15} N against the lever rule's {:.15} N, {:.15} N: {worst:.2e} \
         of F_p; residual {residual:.2e}",
        forces[0], forces[1], expected[0], expected[1]
    );
    assert!(worst < 1e-10, "the shares miss the lever rule by {worst:e}");
    let u = ode.actuator_rest_m().unwrap();
    for h in tip_heights_m(&ode, &lattice, &points) {
        assert!(
            (h - u).abs() <= 1e-12 * u.abs(),
            "a tip at {h} m, the actuator at {u} m"
        );
    }
}

/// The 3 × 3-rod, 4-layer lattice of [`three_by_four`] on six supports, under each bottom rod
/// at y = ±20 mm, so that no combination of rigid modes is free.
fn three_by_four_on_six_supports() -> Lattice {
    let base = three_by_four(4);
    let layer = three_rod_layer();
    let supports = base
        .supports()
        .flat_map(|s| [-20e-3, 20e-3].map(|y| [s.point_m[0], y]))
        .collect();
    LatticeBuilder {
        supports: Supports::Points(supports),
        ..LatticeBuilder::new(vec![layer; 4], 4)
    }
    .build()
    .unwrap()
}

/// The top rods' indices and the points at s = +5, −15, +18 mm on them.
const POINTS_S_MM: [f64; 3] = [5.0, -15.0, 18.0];

fn top_rods(lattice: &Lattice) -> Vec<usize> {
    let top: Vec<usize> = (0..lattice.rods.len())
        .filter(|&r| lattice.rods[r].layer == 1)
        .collect();
    assert_eq!(top.len(), 3);
    top
}

#[test]
fn an_asymmetric_set_of_points_shares_the_preload_at_one_actuator_height() {
    let lattice = three_by_four_on_six_supports();
    let (fp, hold_s) = (3.0, 1e-3);
    let (mut ode, points) = pressed(&lattice, &top_rods(&lattice), &POINTS_S_MM, fp, hold_s);
    let (forces, residual) = ode.static_forces_n();
    let tips = forces[..3].to_vec();
    let sum: f64 = tips.iter().sum();
    let (low, high) = tips
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(l, h), &f| (l.min(f), h.max(f)));
    let u = ode.actuator_rest_m().unwrap();
    let heights = tip_heights_m(&ode, &lattice, &points);
    let worst_height = heights
        .iter()
        .map(|h| (h - u).abs() / u.abs())
        .fold(0.0_f64, f64::max);
    eprintln!(
        "tips {tips:?} N, sum − F_p = {:.2e} N, spread {:.3} of F_p/N; actuator at {u:.6e} m, \
         tips' heights within {worst_height:.2e} of it; residual {residual:.2e}",
        sum - fp,
        (high - low) / (fp / 3.0)
    );
    assert!((sum - fp).abs() <= 1e-12 * fp, "the tips carry {sum} N");
    assert!(
        worst_height <= 1e-12,
        "a tip is shimmed by {worst_height:e} of u*"
    );
    assert!(
        high - low > 0.1 * fp / 3.0,
        "the shares {tips:?} are (nearly) equal"
    );

    let settings = RunSettings {
        duration_s: hold_s,
        method: Method::Dopri5 {
            rtol: 1e-10,
            atol: 1e-14,
        },
        sample_interval_s: 1e-5,
    };
    let run = simulate_lattice(&mut ode, &settings).unwrap();
    let mut drift = 0.0_f64;
    for (c, f0) in tips.iter().enumerate() {
        for f in run.contact_force_n(c) {
            drift = drift.max((f - f0).abs() / fp);
        }
    }
    eprintln!("held still for {hold_s} s: the tips' forces drift by {drift:.2e} of F_p");
    assert!(drift < 1e-7, "the tips' forces drift by {drift:e} of F_p");
}

#[test]
fn on_a_line_of_supports_the_mechanisms_put_the_whole_preload_on_the_middle_tip() {
    let lattice = three_by_four(4);
    let top = top_rods(&lattice);
    let middle = top
        .iter()
        .position(|&r| lattice.rods[r].centre_m[1] == 0.0)
        .unwrap();
    let fp = 3.0;
    let (ode, _) = pressed(&lattice, &top, &POINTS_S_MM, fp, 1e-4);
    let (forces, residual) = ode.static_forces_n();
    let outer = (0..3)
        .filter(|&i| i != middle)
        .map(|i| forces[i])
        .fold(0.0_f64, f64::max);
    eprintln!(
        "line of supports: middle tip {:.15} N, outer tips at most {outer:.2e} N; residual \
         {residual:.2e}",
        forces[middle]
    );
    assert!((forces[middle] - fp).abs() <= 1e-12 * fp);
    assert!(outer <= 1e-12 * fp);

    // The same points under a force drive with F_p/3 each: no equilibrium.
    let points_m = top
        .iter()
        .zip(&POINTS_S_MM)
        .map(|(&r, &s)| lattice.rods[r].point_m(s * 1e-3))
        .collect();
    let excitation = LatticeExcitation::Drive {
        drive: Drive {
            quantity: DriveQuantity::Force,
            ..held_drive(1e-4)
        },
        points: LoadPoints::Points(points_m),
    };
    let lab = LatticeLab {
        preload: Preload {
            force_n: fp,
            gravity_m_s2: 0.0,
        },
        ..LatticeLab::default()
    };
    let refused = LatticeOde::build(&lattice, &excitation, &lab).unwrap_err();
    eprintln!("equal shares: {refused}");
    assert!(refused.to_string().contains("preload"), "{refused}");
}

#[test]
fn a_rod_the_actuator_tips_over_is_refused_naming_the_preload() {
    // An outer top rod pressed at s = +31 mm alone, beyond its last crossing (+20 mm): it tips
    // over. (With a second point elsewhere the actuator would rest on that one alone.)
    let lattice = three_by_four_on_six_supports();
    let top = top_rods(&lattice);
    let excitation = LatticeExcitation::Drive {
        drive: held_drive(1e-4),
        points: LoadPoints::Points(vec![lattice.rods[top[0]].point_m(31e-3)]),
    };
    let lab = LatticeLab {
        preload: Preload {
            force_n: 2.0,
            gravity_m_s2: 0.0,
        },
        ..LatticeLab::default()
    };
    match LatticeOde::build(&lattice, &excitation, &lab) {
        Err(woodpile::Error::InvalidParameter { field, value, .. }) => {
            eprintln!("refused: {field} = {value}");
            assert_eq!(field, "preload");
            let residual: f64 = value.rsplit(' ').next().unwrap().parse().unwrap();
            assert!(residual > 1e-12, "{value}");
        }
        Err(e) => panic!("refused otherwise: {e}"),
        Ok(_) => panic!("a tipped-over rod found an equilibrium"),
    }
}

#[test]
fn without_a_preload_the_actuator_rests_on_its_highest_point() {
    let lattice = three_by_four_on_six_supports();
    let gravity = Preload {
        force_n: 0.0,
        gravity_m_s2: 9.81,
    };
    let (ode, points) = pressed_under(&lattice, (&top_rods(&lattice), &POINTS_S_MM), gravity, 1e-4);
    let (forces, _) = ode.static_forces_n();
    let u = ode.actuator_rest_m().unwrap();
    // With no force on a tip its implied height is its point's deflection w_i(q*).
    let deflections = tip_heights_m(&ode, &lattice, &points);
    let highest = deflections.iter().copied().fold(f64::INFINITY, f64::min);
    let gaps: Vec<f64> = deflections.iter().map(|w| (w - u) / u.abs()).collect();
    eprintln!(
        "tips' static forces {:?} N; actuator at {u:.6e} m, points at {deflections:?} m: \
         gaps {gaps:?} of u*",
        &forces[..3]
    );
    assert!(forces[..3].iter().all(|&f| f == 0.0), "{:?}", &forces[..3]);
    assert!(
        (u - highest).abs() <= 1e-12 * u.abs(),
        "the actuator at {u}, the highest point at {highest}"
    );
    let open = gaps.iter().filter(|&&g| g > 1e-6).count();
    assert_eq!(open, 2, "gaps {gaps:?}");
}
