//! Run outputs: `summary.json`, `run.json`, CSV and NumPy files, written atomically.
//!
//! Everything is written into a sibling staging directory `.NAME.partial-PID` and renamed to the
//! output directory at the end, so a directory named like the output never holds a half-written
//! run. An existing output directory is replaced only when it holds a previous run (`run.json`)
//! or is empty.

use crate::error::CliError;
use crate::scenario::{Resolved, Scenario};
use serde::Serialize;
use std::fs;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use woodpile::{Excitation, Method, RunSummary, Trajectory};

/// The file that marks a directory as a previous `woodpile` run.
pub const RUN_MARKER: &str = "run.json";

/// Turns an I/O error on `path` into [`CliError::Output`] naming the path.
pub(crate) fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> CliError + '_ {
    move |e| CliError::Output {
        path: path.to_path_buf(),
        source: e,
    }
}

/// What an existing output directory holds.
fn check_target(target: &Path) -> Result<(), CliError> {
    match fs::read_dir(target) {
        Ok(mut entries) => {
            if entries.next().is_none() || target.join(RUN_MARKER).is_file() {
                Ok(())
            } else {
                Err(CliError::OutputNotEmpty {
                    path: target.to_path_buf(),
                })
            }
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) if target.exists() && !target.is_dir() => Err(CliError::Output {
            path: target.to_path_buf(),
            source: std::io::Error::new(e.kind(), "exists and is not a directory"),
        }),
        Err(e) => Err(io_err(target)(e)),
    }
}

/// A staging directory next to the output directory; removed on drop unless committed.
#[derive(Debug)]
pub struct Staging {
    dir: PathBuf,
    target: PathBuf,
    committed: bool,
}

impl Staging {
    /// Checks that `target` may be written (absent, empty, or a previous run) and creates the
    /// staging directory beside it (and any missing parents).
    pub fn prepare(target: &Path) -> Result<Self, CliError> {
        check_target(target)?;
        let name = target
            .file_name()
            .ok_or_else(|| CliError::Output {
                path: target.to_path_buf(),
                source: std::io::Error::new(
                    std::io::ErrorKind::InvalidInput,
                    "not a directory name",
                ),
            })?
            .to_string_lossy()
            .into_owned();
        let parent = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        fs::create_dir_all(&parent).map_err(io_err(&parent))?;
        let dir = parent.join(format!(".{name}.partial-{}", std::process::id()));
        if dir.exists() {
            fs::remove_dir_all(&dir).map_err(io_err(&dir))?;
        }
        fs::create_dir(&dir).map_err(io_err(&dir))?;
        Ok(Staging {
            dir,
            target: target.to_path_buf(),
            committed: false,
        })
    }

    /// Where to write the files.
    pub fn path(&self) -> &Path {
        &self.dir
    }

    /// The final output directory.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Moves the staged files into place, replacing a previous run.
    pub fn commit(mut self) -> Result<PathBuf, CliError> {
        check_target(&self.target)?;
        let mut old = None;
        if self.target.exists() {
            if self.target.join(RUN_MARKER).is_file() {
                let aside = self.dir.with_file_name(format!(
                    ".{}.old-{}",
                    self.target
                        .file_name()
                        .unwrap_or_default()
                        .to_string_lossy(),
                    std::process::id()
                ));
                fs::rename(&self.target, &aside).map_err(io_err(&self.target))?;
                old = Some(aside);
            } else {
                fs::remove_dir(&self.target).map_err(io_err(&self.target))?;
            }
        }
        if let Err(e) = fs::rename(&self.dir, &self.target) {
            if let Some(aside) = &old {
                let _ = fs::rename(aside, &self.target);
            }
            return Err(io_err(&self.target)(e));
        }
        self.committed = true;
        if let Some(aside) = old {
            let _ = fs::remove_dir_all(aside);
        }
        Ok(self.target.clone())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if !self.committed {
            let _ = fs::remove_dir_all(&self.dir);
        }
    }
}

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
#[derive(Debug, Clone, Serialize)]
pub struct EnergyJson {
    /// Total energy at t = 0 \[J\].
    pub initial_j: f64,
    /// Total energy at the end \[J\].
    pub final_j: f64,
    /// Work done by the load \[J\].
    pub input_work_j: f64,
    /// Largest relative error of the energy balance.
    pub max_relative_error: f64,
}

/// Integrator work in `summary.json` / `run.json`.
#[derive(Debug, Clone, Serialize)]
pub struct IntegratorJson {
    /// `rk4` or `dopri5`.
    pub method: &'static str,
    /// Accepted steps.
    pub steps: u64,
    /// Right-hand-side evaluations.
    pub rhs_evaluations: u64,
    /// Rejected steps.
    pub rejected_steps: u64,
}

/// The contents of `summary.json`: the figures of merit (model.md §8), units in the key names.
#[derive(Debug, Clone, Serialize)]
pub struct SummaryJson {
    /// Scenario name.
    pub scenario: String,
    /// `impact` or `blast`.
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
    /// Transmitted / incident.
    pub transmission_ratio: f64,
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

fn method_name(m: &Method) -> &'static str {
    match m {
        Method::Rk4 { .. } => "rk4",
        Method::Dopri5 { .. } => "dopri5",
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
        SummaryJson {
            scenario: r.name.to_string(),
            excitation: match r.resolved.excitation {
                Excitation::Impact(_) => "impact",
                Excitation::Blast(_) => "blast",
            },
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
            transmission_ratio: s.transmission_ratio,
            restitution_coefficient: s.restitution.map(|e| e.coefficient),
            striker_separated: s.restitution.map(|e| e.separated),
            contact_peak_forces_n: s.contact_peak_forces_n.clone(),
            contact_peak_times_s: s.contact_peak_times_s.clone(),
            layer_peak_energies_j: layer_peaks,
            energy: EnergyJson {
                initial_j: s.energy.initial_j,
                final_j: s.energy.final_j,
                input_work_j: s.energy.input_work_j,
                max_relative_error: s.energy.max_relative_error,
            },
            integrator: IntegratorJson {
                method: method_name(&r.resolved.settings.method),
                steps: s.stats.steps,
                rhs_evaluations: s.stats.rhs_evaluations,
                rejected_steps: s.stats.rejected_steps,
            },
            wall_time_s: s.wall_time_s,
        }
    }
}

/// Contact coefficients of a run in `run.json` \[N/m^1.5\].
#[derive(Debug, Clone, Serialize)]
struct BetasJson {
    /// Striker – element 1 (impact).
    striker: Option<f64>,
    /// Contacts 1..N−1, element i – element i+1.
    inner: Vec<f64>,
    /// Contact N, element N – wall (null for a free end).
    wall: Option<f64>,
}

#[derive(Debug, Clone, Serialize)]
struct ElementJson {
    label: String,
    total_mass_kg: f64,
    primary_mass_kg: f64,
    resonator_masses_kg: Vec<f64>,
    resonator_stiffnesses_n_per_m: Vec<f64>,
}

#[derive(Debug, Clone, Serialize)]
struct RunJson<'a> {
    tool: &'static str,
    version: &'static str,
    scenario_name: &'a str,
    scenario_file: Option<String>,
    /// The scenario with every default filled in (the same structure as the TOML file).
    scenario: Scenario,
    contact_betas_n_per_m1_5: BetasJson,
    striker_mass_kg: Option<f64>,
    striker_velocity_m_s: Option<f64>,
    elements: Vec<ElementJson>,
    integrator: IntegratorJson,
    n_samples: usize,
    wall_time_s: f64,
}

fn write_json<T: Serialize>(path: &Path, value: &T) -> Result<(), CliError> {
    let file = fs::File::create(path).map_err(io_err(path))?;
    let mut w = BufWriter::new(file);
    serde_json::to_writer_pretty(&mut w, value)
        .map_err(|e| io_err(path)(std::io::Error::other(e)))?;
    writeln!(w).and_then(|_| w.flush()).map_err(io_err(path))
}

/// Writes a CSV with a header and one row per sample (`time_s` then the row's values).
fn write_csv(
    path: &Path,
    header: &[String],
    times: &[f64],
    rows: impl Iterator<Item = Vec<f64>>,
) -> Result<(), CliError> {
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
pub fn write_npy(path: &Path, shape: &[u64], data: &[f64]) -> Result<(), CliError> {
    use npyz::WriterBuilder;
    let file = BufWriter::new(fs::File::create(path).map_err(io_err(path))?);
    let mut w = npyz::WriteOptions::<f64>::new()
        .default_dtype()
        .shape(shape)
        .writer(file)
        .begin_nd()
        .map_err(io_err(path))?;
    w.extend(data.iter().copied()).map_err(io_err(path))?;
    w.finish().map_err(io_err(path))
}

/// Writes every output file of a run into `dir`.
///
/// Files: `summary.json`, `run.json`, `forces.csv`, `energy.csv`, `displacements.csv`,
/// `velocities.csv`, `striker.csv` (impact), and `time_s.npy`, `forces_n.npy`
/// (samples × contacts 0..=N), `energy_j.npy` (samples × layers 0..=N), `wall_energy_j.npy`,
/// `input_work_j.npy`, `displacements_m.npy`, `velocities_m_s.npy` (samples × N),
/// `striker.npy` (impact: samples × \[position m, velocity m/s\]).
pub fn write_run(dir: &Path, r: &RunRecord<'_>) -> Result<(), CliError> {
    let t = r.trajectory;
    let n = t.n_elements;
    let nc = t.n_contacts();
    let ns = t.len();
    let chain = &r.resolved.chain;

    write_json(&dir.join("summary.json"), &SummaryJson::new(r))?;

    let (striker_beta, striker_mass, striker_v0) = match &r.resolved.excitation {
        Excitation::Impact(s) => (
            s.contact_beta(chain).ok(),
            Some(s.mass_kg()),
            Some(s.velocity_m_s),
        ),
        Excitation::Blast(_) => (None, None, None),
    };
    let s = r.summary;
    let run = RunJson {
        tool: "woodpile",
        version: env!("CARGO_PKG_VERSION"),
        scenario_name: r.name,
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
        integrator: IntegratorJson {
            method: method_name(&r.resolved.settings.method),
            steps: s.stats.steps,
            rhs_evaluations: s.stats.rhs_evaluations,
            rejected_steps: s.stats.rejected_steps,
        },
        n_samples: s.n_samples,
        wall_time_s: s.wall_time_s,
    };

    // CSV
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
    header.extend(["wall_j", "total_j", "input_work_j"].map(String::from));
    let energy_rows = t
        .layer_energies_j
        .chunks(nc)
        .zip(&t.wall_energy_j)
        .zip(&t.input_work_j)
        .map(|((row, &w), &work)| {
            let mut v = row.to_vec();
            let total = row.iter().sum::<f64>() + w;
            v.extend([w, total, work]);
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

    // NumPy
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

    // run.json last: its presence marks a complete run.
    write_json(&dir.join(RUN_MARKER), &run)
}
