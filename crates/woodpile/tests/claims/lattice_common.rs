//! The lattice the lattice claims share: four layers of three 80 mm quartz rods (5 mm, pitch
//! 20 mm) crossed at 90° on the paper's sensors, one under the centre of each bottom rod.

use woodpile::model::{Lattice, LatticeBuilder, LayerSpec};
use woodpile::Material;

/// The 3 × 3-rod, 4-layer lattice with `elements` per half rod.
pub fn three_by_four(elements: usize) -> Lattice {
    let layer = LayerSpec {
        rods: 3,
        pitch_m: 20e-3,
        length_m: 80e-3,
        diameter_m: 5e-3,
        material: Material::fused_quartz(),
        angle_deg: 90.0,
    };
    LatticeBuilder::new(vec![layer; 4], elements)
        .build()
        .unwrap()
}
