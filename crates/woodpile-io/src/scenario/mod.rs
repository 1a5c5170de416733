//! The scenario file: a TOML description of a chain, its excitation, its support and the run.
//!
//! The structs here mirror the file one to one (`#[serde(deny_unknown_fields)]` everywhere, so a
//! misspelt key is an error). Every key is optional where docs/physics.md gives a default;
//! [`Scenario::complete`] fills them all in, and [`resolve`] turns a scenario into the library's
//! [`woodpile::Chain`], [`woodpile::Excitation`] and [`woodpile::RunSettings`].
//!
//! ```
//! use woodpile_io::scenario::{resolve, Scenario};
//!
//! let scenario = Scenario::parse(
//!     r#"
//!     [chain]
//!     rods_mm = [80, 40, 20]
//!     [run]
//!     duration_s = 1e-4
//!     "#,
//! )?;
//! let resolved = resolve(&scenario, std::path::Path::new("."))?;
//! assert_eq!(resolved.chain.len(), 3);
//! # Ok::<(), woodpile_io::Error>(())
//! ```

mod builtin;
mod emit;
mod keys;
mod resolve;
pub(crate) mod scatter;

pub use builtin::{
    all as builtins, builtin, builtin_names, BuiltinScenario, DEFAULT_SCENARIO, OPTIMIZED_CHAIN_MM,
};
pub use keys::{key, keys, Key, KeyDefault, KeyType};
pub(crate) use resolve::material as material_of;
pub(crate) use resolve::resolve_run_spec;
pub(crate) use resolve::striker_of;
pub(crate) use resolve::{
    blast_profile_of, damping_of, drive_quantity_of, refuse_excitation_keys, signal_of, BLAST_KEYS,
    DRIVE_KEYS,
};
pub use resolve::{resolve, resolve_element, resolve_with_keys, ChainKeys, Resolved};

use crate::error::Error;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// A whole scenario file.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// One line saying what the scenario is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// The column of elements (`[chain]`).
    pub chain: ChainSpec,
    /// What drives the chain (`[excitation]`, default: the paper's impact).
    #[serde(default)]
    pub excitation: ExcitationSpec,
    /// The support under the last element (`[wall]`, default: the paper's sensor).
    #[serde(default)]
    pub wall: WallSpec,
    /// Dissipation (`[damping]`, default: none, the paper's lossless model).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<DampingSpec>,
    /// Static load (`[preload]`, default: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preload: Option<PreloadSpec>,
    /// Duration, integrator and sampling (`[run]`).
    #[serde(default)]
    pub run: RunSpec,
    /// Manufacturing scatter (`[uncertainty]`, default: none; used by `--samples` studies).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uncertainty: Option<scatter::UncertaintySpec>,
}

/// Resonant (Table 1 cell with its resonators) or rigid (one body of the total mass).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ModelSpec {
    /// Primary mass plus internal resonators (the paper's locally resonant model).
    #[default]
    Resonant,
    /// One rigid body of the total mass (the paper's reference case).
    Rigid,
}

impl ModelSpec {
    /// The library's cell model.
    pub fn cell_model(self) -> woodpile::CellModel {
        match self {
            ModelSpec::Resonant => woodpile::CellModel::Resonant,
            ModelSpec::Rigid => woodpile::CellModel::Rigid,
        }
    }

    /// The name used in files.
    pub const fn name(self) -> &'static str {
        match self {
            ModelSpec::Resonant => "resonant",
            ModelSpec::Rigid => "rigid",
        }
    }
}

/// `[chain]`: either `rods_mm` (Table 1 rods) or `elements` (the general form).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChainSpec {
    /// Table 1 catalogue rods by length \[mm\], top to bottom.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rods_mm: Option<Vec<u32>>,
    /// General form: one entry per element, top to bottom.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elements: Option<Vec<ElementSpec>>,
    /// Cell model of every catalogue rod (default `resonant`); an element may override it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub model: Option<ModelSpec>,
    /// Angle between the axes of neighbouring rods \[deg\] (default 90).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crossing_angle_deg: Option<f64>,
    /// Contact coefficients set directly, by contact number (1 = elements 1–2, N = wall).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub contact_beta: Vec<BetaOverride>,
}

/// `{ contact = 3, beta = 2.5e9 }`: β of one contact set directly.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BetaOverride {
    /// Contact number in the paper's numbering: 1..N−1 between elements, N = the wall.
    pub contact: usize,
    /// Contact coefficient β \[N/m^1.5\].
    pub beta: f64,
}

/// What an entry of `chain.elements` is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ElementKind {
    /// A rod of the Table 1 catalogue (`rod_mm = 40`); the default when `rod_mm` is given.
    Catalogue,
    /// A user-defined rod: diameter, length, material and unit cell.
    Rod,
    /// A sphere: diameter and material (one rigid body).
    Sphere,
}

impl ElementKind {
    /// The name used in files.
    pub const fn name(self) -> &'static str {
        match self {
            ElementKind::Catalogue => "catalogue",
            ElementKind::Rod => "rod",
            ElementKind::Sphere => "sphere",
        }
    }
}

/// One entry of `chain.elements`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ElementSpec {
    /// `catalogue` (default when `rod_mm` is given), `rod` or `sphere`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kind: Option<ElementKind>,
    /// Catalogue rod length \[mm\] (kind `catalogue`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rod_mm: Option<u32>,
    /// Cell model of this element (default: `chain.model`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub model: Option<ModelSpec>,
    /// Diameter \[mm\] (kinds `rod`, `sphere`; default 5 for a rod); the outer one of a tube.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diameter_mm: Option<f64>,
    /// Angle between this rod's axis and the axis of the rod above it \[deg\] (rods below the
    /// top; default `chain.crossing_angle_deg`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crossing_angle_deg: Option<f64>,
    /// Inner diameter of a tube \[mm\] (kind `rod`; default: a solid rod).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inner_diameter_mm: Option<f64>,
    /// Length \[mm\] (kind `rod`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length_mm: Option<f64>,
    /// Material (kinds `rod`, `sphere`; default `fused-quartz`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<MaterialSpec>,
    /// Unit cell (kind `rod`): given (`primary_mass_g`, `resonators`), derived from the rod by
    /// beam theory (absent, or `{ modes = l, reduction = "…" }`), or the finite-element rod
    /// (`{ fe_elements = n }`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cell: Option<CellSpec>,
}

/// The unit cell of a user rod: given by its masses and springs, or derived from the rod's
/// geometry and material (docs/physics.md §13).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CellSpec {
    /// Primary mass M \[g\] of a given cell.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub primary_mass_g: Option<f64>,
    /// Internal resonators of a given cell (none: a rigid body).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub resonators: Vec<ResonatorSpec>,
    /// Resonators of a derived cell, 1–4 (default: one per centre-blocked mode below 38 kHz).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modes: Option<usize>,
    /// Reduction of a derived cell: `pole-zero` (default) or `modal-mass`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reduction: Option<ReductionSpec>,
    /// The rod itself as a finite-element beam with this many elements per half rod (1–64):
    /// one resonator per mode; needs a small RK4 step or dopri5 (docs/physics.md §12, §13).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fe_elements: Option<usize>,
}

/// How a derived cell is reduced ([`woodpile::Reduction`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ReductionSpec {
    /// Total mass, first l poles and first l zeros exactly.
    #[default]
    PoleZero,
    /// First l poles exactly; modal effective masses.
    ModalMass,
}

impl ReductionSpec {
    /// The name used in files.
    pub const fn name(self) -> &'static str {
        match self {
            ReductionSpec::PoleZero => "pole-zero",
            ReductionSpec::ModalMass => "modal-mass",
        }
    }

    /// The library's reduction.
    pub fn reduction(self) -> woodpile::Reduction {
        match self {
            ReductionSpec::PoleZero => woodpile::Reduction::PoleZero,
            ReductionSpec::ModalMass => woodpile::Reduction::ModalMass,
        }
    }
}

/// One internal resonator of a user cell.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ResonatorSpec {
    /// Auxiliary mass m_j \[g\].
    pub mass_g: f64,
    /// Spring stiffness k_j \[kN/mm\].
    pub stiffness_kn_per_mm: f64,
}

/// A material: a preset name (`"fused-quartz"`, …) or an inline table of constants.
#[derive(Debug, Clone, PartialEq)]
pub enum MaterialSpec {
    /// A preset of [`woodpile::Material::preset_names`].
    Preset(String),
    /// User constants.
    Custom(CustomMaterial),
}

/// A user-defined material `{ name, youngs_modulus_pa, poisson_ratio, density_kg_m3 }`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CustomMaterial {
    /// Name, for reports.
    pub name: String,
    /// Young's modulus E \[Pa\].
    pub youngs_modulus_pa: f64,
    /// Poisson's ratio ν.
    pub poisson_ratio: f64,
    /// Density ρ \[kg/m³\].
    pub density_kg_m3: f64,
}

impl MaterialSpec {
    /// A preset by name.
    pub fn preset(name: &str) -> Self {
        MaterialSpec::Preset(name.to_string())
    }
}

impl Serialize for MaterialSpec {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            MaterialSpec::Preset(name) => s.serialize_str(name),
            MaterialSpec::Custom(m) => m.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for MaterialSpec {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = MaterialSpec;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                write!(
                    f,
                    "a material preset name ({}) or a table {{ name, youngs_modulus_pa, poisson_ratio, density_kg_m3 }}",
                    woodpile::Material::preset_names().join(", ")
                )
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<MaterialSpec, E> {
                Ok(MaterialSpec::Preset(v.to_string()))
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                map: A,
            ) -> Result<MaterialSpec, A::Error> {
                CustomMaterial::deserialize(serde::de::value::MapAccessDeserializer::new(map))
                    .map(MaterialSpec::Custom)
            }
        }
        d.deserialize_any(Visitor)
    }
}

/// `impact`, `blast`, `drive` or `rest`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ExcitationKind {
    /// A striker sphere hits the top element.
    #[default]
    Impact,
    /// A prescribed force acts on the top element.
    Blast,
    /// An actuator drives the top element with a signal.
    Drive,
    /// Nothing: the column is left at rest.
    Rest,
}

impl ExcitationKind {
    /// The name used in files.
    pub const fn name(self) -> &'static str {
        match self {
            ExcitationKind::Impact => "impact",
            ExcitationKind::Blast => "blast",
            ExcitationKind::Drive => "drive",
            ExcitationKind::Rest => "rest",
        }
    }
}

/// What a drive prescribes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DriveKind {
    /// A force on the top element \[N\].
    #[default]
    Force,
    /// An actuator's displacement \[m\], pushing through its tip.
    Displacement,
}

/// The time history of a drive.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SignalKind {
    /// A sin(2π f t).
    Harmonic,
    /// A sweep from `start_hz` to `end_hz` over `sweep_duration_s`.
    Chirp,
    /// A (time_s, value) table from a CSV file, linearly interpolated.
    Table,
}

/// How a chirp sweeps ([`woodpile::Sweep`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SweepSpec {
    /// Frequency linear in time.
    #[default]
    Linear,
    /// Frequency exponential in time.
    Logarithmic,
}

impl SweepSpec {
    /// The name used in files.
    pub const fn name(self) -> &'static str {
        match self {
            SweepSpec::Linear => "linear",
            SweepSpec::Logarithmic => "logarithmic",
        }
    }
}

/// A contact damping law ([`woodpile::ContactDamping`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ContactLaw {
    /// Lossless.
    #[default]
    None,
    /// Coefficient of restitution `restitution`.
    Restitution,
    /// Hunt–Crossley aimed at `restitution`.
    HuntCrossley,
    /// Viscoelastic spheres with dissipative time `viscous_time_s`.
    Viscoelastic,
}

impl DriveKind {
    /// The name used in files.
    pub const fn name(self) -> &'static str {
        match self {
            DriveKind::Force => "force",
            DriveKind::Displacement => "displacement",
        }
    }
}

impl SignalKind {
    /// The name used in files.
    pub const fn name(self) -> &'static str {
        match self {
            SignalKind::Harmonic => "harmonic",
            SignalKind::Chirp => "chirp",
            SignalKind::Table => "table",
        }
    }
}

impl SweepSpec {
    /// The library's sweep.
    pub fn sweep(self) -> woodpile::Sweep {
        match self {
            SweepSpec::Linear => woodpile::Sweep::Linear,
            SweepSpec::Logarithmic => woodpile::Sweep::Logarithmic,
        }
    }
}

impl ContactLaw {
    /// The name used in files.
    pub const fn name(self) -> &'static str {
        match self {
            ContactLaw::None => "none",
            ContactLaw::Restitution => "restitution",
            ContactLaw::HuntCrossley => "hunt-crossley",
            ContactLaw::Viscoelastic => "viscoelastic",
        }
    }
}

/// `[damping]`: the contact law of every contact (overridable at the striker or actuator and at
/// the wall), resonator and on-site damping (docs/physics.md §14).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DampingSpec {
    /// `none` (default), `restitution`, `hunt-crossley` or `viscoelastic`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact: Option<ContactLaw>,
    /// Coefficient of restitution e (restitution, hunt-crossley).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub restitution: Option<f64>,
    /// Dissipative time A \[s\] (viscoelastic).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub viscous_time_s: Option<f64>,
    /// The striker's (or a displacement actuator's) contact, when it differs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub striker: Option<ContactSpec>,
    /// The wall contact, when it differs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wall: Option<ContactSpec>,
    /// Whether a damped contact may pull near separation (default false).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub allow_pull: Option<bool>,
    /// The Hunt–Crossley impact speed v_in \[m/s\] (default: the striker's speed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub impact_speed_m_s: Option<f64>,
    /// Damping ratio ζ of every resonator (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub resonator_ratio: Option<f64>,
    /// Per-resonator ratios.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub resonators: Vec<ResonatorDampingSpec>,
    /// On-site damping time τ \[s\] of every mass (default: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub on_site_time_s: Option<f64>,
    /// Damping ratio ζ of every elastic mode of every rod of a lattice (lattices only; default
    /// 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modal_ratio: Option<f64>,
}

/// `damping.striker` / `damping.wall`: one contact's law.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// The law (default: `damping.contact`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact: Option<ContactLaw>,
    /// Coefficient of restitution e (restitution, hunt-crossley).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub restitution: Option<f64>,
    /// Dissipative time A \[s\] (viscoelastic).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub viscous_time_s: Option<f64>,
}

/// `{ element = 3, resonator = 1, ratio = 0.05 }`: one resonator's damping ratio.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ResonatorDampingSpec {
    /// Element, from 1 at the top.
    pub element: usize,
    /// Resonator of that element, from 1.
    pub resonator: usize,
    /// Damping ratio ζ.
    pub ratio: f64,
}

/// `[preload]`: a static force on the top element and gravity along the column.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PreloadSpec {
    /// Static force on the top element \[N\] (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub force_n: Option<f64>,
    /// Gravity toward the wall \[m/s²\] (default 0; 9.81 for a column on a table).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gravity_m_s2: Option<f64>,
}

/// Shape of a blast force history.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ProfileKind {
    /// Friedlander positive phase F0 (1 − t/Td) exp(−b t/Td).
    #[default]
    Friedlander,
    /// A (time_s, force_n) table from a CSV file, linearly interpolated.
    Table,
}

impl ProfileKind {
    /// The name used in files.
    pub const fn name(self) -> &'static str {
        match self {
            ProfileKind::Friedlander => "friedlander",
            ProfileKind::Table => "table",
        }
    }
}

/// `[excitation]`. Impact keys: `drop_height_m` or `velocity_m_s`, `striker`, `beta`.
/// Blast keys: `profile`, then `peak_force_n`, `duration_s`, `decay` (Friedlander) or `file` (table).
/// Drive keys: `drive`, `signal`, then `amplitude` with `frequency_hz` (harmonic) or `start_hz`,
/// `end_hz`, `sweep_duration_s`, `sweep` (chirp), or `file` (table); `ramp_s`; `tip` (displacement).
/// Rest: no keys.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExcitationSpec {
    /// `impact` (default), `blast`, `drive` or `rest`.
    #[serde(default)]
    pub kind: ExcitationKind,
    /// Drop height h \[m\] (impact; default 0.20): v0 = sqrt(2 g h).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub drop_height_m: Option<f64>,
    /// Initial striker velocity v0 \[m/s\] (impact; instead of `drop_height_m`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity_m_s: Option<f64>,
    /// The striker sphere (impact).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub striker: Option<StrikerSpec>,
    /// Striker–element 1 contact coefficient β \[N/m^1.5\] (impact; default: Hertz theory).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub beta: Option<f64>,
    /// `friedlander` (default) or `table` (blast).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<ProfileKind>,
    /// Friedlander peak force F0 \[N\] (default 200).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub peak_force_n: Option<f64>,
    /// Friedlander positive-phase duration Td \[s\] (default 2e-4).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub duration_s: Option<f64>,
    /// Friedlander decay b (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub decay: Option<f64>,
    /// Table profile or signal: CSV file with columns `time_s, force_n` (blast) or
    /// `time_s, value` (drive), relative to the scenario file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// `force` (default) or `displacement` (drive).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub drive: Option<DriveKind>,
    /// `harmonic`, `chirp` or `table` (drive; required).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub signal: Option<SignalKind>,
    /// Amplitude: N for a force, m for a displacement (harmonic, chirp).
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
    /// `linear` (default) or `logarithmic` (chirp).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sweep: Option<SweepSpec>,
    /// Smooth ramp time \[s\] (drive; default: the signal's, [`woodpile::Signal::default_ramp_s`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ramp_s: Option<f64>,
    /// The actuator's tip, keys as in `[wall]` (displacement drive; default: the paper's sensor).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tip: Option<WallSpec>,
}

impl ExcitationSpec {
    /// The drive signal's shape as far as its defaults need it (the ramp, the run duration):
    /// None when that is not given. Amplitudes and unrelated frequencies are left zero.
    pub fn signal_shape(&self) -> Option<woodpile::Signal> {
        use woodpile::Signal;
        Some(match self.signal? {
            SignalKind::Harmonic => Signal::Harmonic {
                amplitude: 0.0,
                frequency_hz: self.frequency_hz?,
            },
            SignalKind::Chirp => Signal::Chirp {
                amplitude: 0.0,
                start_hz: 0.0,
                end_hz: 0.0,
                duration_s: self.sweep_duration_s?,
                sweep: self.sweep.unwrap_or_default().sweep(),
            },
            SignalKind::Table => Signal::Table {
                times_s: Vec::new(),
                values: Vec::new(),
            },
        })
    }

    /// The run duration \[s\] when `run.duration_s` is not given:
    /// [`woodpile::RunSettings::paper_for`] this excitation (None: a drive whose signal is not
    /// given enough to tell).
    pub fn default_duration_s(&self) -> Option<f64> {
        use woodpile::{BlastProfile, Drive, Excitation, Striker};
        let x = match self.kind {
            ExcitationKind::Impact => Excitation::Impact(Striker::paper()),
            ExcitationKind::Blast => Excitation::Blast(BlastProfile::paper()),
            ExcitationKind::Drive => Excitation::Drive(Drive::force(self.signal_shape()?)),
            ExcitationKind::Rest => Excitation::Rest,
        };
        Some(woodpile::RunSettings::paper_for(&x).duration_s)
    }
}

/// The striker sphere.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrikerSpec {
    /// Diameter \[mm\] (default 10).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diameter_mm: Option<f64>,
    /// Material (default `soda-lime-glass`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<MaterialSpec>,
}

/// What the last element stands on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum WallKind {
    /// A fixed sensor with a spherical cap (`material`, `cap_radius_mm`): the default.
    #[default]
    Cap,
    /// A fixed flat (`material`): a point contact only under a sphere.
    Flat,
    /// A fixed support with its contact coefficient given directly (`beta`).
    Beta,
    /// No support: the last element is free.
    Free,
}

impl WallKind {
    /// The name used in files.
    pub const fn name(self) -> &'static str {
        match self {
            WallKind::Cap => "cap",
            WallKind::Flat => "flat",
            WallKind::Beta => "beta",
            WallKind::Free => "free",
        }
    }
}

/// `[wall]`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WallSpec {
    /// `cap` (default), `flat`, `beta` (implied by a `beta` key) or `free`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kind: Option<WallKind>,
    /// Material of the cap or flat (default `stainless-steel`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<MaterialSpec>,
    /// Cap radius R_c \[mm\] (default 5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cap_radius_mm: Option<f64>,
    /// Contact coefficient β \[N/m^1.5\] of the wall contact.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub beta: Option<f64>,
}

/// Integration method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum IntegratorKind {
    /// Classical RK4 with a fixed step (the paper's method).
    #[default]
    Rk4,
    /// Dormand–Prince 5(4) with error control and dense output.
    Dopri5,
}

impl IntegratorKind {
    /// The name used in files.
    pub const fn name(self) -> &'static str {
        match self {
            IntegratorKind::Rk4 => "rk4",
            IntegratorKind::Dopri5 => "dopri5",
        }
    }
}

/// `[run]`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunSpec {
    /// Simulated time \[s\] (default: [`ExcitationSpec::default_duration_s`]; 2e-3 for an
    /// impact, 3e-3 for a blast).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub duration_s: Option<f64>,
    /// Relative accuracy wanted on every contact peak, instead of an integrator: woodpile then
    /// chooses the method and its settings ([`woodpile::Method::for_peak_tolerance`]). Excludes
    /// `integrator`, `time_step_s`, `rtol` and `atol`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub peak_tolerance: Option<f64>,
    /// `rk4` (default) or `dopri5`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub integrator: Option<IntegratorKind>,
    /// RK4 time step Δt \[s\] (default 1e-7).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time_step_s: Option<f64>,
    /// DOPRI5 relative tolerance (default 1e-9).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rtol: Option<f64>,
    /// DOPRI5 absolute tolerance \[m\] (default 1e-15).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub atol: Option<f64>,
    /// Spacing of the uniform sample grid \[s\] (default 1e-6).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sample_interval_s: Option<f64>,
}

impl RunSpec {
    /// In words: how a run of these settings is integrated (a design study's reports).
    pub fn accuracy_text(&self) -> String {
        match (self.peak_tolerance, self.integrator, self.time_step_s) {
            (Some(t), _, _) => format!("every contact peak within {t:e} (relative)"),
            (None, Some(IntegratorKind::Dopri5), _) => format!(
                "dopri5, rtol {:e}, atol {:e} m",
                self.rtol.unwrap_or(woodpile::defaults::RTOL),
                self.atol.unwrap_or(woodpile::defaults::ATOL)
            ),
            (None, _, dt) => format!(
                "rk4 at {:e} s",
                dt.unwrap_or(woodpile::defaults::TIME_STEP_S)
            ),
        }
    }
}

/// The model's defaults, from the physics core (their single source).
pub mod defaults {
    pub use woodpile::defaults::*;
    /// Friedlander peak \[N\] (scenario key `excitation.peak_force_n`).
    pub const PEAK_FORCE_N: f64 = BLAST_PEAK_FORCE_N;
    /// Friedlander decay (scenario key `excitation.decay`).
    pub const DECAY: f64 = BLAST_DECAY;
    /// Wall cap radius \[mm\] (scenario key `wall.cap_radius_mm`).
    pub const CAP_RADIUS_MM: f64 = WALL_CAP_RADIUS_MM;
}

impl Scenario {
    /// Parses a scenario from TOML text. Syntax errors and unknown keys give the line and column.
    pub fn parse(text: &str) -> Result<Self, Error> {
        Self::parse_named(text, "scenario")
    }

    /// [`Scenario::parse`] naming the text `source_name` in errors. A lattice scenario (a
    /// top-level `lattice` table) is [`Error::ChainsOnly`] rather than an unknown key.
    fn parse_named(text: &str, source_name: &str) -> Result<Self, Error> {
        toml::from_str(text).map_err(|e| {
            let lattice = text
                .parse::<toml::Table>()
                .is_ok_and(|t| t.contains_key("lattice"));
            if lattice {
                return Error::ChainsOnly {
                    source_name: source_name.into(),
                };
            }
            Error::Parse {
                source_name: source_name.into(),
                message: e.to_string(),
            }
        })
    }

    /// Reads and parses a scenario file.
    pub fn load(path: &Path) -> Result<Self, Error> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::Read {
            path: path.to_path_buf(),
            source: e,
        })?;
        Self::parse_named(&text, &path.display().to_string())
    }

    /// The same scenario with every default written out (the keys that apply to the chosen kinds).
    /// Resolving it gives the same model as resolving `self`.
    pub fn complete(&self) -> Scenario {
        use defaults::*;
        let mut s = self.clone();
        // chain
        let c = &mut s.chain;
        let chain_model = *c.model.get_or_insert(ModelSpec::Resonant);
        c.crossing_angle_deg.get_or_insert(CROSSING_ANGLE_DEG);
        if let Some(elements) = &mut c.elements {
            for e in elements {
                e.complete();
                if e.kind != Some(ElementKind::Sphere) {
                    e.model.get_or_insert(chain_model);
                }
            }
        }
        // excitation
        let x = &mut s.excitation;
        match x.kind {
            ExcitationKind::Impact => {
                if x.velocity_m_s.is_none() {
                    x.drop_height_m.get_or_insert(DROP_HEIGHT_M);
                }
                let st = x.striker.get_or_insert_with(StrikerSpec::default);
                st.diameter_mm.get_or_insert(STRIKER_DIAMETER_MM);
                st.material
                    .get_or_insert_with(|| MaterialSpec::preset(STRIKER_MATERIAL));
            }
            ExcitationKind::Blast => match *x.profile.get_or_insert(ProfileKind::Friedlander) {
                ProfileKind::Friedlander => {
                    x.peak_force_n.get_or_insert(PEAK_FORCE_N);
                    x.duration_s.get_or_insert(BLAST_DURATION_S);
                    x.decay.get_or_insert(DECAY);
                }
                ProfileKind::Table => {}
            },
            ExcitationKind::Drive => {
                if *x.drive.get_or_insert(DriveKind::Force) == DriveKind::Displacement {
                    x.tip.get_or_insert_with(WallSpec::default).complete();
                }
                if x.signal == Some(SignalKind::Chirp) {
                    x.sweep.get_or_insert(SweepSpec::Linear);
                }
                if x.ramp_s.is_none() {
                    x.ramp_s = x.signal_shape().map(|s| s.default_ramp_s());
                }
            }
            ExcitationKind::Rest => {}
        }
        s.wall.complete();
        if let Some(d) = &mut s.damping {
            let none = woodpile::Damping::default();
            let law = *d.contact.get_or_insert(ContactLaw::None);
            for c in [&mut d.striker, &mut d.wall].into_iter().flatten() {
                c.contact.get_or_insert(law);
            }
            d.allow_pull.get_or_insert(none.allow_pull);
            d.resonator_ratio.get_or_insert(none.resonator_ratio);
        }
        if let Some(p) = &mut s.preload {
            let none = woodpile::Preload::default();
            p.force_n.get_or_insert(none.force_n);
            p.gravity_m_s2.get_or_insert(none.gravity_m_s2);
        }
        // run
        let r = &mut s.run;
        if r.duration_s.is_none() {
            r.duration_s = s.excitation.default_duration_s();
        }
        // A stated peak accuracy leaves the integrator to woodpile.
        if r.peak_tolerance.is_none() {
            match *r.integrator.get_or_insert(IntegratorKind::Rk4) {
                IntegratorKind::Rk4 => {
                    r.time_step_s.get_or_insert(TIME_STEP_S);
                }
                IntegratorKind::Dopri5 => {
                    r.rtol.get_or_insert(RTOL);
                    r.atol.get_or_insert(ATOL);
                }
            }
        }
        r.sample_interval_s.get_or_insert(SAMPLE_INTERVAL_S);
        s
    }

    /// The scenario as commented TOML with every default written out; `woodpile simulate` accepts
    /// it and runs exactly the same model.
    pub fn to_toml(&self) -> String {
        emit::to_toml(&self.complete())
    }
}

impl ElementSpec {
    /// The kind: as given, else a catalogue rod when `rod_mm` is given, else a user rod.
    pub fn effective_kind(&self) -> ElementKind {
        self.kind.unwrap_or(if self.rod_mm.is_some() {
            ElementKind::Catalogue
        } else {
            ElementKind::Rod
        })
    }

    /// Writes out the kind (none for a catalogue rod) and the defaults of the keys it uses,
    /// but not the cell model, which follows `chain.model`.
    pub fn complete(&mut self) {
        let kind = self.effective_kind();
        self.kind = (kind != ElementKind::Catalogue).then_some(kind);
        if kind == ElementKind::Catalogue {
            return;
        }
        self.material
            .get_or_insert_with(|| MaterialSpec::preset(defaults::ELEMENT_MATERIAL));
        if kind == ElementKind::Rod {
            self.diameter_mm.get_or_insert(defaults::ROD_DIAMETER_MM);
            // A derived cell (neither given masses nor a finite-element rod).
            if let Some(c) = &mut self.cell {
                if c.primary_mass_g.is_none() && c.fe_elements.is_none() {
                    c.reduction.get_or_insert(ReductionSpec::PoleZero);
                }
            }
        }
    }
}

impl WallSpec {
    /// The kind, with `beta` implying [`WallKind::Beta`] when no kind is given.
    pub fn effective_kind(&self) -> WallKind {
        self.kind.unwrap_or(if self.beta.is_some() {
            WallKind::Beta
        } else {
            WallKind::Cap
        })
    }

    /// Writes out the kind and the defaults of the keys it uses.
    fn complete(&mut self) {
        let kind = self.effective_kind();
        self.kind = Some(kind);
        if matches!(kind, WallKind::Cap | WallKind::Flat) {
            self.material
                .get_or_insert_with(|| MaterialSpec::preset(defaults::WALL_MATERIAL));
        }
        if kind == WallKind::Cap {
            self.cap_radius_mm.get_or_insert(defaults::CAP_RADIUS_MM);
        }
    }
}
