//! What the fit claims share: a synthetic calibration problem on a short impacted chain, whose
//! "measurement" is the model itself at known parameter values (plus seeded Gaussian noise). Not
//! a claim.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use woodpile::fit::{self, Built, Measurement, Output, Parameter, Problem};
use woodpile::{
    CellModel, ChainBuilder, ContactDamping, Damping, Excitation, Method, RunSettings, Striker,
    Wall,
};

/// The paper's sensor β under a 20 mm rod [N/m^1.5], computed once per build from the chain.
fn sensor_beta() -> f64 {
    ChainBuilder::table1_rods(&[80, 40, 20], CellModel::Resonant)
        .unwrap()
        .build()
        .unwrap()
        .wall_beta()
        .unwrap()
}

/// The model of the claims: 80, 40 and 20 mm resonant rods on the sensor, struck by the
/// paper's sphere. Parameters, in order: the contacts' restitution e (the restitution law of
/// docs/physics.md §14), a scale of the wall's β, and the striker's speed [m/s]. RK4 at 0.1 µs.
pub fn model(values: &[f64]) -> woodpile::Result<Built> {
    model_with_step(values, 1e-7)
}

/// [`model`] with RK4 at `time_step_s`.
pub fn model_with_step(values: &[f64], time_step_s: f64) -> woodpile::Result<Built> {
    let damping = Damping {
        contacts: ContactDamping::Restitution {
            coefficient: values[0],
        },
        ..Damping::default()
    };
    let chain = ChainBuilder::table1_rods(&[80, 40, 20], CellModel::Resonant)?
        .wall(Wall::Beta(values[1] * sensor_beta()))
        .damping(damping)
        .build()?;
    let excitation = Excitation::Impact(Striker {
        velocity_m_s: values[2],
        ..Striker::paper()
    });
    let settings = RunSettings {
        duration_s: 4e-4,
        method: Method::Rk4 { time_step_s },
        sample_interval_s: 1e-6,
    };
    Ok(Built {
        chain,
        excitation,
        settings,
    })
}

/// The true values: e = 0.85, wall β × 1.3, v0 = 1.98 m/s; a time shift of 3 µs.
pub const TRUTH: [f64; 4] = [0.85, 1.3, 1.98, 3e-6];

/// The parameters with their bounds, every start at the bounds' middle.
pub fn parameters() -> (Vec<Parameter>, Parameter) {
    let p = |name: &str, lo: f64, hi: f64| Parameter {
        name: name.into(),
        initial: 0.5 * (lo + hi),
        bounds: Some((lo, hi)),
        log_scale: false,
    };
    (
        vec![
            p("damping.restitution", 0.6, 1.0),
            p("contact_beta_scale.wall", 0.5, 2.0),
            p("excitation.velocity_m_s", 1.5, 2.5),
        ],
        p("time_shift_s", -1e-5, 1e-5),
    )
}

/// Measured times: 0 to 300 µs every 1 µs.
pub fn times() -> Vec<f64> {
    (0..=300).map(|i| i as f64 * 1e-6).collect()
}

/// The signals measured: the wall sensor's force and the top element's velocity.
pub const OUTPUTS: [Output; 2] = [
    Output::ContactForce { contact: 3 },
    Output::ElementVelocity { element: 1 },
];

/// A problem over `measurements`.
pub fn problem<'a>(measurements: Vec<Measurement>, m: &'a fit::ModelFn<'a>) -> Problem<'a> {
    let (parameters, shift) = parameters();
    Problem {
        parameters,
        time_shift_s: Some(shift),
        measurements,
        window_s: None,
        model: m,
    }
}

/// The model's signals at [`TRUTH`] with Gaussian noise of `noise` times each signal's peak
/// (seeded; `noise` = 0: exact), as measurements scaled by their peaks.
pub fn synthetic(noise: f64, seed: u64) -> Vec<Measurement> {
    let blank: Vec<Measurement> = OUTPUTS
        .iter()
        .map(|&output| Measurement {
            label: output.name(),
            output,
            times_s: times(),
            values: vec![0.0; times().len()],
            scale: 1.0,
            weight: 1.0,
            sensor_cutoff_hz: None,
        })
        .collect();
    let exact = fit::predict(&problem(blank.clone(), &model), &TRUTH).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    blank
        .into_iter()
        .zip(exact.values)
        .map(|(mut m, values)| {
            let peak = values.iter().fold(0.0, |a: f64, v| a.max(v.abs()));
            m.values = values
                .iter()
                .map(|v| v + noise * peak * standard_normal(&mut rng))
                .collect();
            m.scale = peak;
            m
        })
        .collect()
}

/// A standard normal deviate (Box–Muller).
fn standard_normal(rng: &mut ChaCha8Rng) -> f64 {
    let u1: f64 = 1.0 - rng.random::<f64>();
    let u2: f64 = rng.random();
    (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
}
