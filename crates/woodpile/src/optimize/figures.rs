//! Objectives as data: the figures a design study can minimise ([`DesignFigure`]), evaluated for
//! many designs at once ([`figures_many`]). Figures that need no simulation (mass, height,
//! layers) cost none; those of a run share one run per design where they can (the transmitted
//! force, the ratio and the contact pressure come from one run in SIMD lanes).

use super::objective::{Objective, StandardObjective};
use super::space::DesignSpace;
use crate::error::{Error, Result};
use crate::lanes::{simulate_many_watching, Job, LaneWidth};
use crate::model::{hertz_contact, Chain, EllipseSolution, Surface, Wall};
use crate::simulate::{PeakWatch, RunSettings, RunSummary};

/// A figure of a design to minimise (`[ga] objectives`), by its name in config files.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DesignFigure {
    /// A figure of one run ([`StandardObjective`]).
    Run(StandardObjective),
    /// Total mass of the chain \[kg\] (no simulation).
    TotalMass,
    /// Height of the stack \[m\]: the sum of the elements' heights along the chain axis (a rod's
    /// and a sphere's diameter; no simulation).
    StackHeight,
    /// Number of layers (elements) of the design (no simulation).
    Layers,
    /// The Hertz peak pressure \[Pa\] of the worst contact of the structure (contacts 1..=N:
    /// element–element and element–wall; the striker's or load's contact 0 is the load's, not
    /// the design's), from each contact's geometry and its peak force over the run
    /// ([`crate::model::HertzContact::peak_pressure_pa`]).
    MaxContactPressure,
}

impl DesignFigure {
    /// Every figure, in the order the names are listed.
    pub const ALL: [DesignFigure; 8] = [
        DesignFigure::Run(StandardObjective::TransmittedForce),
        DesignFigure::Run(StandardObjective::TransmissionRatio),
        DesignFigure::Run(StandardObjective::TransmittedEnergy),
        DesignFigure::Run(StandardObjective::TransmittedImpulse),
        DesignFigure::TotalMass,
        DesignFigure::StackHeight,
        DesignFigure::Layers,
        DesignFigure::MaxContactPressure,
    ];

    /// The name used in config files and column headers.
    pub fn as_str(self) -> &'static str {
        match self {
            DesignFigure::Run(o) => o.as_str(),
            DesignFigure::TotalMass => "total-mass",
            DesignFigure::StackHeight => "stack-height",
            DesignFigure::Layers => "layers",
            DesignFigure::MaxContactPressure => "max-contact-pressure",
        }
    }

    /// The figure with this name.
    pub fn from_name(name: &str) -> Result<Self> {
        Self::ALL
            .into_iter()
            .find(|f| f.as_str() == name)
            .ok_or_else(|| Error::Unknown {
                what: "objective",
                name: name.to_string(),
                valid: Self::ALL.map(DesignFigure::as_str).join(", "),
            })
    }

    /// SI unit of the value.
    pub fn unit(self) -> &'static str {
        match self {
            DesignFigure::Run(o) => match o {
                StandardObjective::TransmittedForce => "N",
                StandardObjective::TransmissionRatio => "1",
                StandardObjective::TransmittedEnergy => "J",
                StandardObjective::TransmittedImpulse => "N s",
            },
            DesignFigure::TotalMass => "kg",
            DesignFigure::StackHeight => "m",
            DesignFigure::Layers => "1",
            DesignFigure::MaxContactPressure => "Pa",
        }
    }

    /// Whether the value needs a simulation of the design.
    pub fn needs_run(self) -> bool {
        matches!(
            self,
            DesignFigure::Run(_) | DesignFigure::MaxContactPressure
        )
    }
}

/// The Hertz peak pressures \[Pa\] of contacts 1..=N of `chain` (N = the wall; absent for a free
/// end or a wall given by β alone, whose geometry is unknown) under the contact peak forces of
/// `summary` (every contact tracked, [`PeakWatch::Every`]).
pub fn contact_peak_pressures_pa(chain: &Chain, summary: &RunSummary) -> Result<Vec<f64>> {
    let elements = chain.elements();
    let n = elements.len();
    let angle = chain.crossing_angle_rad();
    let mut pressures = Vec::with_capacity(n);
    for c in 1..n {
        let (a, b) = (&elements[c - 1], &elements[c]);
        let geometry = hertz_contact(
            a.surface(0.0),
            &a.material,
            b.surface(angle),
            &b.material,
            EllipseSolution::Exact,
        )?;
        pressures.push(geometry.peak_pressure_pa(summary.contact_peak_forces_n[c]));
    }
    let last = &elements[n - 1];
    let wall = match chain.wall() {
        Wall::Cap { material, radius_m } => Some((
            Surface::Sphere {
                radius_m: *radius_m,
            },
            material,
        )),
        Wall::Flat { material } => Some((Surface::Flat, material)),
        Wall::Free | Wall::Beta(_) => None,
    };
    if let Some((surface, material)) = wall {
        let geometry = hertz_contact(
            last.surface(angle * (n - 1) as f64),
            &last.material,
            surface,
            material,
            EllipseSolution::Exact,
        )?;
        pressures.push(geometry.peak_pressure_pa(summary.contact_peak_forces_n[n]));
    }
    Ok(pressures)
}

/// The values of `figures` for each genome, in order: simulation-free figures from the
/// catalogue, the others from runs under `settings` on the current rayon pool
/// ([`run_figures_many`]). A design whose chain does not build, or whose run fails, has its
/// error.
pub fn figures_many(
    space: &DesignSpace,
    figures: &[DesignFigure],
    genomes: &[&[u8]],
    settings: &RunSettings,
    lanes: LaneWidth,
) -> Vec<Result<Vec<f64>>> {
    use rayon::prelude::*;
    if !figures.iter().any(|f| f.needs_run()) {
        return genomes
            .iter()
            .map(|g| Ok(figures.iter().map(|f| static_value(space, *f, g)).collect()))
            .collect();
    }
    let chains: Vec<Result<Chain>> = genomes.par_iter().map(|g| space.chain(g)).collect();
    let built: Vec<Chain> = chains
        .iter()
        .filter_map(|c| c.as_ref().ok().cloned())
        .collect();
    let jobs = Job::for_each_chain(&built, &space.excitation, settings);
    let mut runs = run_figures_many(figures, &jobs, lanes).into_iter();
    chains
        .into_iter()
        .zip(genomes)
        .map(|(chain, g)| {
            chain?;
            let mut values = runs.next().expect("one result per built chain")?;
            for (v, f) in values.iter_mut().zip(figures) {
                if !f.needs_run() {
                    *v = static_value(space, *f, g);
                }
            }
            Ok(values)
        })
        .collect()
}

/// The value of a simulation-free figure.
fn static_value(space: &DesignSpace, figure: DesignFigure, genome: &[u8]) -> f64 {
    match figure {
        DesignFigure::TotalMass => space.mass_kg(genome),
        DesignFigure::StackHeight => space.height_m(genome),
        DesignFigure::Layers => genome.len() as f64,
        DesignFigure::Run(_) | DesignFigure::MaxContactPressure => f64::NAN,
    }
}

/// The figures of each run of `jobs` (any chain, excitation and settings each), in order: the
/// figures that need a run from it ([`DesignFigure::needs_run`]), NaN in the places of the
/// others. Force, ratio and pressure come from one run per job in SIMD lanes `lanes` wide
/// (peaks only); energy and impulse from one recorded run each, on the current rayon pool. A
/// run that fails, or whose wave never reached the wall, has its error.
pub fn run_figures_many(
    figures: &[DesignFigure],
    jobs: &[Job<'_>],
    lanes: LaneWidth,
) -> Vec<Result<Vec<f64>>> {
    use rayon::prelude::*;
    let forces = figures.iter().any(|f| {
        matches!(
            f,
            DesignFigure::MaxContactPressure
                | DesignFigure::Run(StandardObjective::TransmittedForce)
                | DesignFigure::Run(StandardObjective::TransmissionRatio)
        )
    });
    let watch = if figures.contains(&DesignFigure::MaxContactPressure) {
        PeakWatch::Every
    } else {
        PeakWatch::FiguresOfMerit
    };
    let peaks_only: Vec<RunSettings> = jobs
        .iter()
        .map(|j| RunSettings {
            sample_interval_s: j.settings.duration_s,
            ..*j.settings
        })
        .collect();
    let summaries: Vec<Option<Result<RunSummary>>> = if forces {
        let peak_jobs: Vec<Job<'_>> = jobs
            .iter()
            .zip(&peaks_only)
            .map(|(j, settings)| Job { settings, ..*j })
            .collect();
        simulate_many_watching(&peak_jobs, lanes, watch)
            .into_iter()
            .map(Some)
            .collect()
    } else {
        jobs.iter().map(|_| None).collect()
    };
    // Energy and impulse: recorders on the sample grid, one run per job and figure.
    let recorded: Vec<(DesignFigure, Vec<Result<f64>>)> = figures
        .iter()
        .filter_map(|f| match f {
            DesignFigure::Run(
                o @ (StandardObjective::TransmittedEnergy | StandardObjective::TransmittedImpulse),
            ) => Some((
                *f,
                jobs.par_iter()
                    .map(|j| o.evaluate(j.chain, j.excitation, j.settings))
                    .collect(),
            )),
            _ => None,
        })
        .collect();
    summaries
        .into_iter()
        .zip(jobs)
        .enumerate()
        .map(|(k, (summary, job))| job_values(figures, job, summary, &recorded, k))
        .collect()
}

/// The run figures of the `k`-th job from its run summary and recorded values.
fn job_values(
    figures: &[DesignFigure],
    job: &Job<'_>,
    summary: Option<Result<RunSummary>>,
    recorded: &[(DesignFigure, Vec<Result<f64>>)],
    k: usize,
) -> Result<Vec<f64>> {
    let summary = summary.transpose()?;
    if let Some(s) = &summary {
        if !s.wave_arrived {
            return Err(Error::WaveNotArrived {
                duration_s: job.settings.duration_s,
                transmitted_n: s.transmitted_peak_force_n,
                incident_n: s.incident_peak_force_n,
            });
        }
    }
    let mut values = Vec::with_capacity(figures.len());
    for &f in figures {
        let v = match f {
            DesignFigure::Run(StandardObjective::TransmittedForce) => {
                summary
                    .as_ref()
                    .expect("forces run")
                    .transmitted_peak_force_n
            }
            DesignFigure::Run(StandardObjective::TransmissionRatio) => summary
                .as_ref()
                .expect("forces run")
                .transmission_ratio
                .unwrap_or(f64::NAN),
            DesignFigure::MaxContactPressure => {
                let s = summary.as_ref().expect("forces run");
                contact_peak_pressures_pa(job.chain, s)?
                    .into_iter()
                    .fold(0.0, f64::max)
            }
            DesignFigure::Run(_) => {
                let (_, list) = recorded
                    .iter()
                    .find(|(r, _)| *r == f)
                    .expect("recorded figure");
                list[k].clone()?
            }
            DesignFigure::TotalMass | DesignFigure::StackHeight | DesignFigure::Layers => f64::NAN,
        };
        values.push(v);
    }
    Ok(values)
}

/// How [`crate::optimize::Nsga2`] evaluates its figures for a batch of genomes of its space, on
/// the current rayon pool: [`NominalFigures`] by default, or one a front end supplies (the
/// statistics over scattered scenarios of a robust study) without this crate knowing its
/// scenarios. Values come in the order of `genomes`, one per figure.
pub trait FigureEvaluator: Send + Sync {
    /// The values of `figures` for each genome (its error where it has none).
    fn figures_many(
        &self,
        space: &DesignSpace,
        figures: &[DesignFigure],
        genomes: &[&[u8]],
        lanes: LaneWidth,
    ) -> Vec<Result<Vec<f64>>>;
}

/// The figures of each design under the space's one excitation and settings ([`figures_many`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct NominalFigures;

impl FigureEvaluator for NominalFigures {
    fn figures_many(
        &self,
        space: &DesignSpace,
        figures: &[DesignFigure],
        genomes: &[&[u8]],
        lanes: LaneWidth,
    ) -> Vec<Result<Vec<f64>>> {
        figures_many(space, figures, genomes, &space.settings, lanes)
    }
}
