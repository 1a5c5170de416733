//! Claim: a cell derived from a rod with l = 1..4 resonators (pole–zero reduction) has the rod's
//! total mass ρ·A·L, its effective-mass poles at the centre-blocked frequencies ω_j and its zeros
//! at the free–free symmetric frequencies Ω_j; the modal-mass reduction keeps the mass and the
//! poles. Checked on a solid 80 mm quartz rod and on a steel tube (D 6, d 4 mm, 60 mm). The
//! zeros are found by the cell's own root finder, independent of the beam solver. Tolerance
//! 1e-9 relative: both are bisected to machine precision; the closed-form residues lose a few
//! digits when poles are close.

use woodpile::{BeamTheory, Material, Reduction, Rod, UnitCell};

fn close(a: f64, b: f64, what: &str) {
    assert!((a - b).abs() <= 1e-9 * b.abs(), "{what}: {a} vs {b}");
}

#[test]
fn derived_cells_match_mass_poles_and_zeros() {
    let rods = [
        Rod::new(0.08, 0.005, 0.0, Material::preset("fused-quartz").unwrap()).unwrap(),
        Rod::new(0.06, 0.006, 0.004, Material::preset("steel").unwrap()).unwrap(),
    ];
    for rod in &rods {
        for l in 1..=4 {
            let t = BeamTheory::Timoshenko;
            let poles = rod.centre_blocked_frequencies_hz(t, l).unwrap();
            let zeros = rod.free_symmetric_frequencies_hz(t, l).unwrap();
            let cell = UnitCell::from_rod(rod, Some(l), Reduction::PoleZero).unwrap();
            close(cell.total_mass_kg(), rod.mass_kg(), "total mass");
            for (a, b) in cell.local_resonances_hz().iter().zip(&poles) {
                close(*a, *b, &format!("pole, l = {l}"));
            }
            for (a, b) in cell.free_resonances_hz().iter().zip(&zeros) {
                close(*a, *b, &format!("zero, l = {l}"));
            }
            let modal = UnitCell::from_rod(rod, Some(l), Reduction::ModalMass).unwrap();
            close(modal.total_mass_kg(), rod.mass_kg(), "modal total mass");
            for (a, b) in modal.local_resonances_hz().iter().zip(&poles) {
                close(*a, *b, &format!("modal pole, l = {l}"));
            }
        }
    }
}
