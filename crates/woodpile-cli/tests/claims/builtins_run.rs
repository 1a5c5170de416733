//! Claim: the built-in scenarios are the list (the paper's homogeneous 20/40/80 mm chains
//! and docs/physics.md §9's optimised chain, under impact and blast, each resonant and rigid), every one
//! resolves to a 20-element chain, and a short run (0.1 ms) of each completes with finite,
//! positive peak forces.

use std::path::Path;
use woodpile::{simulate, Excitation, RunSettings};
use woodpile_io::scenario::{builtin, builtin_names, resolve, DEFAULT_SCENARIO};

#[test]
fn the_list_is_complete() {
    let names = builtin_names();
    for load in ["impact", "blast"] {
        for chain in ["20mm", "40mm", "80mm", "optimized"] {
            for suffix in ["", "-rigid"] {
                let n = format!("paper-{load}-{chain}{suffix}");
                assert!(names.contains(&n), "missing {n}");
            }
        }
    }
    assert_eq!(names.len(), 16);
    assert_eq!(DEFAULT_SCENARIO, "paper-impact-optimized");
}

#[test]
fn every_builtin_resolves_and_runs() {
    for name in builtin_names() {
        let s = builtin(&name).unwrap();
        assert!(s.description.is_some(), "{name} has a description");
        let r = resolve(&s, Path::new(".")).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(r.chain.len(), 20, "{name}");
        let rigid = name.ends_with("-rigid");
        let any_resonators = r
            .chain
            .elements()
            .iter()
            .any(|e| !e.cell.resonators.is_empty());
        assert_eq!(any_resonators, !rigid, "{name}: model");
        match (&r.excitation, name.contains("impact")) {
            (Excitation::Impact(_), true) | (Excitation::Blast(_), false) => {}
            _ => panic!("{name}: wrong excitation"),
        }
        let expected_duration = if name.contains("impact") { 2e-3 } else { 3e-3 };
        assert_eq!(r.settings.duration_s, expected_duration, "{name}");
        let short = RunSettings {
            duration_s: 1e-4,
            ..r.settings
        };
        let summary = simulate(&r.chain, &r.excitation, &short, &mut ()).unwrap();
        assert!(summary.incident_peak_force_n > 0.0 && summary.incident_peak_force_n.is_finite());
        assert!(summary.contact_peak_forces_n.iter().all(|f| f.is_finite()));
    }
}
