//! What the lattice claims share: four layers of three 80 mm quartz rods (5 mm, pitch 20 mm)
//! crossed at 90° on the paper's sensors, one under the centre of each bottom rod; and the
//! elements of an FE-rod chain a one-rod-per-layer lattice is compared with.

use woodpile::model::{Lattice, LatticeBuilder, LayerSpec};
use woodpile::{Element, Material, Rod, UnitCell};

/// A layer of `rods` fused-quartz rods of `length_m`, 5 mm across, at a 20 mm pitch, crossed
/// at 90° with the layer above.
pub fn quartz_layer(rods: usize, length_m: f64) -> LayerSpec {
    LayerSpec {
        rods,
        pitch_m: 20e-3,
        length_m,
        diameter_m: 5e-3,
        material: Material::fused_quartz(),
        angle_deg: 90.0,
    }
}

/// A layer of three 80 mm, 5 mm quartz rods at a 20 mm pitch, crossed at 90°.
pub fn three_rod_layer() -> LayerSpec {
    quartz_layer(3, 80e-3)
}

/// The 3 × 3-rod, 4-layer lattice with `elements` per half rod.
pub fn three_by_four(elements: usize) -> Lattice {
    LatticeBuilder::new(vec![three_rod_layer(); 4], elements)
        .build()
        .unwrap()
}

/// A chain's elements: 5 mm quartz rods of `lengths_mm`, each a finite-element rod of `elements`
/// per half rod (`cell = { fe_elements }`).
pub fn fe_rod_elements(lengths_mm: &[f64], elements: usize) -> Vec<Element> {
    let quartz = Material::fused_quartz();
    lengths_mm
        .iter()
        .map(|&l| {
            let rod = Rod::new(l * 1e-3, 5e-3, 0.0, quartz.clone()).unwrap();
            Element {
                label: format!("{l}mm"),
                body: woodpile::Body::Rod {
                    diameter_m: 5e-3,
                    length_m: l * 1e-3,
                },
                material: quartz.clone(),
                cell: UnitCell::from_rod_fe(&rod, elements).unwrap(),
            }
        })
        .collect()
}
