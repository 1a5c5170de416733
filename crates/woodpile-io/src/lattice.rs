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
//! A blast or a drive (`kind = "blast"` / `"drive"`, the chains' keys) acts on
//! `points = "top-crossings"` (default) or `points_mm = [[x, y], …]`: a force split equally, or
//! a displacement actuator's tip (`excitation.tip`, keys as in a chain's `[wall]`) pressing on
//! each point; `[damping]` (the chains' keys and `modal_ratio`) and `[preload]` (gravity, and a
//! force on the load points) are read by the chains' readers (docs/physics.md §16).
//!
//! The run directory holds `run.json` (the completed scenario and the `contacts` in output
//! order, each `{ layer_above, rod_above, layer_below, rod_below, x_mm, y_mm }`: the striker is
//! layer 0, the supports layer L + 1 with the support's number as their rod), `summary.json`
//! (`contact_peak_forces_n` in that order, the transmitted peak, the energy balance),
//! `forces.csv` / `forces_n.npy` (samples × contacts), `supports.csv` (each support's force and
//! their sum, `transmitted_n`), `energy.csv` (with damping or loads also `work_j`,
//! `dissipated_j`; `summary.json` then has `lab`), each body's energy (`rod_energies.csv`,
//! `energy_j.npy`, `support_energy_j.npy`), each contact's Hertz potential
//! (`contact_energies.csv`, `contact_energy_j.npy`, samples × contacts), with lab physics each
//! contact's dissipated energy since the start (`contact_dissipated.csv`,
//! `contact_dissipated_j.npy`), and `time_s.npy`. Under a blast or drive the load points (a
//! displacement actuator's tip contacts) are the contacts of layer 0.
//! [`read_lattice_run`] reads `run.json`, `time_s.npy` and `forces_n.npy` back (for figures).

use crate::error::Error;
use crate::scenario::{
    material_of, resolve_run_spec, DampingSpec, DriveKind, ExcitationKind, ExcitationSpec, Key,
    KeyDefault, KeyType, MaterialSpec, PreloadSpec, ProfileKind, RunSpec, Scenario, SignalKind,
    StrikerSpec, SweepSpec,
};
use serde::{Deserialize, Serialize};
use std::path::Path;
use woodpile::model::{
    Lattice, LatticeBuilder, LatticeExcitation, LatticeLab, LayerSpec, LoadPoints, RodOverrides,
    Supports,
};
use woodpile::simulate::LatticeRun;
use woodpile::{Method, RunSettings, Striker};

/// Files a lattice run writes (its own, for the staging's overwrite policy).
pub const LATTICE_RUN_FILES: &[&str] = &[
    "run.json",
    "summary.json",
    "forces.csv",
    "supports.csv",
    "energy.csv",
    "rod_energies.csv",
    "forces_n.npy",
    "time_s.npy",
    "energy_j.npy",
    "support_energy_j.npy",
    "contact_energies.csv",
    "contact_energy_j.npy",
    "contact_dissipated.csv",
    "contact_dissipated_j.npy",
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
    /// `[damping]`: the chains' keys, and `modal_ratio` (default: lossless).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<DampingSpec>,
    /// `[preload]`: a static force on the load points and gravity (default: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preload: Option<PreloadSpec>,
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
    /// Each rod's length \[mm\], one per rod (graded designs; not taken by the layer below).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lengths_mm: Option<Vec<f64>>,
    /// Each rod's shift along its own axis \[mm\], one per rod (staggered designs; not taken by
    /// the layer below).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub offsets_mm: Option<Vec<f64>>,
}

/// `rod = { fe_elements = n }` or `rod = { modes = l }` (alternatives).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RodToml {
    /// Finite elements per half rod.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fe_elements: Option<usize>,
    /// The l lowest analytic free–free bending modes (and the two rigid modes) instead.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modes: Option<usize>,
}

/// `[excitation]` of a lattice: an impact at a point of the top layer, a blast or a force drive
/// on load points (the chains' keys, and `points` or `points_mm`), or rest.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LatticeExcitationSpec {
    /// `impact` (default), `blast`, `drive` or `rest`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kind: Option<String>,
    /// (x, y) of the impact \[mm\] (default: the centre).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "xy_mm"
    )]
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
    /// `"top-crossings"` (blast, drive, rest; default): every crossing of the top layer.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub points: Option<String>,
    /// The load points (x, y) \[mm\], each on a top rod (instead of `points`).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "xy_list_mm"
    )]
    pub points_mm: Option<Vec<[f64; 2]>>,
    /// Blast profile, as a chain's `excitation.profile`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<ProfileKind>,
    /// Friedlander peak force F0 of the whole lattice \[N\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub peak_force_n: Option<f64>,
    /// Friedlander duration Td \[s\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub duration_s: Option<f64>,
    /// Friedlander decay b.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub decay: Option<f64>,
    /// Table of a blast (`time_s, force_n`) or a drive (`time_s, value`), relative to the
    /// scenario file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// `force` (default: the total, split over the points) or `displacement` (an actuator
    /// pressing on every point through its tip).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub drive: Option<DriveKind>,
    /// A displacement actuator's tip, keys as in a chain's `[wall]` (default: the paper's
    /// sensor).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tip: Option<crate::scenario::WallSpec>,
    /// `harmonic`, `chirp` or `table` (drive).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub signal: Option<SignalKind>,
    /// Amplitude of the total force \[N\] (harmonic, chirp).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub amplitude: Option<f64>,
    /// Frequency \[Hz\] (harmonic).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frequency_hz: Option<f64>,
    /// Start frequency \[Hz\] (chirp).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start_hz: Option<f64>,
    /// End frequency \[Hz\] (chirp).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub end_hz: Option<f64>,
    /// Sweep duration \[s\] (chirp).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sweep_duration_s: Option<f64>,
    /// `linear` or `logarithmic` (chirp).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sweep: Option<SweepSpec>,
    /// Smooth ramp time \[s\] (drive).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ramp_s: Option<f64>,
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
    /// What drives it (an impact: `striker` at `at_m`).
    pub excitation: LatticeExcitation,
    /// Damping and static load.
    pub lab: LatticeLab,
}

/// The built-in lattice scenarios (name, TOML text), listed by `woodpile scenarios` after the
/// chains' and run by name as they are.
pub const BUILTIN_LATTICES: &[(&str, &str)] = &[("lattice", BUILTIN_LATTICE)];

/// `lattice`: the 3 × 3-rod, 4-layer quartz woodpile of docs/physics.md §16 struck off its
/// centre.
const BUILTIN_LATTICE: &str = r#"description = "3 x 3-rod, 4-layer quartz woodpile (80 mm rods, pitch 20 mm) struck at (13, 0) mm, 0.5 ms"
[lattice]
layers = [
  { rods = 3, pitch_mm = 20.0, length_mm = 80.0, diameter_mm = 5.0, material = "fused-quartz" },
  { rods = 3 },
  { rods = 3 },
  { rods = 3 },
]
rod = { fe_elements = 8 }
[excitation]
kind = "impact"
at_mm = [13.0, 0.0]
[wall]
supports = "centres"
[run]
duration_s = 5e-4
"#;

/// A built-in lattice scenario's TOML text by name.
pub fn builtin_lattice(name: &str) -> Option<&'static str> {
    BUILTIN_LATTICES
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, text)| *text)
}

/// Every key of a lattice scenario (`[lattice]`, `[excitation]`, `[wall]`, `[damping]`,
/// `[preload]`, `[run]`), in the order of the file, in the form of the chain's table
/// ([`crate::scenario::keys`], whose rows it reuses where a key means the same). Defaults are
/// read from [`woodpile::defaults`]; claim `lattice_keys_table`.
pub fn lattice_keys() -> &'static [Key] {
    static KEYS: std::sync::LazyLock<Vec<Key>> = std::sync::LazyLock::new(lattice_key_table);
    &KEYS
}

#[rustfmt::skip] // one row per key
fn lattice_key_table() -> Vec<Key> {
    use woodpile::defaults as d;
    use KeyDefault::{Derived, Float, Name};
    let above = || Derived("the layer above's".into());
    let key = |name, ty, unit, default, valid, doc| Key { name, ty, unit, default, choices: &[], alternatives: &[], valid, doc };
    vec![
        key("lattice", KeyType::Table, "", KeyDefault::None, "", "layers of parallel rods, every crossing a contact (instead of [chain])"),
        key("lattice.layers", KeyType::TableList, "", KeyDefault::None, "at least one layer", "the layers, top to bottom; unset keys take the layer above's"),
        key("lattice.layers[].rods", KeyType::Integer, "", above(), ">= 1; required in the top layer", "number of parallel rods"),
        key("lattice.layers[].pitch_mm", KeyType::Float, "mm", above(), "more than diameter_mm; required in the top layer when rods > 1", "distance between neighbouring rods' axes"),
        key("lattice.layers[].length_mm", KeyType::Float, "mm", above(), "> 0; required in the top layer unless lengths_mm is given", "rod length"),
        key("lattice.layers[].diameter_mm", KeyType::Float, "mm", Derived(format!("{} in the top layer, else the layer above's", d::ROD_DIAMETER_MM)), "> 0", "rod diameter"),
        key("lattice.layers[].material", KeyType::Material, "", Derived(format!("\"{}\" in the top layer, else the layer above's", d::ELEMENT_MATERIAL)), "a preset name or a table", "rod material"),
        key("lattice.layers[].angle_deg", KeyType::Float, "deg", Derived(format!("{}, or the layer above's", d::CROSSING_ANGLE_DEG)), "at least 1 deg from 0 and 180; not in the top layer", "angle of the rods to those of the layer above"),
        key("lattice.layers[].lengths_mm", KeyType::FloatList, "mm", KeyDefault::None, "one entry per rod, each > 0", "each rod's length, rod 1 first (graded designs; not taken by the layer below)"),
        key("lattice.layers[].offsets_mm", KeyType::FloatList, "mm", KeyDefault::None, "one entry per rod, finite; every rod must still cross a rod of an adjacent layer", "each rod's shift along its own axis (staggered designs; not taken by the layer below)"),
        key("lattice.rod", KeyType::Table, "", KeyDefault::None, "", "how every rod moves: { fe_elements = n } or { modes = l }"),
        Key { alternatives: &["lattice.rod.modes"], ..key("lattice.rod.fe_elements", KeyType::Integer, "", Float(8.0), "1..=64", "finite-element Timoshenko beam elements per half rod") },
        Key { alternatives: &["lattice.rod.fe_elements"], ..key("lattice.rod.modes", KeyType::Integer, "", KeyDefault::None, ">= 1, at most the rod's bending modes below its shear cutoff", "the l lowest analytic free-free Timoshenko bending modes (and the two rigid modes) instead of finite elements") },
        key("excitation", KeyType::Table, "", KeyDefault::None, "", "what loads the lattice: a striker, a blast, a drive, or nothing (a static load alone)"),
        Key { choices: &["impact", "blast", "drive", "rest"], ..key("excitation.kind", KeyType::Name, "", Name("impact"), "one of the choices", "a striker, a blast or a drive on the load points, or rest (a [preload] alone)") },
        key("excitation.at_mm", KeyType::FloatList, "mm", Derived("[0.0, 0.0], the centre".into()), "(x, y) on a rod of the top layer", "where the striker hits the top layer"),
        Key { alternatives: &["excitation.velocity_m_s"], ..key("excitation.drop_height_m", KeyType::Float, "m", Float(d::DROP_HEIGHT_M), "> 0", "drop height h, v0 = sqrt(2 g h)") },
        Key { alternatives: &["excitation.drop_height_m"], ..key("excitation.velocity_m_s", KeyType::Float, "m/s", KeyDefault::None, "> 0", "initial striker velocity") },
        key("excitation.striker", KeyType::Table, "", KeyDefault::None, "", "the striker sphere"),
        key("excitation.striker.diameter_mm", KeyType::Float, "mm", Float(d::STRIKER_DIAMETER_MM), "> 0", "striker diameter"),
        key("excitation.striker.material", KeyType::Material, "", Name(d::STRIKER_MATERIAL), "a preset name or a table", "striker material"),
        Key { choices: &["top-crossings"], alternatives: &["excitation.points_mm"], ..key("excitation.points", KeyType::Name, "", Name("top-crossings"), "one of the choices", "blast and drive: the load points, every crossing under the top layer's rods (the load split equally)") },
        Key { alternatives: &["excitation.points"], ..key("excitation.points_mm", KeyType::FloatList, "mm", KeyDefault::None, "a list of [x, y], each on a rod of the top layer", "blast and drive: the load points (the load split equally)") },
        doc("excitation.profile", "blast: F0 (1 - t/Td) exp(-b t/Td), or a CSV table; the total over the load points"),
        doc("excitation.peak_force_n", "blast: peak total force F0, split equally over the load points"),
        chain("excitation.duration_s"),
        chain("excitation.decay"),
        chain("excitation.file"),
        doc("excitation.drive", "drive: a total force (N, split over the load points) or a displacement (m, of one rigid actuator pressing through a tip at every load point)"),
        chain("excitation.signal"),
        chain("excitation.amplitude"),
        chain("excitation.frequency_hz"),
        chain("excitation.start_hz"),
        chain("excitation.end_hz"),
        chain("excitation.sweep_duration_s"),
        chain("excitation.sweep"),
        chain("excitation.ramp_s"),
        doc("excitation.tip", "displacement drive: the actuator's tip at every load point, keys as in a chain's [wall]"),
        chain("excitation.tip.kind"),
        chain("excitation.tip.material"),
        chain("excitation.tip.cap_radius_mm"),
        chain("excitation.tip.beta"),
        key("wall", KeyType::Table, "", KeyDefault::None, "", "the supports under the bottom layer (the paper's sensor each)"),
        Key { choices: &["centres"], ..key("wall.supports", KeyType::Name, "", Name("centres"), "\"centres\" or a list of { x_mm, y_mm }", "one support under every bottom rod's centre, or at the points given") },
        key("wall.supports[].x_mm", KeyType::Float, "mm", KeyDefault::None, "under a bottom rod, within its length and radius", "x of a support"),
        key("wall.supports[].y_mm", KeyType::Float, "mm", KeyDefault::None, "under a bottom rod, within its length and radius", "y of a support"),
        doc("damping", "contact laws at every crossing, striker, tip and support; modal and on-site damping of the rods (docs/physics.md §16); none: lossless"),
        chain("damping.contact"),
        chain("damping.restitution"),
        chain("damping.viscous_time_s"),
        chain("damping.striker"),
        chain("damping.striker.contact"),
        chain("damping.striker.restitution"),
        chain("damping.striker.viscous_time_s"),
        doc("damping.wall", "the supports' contacts, when they differ"),
        chain("damping.wall.contact"),
        chain("damping.wall.restitution"),
        chain("damping.wall.viscous_time_s"),
        chain("damping.allow_pull"),
        chain("damping.impact_speed_m_s"),
        chain("damping.on_site_time_s"),
        doc("damping.modal_ratio", "damping ratio zeta of every elastic mode of every rod"),
        doc("preload", "a static force on the load points and gravity; the run starts from the static equilibrium (docs/physics.md §16); none: unloaded"),
        doc("preload.force_n", "static total force on the load points, split equally (through a displacement actuator's tips: the shares of the static equilibrium)"),
        doc("preload.gravity_m_s2", "gravity, downward through the layers"),
        chain("run"),
        chain("run.duration_s"),
        chain("run.peak_tolerance"),
        chain("run.integrator"),
        chain("run.time_step_s"),
        chain("run.rtol"),
        chain("run.atol"),
        chain("run.sample_interval_s"),
    ]
}

/// The chain's row of `name` (a key whose meaning is the same in a lattice).
fn chain(name: &str) -> Key {
    crate::scenario::keys()
        .iter()
        .find(|k| k.name == name)
        .unwrap_or_else(|| panic!("{name} is a key of the chain's table"))
        .clone()
}

/// The chain's row of `name` with the lattice's meaning `doc`.
fn doc(name: &str, doc: &'static str) -> Key {
    Key { doc, ..chain(name) }
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
        complete_rod(&mut s.lattice.rod);
        let x = &mut s.excitation;
        if x.kind.get_or_insert("impact".into()) == "impact" {
            x.at_mm.get_or_insert([0.0, 0.0]);
            if x.velocity_m_s.is_none() {
                x.drop_height_m.get_or_insert(DROP_HEIGHT_M);
            }
            let st = x.striker.get_or_insert(StrikerSpec::default());
            st.diameter_mm.get_or_insert(STRIKER_DIAMETER_MM);
            st.material
                .get_or_insert(MaterialSpec::Preset(STRIKER_MATERIAL.into()));
        }
        complete_lab(&mut s);
        s.wall
            .supports
            .get_or_insert(SupportsToml::Named("centres".into()));
        let duration_s = default_duration_s(&s.excitation);
        let r = &mut s.run;
        r.duration_s.get_or_insert(duration_s);
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
    /// the keys. A table file is read relative to the working directory
    /// ([`LatticeScenario::resolve_in`]: relative to the scenario's).
    pub fn resolve(&self) -> Result<ResolvedLattice, Error> {
        self.resolve_in(Path::new("."))
    }

    /// [`LatticeScenario::resolve`] with table files relative to `base_dir`.
    pub fn resolve_in(&self, base_dir: &Path) -> Result<ResolvedLattice, Error> {
        let s = self.complete();
        if s.lattice.layers.is_empty() {
            return Err(Error::invalid(
                "lattice.layers",
                "[]",
                "give at least one layer",
            ));
        }
        let layers = layer_specs(&s.lattice.layers, &self.lattice.layers)?;
        let (fe_elements, bending_modes) = rod_model(s.lattice.rod.expect("completed"))?;
        check_size(&layers, fe_elements)?;
        if let Some(l) = bending_modes {
            check_modes(&layers, l)?;
        }
        let supports = supports_of(s.wall.supports.as_ref().expect("completed"))?;
        let mut builder = LatticeBuilder::new(layers, fe_elements);
        builder.supports = supports;
        builder.overrides = rod_overrides(&s.lattice.layers);
        builder.bending_modes = bending_modes;
        check_distinct_rods(&builder.layers, &builder.overrides)?;
        let lattice = builder.build()?;
        let (excitation, lab) = self.resolve_lab(&s, base_dir)?;
        let (striker, at_m) = match &excitation {
            LatticeExcitation::Impact { striker, at_m } => {
                lattice.top_point(*at_m, "excitation.at_mm")?;
                (striker.clone(), *at_m)
            }
            _ => (Striker::paper(), [0.0, 0.0]),
        };
        let settings = resolve_run_spec(&s.run)?;
        check_against_run(&excitation, &settings)?;
        if let Some(points) = excitation.load_points() {
            points.on(&lattice)?;
        }
        if let Some(tip) = excitation.actuator_tip() {
            // Fails early (as a usage error) when the tip cannot touch a top rod.
            for rod in lattice.rods.iter().filter(|r| r.layer == 1) {
                tip.beta_against(rod.surface(), &rod.rod.material)
                    .map_err(Error::at("excitation.tip"))?;
            }
        }
        Ok(ResolvedLattice {
            builder,
            lattice,
            striker,
            at_m,
            settings,
            excitation,
            lab,
        })
    }
}

/// Each layer of a completed `[lattice]` (`completed`; `given`: the layers as the user wrote
/// them) as the library's [`LayerSpec`]; errors name `lattice.layers[k].…`.
fn layer_specs(completed: &[LayerToml], given: &[LayerToml]) -> Result<Vec<LayerSpec>, Error> {
    let mut layers = Vec::new();
    for (k, l) in completed.iter().enumerate() {
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
            if let Some(a) = given[0].angle_deg {
                return Err(Error::invalid(key("angle_deg"), a, "the top layer's rods lie along x; angle_deg is a lower layer's angle to the layer above"));
            }
        }
        let rods = l
            .rods
            .ok_or_else(|| Error::invalid(key("rods"), "(unset)", "required in the top layer"))?;
        let pitch = if rods > 1 {
            required("pitch_mm", l.pitch_mm)?
        } else {
            l.pitch_mm.unwrap_or(0.0)
        };
        let length_mm = match (&l.lengths_mm, l.length_mm) {
            (Some(v), None) => v.first().copied().unwrap_or(f64::NAN),
            _ => required("length_mm", l.length_mm)?,
        };
        let diameter_mm = required("diameter_mm", l.diameter_mm)?;
        check_slenderness(&given[k], k, diameter_mm)?;
        layers.push(LayerSpec {
            rods,
            pitch_m: pitch * 1e-3,
            length_m: length_mm * 1e-3,
            diameter_m: diameter_mm * 1e-3,
            material: material_of(&key("material"), l.material.as_ref().expect("completed"))?,
            angle_deg: l.angle_deg.unwrap_or(0.0),
        });
    }
    Ok(layers)
}

/// Refuses a rod length layer `k` gives (`length_mm` or an entry of `lengths_mm`) longer than
/// [`woodpile::defaults::ROD_MAX_SLENDERNESS`] diameters, as a chain's rods are: such a rod's
/// bending modes lie below a hertz (a 5 mm rod of 50 m: 6.4 mHz) and its set-up grows with it.
fn check_slenderness(given: &LayerToml, k: usize, diameter_mm: f64) -> Result<(), Error> {
    let most = woodpile::defaults::ROD_MAX_SLENDERNESS * diameter_mm;
    if !(most.is_finite() && most > 0.0) {
        return Ok(()); // the diameter's own check names it
    }
    let mut lengths: Vec<(String, f64)> = given
        .lengths_mm
        .iter()
        .flatten()
        .enumerate()
        .map(|(i, &v)| (format!("lattice.layers[{k}].lengths_mm[{i}]"), v))
        .collect();
    lengths.extend(
        given
            .length_mm
            .map(|v| (format!("lattice.layers[{k}].length_mm"), v)),
    );
    match lengths.into_iter().find(|(_, v)| *v > most) {
        Some((field, v)) => Err(Error::invalid(
            field,
            v,
            format!(
                "at most {:.0e} diameters ({most} mm for rods of {diameter_mm} mm): a longer rod's bending modes lie below a hertz",
                woodpile::defaults::ROD_MAX_SLENDERNESS
            ),
        )),
        None => Ok(()),
    }
}

/// A point `[x, y]` in mm: exactly two numbers (a third, such as a z, would be dropped
/// silently: points lie on a layer, whose height the lattice gives).
fn xy_mm<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<[f64; 2]>, D::Error> {
    Option::<Vec<f64>>::deserialize(d)?.map(xy).transpose()
}

/// A list of points `[[x, y], …]` in mm, each as [`xy_mm`].
fn xy_list_mm<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<Vec<[f64; 2]>>, D::Error> {
    Option::<Vec<Vec<f64>>>::deserialize(d)?
        .map(|points| points.into_iter().map(xy).collect())
        .transpose()
}

fn xy<E: serde::de::Error>(v: Vec<f64>) -> Result<[f64; 2], E> {
    match v[..] {
        [x, y] => Ok([x, y]),
        _ => Err(E::invalid_length(
            v.len(),
            &"a point [x, y] in mm: two numbers (a point lies on a layer, whose height the lattice gives)",
        )),
    }
}

/// `wall.supports` as the library's [`Supports`].
fn supports_of(supports: &SupportsToml) -> Result<Supports, Error> {
    Ok(match supports {
        SupportsToml::Named(n) if n == "centres" => Supports::Centres,
        SupportsToml::Named(n) => {
            return Err(Error::invalid(
                "wall.supports",
                format!("\"{n}\""),
                "\"centres\" or a list of points [{ x_mm = …, y_mm = … }, …]",
            ))
        }
        // The library takes a free lattice (no support: a rod struck in flight); a file
        // without supports would print a transmitted force of nothing.
        SupportsToml::Points(p) if p.is_empty() => {
            return Err(Error::invalid(
                "wall.supports",
                "[]",
                "a lattice stands on at least one support: give points [{ x_mm = …, y_mm = … }, …] or \"centres\"",
            ))
        }
        SupportsToml::Points(p) => {
            // Two supports at one point would each carry, and report, the same contact.
            for (j, b) in p.iter().enumerate() {
                let same = |a: &&PointToml| (a.x_mm - b.x_mm).hypot(a.y_mm - b.y_mm) < 1e-6;
                if let Some(i) = p[..j].iter().position(|a| same(&a)) {
                    return Err(Error::invalid(
                        format!("wall.supports[{j}]"),
                        format!("{{ x_mm = {}, y_mm = {} }}", b.x_mm, b.y_mm),
                        format!("wall.supports[{i}] is at this point already (within 1e-6 mm): one support per point"),
                    ));
                }
            }
            Supports::Points(p.iter().map(|p| [p.x_mm * 1e-3, p.y_mm * 1e-3]).collect())
        }
    })
}

/// The default rod: the finite-element rod of 8 elements per half rod, unless `modes` is given.
fn complete_rod(rod: &mut Option<RodToml>) {
    let r = rod.get_or_insert_with(RodToml::default);
    if r.modes.is_none() {
        r.fe_elements.get_or_insert(8);
    }
}

/// (finite elements per half rod, analytic bending modes) of a completed `rod`; `fe_elements`
/// and `modes` are alternatives (with `modes`, the elements are not used).
fn rod_model(rod: RodToml) -> Result<(usize, Option<usize>), Error> {
    match (rod.fe_elements, rod.modes) {
        (Some(_), Some(l)) => Err(Error::invalid(
            "lattice.rod.modes",
            l,
            "fe_elements and modes are alternatives: give rod = { fe_elements = n } (the finite-element rod) or rod = { modes = l } (its l lowest analytic bending modes), not both",
        )),
        (_, Some(l)) => Ok((1, Some(l))),
        (n, None) => Ok((n.unwrap_or(8), None)),
    }
}

/// Refuses more modal coordinates than [`MAX_LATTICE_MODES`] with `rod = { modes = l }`: l + 2
/// per rod.
fn check_modes(layers: &[LayerSpec], l: usize) -> Result<(), Error> {
    let rods = layers.iter().fold(0usize, |n, x| n.saturating_add(x.rods));
    let modes = rods.saturating_mul(l.saturating_add(2));
    if modes > MAX_LATTICE_MODES {
        return Err(Error::invalid(
            "lattice.rod.modes",
            l,
            format!("{rods} rods of {l} bending modes and 2 rigid ones have {modes} modal coordinates, more than {MAX_LATTICE_MODES}: fewer modes or fewer rods"),
        ));
    }
    Ok(())
}

/// The per-rod `lengths_mm` and `offsets_mm` of every layer, in metres (checked by the core's
/// builder, whose errors name these keys).
fn rod_overrides(layers: &[LayerToml]) -> Vec<RodOverrides> {
    let metres = |v: &Option<Vec<f64>>| {
        v.as_ref()
            .map(|v| v.iter().map(|x| x * 1e-3).collect::<Vec<f64>>())
    };
    layers
        .iter()
        .map(|l| RodOverrides {
            lengths_m: metres(&l.lengths_mm),
            offsets_m: metres(&l.offsets_mm),
        })
        .collect()
}

/// Most distinct rods (length, diameter, material) of a lattice: each is one eigenproblem
/// (identical rods share theirs), as many as [`MAX_LATTICE_LAYERS`] layers of rods of one kind.
pub const MAX_LATTICE_DISTINCT_RODS: usize = MAX_LATTICE_LAYERS;

/// Refuses more distinct rods than [`MAX_LATTICE_DISTINCT_RODS`] before any rod's modes are
/// computed (per-rod `lengths_mm` can make every rod different).
fn check_distinct_rods(layers: &[LayerSpec], overrides: &[RodOverrides]) -> Result<(), Error> {
    let mut kinds: Vec<(u64, u64, &woodpile::Material)> = Vec::new();
    for (k, layer) in layers.iter().enumerate() {
        let lengths = overrides.get(k).and_then(|o| o.lengths_m.as_ref());
        for i in 0..layer.rods {
            let length = lengths.and_then(|v| v.get(i)).unwrap_or(&layer.length_m);
            let kind = (
                length.to_bits(),
                layer.diameter_m.to_bits(),
                &layer.material,
            );
            if !kinds.contains(&kind) {
                kinds.push(kind);
            }
            if kinds.len() > MAX_LATTICE_DISTINCT_RODS {
                return Err(Error::invalid(
                    format!("lattice.layers[{k}].lengths_mm[{i}]"),
                    length * 1e3,
                    format!("more than {MAX_LATTICE_DISTINCT_RODS} distinct rods (length, diameter, material) in the lattice: each is one eigenproblem; use fewer distinct lengths"),
                ));
            }
        }
    }
    Ok(())
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
/// holds per sample (each contact's force and energy in CSV and NPY, with lab physics its
/// dissipated energy too, the supports and their sum, each rod's energy, time).
pub fn run_size(r: &ResolvedLattice) -> crate::limits::RunSize {
    let contacts = r.lattice.contacts.len();
    let per_contact = if r.lab.is_none() && matches!(r.excitation, LatticeExcitation::Impact { .. })
    {
        4
    } else {
        6
    };
    crate::limits::RunSize::with_columns(
        &r.settings,
        per_contact * contacts + 2 * r.lattice.rods.len() + 8,
    )
}

/// The excitation kind of a lattice's `[excitation]`.
fn kind_of(kind: &str) -> Result<ExcitationKind, Error> {
    match kind {
        "impact" => Ok(ExcitationKind::Impact),
        "blast" => Ok(ExcitationKind::Blast),
        "drive" => Ok(ExcitationKind::Drive),
        "rest" => Ok(ExcitationKind::Rest),
        other => Err(Error::invalid(
            "excitation.kind",
            format!("\"{other}\""),
            "\"impact\", \"blast\", \"drive\" or \"rest\"",
        )),
    }
}

/// The chain's `[excitation]` of the same keys (those a lattice shares with a chain), so that
/// the chains' readers and completion serve lattices.
fn chain_spec(x: &LatticeExcitationSpec, kind: ExcitationKind) -> ExcitationSpec {
    ExcitationSpec {
        kind,
        drop_height_m: x.drop_height_m,
        velocity_m_s: x.velocity_m_s,
        striker: x.striker.clone(),
        profile: x.profile,
        peak_force_n: x.peak_force_n,
        duration_s: x.duration_s,
        decay: x.decay,
        file: x.file.clone(),
        drive: x.drive,
        signal: x.signal,
        amplitude: x.amplitude,
        frequency_hz: x.frequency_hz,
        start_hz: x.start_hz,
        end_hz: x.end_hz,
        sweep_duration_s: x.sweep_duration_s,
        sweep: x.sweep,
        ramp_s: x.ramp_s,
        tip: x.tip.clone(),
        ..ExcitationSpec::default()
    }
}

/// Writes the defaults of a blast or drive (the chains' completion), of `[damping]` and
/// `[preload]`, and the load points.
fn complete_lab(s: &mut LatticeScenario) {
    let Ok(kind) = kind_of(s.excitation.kind.as_deref().unwrap_or("impact")) else {
        return;
    };
    let chain = Scenario {
        excitation: chain_spec(&s.excitation, kind),
        damping: s.damping.clone(),
        preload: s.preload,
        ..Scenario::default()
    }
    .complete();
    let (x, c) = (&mut s.excitation, &chain.excitation);
    match kind {
        ExcitationKind::Blast => {
            (x.profile, x.peak_force_n, x.duration_s, x.decay) =
                (c.profile, c.peak_force_n, c.duration_s, c.decay);
        }
        ExcitationKind::Drive => {
            (x.drive, x.sweep, x.ramp_s) = (c.drive, c.sweep, c.ramp_s);
            x.tip.clone_from(&c.tip);
        }
        _ => {}
    }
    if kind != ExcitationKind::Impact && x.points.is_none() && x.points_mm.is_none() {
        x.points = Some(TOP_CROSSINGS.into());
    }
    let given = s.damping.as_ref().and_then(|d| d.resonator_ratio);
    s.damping = chain.damping;
    if let Some(d) = &mut s.damping {
        d.modal_ratio.get_or_insert(0.0);
        // A chain's key with no meaning for a lattice's rods: written only as the user gave it.
        d.resonator_ratio = given;
    }
    s.preload = chain.preload;
}

/// `points = "top-crossings"`.
const TOP_CROSSINGS: &str = "top-crossings";

/// The run duration when `run.duration_s` is not given: the chains' for the same excitation.
fn default_duration_s(x: &LatticeExcitationSpec) -> f64 {
    kind_of(x.kind.as_deref().unwrap_or("impact"))
        .ok()
        .and_then(|kind| chain_spec(x, kind).default_duration_s())
        .unwrap_or(woodpile::defaults::IMPACT_DURATION_S)
}

/// Refuses a blast's decay within one fixed step and a drive above the step's Nyquist
/// frequency, as for chains.
fn check_against_run(x: &LatticeExcitation, settings: &RunSettings) -> Result<(), Error> {
    let fixed = match settings.method {
        Method::Rk4 { time_step_s } => Some(time_step_s),
        _ => None,
    };
    Ok(x.as_chain_excitation().check_against_run(fixed)?)
}

impl LatticeScenario {
    /// The excitation and the lab physics of the completed scenario `s` (keys the user gave
    /// that do not apply are refused, naming them).
    fn resolve_lab(
        &self,
        s: &LatticeScenario,
        base_dir: &Path,
    ) -> Result<(LatticeExcitation, LatticeLab), Error> {
        use crate::scenario::{blast_profile_of, refuse_excitation_keys, signal_of};
        let x = &s.excitation;
        let kind = kind_of(x.kind.as_deref().unwrap_or("impact"))?;
        let given = &self.excitation;
        let user = chain_spec(given, kind);
        let full = chain_spec(x, kind);
        let why = format!("with excitation.kind = \"{}\"", kind.name());
        let points = load_points(given, kind, &why)?;
        let excitation = match kind {
            ExcitationKind::Impact => {
                refuse_excitation_keys(&user, &["drop_height_m", "velocity_m_s", "striker"], &why)?;
                let at = x.at_mm.expect("completed");
                LatticeExcitation::Impact {
                    striker: crate::scenario::striker_of(
                        x.drop_height_m,
                        x.velocity_m_s,
                        x.striker.as_ref(),
                        None,
                    )?,
                    at_m: [at[0] * 1e-3, at[1] * 1e-3],
                }
            }
            ExcitationKind::Blast => {
                refuse_excitation_keys(&user, &crate::scenario::BLAST_KEYS, &why)?;
                LatticeExcitation::Blast {
                    profile: blast_profile_of(&full, base_dir)?,
                    points,
                }
            }
            ExcitationKind::Drive => {
                refuse_excitation_keys(&user, &crate::scenario::DRIVE_KEYS, &why)?;
                let signal = signal_of(&full, base_dir)?;
                let ramp_s = full.ramp_s.ok_or_else(|| {
                    Error::invalid("excitation.ramp_s", "(unset)", "give ramp_s = … [s]")
                })?;
                let drive = woodpile::Drive {
                    quantity: crate::scenario::drive_quantity_of(&full)?,
                    ramp_s,
                    signal,
                };
                drive.validate()?;
                LatticeExcitation::Drive { drive, points }
            }
            ExcitationKind::Rest => {
                refuse_excitation_keys(&user, &[], &format!("{why} (nothing drives the lattice)"))?;
                LatticeExcitation::Rest { points }
            }
        };
        let lab = lattice_lab(s, kind, excitation.actuator_tip().is_some())?;
        Ok((excitation, lab))
    }
}

/// The load points of a blast, drive or rest: `points = "top-crossings"` or `points_mm`, not
/// both, and neither with an impact (whose point is `at_mm`); `at_mm` only with an impact.
fn load_points(
    x: &LatticeExcitationSpec,
    kind: ExcitationKind,
    why: &str,
) -> Result<LoadPoints, Error> {
    let not_applicable = |key: &str, value: String, why: &str| {
        Error::invalid(
            format!("excitation.{key}"),
            value,
            format!("not used {why}"),
        )
    };
    if kind == ExcitationKind::Impact {
        if let Some(p) = &x.points {
            return Err(not_applicable(
                "points",
                format!("\"{p}\""),
                &format!("{why} (the striker hits at at_mm)"),
            ));
        }
        if let Some(p) = &x.points_mm {
            return Err(not_applicable(
                "points_mm",
                format!("{p:?}"),
                &format!("{why} (the striker hits at at_mm)"),
            ));
        }
        return Ok(LoadPoints::TopCrossings);
    }
    if let Some(at) = x.at_mm {
        return Err(not_applicable("at_mm", format!("{at:?}"), &format!("{why}: it is the striker's impact point; a load acts on points = \"top-crossings\" or points_mm = [[x, y], …]")));
    }
    match (&x.points, &x.points_mm) {
        (Some(p), Some(_)) => Err(Error::invalid(
            "excitation.points",
            format!("\"{p}\""),
            "give either points = \"top-crossings\" or points_mm = [[x, y], …], not both",
        )),
        (Some(p), None) if p != TOP_CROSSINGS => Err(Error::invalid(
            "excitation.points",
            format!("\"{p}\""),
            "\"top-crossings\" (every crossing of the top layer), or give points_mm = [[x, y], …] (mm, each on a top rod)",
        )),
        (_, Some(p)) => Ok(LoadPoints::Points(
            p.iter().map(|xy| [xy[0] * 1e-3, xy[1] * 1e-3]).collect(),
        )),
        _ => Ok(LoadPoints::TopCrossings),
    }
}

/// `[damping]` and `[preload]` of a completed lattice scenario: the chains' readers, and
/// `damping.modal_ratio` (`damping.striker` is the striker's or a displacement actuator's
/// tips'). A lattice left at rest needs a static load.
fn lattice_lab(
    s: &LatticeScenario,
    kind: ExcitationKind,
    actuator: bool,
) -> Result<LatticeLab, Error> {
    let struck = kind == ExcitationKind::Impact;
    let (damping, modal_ratio) = match &s.damping {
        None => (woodpile::Damping::default(), 0.0),
        Some(d) => {
            let mut d = d.clone();
            d.resonator_ratio.get_or_insert(0.0);
            (
                crate::scenario::damping_of(&d, struck || actuator, true, struck)?,
                d.modal_ratio.unwrap_or(0.0),
            )
        }
    };
    let preload = s
        .preload
        .map_or(woodpile::Preload::default(), |p| woodpile::Preload {
            force_n: p.force_n.unwrap_or(0.0),
            gravity_m_s2: p.gravity_m_s2.unwrap_or(0.0),
        });
    if kind == ExcitationKind::Rest && preload.is_none() {
        return Err(Error::invalid(
            "excitation.kind",
            "\"rest\"",
            "nothing would move: a lattice left at rest needs a static load ([preload] force_n or gravity_m_s2); or strike, blast or drive it",
        ));
    }
    let lab = LatticeLab {
        damping,
        modal_ratio,
        preload,
    };
    lab.validate()?;
    Ok(lab)
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

/// The contacts in output order: the striker's (or the load points, numbered from 1 as the
/// rods of layer 0), the crossings, the supports.
pub fn contacts_json(r: &ResolvedLattice) -> Vec<ContactJson> {
    let lattice = &r.lattice;
    let mut out = incident_contacts_json(r);
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

/// The contacts of layer 0: the striker's, or one per load point (none at rest without a
/// preload).
fn incident_contacts_json(r: &ResolvedLattice) -> Vec<ContactJson> {
    let lattice = &r.lattice;
    let points = match r.excitation.load_points() {
        None => vec![lattice
            .top_point(r.at_m, "excitation.at_mm")
            .expect("checked by resolve")],
        Some(_)
            if matches!(r.excitation, LatticeExcitation::Rest { .. })
                && r.lab.preload.force_n == 0.0 =>
        {
            Vec::new()
        }
        Some(p) => p.on(lattice).expect("checked by resolve"),
    };
    points
        .iter()
        .enumerate()
        .map(|(k, hit)| {
            let top = &lattice.rods[hit.rod];
            let p = top.point_m(hit.s_m);
            ContactJson {
                layer_above: 0,
                rod_above: k + 1,
                layer_below: 1,
                rod_below: top.number,
                x_mm: p[0] * 1e3,
                y_mm: p[1] * 1e3,
            }
        })
        .collect()
}

/// `run.json` of a lattice run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LatticeRunJson {
    /// `woodpile`.
    pub tool: String,
    /// [`RUN_FORMAT`](crate::rundir::RUN_FORMAT), as a chain's run (runs written before the
    /// formats were one: [`LEGACY_LATTICE_RUN_FORMAT`](crate::rundir::LEGACY_LATTICE_RUN_FORMAT)).
    pub format: String,
    /// `lattice` ([`Structure::Lattice`](crate::rundir::Structure); absent in runs written
    /// before the formats were one).
    #[serde(default = "lattice_structure")]
    pub structure: crate::rundir::Structure,
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
    /// Integrator steps taken (also in `integrator`).
    pub steps: u64,
    /// The method and its work, as a chain's run.json (absent in runs written before).
    #[serde(default)]
    pub integrator: Option<crate::rundir::IntegratorJson>,
    /// Number of samples.
    pub n_samples: usize,
}

/// The structure of a lattice run.json written before the key existed.
fn lattice_structure() -> crate::rundir::Structure {
    crate::rundir::Structure::Lattice
}

/// `summary.json` of a lattice run: a chain's keys (docs/reference/outputs.md) where they mean
/// the same, `energy` and `integrator` nested as a chain's, and the lattice's own (`supports`,
/// the dissipation per contact and in the rods' modes, the static solve's residual).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LatticeSummaryJson {
    /// Scenario name.
    pub scenario: String,
    /// `lattice`.
    pub structure: crate::rundir::Structure,
    /// `impact`, `blast`, `drive` or `rest`.
    pub excitation: String,
    /// Number of contacts (`run.json`'s `contacts`).
    pub n_contacts: usize,
    /// Number of samples.
    pub n_samples: usize,
    /// Peak of the striker's contact, or of the sum of the load points' forces \[N\].
    pub incident_peak_force_n: f64,
    /// Peak of the sum of the support forces \[N\].
    pub transmitted_peak_force_n: f64,
    /// Under a static load: the incident peak less its static part \[N\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub incident_dynamic_peak_force_n: Option<f64>,
    /// Under a static load: the transmitted peak less the supports' static forces \[N\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transmitted_dynamic_peak_force_n: Option<f64>,
    /// Transmitted / incident (of the dynamic parts under a static load); null when the incident
    /// force is zero or the wave never reached the supports (`wave_arrived` false).
    pub transmission_ratio: Option<f64>,
    /// Each contact's force in the static equilibrium the run started from \[N\] (absent
    /// without a static load).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub static_contact_forces_n: Vec<f64>,
    /// The static solve's relative residual |∇Π| / |f| (0 without a static load).
    #[serde(default)]
    pub static_residual: f64,
    /// Under a displacement drive: its rigid actuator's static position u* \[m\], downward,
    /// every tip's overlap δ_i = u* + u(t) − w_i (docs/physics.md §16); absent without one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub actuator_rest_m: Option<f64>,
    /// Whether the wave reached the supports (the transmitted peak's dynamic part at least
    /// `woodpile::defaults::WAVE_ARRIVAL_FRACTION` of the incident one's); false: the run was too
    /// short for the transmitted force to mean anything.
    pub wave_arrived: bool,
    /// Whether the energy balance closes to within `woodpile::defaults::ENERGY_ERROR_WARN`.
    pub energy_balance_ok: bool,
    /// Peak force per contact, in `run.json`'s order \[N\].
    pub contact_peak_forces_n: Vec<f64>,
    /// When each peak occurred \[s\].
    pub contact_peak_times_s: Vec<f64>,
    /// The supports' contacts, in `run.json`'s order.
    pub supports: Vec<usize>,
    /// Energy dissipated at each contact over the run, in `run.json`'s order \[J\] (absent
    /// without damping, a static load, a blast or a drive).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub contact_dissipated_j: Vec<f64>,
    /// The part of `energy.dissipated_j` dissipated by the damping of the rods' modes \[J\].
    #[serde(default)]
    pub modal_dissipated_j: f64,
    /// Energy balance, as a chain's.
    pub energy: crate::rundir::EnergyJson,
    /// The method the run stepped with (a stated peak tolerance resolved for the lattice:
    /// `exact-modes` for finite-element rods) and its work.
    pub integrator: crate::rundir::IntegratorJson,
    /// Wall-clock time of the run \[s\].
    pub wall_time_s: f64,
}

/// Reads a lattice run's `summary.json`, whose `contact_peak_forces_n` must list `contacts`
/// finite peaks (those of `run.json`); a missing or damaged file is an error naming it.
pub fn read_lattice_summary(dir: &Path, contacts: usize) -> Result<LatticeSummaryJson, Error> {
    use crate::atomic::read_error;
    let path = dir.join("summary.json");
    let text = std::fs::read_to_string(&path).map_err(|e| Error::Read {
        path: path.clone(),
        source: e,
    })?;
    let summary: LatticeSummaryJson = serde_json::from_str(&text).map_err(|e| {
        read_error(
            &path,
            format!("not a lattice run's summary.json ({e}); re-run `woodpile simulate`"),
        )
    })?;
    let peaks = &summary.contact_peak_forces_n;
    if peaks.len() != contacts || peaks.iter().any(|p| !p.is_finite()) {
        return Err(read_error(
            &path,
            format!(
                "contact_peak_forces_n holds {} values (finite: {}) for the {contacts} contacts of run.json; re-run `woodpile simulate`",
                peaks.len(),
                peaks.iter().all(|p| p.is_finite())
            ),
        ));
    }
    Ok(summary)
}

impl LatticeSummaryJson {
    /// The summary of a run of the scenario `name` under `excitation`.
    pub fn of(name: &str, excitation: &LatticeExcitation, run: &LatticeRun) -> Self {
        let statics = !run.contact_static_forces_n.iter().all(|&f| f == 0.0);
        let e = &run.energy;
        LatticeSummaryJson {
            scenario: name.to_string(),
            structure: crate::rundir::Structure::Lattice,
            excitation: excitation.as_chain_excitation().kind_name().to_string(),
            n_contacts: run.contacts,
            n_samples: run.times_s.len(),
            incident_peak_force_n: run.incident_peak_force_n,
            transmitted_peak_force_n: run.transmitted_peak_force_n,
            incident_dynamic_peak_force_n: statics
                .then_some(run.incident_peak_force_n - run.static_incident_force_n),
            transmitted_dynamic_peak_force_n: statics
                .then_some(run.transmitted_peak_force_n - run.static_transmitted_force_n),
            transmission_ratio: run.transmission_ratio,
            static_contact_forces_n: if statics {
                run.contact_static_forces_n.clone()
            } else {
                Vec::new()
            },
            static_residual: run.static_residual,
            actuator_rest_m: run.actuator_rest_m,
            wave_arrived: run.wave_arrived,
            energy_balance_ok: e.max_relative_error <= woodpile::defaults::ENERGY_ERROR_WARN,
            contact_peak_forces_n: run.contact_peak_forces_n.clone(),
            contact_peak_times_s: run.contact_peak_times_s.clone(),
            supports: run.supports.clone(),
            contact_dissipated_j: run.contact_dissipated_j.clone(),
            modal_dissipated_j: run.modal_dissipated_j,
            energy: crate::rundir::EnergyJson {
                initial_j: e.initial_j,
                final_j: e.final_j,
                input_work_j: e.input_work_j,
                dissipated_j: e.dissipated_j,
                max_relative_error: e.max_relative_error,
            },
            integrator: crate::rundir::IntegratorJson::of(run.method, &run.stats),
            wall_time_s: run.wall_time_s,
        }
    }
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
        format: crate::rundir::RUN_FORMAT.into(),
        structure: crate::rundir::Structure::Lattice,
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
        integrator: Some(crate::rundir::IntegratorJson::of(run.method, &run.stats)),
        n_samples: run.times_s.len(),
        contacts,
    };
    let summary = LatticeSummaryJson::of(name, &resolved.excitation, run);
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
    write_energy_csv(dir, run)?;
    write_body_energies(dir, resolved, run)?;
    write_contact_energies(dir, run)?;
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

/// Each body's energy as a chain's layer energy (kinetic, strain and half of each of its
/// contacts' potential): `rod_energies.csv` (`striker_j` when struck, `actuator_j` under a
/// displacement drive (its halves of the tip contacts), `layer_{k}_rod_{i}_j`, `supports_j`:
/// the supports' halves) and `energy_j.npy` (samples × bodies) with `support_energy_j.npy`.
fn write_body_energies(
    dir: &Path,
    resolved: &ResolvedLattice,
    run: &LatticeRun,
) -> Result<(), Error> {
    let lattice = &resolved.lattice;
    let mut header = vec!["time_s".to_string()];
    if run.bodies > lattice.rods.len() {
        header.push(match resolved.excitation.actuator_tip() {
            Some(_) => "actuator_j".into(),
            None => "striker_j".into(),
        });
    }
    header.extend(
        lattice
            .rods
            .iter()
            .map(|r| format!("layer_{}_rod_{}_j", r.layer, r.number)),
    );
    header.push("supports_j".into());
    crate::rundir::write_csv(
        &dir.join("rod_energies.csv"),
        &header,
        &run.times_s,
        run.body_energies_j
            .chunks(run.bodies)
            .zip(&run.support_energy_j)
            .map(|(row, &s)| {
                let mut v = row.to_vec();
                v.push(s);
                v
            }),
    )?;
    let n = run.times_s.len() as u64;
    crate::rundir::write_npy(
        &dir.join("energy_j.npy"),
        &[n, run.bodies as u64],
        &run.body_energies_j,
    )?;
    crate::rundir::write_npy(
        &dir.join("support_energy_j.npy"),
        &[n],
        &run.support_energy_j,
    )
}

/// Each contact's Hertz potential (`contact_energies.csv`, `contact_{c}_j` in `run.json`'s
/// order, and `contact_energy_j.npy`, samples × contacts) and, with lab physics, its dissipated
/// energy since the start (`contact_dissipated.csv`, `contact_dissipated_j.npy`).
fn write_contact_energies(dir: &Path, run: &LatticeRun) -> Result<(), Error> {
    let header: Vec<String> = std::iter::once("time_s".to_string())
        .chain((0..run.contacts).map(|c| format!("contact_{c}_j")))
        .collect();
    let n = run.times_s.len() as u64;
    let mut series = vec![(
        "contact_energies.csv",
        "contact_energy_j.npy",
        &run.contact_energies_j,
    )];
    if !run.work_j.is_empty() {
        series.push((
            "contact_dissipated.csv",
            "contact_dissipated_j.npy",
            &run.contact_dissipated_samples_j,
        ));
    }
    for (csv, npy, values) in series {
        crate::rundir::write_csv(
            &dir.join(csv),
            &header,
            &run.times_s,
            values.chunks(run.contacts).map(<[f64]>::to_vec),
        )?;
        crate::rundir::write_npy(&dir.join(npy), &[n, run.contacts as u64], values)?;
    }
    Ok(())
}

/// `energy.csv`: E(t) (`total_j`), and with lab physics the work W(t) (`work_j`) and the
/// dissipated energy D(t) (`dissipated_j`).
fn write_energy_csv(dir: &Path, run: &LatticeRun) -> Result<(), Error> {
    let lab = !run.work_j.is_empty();
    let mut header = vec!["time_s".to_string(), "total_j".into()];
    if lab {
        header.extend(["work_j".into(), "dissipated_j".into()]);
    }
    crate::rundir::write_csv(
        &dir.join("energy.csv"),
        &header,
        &run.times_s,
        (0..run.times_s.len()).map(|k| {
            let mut row = vec![run.energy_j[k]];
            if lab {
                row.extend([run.work_j[k], run.dissipated_j[k]]);
            }
            row
        }),
    )
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

/// Whether `dir` holds a lattice run (its `run.json` says `"structure": "lattice"`, or has the
/// lattice runs' earlier format tag).
pub fn is_lattice_run(dir: &Path) -> bool {
    std::fs::read_to_string(dir.join(crate::atomic::RUN_MARKER))
        .ok()
        .and_then(|text| serde_json::from_str::<serde_json::Value>(&text).ok())
        .is_some_and(|v| {
            crate::rundir::Structure::of_run_json(&v) == Some(crate::rundir::Structure::Lattice)
        })
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
    let known = [
        crate::rundir::RUN_FORMAT,
        crate::rundir::LEGACY_LATTICE_RUN_FORMAT,
    ];
    if run.tool != "woodpile"
        || !known.contains(&run.format.as_str())
        || run.structure != crate::rundir::Structure::Lattice
    {
        return Err(read_error(
            &path,
            format!(
                "tool `{}`, format `{}`, structure `{}`: not a woodpile lattice run (`{}`, `lattice`)",
                run.tool,
                run.format,
                run.structure.name(),
                crate::rundir::RUN_FORMAT
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
