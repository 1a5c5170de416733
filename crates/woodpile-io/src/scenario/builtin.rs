//! The built-in scenarios: the paper's homogeneous and optimised chains under impact and blast,
//! each in resonant and rigid form.

use super::{ChainSpec, ExcitationKind, ExcitationSpec, ModelSpec, Scenario};

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
    for kind in [ExcitationKind::Impact, ExcitationKind::Blast] {
        for (stem, rods, what) in chains() {
            for model in [ModelSpec::Resonant, ModelSpec::Rigid] {
                let (kind_name, load) = match kind {
                    ExcitationKind::Impact => (
                        "impact",
                        "striker: 10 mm glass sphere dropped from 0.20 m, 2 ms",
                    ),
                    ExcitationKind::Blast => {
                        ("blast", "Friedlander blast F0 = 200 N, Td = 0.2 ms, 3 ms")
                    }
                };
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
    out
}

/// A built-in scenario by name, with every default written out.
pub fn builtin(name: &str) -> Option<Scenario> {
    all()
        .into_iter()
        .find(|b| b.name == name)
        .map(|b| b.scenario)
}
