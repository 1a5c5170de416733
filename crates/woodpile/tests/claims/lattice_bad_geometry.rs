//! Claim: a lattice that cannot stand as described is refused with an error naming the
//! scenario key and the value (docs/physics.md §16): layers whose rods do not cross within
//! both lengths (`lattice.layers[k]`), a support under no bottom rod (`wall.supports[j]`), an
//! impact point on no top rod (`excitation.at_mm`), parallel layers (`lattice.layers[k].angle_deg`)
//! and rods of a layer that overlap (`lattice.layers[k].pitch_mm`).

use woodpile::model::{LatticeBuilder, LayerSpec, Supports};
use woodpile::ode::LatticeOde;
use woodpile::{Error, Material, Striker};

fn layer(rods: usize, pitch_mm: f64, length_mm: f64) -> LayerSpec {
    LayerSpec {
        rods,
        pitch_m: pitch_mm * 1e-3,
        length_m: length_mm * 1e-3,
        diameter_m: 5e-3,
        material: Material::fused_quartz(),
        angle_deg: 90.0,
    }
}

fn field(e: Error) -> String {
    match e {
        Error::InvalidParameter { field, .. } => field,
        other => panic!("expected an invalid parameter, got {other}"),
    }
}

#[test]
fn refused_geometries_name_their_key() {
    // Two short rods at x = ±30 mm under a 20 mm rod along x at the origin: no crossing.
    let apart = LatticeBuilder::new(vec![layer(1, 20.0, 20.0), layer(2, 60.0, 20.0)], 2);
    let e = apart.build().unwrap_err();
    assert!(e.to_string().contains("do not touch"), "{e}");
    assert_eq!(field(e), "lattice.layers[1]");

    let mut parallel = vec![layer(3, 20.0, 80.0), layer(3, 20.0, 80.0)];
    parallel[1].angle_deg = 180.0;
    let e = LatticeBuilder::new(parallel, 2).build().unwrap_err();
    assert_eq!(field(e), "lattice.layers[1].angle_deg");

    let crowded = LatticeBuilder::new(vec![layer(3, 4.0, 80.0), layer(3, 20.0, 80.0)], 2);
    assert_eq!(
        field(crowded.build().unwrap_err()),
        "lattice.layers[0].pitch_mm"
    );

    let mut off = LatticeBuilder::new(vec![layer(3, 20.0, 80.0), layer(3, 20.0, 80.0)], 2);
    off.supports = Supports::Points(vec![[-20e-3, 0.0], [10e-3, 10e-3]]);
    let e = off.build().unwrap_err();
    assert!(e.to_string().contains("y_mm = 10"), "{e}");
    assert_eq!(field(e), "wall.supports[1]");

    let lattice = LatticeBuilder::new(vec![layer(3, 20.0, 80.0), layer(3, 20.0, 80.0)], 2)
        .build()
        .unwrap();
    let e = LatticeOde::new(&lattice, &Striker::paper(), [10e-3, 10e-3]).unwrap_err();
    assert_eq!(field(e), "excitation.at_mm");
    let e = LatticeOde::new(&lattice, &Striker::paper(), [45e-3, 0.0]).unwrap_err();
    assert_eq!(field(e), "excitation.at_mm");
    assert!(LatticeOde::new(&lattice, &Striker::paper(), [39e-3, 2e-3]).is_ok());
}
