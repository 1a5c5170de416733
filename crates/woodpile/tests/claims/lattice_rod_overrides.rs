//! Claim: per-rod overrides of a layer (`lengths_mm`, `offsets_mm`; docs/physics.md §16) move
//! the crossings where the geometry says. A rod shifted by o along its own axis meets a crossing
//! rod at the axial coordinate s − o (exactly: the crossing point is the same, the rod's centre
//! moved); a shorter rod of a graded layer loses the crossings beyond its ends and keeps the
//! others with the same β; overrides equal to the layer's own length and no offset give the
//! identical lattice. Overrides that cannot stand are refused naming the dotted key as written
//! (`lattice.layers[k].lengths_mm`, `…lengths_mm[i]`, `…offsets_mm[i]`), the value in mm and what
//! is valid: a wrong count, a length that is not > 0, an offset that is not finite, a rod moved
//! off every rod of the adjacent layers.

use woodpile::model::{LatticeBuilder, LayerSpec, RodOverrides};
use woodpile::{Error, Material};

fn layer() -> LayerSpec {
    super::lattice_common::three_rod_layer()
}

fn with(overrides: Vec<RodOverrides>) -> LatticeBuilder {
    let mut b = LatticeBuilder::new(vec![layer(), layer()], 2);
    b.overrides = overrides;
    b
}

fn mm(v: &[f64]) -> Option<Vec<f64>> {
    Some(v.iter().map(|x| x * 1e-3).collect())
}

fn refusal(b: LatticeBuilder) -> (String, String, String) {
    match b.build().unwrap_err() {
        Error::InvalidParameter {
            field,
            value,
            reason,
        } => (field, value, reason),
        other => panic!("expected an invalid parameter, got {other}"),
    }
}

#[test]
fn overrides_move_the_crossings_where_the_geometry_says() {
    let plain = with(Vec::new()).build().unwrap();
    let same = with(vec![
        RodOverrides {
            lengths_m: mm(&[80.0, 80.0, 80.0]),
            offsets_m: mm(&[0.0, 0.0, 0.0]),
        };
        2
    ])
    .build()
    .unwrap();
    assert_eq!(plain, same, "overrides equal to the layer's own values");

    // Top rods along x at y = −20, 0, 20 mm, shifted by −10, 0, 10 mm along x; the lower rods
    // along y at x = −20, 0, 20 mm, the middle one 30 mm long (it reaches y = ±15 mm only).
    let offsets = [-10.0, 0.0, 10.0];
    let graded = with(vec![
        RodOverrides {
            lengths_m: None,
            offsets_m: mm(&offsets),
        },
        RodOverrides {
            lengths_m: mm(&[80.0, 30.0, 80.0]),
            offsets_m: None,
        },
    ])
    .build()
    .unwrap();
    let crossings: Vec<_> = graded
        .contacts
        .iter()
        .filter(|c| c.below.is_some())
        .collect();
    assert_eq!(
        crossings.len(),
        7,
        "9 crossings less the middle rod's two beyond ±15 mm"
    );
    for c in &crossings {
        let (a, b) = (
            &graded.rods[c.above.rod],
            &graded.rods[c.below.unwrap().rod],
        );
        let (x, y) = (
            (b.number as f64 - 2.0) * 20e-3,
            (a.number as f64 - 2.0) * 20e-3,
        );
        assert!(
            b.number != 2 || a.number == 2,
            "the short rod meets only the middle top rod"
        );
        assert!((c.point_m[0] - x).abs() < 1e-15 && (c.point_m[1] - y).abs() < 1e-15);
        let shift = offsets[a.number - 1] * 1e-3;
        assert!(
            (c.above.s_m - (x - shift)).abs() < 1e-15,
            "s on the shifted rod"
        );
        assert!(
            (c.below.unwrap().s_m - y).abs() < 1e-15,
            "s on the lower rod"
        );
        let twin = plain
            .contacts
            .iter()
            .find(|p| {
                p.below.is_some()
                    && (p.point_m[0] - c.point_m[0]).abs() < 1e-15
                    && (p.point_m[1] - c.point_m[1]).abs() < 1e-15
            })
            .unwrap();
        assert_eq!(
            c.beta, twin.beta,
            "β depends on the sections and the angle only"
        );
    }
    // The short rod is lighter by 50 mm of rod.
    let rod = woodpile::Rod::new(80e-3, 5e-3, 0.0, Material::fused_quartz()).unwrap();
    let expected = plain.mass_kg() - rod.mass_kg() * 50.0 / 80.0;
    assert!((graded.mass_kg() / expected - 1.0).abs() < 1e-14);
}

#[test]
fn bad_overrides_are_refused_naming_the_key() {
    let lower = |o: RodOverrides| with(vec![RodOverrides::default(), o]);
    let (field, value, reason) = refusal(lower(RodOverrides {
        lengths_m: mm(&[80.0, 80.0]),
        offsets_m: None,
    }));
    assert_eq!(field, "lattice.layers[1].lengths_mm");
    assert_eq!(value, "2 entries");
    assert!(
        reason.contains("one entry per rod of the layer: 3"),
        "{reason}"
    );

    let (field, value, reason) = refusal(lower(RodOverrides {
        lengths_m: mm(&[80.0, -5.0, 80.0]),
        offsets_m: None,
    }));
    assert_eq!(
        (field.as_str(), value.as_str()),
        ("lattice.layers[1].lengths_mm[1]", "-5")
    );
    assert!(reason.contains("> 0"), "{reason}");

    let (field, _, _) = refusal(lower(RodOverrides {
        lengths_m: None,
        offsets_m: Some(vec![0.0, f64::NAN, 0.0]),
    }));
    assert_eq!(field, "lattice.layers[1].offsets_mm[1]");

    let (field, value, reason) = refusal(lower(RodOverrides {
        lengths_m: None,
        offsets_m: mm(&[0.0, 0.0, 200.0]),
    }));
    assert_eq!(
        (field.as_str(), value.as_str()),
        ("lattice.layers[1].offsets_mm[2]", "200")
    );
    assert!(
        reason.contains("rod 3 of this layer crosses no rod"),
        "{reason}"
    );

    // Under two top rods (y = ±10 mm), a lower rod cut to 4 mm spans y = ±2 mm and meets none.
    let mut two = vec![layer(), layer()];
    two[0].rods = 2;
    let mut short = LatticeBuilder::new(two, 2);
    short.overrides = vec![
        RodOverrides::default(),
        RodOverrides {
            lengths_m: mm(&[80.0, 80.0, 4.0]),
            offsets_m: None,
        },
    ];
    let (field, value, _) = refusal(short);
    assert_eq!(
        (field.as_str(), value.as_str()),
        ("lattice.layers[1].lengths_mm[2]", "4")
    );
}
