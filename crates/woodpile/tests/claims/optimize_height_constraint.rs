//! Claim: `max_stack_height_m` is a constraint the GA proves satisfiable before any simulation
//! (a limit below the lowest design is refused with both heights) and keeps by repair: random
//! genomes repaired under a height and a mass limit together meet both, on a catalogue where
//! the lighter rods are the taller ones (so the two repairs pull against each other).
//!
//! Tolerance: the limits' relative slack of 1e-12 (summation order).

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use woodpile::optimize::{DesignSpace, FeasibleSet, OptimizeError};
use woodpile::{Body, CellModel, Element};

/// Table 1 rods of 5 mm, and a thick (8 mm) copy of the 20 mm rod that is lighter than the
/// 40 mm rod: heights and masses disagree.
fn space() -> DesignSpace {
    let mut s = DesignSpace::paper_impact(CellModel::Resonant);
    s.positions = 6;
    let mut thick = Element::table1_rod(20, CellModel::Resonant).unwrap();
    thick.label = "20mm-d8".into();
    thick.body = Body::Rod {
        diameter_m: 8e-3,
        length_m: 20e-3,
    };
    s.catalogue = vec![
        thick,
        Element::table1_rod(40, CellModel::Resonant).unwrap(),
        Element::table1_rod(80, CellModel::Resonant).unwrap(),
    ];
    s
}

#[test]
fn a_height_no_design_meets_is_refused_with_the_numbers() {
    let mut s = space();
    s.constraints.max_stack_height_m = Some(29e-3);
    match FeasibleSet::new(&s) {
        Err(
            e @ OptimizeError::TooTall {
                lowest_m,
                max_stack_height_m,
                ..
            },
        ) => {
            assert!(
                (lowest_m - 30e-3).abs() < 1e-15,
                "six 5 mm rods stand 30 mm: {lowest_m}"
            );
            assert_eq!(max_stack_height_m, 29e-3);
            assert!(e.to_string().contains("max_stack_height_m"), "{e}");
        }
        other => panic!("expected TooTall, got {other:?}"),
    }
    s.constraints.max_stack_height_m = Some(-1.0);
    let e = FeasibleSet::new(&s).unwrap_err().to_string();
    assert!(e.contains("max_stack_height_m") && e.contains("-1"), "{e}");
}

#[test]
fn repair_meets_height_and_mass_together() {
    let mut s = space();
    let masses: Vec<f64> = s.catalogue.iter().map(|e| e.cell.total_mass_kg()).collect();
    assert!(masses[0] < masses[1], "the thick rod is the lighter one");
    // At most two thick rods (6 × 5 mm + 2 × 3 mm = 36 mm), and lighter than four 40 mm rods
    // and two 80 mm ones.
    s.constraints.max_stack_height_m = Some(36e-3);
    s.constraints.max_total_mass_kg = Some(4.0 * masses[1] + 2.0 * masses[0]);
    let set = FeasibleSet::new(&s).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let limit_h = 36e-3 * (1.0 + 1e-12);
    let limit_m = s.constraints.max_total_mass_kg.unwrap() * (1.0 + 1e-12);
    for k in 0..2000u32 {
        let mut g: Vec<u8> = (0..6)
            .map(|i| ((k.wrapping_mul(2654435761) >> (3 * i)) % 3) as u8)
            .collect();
        set.repair(&mut g, &mut rng);
        assert!(
            s.height_m(&g) <= limit_h,
            "{g:?} stands {} m",
            s.height_m(&g)
        );
        assert!(
            s.mass_kg(&g) <= limit_m,
            "{g:?} weighs {} kg",
            s.mass_kg(&g)
        );
        assert!(set.contains(&g));
        let r = set.random(&mut rng);
        assert!(set.contains(&r));
    }
}
