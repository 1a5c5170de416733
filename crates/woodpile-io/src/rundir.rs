//! Run outputs: `summary.json`, `run.json`, CSV and NumPy files, written atomically.
//!
//! Everything is written into a sibling staging directory `.NAME.partial-PID` and renamed to the
//! output directory at the end, so a directory named like the output never holds a half-written
//! run. An existing output directory is replaced only when it holds a previous run (`run.json`)
//! or is empty.

pub use crate::atomic::read_error;
use crate::atomic::{io_err, RUN_MARKER};
use crate::error::Error;
use crate::scenario::{resolve, ExcitationKind, Resolved, Scenario};
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::fs;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use woodpile::{Chain, Excitation, Method, Resonator, RunSummary, Trajectory, UnitCell};

/// Every file a run directory may hold, written by [`write_run`] (`run.json` last). Only these
/// are ever replaced or removed in an existing run directory.
pub const RUN_FILES: &[&str] = &[
    "summary.json",
    "forces.csv",
    "energy.csv",
    "displacements.csv",
    "velocities.csv",
    "striker.csv",
    "time_s.npy",
    "forces_n.npy",
    "energy_j.npy",
    "wall_energy_j.npy",
    "input_work_j.npy",
    "dissipated_j.npy",
    "displacements_m.npy",
    "velocities_m_s.npy",
    "striker.npy",
    RUN_MARKER,
];

/// Everything a run produced, for the writers.
#[derive(Debug, Clone, Copy)]
pub struct RunRecord<'a> {
    /// Scenario name (built-in name or file stem).
    pub name: &'a str,
    /// The scenario file, if the run came from one.
    pub file: Option<&'a Path>,
    /// The scenario as given.
    pub scenario: &'a Scenario,
    /// What the library ran.
    pub resolved: &'a Resolved,
    /// Figures of merit.
    pub summary: &'a RunSummary,
    /// Samples.
    pub trajectory: &'a Trajectory,
}

/// Energy bookkeeping in `summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EnergyJson {
    /// Total energy at t = 0 \[J\].
    pub initial_j: f64,
    /// Total energy at the end \[J\].
    pub final_j: f64,
    /// Work done by the load \[J\].
    pub input_work_j: f64,
    /// Energy dissipated \[J\] (0 without damping, and in runs written before it existed).
    #[serde(default)]
    pub dissipated_j: f64,
    /// Largest relative error of the energy balance.
    pub max_relative_error: f64,
}

/// Integrator work in `summary.json` / `run.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct IntegratorJson {
    /// `rk4`, `dopri5`, `dopri5-events` (`run.peak_tolerance`, blast or lab physics), `rkn64`
    /// (`run.peak_tolerance`, an impact of the paper's physics) or `exact-modes`
    /// (`run.peak_tolerance`, such an impact with finite-element rods: docs/physics.md §8).
    pub method: String,
    /// Accepted steps.
    pub steps: u64,
    /// Right-hand-side evaluations.
    pub rhs_evaluations: u64,
    /// Rejected steps.
    pub rejected_steps: u64,
}

impl IntegratorJson {
    /// The method a run stepped with and its counters.
    pub fn of(method: Method, stats: &woodpile::IntegratorStats) -> Self {
        IntegratorJson {
            method: method_label(method).to_string(),
            steps: stats.steps,
            rhs_evaluations: stats.rhs_evaluations,
            rejected_steps: stats.rejected_steps,
        }
    }
}

/// What a run directory holds: a chain's run or a lattice's (`structure` in `run.json` and
/// `summary.json`; both are [`RUN_FORMAT`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Structure {
    /// A column of elements on a wall (`[chain]`).
    #[default]
    Chain,
    /// Layers of rods on supports (`[lattice]`, docs/physics.md §16).
    Lattice,
}

impl Structure {
    /// `chain` or `lattice`.
    pub fn name(self) -> &'static str {
        match self {
            Structure::Chain => "chain",
            Structure::Lattice => "lattice",
        }
    }

    /// The structure a `run.json` names: its `structure`, or a lattice by the earlier lattice
    /// tag, or a chain for a woodpile run without the key; None for anything else.
    pub fn of_run_json(run: &Value) -> Option<Structure> {
        if run.get("tool").and_then(Value::as_str) != Some("woodpile") {
            return None;
        }
        let format = run.get("format").and_then(Value::as_str);
        if format == Some(LEGACY_LATTICE_RUN_FORMAT) {
            return Some(Structure::Lattice);
        }
        match run.get("structure") {
            None => Some(Structure::Chain),
            Some(v) => serde_json::from_value(v.clone()).ok(),
        }
    }
}

/// The contents of `summary.json`: the figures of merit (docs/physics.md §8), units in the key names.
#[derive(Debug, Clone, Serialize)]
pub struct SummaryJson {
    /// Scenario name.
    pub scenario: String,
    /// `chain`.
    pub structure: Structure,
    /// `impact`, `blast`, `drive` or `rest`.
    pub excitation: &'static str,
    /// Element labels, top to bottom.
    pub chain_labels: Vec<String>,
    /// Number of elements N.
    pub n_elements: usize,
    /// Number of samples.
    pub n_samples: usize,
    /// Peak of contact 1 \[N\].
    pub incident_peak_force_n: f64,
    /// Peak of contact N (the wall) \[N\].
    pub transmitted_peak_force_n: f64,
    /// Under a static load: the incident peak minus contact 1's static force \[N\].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub incident_dynamic_peak_force_n: Option<f64>,
    /// Under a static load: the transmitted peak minus contact N's static force \[N\].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub transmitted_dynamic_peak_force_n: Option<f64>,
    /// Transmitted / incident (of the dynamic parts under a static load); null when the incident
    /// force is zero or the wave never reached the wall (`wave_arrived` false).
    pub transmission_ratio: Option<f64>,
    /// Static force of every contact 0..=N under a preload or gravity \[N\] (absent without one).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub static_contact_forces_n: Vec<f64>,
    /// Under a displacement drive: its tip's static position u* \[m\], downward, the tip's
    /// overlap δ₀ = u* + u(t) − x₁ (docs/physics.md §14; absent without one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub actuator_rest_m: Option<f64>,
    /// Whether the transmitted peak reached the documented fraction of the incident one.
    pub wave_arrived: bool,
    /// Whether the energy balance closes to within `woodpile::defaults::ENERGY_ERROR_WARN`
    /// (false: the run was kept with a warning or because inaccuracy was allowed).
    pub energy_balance_ok: bool,
    /// Striker restitution e (impact; null for a blast).
    pub restitution_coefficient: Option<f64>,
    /// Whether the striker had left for good at the end (impact; null for a blast).
    pub striker_separated: Option<bool>,
    /// Peak of every contact 0..=N \[N\].
    pub contact_peak_forces_n: Vec<f64>,
    /// Time of each peak \[s\].
    pub contact_peak_times_s: Vec<f64>,
    /// Largest sampled energy of every layer 0..=N \[J\].
    pub layer_peak_energies_j: Vec<f64>,
    /// Energy balance.
    pub energy: EnergyJson,
    /// Integrator statistics.
    pub integrator: IntegratorJson,
    /// Wall-clock time of the run \[s\].
    pub wall_time_s: f64,
}

/// The method a chain's run stepped with (a stated peak tolerance resolved for its system) and
/// its counters.
fn integrator_json(r: &RunRecord<'_>) -> IntegratorJson {
    let settings = &r.resolved.settings;
    let method = settings
        .method_for(&r.resolved.chain, &r.resolved.excitation)
        .unwrap_or(settings.method);
    IntegratorJson::of(method, &r.summary.stats)
}

/// A method's name in `run.json` and `summary.json` ([`IntegratorJson::method`]).
pub fn method_label(method: Method) -> &'static str {
    match method {
        Method::Rk4 { .. } => "rk4",
        Method::Dopri5 { .. } => "dopri5",
        Method::Dopri5Events { .. } => "dopri5-events",
        Method::Rkn64 { .. } => "rkn64",
        Method::ExactModes { .. } => "exact-modes",
        Method::PeakTolerance { .. } => "peak-tolerance",
    }
}

impl SummaryJson {
    /// Builds the summary of a run.
    pub fn new(r: &RunRecord<'_>) -> Self {
        let s = r.summary;
        let t = r.trajectory;
        let nc = t.n_contacts();
        let mut layer_peaks = vec![0.0_f64; nc];
        for row in t.layer_energies_j.chunks(nc) {
            for (p, &e) in layer_peaks.iter_mut().zip(row) {
                *p = p.max(e);
            }
        }
        let statics = &s.static_contact_forces_n;
        let dynamic = |c: usize, total: f64| statics.get(c).map(|f| total - f);
        SummaryJson {
            scenario: r.name.to_string(),
            structure: Structure::Chain,
            excitation: r.resolved.excitation.kind_name(),
            chain_labels: r
                .resolved
                .chain
                .elements()
                .iter()
                .map(|e| e.label.clone())
                .collect(),
            n_elements: r.resolved.chain.len(),
            n_samples: s.n_samples,
            incident_peak_force_n: s.incident_peak_force_n,
            transmitted_peak_force_n: s.transmitted_peak_force_n,
            incident_dynamic_peak_force_n: dynamic(1, s.incident_peak_force_n),
            transmitted_dynamic_peak_force_n: dynamic(
                r.resolved.chain.len(),
                s.transmitted_peak_force_n,
            ),
            transmission_ratio: s.transmission_ratio,
            static_contact_forces_n: s.static_contact_forces_n.clone(),
            actuator_rest_m: s.actuator_rest_m,
            wave_arrived: s.wave_arrived,
            energy_balance_ok: s.energy.max_relative_error <= woodpile::defaults::ENERGY_ERROR_WARN,
            restitution_coefficient: s.restitution_coefficient(),
            striker_separated: s.restitution.map(|e| e.separated),
            contact_peak_forces_n: s.contact_peak_forces_n.clone(),
            contact_peak_times_s: s.contact_peak_times_s.clone(),
            layer_peak_energies_j: layer_peaks,
            energy: EnergyJson {
                initial_j: s.energy.initial_j,
                final_j: s.energy.final_j,
                input_work_j: s.energy.input_work_j,
                dissipated_j: s.energy.dissipated_j,
                max_relative_error: s.energy.max_relative_error,
            },
            integrator: integrator_json(r),
            wall_time_s: s.wall_time_s,
        }
    }
}

/// Contact coefficients of a run in `run.json` \[N/m^1.5\].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BetasJson {
    /// Striker – element 1 (impact).
    pub striker: Option<f64>,
    /// Contacts 1..N−1, element i – element i+1.
    pub inner: Vec<f64>,
    /// Contact N, element N – wall (null for a free end).
    pub wall: Option<f64>,
}

/// One element of the chain in `run.json`: its label and unit cell.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ElementJson {
    /// Label, e.g. `80mm`.
    pub label: String,
    /// Total mass \[kg\].
    pub total_mass_kg: f64,
    /// Primary mass M \[kg\].
    pub primary_mass_kg: f64,
    /// Resonator masses m_j \[kg\].
    pub resonator_masses_kg: Vec<f64>,
    /// Resonator stiffnesses k_j \[N/m\].
    pub resonator_stiffnesses_n_per_m: Vec<f64>,
}

/// `run.json`: what was run, completely — written by [`write_run`] and read back by
/// [`read_run_info`] through the same type.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunJson {
    /// `woodpile`.
    pub tool: String,
    /// [`RUN_FORMAT`] (absent in runs written before the tag existed).
    #[serde(default)]
    pub format: Option<String>,
    /// `chain` (absent in runs written before lattices shared the format).
    #[serde(default)]
    pub structure: Structure,
    /// Version of woodpile that wrote it.
    pub version: String,
    /// Scenario name (built-in name or file stem).
    pub scenario_name: String,
    /// The scenario file, if the run came from one.
    pub scenario_file: Option<String>,
    /// The scenario with every default filled in (the same structure as the TOML file).
    pub scenario: Scenario,
    /// Every contact coefficient.
    pub contact_betas_n_per_m1_5: BetasJson,
    /// Striker mass \[kg\] (impact).
    pub striker_mass_kg: Option<f64>,
    /// Striker initial velocity \[m/s\] (impact).
    pub striker_velocity_m_s: Option<f64>,
    /// The elements, top to bottom.
    pub elements: Vec<ElementJson>,
    /// Integrator statistics.
    pub integrator: IntegratorJson,
    /// Number of samples.
    pub n_samples: usize,
    /// Wall-clock time of the run \[s\].
    pub wall_time_s: f64,
}

pub(crate) fn write_json<T: Serialize>(path: &Path, value: &T) -> Result<(), Error> {
    let file = fs::File::create(path).map_err(io_err(path))?;
    let mut w = BufWriter::new(file);
    serde_json::to_writer_pretty(&mut w, value)
        .map_err(|e| io_err(path)(std::io::Error::other(e)))?;
    writeln!(w).and_then(|_| w.flush()).map_err(io_err(path))
}

/// Writes a CSV with a header and one row per sample (`time_s` then the row's values).
pub(crate) fn write_csv(
    path: &Path,
    header: &[String],
    times: &[f64],
    rows: impl Iterator<Item = Vec<f64>>,
) -> Result<(), Error> {
    let csv_err = |e: csv::Error| io_err(path)(std::io::Error::other(e));
    let mut w = csv::Writer::from_path(path).map_err(csv_err)?;
    w.write_record(header).map_err(csv_err)?;
    let mut fields = Vec::with_capacity(header.len());
    for (t, row) in times.iter().zip(rows) {
        fields.clear();
        fields.push(format!("{t:e}"));
        fields.extend(row.iter().map(|v| format!("{v:e}")));
        w.write_record(&fields).map_err(csv_err)?;
    }
    w.flush().map_err(io_err(path))
}

/// Writes a C-order float64 `.npy` array of the given shape.
pub fn write_npy(path: &Path, shape: &[u64], data: &[f64]) -> Result<(), Error> {
    let mut file = BufWriter::new(fs::File::create(path).map_err(io_err(path))?);
    crate::npy::write(&mut file, shape, data).map_err(io_err(path))?;
    file.flush().map_err(io_err(path))
}

/// Writes every output file of a run into `dir`.
///
/// Files: `summary.json`, `run.json`, `forces.csv`, `energy.csv` (layers, wall, total, input
/// work, dissipated), `displacements.csv`, `velocities.csv`, `striker.csv` (impact), and
/// `time_s.npy`, `forces_n.npy` (samples × contacts 0..=N), `energy_j.npy` (samples × layers
/// 0..=N), `wall_energy_j.npy`, `input_work_j.npy`, `dissipated_j.npy`, `displacements_m.npy`,
/// `velocities_m_s.npy` (samples × N), `striker.npy` (impact: samples × \[position m, velocity
/// m/s\]).
pub fn write_run(dir: &Path, r: &RunRecord<'_>) -> Result<(), Error> {
    write_run_reporting(dir, r, &mut |_| {})
}

/// Number of stages [`write_run_reporting`] reports.
pub const WRITE_RUN_STAGES: u64 = 3;

/// [`write_run`], telling `stage` what it writes next (the CSV files, the `.npy` files,
/// `run.json`): a long run's files take a while.
pub fn write_run_reporting(
    dir: &Path,
    r: &RunRecord<'_>,
    stage: &mut dyn FnMut(&str),
) -> Result<(), Error> {
    write_json(&dir.join("summary.json"), &SummaryJson::new(r))?;
    stage("writing the CSV files");
    write_csvs(dir, r.trajectory)?;
    stage("writing the .npy files");
    write_npys(dir, r.trajectory)?;
    // run.json last: its presence marks a complete run.
    stage("writing run.json");
    write_json(&dir.join(RUN_MARKER), &run_json(r))
}

/// `run.json`: the completed scenario, the model's numbers and the integrator's statistics.
fn run_json(r: &RunRecord<'_>) -> RunJson {
    let chain = &r.resolved.chain;
    let (striker_beta, striker_mass, striker_v0) = match &r.resolved.excitation {
        Excitation::Impact(s) => (
            s.contact_beta(chain).ok(),
            Some(s.mass_kg()),
            Some(s.velocity_m_s),
        ),
        Excitation::Blast(_) | Excitation::Drive(_) | Excitation::Rest => (None, None, None),
    };
    let s = r.summary;
    RunJson {
        tool: "woodpile".to_string(),
        format: Some(RUN_FORMAT.to_string()),
        structure: Structure::Chain,
        version: crate::VERSION.to_string(),
        scenario_name: r.name.to_string(),
        scenario_file: r.file.map(|p| p.display().to_string()),
        scenario: r.scenario.complete(),
        contact_betas_n_per_m1_5: BetasJson {
            striker: striker_beta,
            inner: chain.inner_betas().to_vec(),
            wall: chain.wall_beta(),
        },
        striker_mass_kg: striker_mass,
        striker_velocity_m_s: striker_v0,
        elements: chain
            .elements()
            .iter()
            .map(|e| ElementJson {
                label: e.label.clone(),
                total_mass_kg: e.cell.total_mass_kg(),
                primary_mass_kg: e.cell.primary_mass_kg,
                resonator_masses_kg: e.cell.resonators.iter().map(|r| r.mass_kg).collect(),
                resonator_stiffnesses_n_per_m: e
                    .cell
                    .resonators
                    .iter()
                    .map(|r| r.stiffness_n_per_m)
                    .collect(),
            })
            .collect(),
        integrator: integrator_json(r),
        n_samples: s.n_samples,
        wall_time_s: s.wall_time_s,
    }
}

/// The samples as CSV: forces, energy, displacements, velocities and the striker.
fn write_csvs(dir: &Path, t: &Trajectory) -> Result<(), Error> {
    let (n, nc, ns) = (t.n_elements, t.n_contacts(), t.len());
    let mut header = vec!["time_s".to_string()];
    header.extend((0..nc).map(|c| format!("contact_{c}_n")));
    write_csv(
        &dir.join("forces.csv"),
        &header,
        &t.times_s,
        t.contact_forces_n.chunks(nc).map(<[f64]>::to_vec),
    )?;
    let mut header = vec!["time_s".to_string()];
    header.extend((0..nc).map(|l| format!("layer_{l}_j")));
    header.extend(["wall_j", "total_j", "input_work_j", "dissipated_j"].map(String::from));
    let energy_rows = t
        .layer_energies_j
        .chunks(nc)
        .zip(&t.wall_energy_j)
        .zip(&t.input_work_j)
        .zip(&t.dissipated_j)
        .map(|(((row, &w), &work), &lost)| {
            let mut v = row.to_vec();
            let total = row.iter().sum::<f64>() + w;
            v.extend([w, total, work, lost]);
            v
        });
    write_csv(&dir.join("energy.csv"), &header, &t.times_s, energy_rows)?;
    if n > 0 {
        let mut header = vec!["time_s".to_string()];
        header.extend((1..=n).map(|i| format!("element_{i}_m")));
        write_csv(
            &dir.join("displacements.csv"),
            &header,
            &t.times_s,
            t.displacements_m.chunks(n).map(<[f64]>::to_vec),
        )?;
        let mut header = vec!["time_s".to_string()];
        header.extend((1..=n).map(|i| format!("element_{i}_m_s")));
        write_csv(
            &dir.join("velocities.csv"),
            &header,
            &t.times_s,
            t.velocities_m_s.chunks(n).map(<[f64]>::to_vec),
        )?;
    }
    let has_striker = t.striker_position_m.len() == ns && ns > 0;
    if has_striker {
        let header = ["time_s", "position_m", "velocity_m_s"].map(String::from);
        write_csv(
            &dir.join("striker.csv"),
            &header,
            &t.times_s,
            t.striker_position_m
                .iter()
                .zip(&t.striker_velocity_m_s)
                .map(|(&x, &v)| vec![x, v]),
        )?;
    }
    Ok(())
}

/// The samples as NumPy arrays, one file per quantity.
fn write_npys(dir: &Path, t: &Trajectory) -> Result<(), Error> {
    let (n, nc, ns) = (t.n_elements, t.n_contacts(), t.len());
    let has_striker = t.striker_position_m.len() == ns && ns > 0;
    let (ns64, nc64, n64) = (ns as u64, nc as u64, n as u64);
    write_npy(&dir.join("time_s.npy"), &[ns64], &t.times_s)?;
    write_npy(
        &dir.join("forces_n.npy"),
        &[ns64, nc64],
        &t.contact_forces_n,
    )?;
    write_npy(
        &dir.join("energy_j.npy"),
        &[ns64, nc64],
        &t.layer_energies_j,
    )?;
    write_npy(&dir.join("wall_energy_j.npy"), &[ns64], &t.wall_energy_j)?;
    write_npy(&dir.join("input_work_j.npy"), &[ns64], &t.input_work_j)?;
    write_npy(&dir.join("dissipated_j.npy"), &[ns64], &t.dissipated_j)?;
    write_npy(
        &dir.join("displacements_m.npy"),
        &[ns64, n64],
        &t.displacements_m,
    )?;
    write_npy(
        &dir.join("velocities_m_s.npy"),
        &[ns64, n64],
        &t.velocities_m_s,
    )?;
    if has_striker {
        let data: Vec<f64> = t
            .striker_position_m
            .iter()
            .zip(&t.striker_velocity_m_s)
            .flat_map(|(&x, &v)| [x, v])
            .collect();
        write_npy(&dir.join("striker.npy"), &[ns64, 2], &data)?;
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// Reading a run directory back.

/// The run-directory format this build reads: `run.json` written by woodpile of the same
/// major.minor version (0.x: every minor version may change the files). A run.json that carries
/// an explicit `format` key must name this one.
pub const RUN_FORMAT: &str = "woodpile-run/1";

/// The format tag lattice runs had before they shared [`RUN_FORMAT`] (read, never written).
pub const LEGACY_LATTICE_RUN_FORMAT: &str = "woodpile-lattice-run/1";

/// What `run.json` says about a run, as far as the figures need it.
#[derive(Debug, Clone)]
pub struct RunInfo {
    /// Scenario name.
    pub name: String,
    /// Element labels, top to bottom.
    pub labels: Vec<String>,
    /// Unit cells of the elements (for the negative-mass bands).
    pub cells: Vec<UnitCell>,
    /// "impact 1.98 m/s", "blast …", "drive chirp" or "rest".
    pub excitation: String,
    /// The chain, when the scenario still resolves (a blast table may have moved).
    pub chain: Option<Chain>,
}

/// The error for a directory that is not a run (named as `RUN_DIR`).
pub fn bad_dir(dir: &Path, reason: impl Into<String>) -> Error {
    Error::invalid("RUN_DIR", dir.display(), reason)
}

/// Reads and checks `run.json`: a woodpile run of a format this build reads.
pub fn read_run_info(dir: &Path) -> Result<RunInfo, Error> {
    if !dir.is_dir() {
        return Err(bad_dir(
            dir,
            "is not a directory; give a directory written by `woodpile simulate`",
        ));
    }
    let path = dir.join(RUN_MARKER);
    if !path.is_file() {
        return Err(bad_dir(
            dir,
            "is not a woodpile run (no run.json); give a directory written by `woodpile simulate` or `woodpile optimize`",
        ));
    }
    let text = fs::read_to_string(&path).map_err(|e| Error::Read {
        path: path.clone(),
        source: e,
    })?;
    let run: Value = serde_json::from_str(&text).map_err(|e| Error::Parse {
        source_name: path.display().to_string(),
        message: e.to_string(),
    })?;
    check_format(&path, &run)?;
    // The format and version are checked on the raw JSON first, so a foreign or older file gets
    // that explanation rather than a missing-field message.
    let run: RunJson = serde_json::from_value(run).map_err(|e| {
        read_error(
            &path,
            format!("not a complete woodpile run.json ({e}); re-run `woodpile simulate`"),
        )
    })?;
    let cells = run
        .elements
        .iter()
        .map(|e| {
            let resonators = e
                .resonator_masses_kg
                .iter()
                .zip(&e.resonator_stiffnesses_n_per_m)
                .map(|(&mass_kg, &stiffness_n_per_m)| Resonator {
                    mass_kg,
                    stiffness_n_per_m,
                })
                .collect();
            UnitCell::new(e.primary_mass_kg, resonators).map_err(Error::Model)
        })
        .collect::<Result<Vec<_>, _>>()?;
    let x = &run.scenario.excitation;
    let excitation = match (
        x.kind,
        run.striker_velocity_m_s,
        x.peak_force_n,
        x.duration_s,
    ) {
        (ExcitationKind::Drive | ExcitationKind::Rest, ..) => {
            let signal = x.signal.map_or(String::new(), |s| format!(" {}", s.name()));
            format!("{}{signal}", x.kind.name())
        }
        (_, Some(v), _, _) => format!("impact {v:.2} m/s"),
        (_, None, Some(f), Some(td)) => format!("blast {f:.0} N / {:.2} ms", td * 1e3),
        (_, None, _, _) => "blast (tabulated load)".to_string(),
    };
    // The chain itself (element bodies, for the picture) comes from the completed scenario,
    // when it still resolves (a blast table may have moved).
    let base = run
        .scenario_file
        .as_deref()
        .and_then(|f| Path::new(f).parent().map(Path::to_path_buf))
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or_else(|| PathBuf::from("."));
    let chain = resolve(&run.scenario, &base).ok().map(|r| r.chain);
    Ok(RunInfo {
        name: run.scenario_name,
        labels: run.elements.into_iter().map(|e| e.label).collect(),
        cells,
        excitation,
        chain,
    })
}

fn check_format(path: &Path, run: &Value) -> Result<(), Error> {
    let tool = run.get("tool").and_then(Value::as_str);
    if tool != Some("woodpile") {
        return Err(read_error(
            path,
            format!(
                "not written by woodpile (tool = {}); give a directory written by `woodpile simulate`",
                tool.unwrap_or("missing")
            ),
        ));
    }
    if Structure::of_run_json(run) == Some(Structure::Lattice) {
        return Err(read_error(
            path,
            "a lattice run (docs/physics.md §16), not a chain run: its files are read by `woodpile_io::lattice::read_lattice_run` (forces_n.npy, supports.csv), its figures drawn by `woodpile plot`",
        ));
    }
    if let Some(format) = run.get("format").and_then(Value::as_str) {
        if format != RUN_FORMAT {
            return Err(read_error(
                path,
                format!("run format `{format}` is not `{RUN_FORMAT}`, the one this woodpile reads; re-run `woodpile simulate` with this version"),
            ));
        }
        return Ok(());
    }
    let version = run
        .get("version")
        .and_then(Value::as_str)
        .unwrap_or("unknown");
    let major_minor = |v: &str| v.split('.').take(2).collect::<Vec<_>>().join(".");
    let ours = crate::VERSION;
    if major_minor(version) != major_minor(ours) {
        return Err(read_error(
            path,
            format!("written by woodpile {version}, whose run format this woodpile {ours} does not read; re-run `woodpile simulate` with this version"),
        ));
    }
    Ok(())
}

/// Reads a run's samples: the `.npy` files, or the CSV files where those are missing.
pub fn read_trajectory(dir: &Path, n_elements: usize) -> Result<Trajectory, Error> {
    let nc = n_elements + 1;
    let npy = [
        "time_s.npy",
        "forces_n.npy",
        "energy_j.npy",
        "wall_energy_j.npy",
    ];
    if npy.iter().all(|f| dir.join(f).is_file()) {
        let times = read_npy(&dir.join("time_s.npy"), &[None])?;
        let ns = times.len();
        let forces = read_npy(&dir.join("forces_n.npy"), &[Some(ns), Some(nc)])?;
        let energies = read_npy(&dir.join("energy_j.npy"), &[Some(ns), Some(nc)])?;
        let wall = read_npy(&dir.join("wall_energy_j.npy"), &[Some(ns)])?;
        // Older runs lack these: 0.
        let optional = |name: &str| match dir.join(name) {
            p if p.is_file() => read_npy(&p, &[Some(ns)]),
            _ => Ok(vec![0.0; ns]),
        };
        let work = optional("input_work_j.npy")?;
        let lost = optional("dissipated_j.npy")?;
        return Ok(trajectory(
            n_elements, times, forces, energies, wall, work, lost,
        ));
    }
    let forces_csv = dir.join("forces.csv");
    let energy_csv = dir.join("energy.csv");
    for f in [&forces_csv, &energy_csv] {
        if !f.is_file() {
            return Err(read_error(
                f,
                format!(
                    "missing: the run has neither {} nor this file; re-run `woodpile simulate`",
                    npy.join(", ")
                ),
            ));
        }
    }
    let (times, forces) = read_csv(
        &forces_csv,
        &(0..nc)
            .map(|c| format!("contact_{c}_n"))
            .collect::<Vec<_>>(),
        0,
    )?;
    let mut energy_cols: Vec<String> = (0..nc).map(|l| format!("layer_{l}_j")).collect();
    energy_cols.extend(["wall_j", "input_work_j", "dissipated_j"].map(String::from));
    let (etimes, e) = read_csv(&energy_csv, &energy_cols, 2)?;
    if etimes.len() != times.len() {
        return Err(read_error(
            &energy_csv,
            format!(
                "{} samples, but forces.csv has {}",
                etimes.len(),
                times.len()
            ),
        ));
    }
    let w = nc + 3;
    let energies = e.chunks(w).flat_map(|r| r[..nc].to_vec()).collect();
    let column = |k: usize| e.chunks(w).map(|r| r[k]).collect();
    let (wall, work, lost) = (column(nc), column(nc + 1), column(nc + 2));
    Ok(trajectory(
        n_elements, times, forces, energies, wall, work, lost,
    ))
}

fn trajectory(
    n_elements: usize,
    times_s: Vec<f64>,
    contact_forces_n: Vec<f64>,
    layer_energies_j: Vec<f64>,
    wall_energy_j: Vec<f64>,
    input_work_j: Vec<f64>,
    dissipated_j: Vec<f64>,
) -> Trajectory {
    Trajectory {
        n_elements,
        times_s,
        contact_forces_n,
        layer_energies_j,
        wall_energy_j,
        input_work_j,
        dissipated_j,
        ..Trajectory::default()
    }
}

/// Reads a float64 `.npy` file and checks its shape (None: any length).
pub(crate) fn read_npy(path: &Path, shape: &[Option<usize>]) -> Result<Vec<f64>, Error> {
    let bytes = fs::read(path).map_err(|e| Error::Read {
        path: path.to_path_buf(),
        source: e,
    })?;
    let (actual, values) = crate::npy::read(&bytes).map_err(|e| read_error(path, e))?;
    let actual: Vec<usize> = actual.iter().map(|&d| d as usize).collect();
    let fits = actual.len() == shape.len()
        && actual
            .iter()
            .zip(shape)
            .all(|(a, s)| s.is_none_or(|s| s == *a));
    if !fits {
        let want: Vec<String> = shape
            .iter()
            .map(|s| s.map_or("any".to_string(), |s| s.to_string()))
            .collect();
        return Err(read_error(
            path,
            format!("array of shape {actual:?}, expected [{}]", want.join(", ")),
        ));
    }
    if let Some(k) = values.iter().position(|v| !v.is_finite()) {
        // A run never writes a non-finite sample (a blow-up is an error, not a file).
        let at = match actual.as_slice() {
            [_, cols] if *cols > 0 => format!("row {}, column {}", k / cols, k % cols),
            _ => format!("element {k}"),
        };
        return Err(read_error(
            path,
            format!("holds {} at {at}: woodpile never writes a non-finite sample, so the file was changed or damaged; re-run `woodpile simulate`", values[k]),
        ));
    }
    Ok(values)
}

/// Reads `time_s` and the named columns of a CSV file: (times, rows of the columns). The last
/// `optional` columns may be missing (older runs): they read 0.
fn read_csv(
    path: &Path,
    columns: &[String],
    optional: usize,
) -> Result<(Vec<f64>, Vec<f64>), Error> {
    let csv_err = |e: csv::Error| read_error(path, e.to_string());
    let mut r = csv::Reader::from_path(path).map_err(csv_err)?;
    let header = r.headers().map_err(csv_err)?.clone();
    let index = |name: &str| {
        header
            .iter()
            .position(|h| h == name)
            .ok_or_else(|| read_error(path, format!("no column `{name}`")))
    };
    let t_col = index("time_s")?;
    let required = columns.len() - optional;
    let cols = columns
        .iter()
        .enumerate()
        .map(|(k, c)| match index(c) {
            Err(_) if k >= required => Ok(None),
            found => found.map(Some),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let (mut times, mut data) = (Vec::new(), Vec::new());
    for (line, rec) in r.records().enumerate() {
        let rec = rec.map_err(csv_err)?;
        let num = |i: usize| -> Result<f64, Error> {
            rec.get(i)
                .and_then(|s| s.trim().parse().ok())
                .ok_or_else(|| {
                    read_error(
                        path,
                        format!("line {}: not a number in column {}", line + 2, i + 1),
                    )
                })
        };
        times.push(num(t_col)?);
        for &c in &cols {
            data.push(c.map_or(Ok(0.0), num)?);
        }
    }
    Ok((times, data))
}

/// What kind of output directory a command was given (`woodpile plot` tells them apart).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DirKind {
    /// A `woodpile simulate` run: it holds `run.json`.
    Run,
    /// A `woodpile optimize` output: it holds `history.csv` and one of `summary.json`,
    /// `best.toml`, `checkpoint.json`.
    Optimization,
    /// A `woodpile sensitivity` study: it holds the files of [`crate::sensitivity::FILES`].
    Sensitivity,
}

/// Files that mark an optimisation output (besides `history.csv`).
const OPT_MARKERS: [&str; 3] = [
    "summary.json",
    "best.toml",
    crate::optimize::CHECKPOINT_FILE,
];

/// A study's directory, told by its files: a sensitivity study (drawn as its bar charts) or a
/// samples study (refused: its figures are columns of `samples.csv`, nothing to draw). None for
/// anything else.
fn study_dir(dir: &Path) -> Result<Option<DirKind>, Error> {
    let has = |f: &str| dir.join(f).is_file();
    if has("indices.csv") && has("outputs.csv") {
        return match has(crate::sensitivity::MARKER) {
            true => Ok(Some(DirKind::Sensitivity)),
            false => Err(bad_dir(dir, "looks like a `woodpile sensitivity` study (it holds indices.csv) but its summary.json is missing: the study did not finish; run it again into a new directory")),
        };
    }
    if has("samples.csv") && dir.join("samples").is_dir() {
        return Err(bad_dir(
            dir,
            "is a samples study of a scenario's [uncertainty] (samples.csv, samples/), which has no figures to draw: each sample's figures of merit are columns of samples.csv; to draw one sample, simulate its scenario (samples/NNN.toml) and plot that run",
        ));
    }
    Ok(None)
}

/// Tells a simulate run from an optimisation output; anything else is a usage error that says
/// what was expected.
pub fn detect_dir(dir: &Path) -> Result<DirKind, Error> {
    if !dir.is_dir() {
        return Err(bad_dir(
            dir,
            "is not a directory; give a directory written by `woodpile simulate` or `woodpile optimize`",
        ));
    }
    if dir.join(RUN_MARKER).is_file() {
        return Ok(DirKind::Run);
    }
    // Files only a simulate run writes (summary.json is written by both).
    let run_only = RUN_FILES
        .iter()
        .filter(|f| **f != "summary.json" && **f != RUN_MARKER)
        .find(|f| dir.join(f).is_file());
    if let Some(found) = run_only {
        return Err(bad_dir(
            dir,
            format!("looks like a `woodpile simulate` run (it holds {found}) but its {RUN_MARKER} is missing, and plotting a run needs it (its layout and settings): re-run the simulation into this directory, replacing the earlier run"),
        ));
    }
    if let Some(kind) = study_dir(dir)? {
        return Ok(kind);
    }
    let history = dir.join("history.csv").is_file();
    let marker = OPT_MARKERS.iter().any(|m| dir.join(m).is_file());
    match (history, marker) {
        (true, true) => Ok(DirKind::Optimization),
        (false, true) => Err(bad_dir(
            dir,
            "looks like a `woodpile optimize` output but holds no history.csv: it was written by another version or is incomplete; re-run `woodpile optimize`",
        )),
        _ => Err(bad_dir(
            dir,
            "is neither a woodpile run (no run.json) nor a `woodpile optimize` output (no history.csv with summary.json, best.toml or checkpoint.json)",
        )),
    }
}
