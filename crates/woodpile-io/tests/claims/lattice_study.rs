//! Claim: a lattice design study (`[lattice]` + `[design]` + `[ga]`) resumes from its checkpoint
//! exactly, each `pareto/NNN.toml` it writes is a lattice scenario whose run gives the front
//! row's transmitted peak force and mass bit for bit, a `{ from_mm, to_mm, step_mm }` range
//! holds the values it names, and bad `[design]` input is refused naming the key.
//!
//! Tolerance: none. The study runs each design with its samples only at the ends (peaks are
//! tracked at every step whatever the sampling), the re-run samples every microsecond: the same
//! steps, so the same peak; JSON keeps f64 bit for bit.

use std::ops::ControlFlow;
use std::sync::atomic::AtomicBool;
use woodpile::optimize::Nsga2State;
use woodpile_io::lattice::LatticeScenario;
use woodpile_io::lattice_study::{
    prepare_output, write_final_outputs, write_generation, LatticeStudyConfig,
};

const CONFIG: &str = r#"
[lattice]
layers = [
  { rods = 3, pitch_mm = 16.0, length_mm = 60.0, diameter_mm = 5.0, material = "fused-quartz" },
  { rods = 3 },
]
rod = { fe_elements = 2 }
[run]
duration_s = 1e-4
peak_tolerance = 1e-4
[design]
length_mm = { from_mm = 50.0, to_mm = 70.0, step_mm = 10.0 }
pitch_mm = [12.0, 16.0]
[ga]
population = 6
generations = 4
stall_generations = 0
seed = 2
"#;

fn without_times(mut s: Nsga2State) -> Nsga2State {
    s.elapsed_s = 0.0;
    for h in &mut s.history {
        h.elapsed_s = 0.0;
    }
    s
}

#[test]
fn a_lattice_study_resumes_exactly_and_its_front_reruns_to_its_figures() {
    let config = LatticeStudyConfig::parse(CONFIG, "c.toml").unwrap();
    let study = config.resolve(2).unwrap();
    let space = study.ga.designs().space();
    assert_eq!(space.lengths_m[0], vec![50e-3, 60e-3, 70e-3]);
    assert_eq!(space.choice_counts(), vec![3, 3, 2]);
    let never = AtomicBool::new(false);
    let (whole, reason) = study
        .ga
        .run(None, &never, &mut |_| ControlFlow::Continue(()))
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let (saved, _) = study
        .ga
        .run(None, &never, &mut |s| {
            if s.generation == 2 {
                write_generation(dir.path(), &study.config, s).unwrap();
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        })
        .unwrap();
    let read = prepare_output(dir.path(), true, &study.config)
        .unwrap()
        .unwrap();
    assert_eq!(read, saved, "the checkpoint is the state");
    let (resumed, _) = study
        .ga
        .run(Some(read), &never, &mut |_| ControlFlow::Continue(()))
        .unwrap();
    assert_eq!(without_times(resumed), without_times(whole.clone()));

    let other = LatticeStudyConfig {
        ga: woodpile_io::lattice_study::LatticeGaSpec {
            seed: Some(3),
            ..study.config.ga.clone()
        },
        ..study.config.clone()
    };
    let refused = prepare_output(dir.path(), true, &other).unwrap_err();
    assert!(
        refused.to_string().contains("different lattice study"),
        "{refused}"
    );

    let out = tempfile::tempdir().unwrap();
    let summary = write_final_outputs(out.path(), &study, &whole, reason).unwrap();
    let front = whole.front();
    assert_eq!(summary.front.len(), front.len());
    assert!(!front.is_empty());
    let csv = std::fs::read_to_string(out.path().join("pareto.csv")).unwrap();
    assert!(csv.starts_with(
        "transmitted-force,total-mass,layer_1_length_mm,layer_2_length_mm,pitch_mm\n"
    ));
    for (name, ind) in summary.front.iter().zip(&front) {
        let text = std::fs::read_to_string(out.path().join(name)).unwrap();
        let scenario = LatticeScenario::parse(&text, name).unwrap();
        let r = scenario.resolve().unwrap();
        let mut ode = woodpile::ode::LatticeOde::new(&r.lattice, &r.striker, r.at_m).unwrap();
        let run = woodpile::simulate::simulate_lattice(&mut ode, &r.settings).unwrap();
        assert_eq!(
            run.transmitted_peak_force_n.to_bits(),
            ind.objectives[0].to_bits(),
            "{name}: transmitted peak force"
        );
        assert_eq!(
            r.lattice.mass_kg().to_bits(),
            ind.objectives[1].to_bits(),
            "{name}: mass"
        );
    }
}

#[test]
fn bad_design_input_names_the_key() {
    let cases = [
        (
            "pitch_mm = [12.0, 16.0]",
            "pitch_mm = [12.0, 4.0]",
            "design.pitch_mm[1]",
        ),
        (
            "pitch_mm = [12.0, 16.0]",
            "pitch_mm = [12.0, 12.0]",
            "design.pitch_mm[1]",
        ),
        (
            "step_mm = 10.0",
            "step_mm = 0.0",
            "design.length_mm.step_mm",
        ),
        (
            "step_mm = 10.0",
            "step_mm = 0.01",
            "design.length_mm.step_mm",
        ),
        ("[design]\n", "[design]\nlayers = [3]\n", "design.layers[0]"),
        ("seed = 2", "objectives = [\"layers\"]", "ga.objectives[0]"),
    ];
    for (from, to, field) in cases {
        let text = CONFIG.replace(from, to);
        let e = LatticeStudyConfig::parse(&text, "c.toml")
            .unwrap()
            .resolve(1)
            .unwrap_err();
        assert_eq!(e.field(), Some(field), "{to}: {e}");
    }
}
