//! The built-in scenarios: the paper's homogeneous and optimised chains under impact and blast,
//! each in resonant and rigid form, and two with lab physics (docs/physics.md §14, §15).

use super::{
    ChainSpec, ContactLaw, DampingSpec, ExcitationKind, ExcitationSpec, ModelSpec, PreloadSpec,
    RunSpec, Scenario, SignalKind, SweepSpec,
};
use woodpile::defaults;

/// The scenario `woodpile simulate` runs without arguments: docs/physics.md §9's optimised chain under
/// the paper's impact.
pub const DEFAULT_SCENARIO: &str = "paper-impact-optimized";

/// docs/physics.md §9: the blast-optimised chain, top to bottom \[mm\].
pub use woodpile::PAPER_OPTIMIZED_CHAIN_MM as OPTIMIZED_CHAIN_MM;

/// A built-in scenario: its name and its scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct BuiltinScenario {
    /// Name, e.g. `paper-impact-80mm-rigid`.
    pub name: String,
    /// The scenario (its `description` says what it is).
    pub scenario: Scenario,
}

/// (stem, rods, description of the chain).
fn chains() -> Vec<(&'static str, Vec<u32>, &'static str)> {
    vec![
        ("20mm", vec![20; 20], "20 identical 20 mm rods"),
        ("40mm", vec![40; 20], "20 identical 40 mm rods"),
        ("80mm", vec![80; 20], "20 identical 80 mm rods"),
        (
            "optimized",
            OPTIMIZED_CHAIN_MM.to_vec(),
            "the optimised 20-rod chain of docs/physics.md §9 (50 80 80 80 60 70 80 80 40 30 40 40 40 30 50 40 20 20 30 50)",
        ),
    ]
}

/// Names of every built-in scenario, in listing order.
pub fn builtin_names() -> Vec<String> {
    all().into_iter().map(|b| b.name).collect()
}

/// Every built-in scenario, in listing order.
pub fn all() -> Vec<BuiltinScenario> {
    let mut out = Vec::new();
    let loads = [
        (
            ExcitationKind::Impact,
            "striker: 10 mm glass sphere dropped from 0.20 m, 2 ms",
        ),
        (
            ExcitationKind::Blast,
            "Friedlander blast F0 = 200 N, Td = 0.2 ms, 3 ms",
        ),
    ];
    for (kind, load) in loads {
        let kind_name = kind.name();
        for (stem, rods, what) in chains() {
            for model in [ModelSpec::Resonant, ModelSpec::Rigid] {
                let suffix = match model {
                    ModelSpec::Resonant => "",
                    ModelSpec::Rigid => "-rigid",
                };
                let scenario = Scenario {
                    description: Some(format!(
                        "{} model, {what}; {load}",
                        match model {
                            ModelSpec::Resonant => "Resonant",
                            ModelSpec::Rigid => "Rigid",
                        }
                    )),
                    chain: ChainSpec {
                        rods_mm: Some(rods.clone()),
                        model: Some(model),
                        ..ChainSpec::default()
                    },
                    excitation: ExcitationSpec {
                        kind,
                        ..ExcitationSpec::default()
                    },
                    ..Scenario::default()
                };
                out.push(BuiltinScenario {
                    name: format!("paper-{kind_name}-{stem}{suffix}"),
                    scenario: scenario.complete(),
                });
            }
        }
    }
    out.extend(lab());
    out
}

/// The lab-physics built-ins: the paper's 40 mm impact with gravity and damping, and the
/// preloaded 80 mm chain of `woodpile transmission`.
fn lab() -> [BuiltinScenario; 2] {
    let rods = |l: u32| ChainSpec {
        rods_mm: Some(vec![l; 20]),
        ..ChainSpec::default()
    };
    let preload_n = 10.0;
    let impact = Scenario {
        description: Some(format!(
            "Resonant model, 20 identical 40 mm rods; the paper's 40 mm impact (10 mm glass sphere dropped from 0.20 m, 2 ms) with gravity ({} m/s^2) and damping (contact restitution e = 0.9, resonator damping ratio 0.01)",
            defaults::GRAVITY_M_S2
        )),
        chain: rods(40),
        damping: Some(DampingSpec {
            contact: Some(ContactLaw::Restitution),
            restitution: Some(0.9),
            resonator_ratio: Some(0.01),
            ..DampingSpec::default()
        }),
        preload: Some(PreloadSpec {
            gravity_m_s2: Some(defaults::GRAVITY_M_S2),
            ..PreloadSpec::default()
        }),
        ..Scenario::default()
    };
    let transmission = Scenario {
        description: Some(format!(
            "Resonant model, 20 identical 80 mm rods preloaded with {preload_n} N, on-site damping time 20 ms; a force chirp 0.1 N, 100 Hz to 30 kHz over 25 ms, 50 ms. `woodpile transmission` uses its chain (docs/physics.md §15)"
        )),
        chain: rods(80),
        damping: Some(DampingSpec {
            on_site_time_s: Some(0.02),
            ..DampingSpec::default()
        }),
        preload: Some(PreloadSpec {
            force_n: Some(preload_n),
            ..PreloadSpec::default()
        }),
        excitation: ExcitationSpec {
            kind: ExcitationKind::Drive,
            signal: Some(SignalKind::Chirp),
            amplitude: Some(defaults::TRANSMISSION_RELATIVE_AMPLITUDE * preload_n),
            start_hz: Some(defaults::TRANSMISSION_START_HZ),
            end_hz: Some(defaults::TRANSMISSION_END_HZ),
            sweep_duration_s: Some(0.025),
            sweep: Some(SweepSpec::Linear),
            ..ExcitationSpec::default()
        },
        run: RunSpec {
            duration_s: Some(0.05),
            time_step_s: Some(2e-7),
            sample_interval_s: Some(defaults::TRANSMISSION_SAMPLE_INTERVAL_S),
            ..RunSpec::default()
        },
        ..Scenario::default()
    };
    [
        ("lab-impact-40mm", impact),
        ("transmission-80mm", transmission),
    ]
    .map(|(name, s)| BuiltinScenario {
        name: name.to_string(),
        scenario: s.complete(),
    })
}

/// A built-in scenario by name, with every default written out.
pub fn builtin(name: &str) -> Option<Scenario> {
    all()
        .into_iter()
        .find(|b| b.name == name)
        .map(|b| b.scenario)
}
