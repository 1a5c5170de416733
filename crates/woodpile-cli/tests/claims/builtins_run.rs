//! Claim: the built-in scenarios are the documented list (the paper's homogeneous 20/40/80 mm chains
//! and docs/physics.md §9's optimised chain, under impact and blast, each resonant and rigid) and
//! the two lab-physics ones (`lab-impact-40mm`: the 40 mm impact with gravity and damping;
//! `transmission-80mm`: the preloaded 80 mm chain under a force chirp, docs/physics.md §14-15),
//! every one resolves to a 20-element chain with its excitation and duration, and a short run
//! (0.1 ms) of each completes with finite, positive peak forces.

use std::path::Path;
use woodpile::{simulate, Excitation, RunSettings, Signal};
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
    for n in ["lab-impact-40mm", "transmission-80mm"] {
        assert!(names.contains(&n.to_string()), "missing {n}");
    }
    assert_eq!(names.len(), 18);
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
        let expected_duration = match (&r.excitation, name.as_str()) {
            (Excitation::Impact(_), n) if n.contains("impact") => 2e-3,
            (Excitation::Blast(_), n) if n.contains("blast") => 3e-3,
            (Excitation::Drive(d), "transmission-80mm") => {
                assert!(matches!(d.signal, Signal::Chirp { .. }), "{name}");
                0.05
            }
            _ => panic!("{name}: wrong excitation"),
        };
        assert_eq!(r.settings.duration_s, expected_duration, "{name}");
        let lab = !name.starts_with("paper-");
        assert_eq!(!r.chain.damping().is_lossless(), lab, "{name}: damping");
        assert_eq!(!r.chain.preload().is_none(), lab, "{name}: preload");
        let short = RunSettings {
            duration_s: 1e-4,
            ..r.settings
        };
        let summary = simulate(&r.chain, &r.excitation, &short, &mut ()).unwrap();
        assert!(summary.incident_peak_force_n > 0.0 && summary.incident_peak_force_n.is_finite());
        assert!(summary.contact_peak_forces_n.iter().all(|f| f.is_finite()));
    }
}
