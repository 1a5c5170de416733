//! Lattice scenarios (`[lattice]` instead of `[chain]`, docs/physics.md §16) and their run
//! directories.
//!
//! ```toml
//! [lattice]
//! layers = [   # top to bottom; unset keys: the layer above's
//!   { rods = 3, pitch_mm = 20.0, length_mm = 80.0, diameter_mm = 5.0, material = "fused-quartz" },
//!   { rods = 3 },
//! ]
//! rod = { fe_elements = 4 }    # elements per half rod
//! [excitation]
//! kind = "impact"
//! at_mm = [0.0, 0.0]
//! [wall]
//! supports = "centres"         # or [{ x_mm = 0.0, y_mm = 20.0 }, …]
//! ```
//!
//! The run directory holds `run.json` (the completed scenario and the `contacts` in output
//! order, each `{ layer_above, rod_above, layer_below, rod_below, x_mm, y_mm }`: the striker is
//! layer 0, the supports layer L + 1 with the support's number as their rod), `summary.json`
//! (`contact_peak_forces_n` in that order, the transmitted peak, the energy balance),
//! `forces.csv` / `forces_n.npy` (samples × contacts), `supports.csv` (each support's force and
//! their sum, `transmitted_n`), `energy.csv` and `time_s.npy`.
//! [`read_lattice_run`] reads `run.json`, `time_s.npy` and `forces_n.npy` back (for figures).

use crate::error::Error;
use crate::scenario::{material_of, resolve_run_spec, MaterialSpec, RunSpec, StrikerSpec};
use serde::{Deserialize, Serialize};
use std::path::Path;
use woodpile::model::{Lattice, LatticeBuilder, LayerSpec, Supports};
use woodpile::simulate::LatticeRun;
use woodpile::{Method, RunSettings, Striker};

/// Run-directory format tag of a lattice run.
pub const LATTICE_RUN_FORMAT: &str = "woodpile-lattice-run/1";

/// Files a lattice run writes (its own, for the staging's overwrite policy).
pub const LATTICE_RUN_FILES: &[&str] = &[
    "run.json",
    "summary.json",
    "forces.csv",
    "supports.csv",
    "energy.csv",
    "forces_n.npy",
    "time_s.npy",
];

/// A whole lattice scenario file.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LatticeScenario {
    /// One line saying what the scenario is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// `[lattice]`.
    pub lattice: LatticeSpec,
    /// `[excitation]` (an impact).
    #[serde(default)]
    pub excitation: LatticeExcitationSpec,
    /// `[wall]`: where the supports are.
    #[serde(default)]
    pub wall: LatticeWallSpec,
    /// `[run]`, as for a chain (default: a peak tolerance of 1e-5, RKN 6(4)).
    #[serde(default)]
    pub run: RunSpec,
}

/// `[lattice]`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LatticeSpec {
    /// The layers, top to bottom.
    pub layers: Vec<LayerToml>,
    /// Every rod a finite-element beam.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rod: Option<RodToml>,
}

/// One layer; unset keys take the layer above's.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LayerToml {
    /// Number of rods.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rods: Option<usize>,
    /// Distance between neighbouring rods' axes \[mm\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pitch_mm: Option<f64>,
    /// Rod length \[mm\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length_mm: Option<f64>,
    /// Rod diameter \[mm\] (default 5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diameter_mm: Option<f64>,
    /// Material (default `fused-quartz`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<MaterialSpec>,
    /// Angle to the rods of the layer above \[deg\] (default 90; not for the top layer).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angle_deg: Option<f64>,
}

/// `rod = { fe_elements = n }`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RodToml {
    /// Finite elements per half rod.
    pub fe_elements: usize,
}

/// `[excitation]` of a lattice: an impact at a point of the top layer.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LatticeExcitationSpec {
    /// `impact` (the only kind for lattices so far).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kind: Option<String>,
    /// (x, y) of the impact \[mm\] (default: the centre).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at_mm: Option<[f64; 2]>,
    /// Drop height \[m\] (default 0.20).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub drop_height_m: Option<f64>,
    /// Initial striker velocity \[m/s\] (instead of `drop_height_m`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity_m_s: Option<f64>,
    /// The striker sphere (default: the paper's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub striker: Option<StrikerSpec>,
}

/// `[wall]` of a lattice: the paper's sensors at the supports.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LatticeWallSpec {
    /// `"centres"` (default) or a list of points.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub supports: Option<SupportsToml>,
}

/// `supports = "centres"` or `supports = [{ x_mm, y_mm }, …]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum SupportsToml {
    /// `"centres"`.
    Named(String),
    /// The points.
    Points(Vec<PointToml>),
}

/// `{ x_mm, y_mm }`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointToml {
    /// x \[mm\].
    pub x_mm: f64,
    /// y \[mm\].
    pub y_mm: f64,
}

/// A lattice scenario resolved into the core's types.
#[derive(Debug, Clone)]
pub struct ResolvedLattice {
    /// What built the lattice (its layers, elements, supports and wall).
    pub builder: LatticeBuilder,
    /// The lattice.
    pub lattice: Lattice,
    /// The striker.
    pub striker: Striker,
    /// The impact point \[m\].
    pub at_m: [f64; 2],
    /// How to run it.
    pub settings: RunSettings,
}

/// Whether a scenario text describes a lattice (has a top-level `lattice` table).
pub fn is_lattice(text: &str) -> bool {
    text.parse::<toml::Table>()
        .map(|t| t.contains_key("lattice"))
        .unwrap_or(false)
}

impl LatticeScenario {
    /// Parses a lattice scenario; syntax errors and unknown keys give the line and column.
    pub fn parse(text: &str, source_name: &str) -> Result<Self, Error> {
        toml::from_str(text).map_err(|e| Error::Parse {
            source_name: source_name.into(),
            message: e.to_string(),
        })
    }

    /// The scenario with every default written out.
    pub fn complete(&self) -> LatticeScenario {
        use woodpile::defaults::*;
        let mut s = self.clone();
        let mut above: Option<LayerToml> = None;
        for layer in &mut s.lattice.layers {
            if let Some(a) = &above {
                layer.rods = layer.rods.or(a.rods);
                layer.pitch_mm = layer.pitch_mm.or(a.pitch_mm);
                layer.length_mm = layer.length_mm.or(a.length_mm);
                layer.diameter_mm = layer.diameter_mm.or(a.diameter_mm);
                layer.material = layer.material.clone().or(a.material.clone());
                layer.angle_deg = layer.angle_deg.or(a.angle_deg).or(Some(CROSSING_ANGLE_DEG));
            } else {
                layer.diameter_mm.get_or_insert(ROD_DIAMETER_MM);
                layer
                    .material
                    .get_or_insert(MaterialSpec::Preset(ELEMENT_MATERIAL.into()));
            }
            above = Some(layer.clone());
        }
        s.lattice.rod.get_or_insert(RodToml { fe_elements: 8 });
        let x = &mut s.excitation;
        x.kind.get_or_insert("impact".into());
        x.at_mm.get_or_insert([0.0, 0.0]);
        if x.velocity_m_s.is_none() {
            x.drop_height_m.get_or_insert(DROP_HEIGHT_M);
        }
        let st = x.striker.get_or_insert(StrikerSpec::default());
        st.diameter_mm.get_or_insert(STRIKER_DIAMETER_MM);
        st.material
            .get_or_insert(MaterialSpec::Preset(STRIKER_MATERIAL.into()));
        s.wall
            .supports
            .get_or_insert(SupportsToml::Named("centres".into()));
        let r = &mut s.run;
        r.duration_s.get_or_insert(IMPACT_DURATION_S);
        r.sample_interval_s.get_or_insert(SAMPLE_INTERVAL_S);
        if r.integrator.is_none() && r.time_step_s.is_none() && r.peak_tolerance.is_none() {
            r.peak_tolerance = Some(STUDY_PEAK_TOLERANCE);
        } else if r.peak_tolerance.is_none() {
            let rk4 = r.integrator.is_none_or(|i| i.name() == "rk4");
            r.integrator
                .get_or_insert(crate::scenario::IntegratorKind::Rk4);
            if rk4 {
                r.time_step_s.get_or_insert(TIME_STEP_S);
            } else {
                r.rtol.get_or_insert(RTOL);
                r.atol.get_or_insert(ATOL);
            }
        }
        s
    }

    /// Checks the scenario and builds the lattice, the striker and the settings; errors name
    /// the keys.
    pub fn resolve(&self) -> Result<ResolvedLattice, Error> {
        let s = self.complete();
        if s.lattice.layers.is_empty() {
            return Err(Error::invalid(
                "lattice.layers",
                "[]",
                "give at least one layer",
            ));
        }
        let mut layers = Vec::new();
        for (k, l) in s.lattice.layers.iter().enumerate() {
            let key = |f: &str| format!("lattice.layers[{k}].{f}");
            let required = |f: &str, v: Option<f64>| {
                v.ok_or_else(|| {
                    Error::invalid(
                        key(f),
                        "(unset)",
                        "required in the top layer (the layers below take the layer above's)",
                    )
                })
            };
            if k == 0 {
                if let Some(a) = self.lattice.layers[0].angle_deg {
                    return Err(Error::invalid(key("angle_deg"), a, "the top layer's rods lie along x; angle_deg is a lower layer's angle to the layer above"));
                }
            }
            let rods = l.rods.ok_or_else(|| {
                Error::invalid(key("rods"), "(unset)", "required in the top layer")
            })?;
            let pitch = if rods > 1 {
                required("pitch_mm", l.pitch_mm)?
            } else {
                l.pitch_mm.unwrap_or(0.0)
            };
            layers.push(LayerSpec {
                rods,
                pitch_m: pitch * 1e-3,
                length_m: required("length_mm", l.length_mm)? * 1e-3,
                diameter_m: required("diameter_mm", l.diameter_mm)? * 1e-3,
                material: material_of(&key("material"), l.material.as_ref().expect("completed"))?,
                angle_deg: l.angle_deg.unwrap_or(0.0),
            });
        }
        let fe_elements = s.lattice.rod.expect("completed").fe_elements;
        check_size(&layers, fe_elements)?;
        let supports = match s.wall.supports.as_ref().expect("completed") {
            SupportsToml::Named(n) if n == "centres" => Supports::Centres,
            SupportsToml::Named(n) => {
                return Err(Error::invalid(
                    "wall.supports",
                    format!("\"{n}\""),
                    "\"centres\" or a list of points [{ x_mm = …, y_mm = … }, …]",
                ))
            }
            SupportsToml::Points(p) => {
                Supports::Points(p.iter().map(|p| [p.x_mm * 1e-3, p.y_mm * 1e-3]).collect())
            }
        };
        let mut builder = LatticeBuilder::new(layers, fe_elements);
        builder.supports = supports;
        let lattice = builder.build()?;
        let striker = resolve_striker(&s.excitation)?;
        let at = s.excitation.at_mm.expect("completed");
        let at_m = [at[0] * 1e-3, at[1] * 1e-3];
        lattice.top_point(at_m, "excitation.at_mm")?;
        let settings = resolve_run_spec(&s.run)?;
        if matches!(settings.method, Method::ExactModes { .. }) {
            return Err(Error::invalid(
                "run.integrator",
                "exact-modes",
                "lattices run with rk4, dopri5 or a peak tolerance",
            ));
        }
        Ok(ResolvedLattice {
            builder,
            lattice,
            striker,
            at_m,
            settings,
        })
    }
}

/// Most layers of a lattice (each layer's rod modes are one eigenproblem: about 0.3 s at 64
/// elements per half rod on the project's machine).
pub const MAX_LATTICE_LAYERS: usize = 100;

/// Most rods of a lattice, all layers together.
pub const MAX_LATTICE_RODS: usize = 10_000;

/// Most modal coordinates of a lattice: rods × 2(2n + 1) for n elements per half rod (a
/// 10-layer lattice of 5 rods at 16 elements has 3,300).
pub const MAX_LATTICE_MODES: usize = 100_000;

/// Most crossings a lattice may have: the products of the rods of adjacent layers, summed (each
/// crossing is a contact; a 10-layer lattice of 5 rods per layer has 225).
pub const MAX_LATTICE_CROSSINGS: usize = 100_000;

/// Refuses a lattice too large to build and run in reasonable time and memory, before its rods'
/// modes or crossings are computed.
fn check_size(layers: &[LayerSpec], fe_elements: usize) -> Result<(), Error> {
    if layers.len() > MAX_LATTICE_LAYERS {
        return Err(Error::invalid(
            "lattice.layers",
            format!("{} layers", layers.len()),
            format!("at most {MAX_LATTICE_LAYERS} layers"),
        ));
    }
    let rods = layers
        .iter()
        .fold(0usize, |sum, l| sum.saturating_add(l.rods));
    if rods > MAX_LATTICE_RODS {
        return Err(Error::invalid(
            "lattice.layers",
            format!("{rods} rods in all"),
            format!("at most {MAX_LATTICE_RODS} rods in all layers together"),
        ));
    }
    let crossings = layers.windows(2).fold(0usize, |sum, w| {
        sum.saturating_add(w[0].rods.saturating_mul(w[1].rods))
    });
    if crossings > MAX_LATTICE_CROSSINGS {
        return Err(Error::invalid(
            "lattice.layers",
            format!("up to {crossings} crossings (rods × rods of adjacent layers)"),
            format!("at most {MAX_LATTICE_CROSSINGS} crossings: fewer rods per layer"),
        ));
    }
    let modes = rods.saturating_mul(2 * (2 * fe_elements.min(1 << 20) + 1));
    if modes > MAX_LATTICE_MODES {
        return Err(Error::invalid(
            "lattice.rod.fe_elements",
            fe_elements,
            format!(
                "{rods} rods of {fe_elements} elements per half rod have {modes} modal coordinates, more than {MAX_LATTICE_MODES}: fewer elements or fewer rods"
            ),
        ));
    }
    Ok(())
}

/// The run-size estimate of a resolved lattice: its steps and the values its run directory
/// holds per sample (each contact's force in CSV and NPY, the supports and their sum, the
/// energies, time).
pub fn run_size(r: &ResolvedLattice) -> crate::limits::RunSize {
    let contacts = r.lattice.contacts.len();
    crate::limits::RunSize::with_columns(&r.settings, 2 * contacts + 8)
}

fn resolve_striker(x: &LatticeExcitationSpec) -> Result<Striker, Error> {
    let kind = x.kind.as_deref().unwrap_or("impact");
    if kind != "impact" {
        return Err(Error::invalid(
            "excitation.kind",
            format!("\"{kind}\""),
            "a lattice is struck (\"impact\"); blasts and drives on lattices are not modelled yet",
        ));
    }
    crate::scenario::striker_of(x.drop_height_m, x.velocity_m_s, x.striker.as_ref(), None)
}

/// One contact in `run.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContactJson {
    /// Layer of the body above (0: the striker).
    pub layer_above: usize,
    /// Its rod number, 1.. (1 for the striker).
    pub rod_above: usize,
    /// Layer of the body below (L + 1: a support).
    pub layer_below: usize,
    /// Its rod number, or the support's number.
    pub rod_below: usize,
    /// Where the contact is \[mm\].
    pub x_mm: f64,
    /// Where the contact is \[mm\].
    pub y_mm: f64,
}

/// The contacts in output order: the striker's, the crossings, the supports.
pub fn contacts_json(r: &ResolvedLattice) -> Vec<ContactJson> {
    let lattice = &r.lattice;
    let hit = lattice
        .top_point(r.at_m, "excitation.at_mm")
        .expect("checked by resolve");
    let top = &lattice.rods[hit.rod];
    let p = top.point_m(hit.s_m);
    let mut out = vec![ContactJson {
        layer_above: 0,
        rod_above: 1,
        layer_below: 1,
        rod_below: top.number,
        x_mm: p[0] * 1e3,
        y_mm: p[1] * 1e3,
    }];
    for c in &lattice.contacts {
        let a = &lattice.rods[c.above.rod];
        let (layer_below, rod_below) = match (c.below, c.support) {
            (Some(b), _) => (lattice.rods[b.rod].layer, lattice.rods[b.rod].number),
            (None, s) => (lattice.layers + 1, s.unwrap_or(0)),
        };
        out.push(ContactJson {
            layer_above: a.layer,
            rod_above: a.number,
            layer_below,
            rod_below,
            x_mm: c.point_m[0] * 1e3,
            y_mm: c.point_m[1] * 1e3,
        });
    }
    out
}

/// `run.json` of a lattice run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LatticeRunJson {
    /// `woodpile`.
    pub tool: String,
    /// [`LATTICE_RUN_FORMAT`].
    pub format: String,
    /// Version of woodpile that wrote it.
    pub version: String,
    /// Scenario name.
    pub scenario_name: String,
    /// The scenario with every default filled in.
    pub scenario: LatticeScenario,
    /// The contacts in output order.
    pub contacts: Vec<ContactJson>,
    /// β per contact in output order [N/m^1.5].
    pub contact_betas_n_per_m1_5: Vec<f64>,
    /// Rods per layer, top to bottom.
    pub rods_per_layer: Vec<usize>,
    /// Total mass of the rods \[kg\].
    pub lattice_mass_kg: f64,
    /// Striker mass \[kg\] and initial velocity \[m/s\].
    pub striker_mass_kg: f64,
    /// Striker initial velocity \[m/s\].
    pub striker_velocity_m_s: f64,
    /// Integrator steps taken.
    pub steps: u64,
    /// Number of samples.
    pub n_samples: usize,
}

/// `summary.json` of a lattice run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LatticeSummaryJson {
    /// Peak force per contact, in `run.json`'s order \[N\].
    pub contact_peak_forces_n: Vec<f64>,
    /// When each peak occurred \[s\].
    pub contact_peak_times_s: Vec<f64>,
    /// Peak of the striker's contact \[N\].
    pub incident_peak_force_n: f64,
    /// Peak of the sum of the support forces \[N\].
    pub transmitted_peak_force_n: f64,
    /// Largest |E(t) − E(0)| / E(0) over the samples.
    pub energy_max_relative_error: f64,
}

/// Writes a lattice run's files into `dir` (a staging directory).
pub fn write_lattice_run(
    dir: &Path,
    name: &str,
    scenario: &LatticeScenario,
    resolved: &ResolvedLattice,
    betas: &[f64],
    run: &LatticeRun,
) -> Result<(), Error> {
    let contacts = contacts_json(resolved);
    let lattice = &resolved.lattice;
    let run_json = LatticeRunJson {
        tool: "woodpile".into(),
        format: LATTICE_RUN_FORMAT.into(),
        version: env!("CARGO_PKG_VERSION").into(),
        scenario_name: name.into(),
        scenario: scenario.complete(),
        rods_per_layer: (1..=lattice.layers)
            .map(|l| lattice.rods.iter().filter(|r| r.layer == l).count())
            .collect(),
        lattice_mass_kg: lattice.mass_kg(),
        striker_mass_kg: resolved.striker.mass_kg(),
        striker_velocity_m_s: resolved.striker.velocity_m_s,
        contact_betas_n_per_m1_5: betas.to_vec(),
        steps: run.stats.steps,
        n_samples: run.times_s.len(),
        contacts,
    };
    let summary = LatticeSummaryJson {
        contact_peak_forces_n: run.contact_peak_forces_n.clone(),
        contact_peak_times_s: run.contact_peak_times_s.clone(),
        incident_peak_force_n: run.incident_peak_force_n,
        transmitted_peak_force_n: run.transmitted_peak_force_n,
        energy_max_relative_error: run.energy.max_relative_error,
    };
    let header = |names: Vec<String>| {
        std::iter::once("time_s".to_string())
            .chain(names)
            .collect::<Vec<_>>()
    };
    let forces_header = header(
        (0..run.contacts)
            .map(|c| format!("contact_{c}_n"))
            .collect(),
    );
    crate::rundir::write_csv(
        &dir.join("forces.csv"),
        &forces_header,
        &run.times_s,
        run.contact_forces_n
            .chunks(run.contacts)
            .map(<[f64]>::to_vec),
    )?;
    let mut support_header: Vec<String> = (1..=run.supports.len())
        .map(|s| format!("support_{s}_n"))
        .collect();
    support_header.push("transmitted_n".into());
    let transmitted = run.transmitted_force_n();
    crate::rundir::write_csv(
        &dir.join("supports.csv"),
        &header(support_header),
        &run.times_s,
        run.contact_forces_n
            .chunks(run.contacts)
            .zip(&transmitted)
            .map(|(row, t)| {
                let mut v: Vec<f64> = run.supports.iter().map(|&s| row[s]).collect();
                v.push(*t);
                v
            }),
    )?;
    crate::rundir::write_csv(
        &dir.join("energy.csv"),
        &header(vec!["total_j".into()]),
        &run.times_s,
        run.energy_j.iter().map(|e| vec![*e]),
    )?;
    let n = run.times_s.len() as u64;
    crate::rundir::write_npy(
        &dir.join("forces_n.npy"),
        &[n, run.contacts as u64],
        &run.contact_forces_n,
    )?;
    crate::rundir::write_npy(&dir.join("time_s.npy"), &[n], &run.times_s)?;
    crate::rundir::write_json(&dir.join("summary.json"), &summary)?;
    crate::rundir::write_json(&dir.join("run.json"), &run_json)
}

/// A lattice run read back from its directory: `run.json` and the sampled contact forces.
#[derive(Debug, Clone, PartialEq)]
pub struct LatticeRunRead {
    /// `run.json`.
    pub run: LatticeRunJson,
    /// Sample times \[s\] (`time_s.npy`).
    pub times_s: Vec<f64>,
    /// Contact forces \[N\], samples × contacts in `run.json`'s order (`forces_n.npy`).
    pub forces_n: Vec<f64>,
}

impl LatticeRunRead {
    /// Number of contacts.
    pub fn n_contacts(&self) -> usize {
        self.run.contacts.len()
    }

    /// The force history of contact `c` \[N\].
    pub fn contact_force_n(&self, c: usize) -> Vec<f64> {
        let n = self.n_contacts();
        self.forces_n.chunks(n).map(|row| row[c]).collect()
    }

    /// The supports' contacts (their layer below is L + 1), in output order.
    pub fn supports(&self) -> Vec<usize> {
        let below = self.run.rods_per_layer.len() + 1;
        (0..self.n_contacts())
            .filter(|&c| self.run.contacts[c].layer_below == below)
            .collect()
    }

    /// The transmitted force, the sum of the supports' forces, at every sample \[N\] (the
    /// `transmitted_n` column of `supports.csv`).
    pub fn transmitted_force_n(&self) -> Vec<f64> {
        let (n, supports) = (self.n_contacts(), self.supports());
        self.forces_n
            .chunks(n)
            .map(|row| supports.iter().map(|&s| row[s]).sum())
            .collect()
    }
}

/// Whether `dir` holds a lattice run (its `run.json` has the format [`LATTICE_RUN_FORMAT`]).
pub fn is_lattice_run(dir: &Path) -> bool {
    std::fs::read_to_string(dir.join(crate::atomic::RUN_MARKER))
        .ok()
        .and_then(|text| serde_json::from_str::<serde_json::Value>(&text).ok())
        .is_some_and(|v| v.get("format").and_then(|f| f.as_str()) == Some(LATTICE_RUN_FORMAT))
}

/// Reads a lattice run directory written by [`write_lattice_run`]: `run.json`, `time_s.npy`
/// and `forces_n.npy`, whose shape must be samples × the contacts `run.json` lists. A missing,
/// foreign or damaged file is an error naming it and saying what is wrong.
pub fn read_lattice_run(dir: &Path) -> Result<LatticeRunRead, Error> {
    use crate::atomic::read_error;
    let path = dir.join(crate::atomic::RUN_MARKER);
    let text = std::fs::read_to_string(&path).map_err(|e| Error::Read {
        path: path.clone(),
        source: e,
    })?;
    let run: LatticeRunJson = serde_json::from_str(&text).map_err(|e| {
        read_error(
            &path,
            format!("not a complete lattice run.json ({e}); re-run `woodpile simulate`"),
        )
    })?;
    if run.tool != "woodpile" || run.format != LATTICE_RUN_FORMAT {
        return Err(read_error(
            &path,
            format!(
                "tool `{}`, format `{}`: not a woodpile lattice run (`{LATTICE_RUN_FORMAT}`)",
                run.tool, run.format
            ),
        ));
    }
    let n = run.contacts.len();
    if n == 0 {
        return Err(read_error(
            &path,
            "lists no contacts; re-run `woodpile simulate`",
        ));
    }
    let missing = |f: &str| {
        read_error(
            &dir.join(f),
            "missing: a lattice run writes it; re-run `woodpile simulate`",
        )
    };
    for f in ["time_s.npy", "forces_n.npy"] {
        if !dir.join(f).is_file() {
            return Err(missing(f));
        }
    }
    let times_s = crate::rundir::read_npy(&dir.join("time_s.npy"), &[None])?;
    let forces_n =
        crate::rundir::read_npy(&dir.join("forces_n.npy"), &[Some(times_s.len()), Some(n)])?;
    Ok(LatticeRunRead {
        run,
        times_s,
        forces_n,
    })
}
