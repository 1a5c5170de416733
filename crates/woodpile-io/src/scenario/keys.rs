//! One table of the scenario's keys: name, type, unit, default, the choices of a named value,
//! the keys it replaces, what is valid and one line of documentation. Emission writes each key's
//! line as its comment; front ends list the keys from it (the Python package's `keys()`, its
//! alternatives when a key is set). The defaults are read from [`woodpile::defaults`] and the
//! core's `Default` impls, never restated; a claim (`scenario_keys_table`) checks that
//! [`Scenario::complete`](super::Scenario::complete) writes exactly these defaults and that every
//! key of the table is a key of the file and round-trips.

use super::{
    ContactLaw, DriveKind, ElementKind, ExcitationKind, IntegratorKind, ModelSpec, ProfileKind,
    ReductionSpec, SignalKind, SweepSpec, WallKind,
};
use std::sync::LazyLock;
use woodpile::defaults as d;

/// The type of a key's value, as written in TOML.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum KeyType {
    /// A floating-point number.
    Float,
    /// A non-negative integer.
    Integer,
    /// `true` or `false`.
    Bool,
    /// A string (a file name, a description).
    String,
    /// One of the key's [`Key::choices`].
    Name,
    /// A material preset name or an inline table `{ name, youngs_modulus_pa, poisson_ratio,
    /// density_kg_m3 }`.
    Material,
    /// An array of integers.
    IntegerList,
    /// An array of numbers.
    FloatList,
    /// An array of inline tables, whose keys are listed as `NAME[].KEY`.
    TableList,
    /// A table, whose keys are listed as `NAME.KEY`.
    Table,
}

impl KeyType {
    /// The name of the type, for listings.
    pub const fn name(self) -> &'static str {
        match self {
            KeyType::Float => "float",
            KeyType::Integer => "integer",
            KeyType::Bool => "bool",
            KeyType::String => "string",
            KeyType::Name => "name",
            KeyType::Material => "material",
            KeyType::IntegerList => "list of integers",
            KeyType::FloatList => "list of numbers",
            KeyType::TableList => "list of tables",
            KeyType::Table => "table",
        }
    }
}

/// A key's default when it is not given.
#[derive(Debug, Clone, PartialEq)]
pub enum KeyDefault {
    /// None: the key is optional without a default, or required where it applies.
    None,
    /// This number.
    Float(f64),
    /// This flag.
    Bool(bool),
    /// This name (a choice or a material preset).
    Name(&'static str),
    /// Follows from other keys, as described.
    Derived(String),
}

impl std::fmt::Display for KeyDefault {
    /// As a TOML value (`1e-7`, `"rk4"`, `true`); a derived default in words, in parentheses;
    /// nothing for none.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            KeyDefault::None => Ok(()),
            KeyDefault::Float(x) => f.write_str(&toml_float(*x)),
            KeyDefault::Bool(b) => write!(f, "{b}"),
            KeyDefault::Name(n) => write!(f, "\"{n}\""),
            KeyDefault::Derived(words) => write!(f, "({words})"),
        }
    }
}

/// One key of the scenario file.
#[derive(Debug, Clone, PartialEq)]
pub struct Key {
    /// Dotted path, as errors name it: `run.time_step_s`; an entry of a list is `LIST[].KEY`
    /// (`chain.elements[].rod_mm`).
    pub name: &'static str,
    /// The type of its value.
    pub ty: KeyType,
    /// Unit of the value ("" when dimensionless or not a number).
    pub unit: &'static str,
    /// The default when it is not given.
    pub default: KeyDefault,
    /// The valid names of a [`KeyType::Name`] key.
    pub choices: &'static [&'static str],
    /// Keys it replaces: setting it drops these (`excitation.velocity_m_s` ↔
    /// `excitation.drop_height_m`); a file gives at most one of them.
    pub alternatives: &'static [&'static str],
    /// What values are valid, in words ("" when any value of the type is).
    pub valid: &'static str,
    /// What it is, in one line (the comment beside it in an emitted file).
    pub doc: &'static str,
}

impl Key {
    /// The comment written beside the key: its doc, unit and choices.
    pub fn comment(&self) -> String {
        let mut c = self.doc.to_string();
        if !self.unit.is_empty() {
            c += &format!(" [{}]", self.unit);
        }
        if !self.choices.is_empty() {
            let quoted: Vec<String> = self.choices.iter().map(|n| format!("\"{n}\"")).collect();
            c += &format!(": {}", quoted.join(", "));
        }
        c
    }
}

/// Every key of the scenario file, in the order of the file: the one table that emission
/// comments from, completion agrees with (claim `scenario_keys_table`) and front ends list
/// (names, types, units, defaults read from [`woodpile::defaults`], choices, alternatives).
pub fn keys() -> &'static [Key] {
    static KEYS: LazyLock<Vec<Key>> = LazyLock::new(table);
    &KEYS
}

/// The key named `name` (dotted, list entries as `LIST[].KEY`).
pub fn key(name: &str) -> Option<&'static Key> {
    keys().iter().find(|k| k.name == name)
}

const MODELS: &[&str] = &[ModelSpec::Resonant.name(), ModelSpec::Rigid.name()];
const ELEMENT_KINDS: &[&str] = &[
    ElementKind::Catalogue.name(),
    ElementKind::Rod.name(),
    ElementKind::Sphere.name(),
];
const EXCITATIONS: &[&str] = &[
    ExcitationKind::Impact.name(),
    ExcitationKind::Blast.name(),
    ExcitationKind::Drive.name(),
    ExcitationKind::Rest.name(),
];
const PROFILES: &[&str] = &[ProfileKind::Friedlander.name(), ProfileKind::Table.name()];
const DRIVES: &[&str] = &[DriveKind::Force.name(), DriveKind::Displacement.name()];
const SIGNALS: &[&str] = &[
    SignalKind::Harmonic.name(),
    SignalKind::Chirp.name(),
    SignalKind::Table.name(),
];
const SWEEPS: &[&str] = &[SweepSpec::Linear.name(), SweepSpec::Logarithmic.name()];
const WALLS: &[&str] = &[
    WallKind::Cap.name(),
    WallKind::Flat.name(),
    WallKind::Beta.name(),
    WallKind::Free.name(),
];
const LAWS: &[&str] = &[
    ContactLaw::None.name(),
    ContactLaw::Restitution.name(),
    ContactLaw::HuntCrossley.name(),
    ContactLaw::Viscoelastic.name(),
];
const INTEGRATORS: &[&str] = &[IntegratorKind::Rk4.name(), IntegratorKind::Dopri5.name()];
const REDUCTIONS: &[&str] = &[
    ReductionSpec::PoleZero.name(),
    ReductionSpec::ModalMass.name(),
];

/// What a positive key accepts (also the wording of resolve's message).
pub(crate) const POSITIVE: &str = "a finite number > 0";
/// What a non-negative key accepts (also the wording of resolve's message).
pub(crate) const NON_NEGATIVE: &str = "a finite number >= 0";
/// What an angle between rods accepts (also the wording of resolve's message).
pub(crate) const ANGLE: &str = "strictly between 0 and 180";
const MATERIAL: &str = "a preset name or a table";
const INTEGRATOR_KEYS: &[&str] = &["run.integrator", "run.time_step_s", "run.rtol", "run.atol"];
const PEAK_TOLERANCE: &[&str] = &["run.peak_tolerance"];

impl Key {
    /// A key with no default, no choices and no alternatives.
    fn new(
        name: &'static str,
        ty: KeyType,
        unit: &'static str,
        valid: &'static str,
        doc: &'static str,
    ) -> Key {
        Key {
            name,
            ty,
            unit,
            default: KeyDefault::None,
            choices: &[],
            alternatives: &[],
            valid,
            doc,
        }
    }

    /// The same key with a default.
    fn or(self, default: KeyDefault) -> Key {
        Key { default, ..self }
    }

    /// The same key replacing `alternatives`.
    fn instead_of(self, alternatives: &'static [&'static str]) -> Key {
        Key {
            alternatives,
            ..self
        }
    }
}

fn float(name: &'static str, unit: &'static str, valid: &'static str, doc: &'static str) -> Key {
    Key::new(name, KeyType::Float, unit, valid, doc)
}

fn int(name: &'static str, unit: &'static str, valid: &'static str, doc: &'static str) -> Key {
    Key::new(name, KeyType::Integer, unit, valid, doc)
}

fn table_key(name: &'static str, doc: &'static str) -> Key {
    Key::new(name, KeyType::Table, "", "", doc)
}

fn list(name: &'static str, valid: &'static str, doc: &'static str) -> Key {
    Key::new(name, KeyType::TableList, "", valid, doc)
}

fn material(name: &'static str, default: &'static str, doc: &'static str) -> Key {
    Key::new(name, KeyType::Material, "", MATERIAL, doc).or(KeyDefault::Name(default))
}

/// A [`KeyType::Name`] key, defaulting to `default` (None: no default).
fn named(
    name: &'static str,
    choices: &'static [&'static str],
    default: Option<&'static str>,
    doc: &'static str,
) -> Key {
    Key {
        choices,
        ..Key::new(name, KeyType::Name, "", "one of the choices", doc)
    }
    .or(default.map_or(KeyDefault::None, KeyDefault::Name))
}

fn derived(name: &str) -> KeyDefault {
    KeyDefault::Derived(name.to_string())
}

fn table() -> Vec<Key> {
    let description = Key::new(
        "description",
        KeyType::String,
        "",
        "",
        "one line saying what the scenario is",
    );
    [
        vec![description],
        chain_keys(),
        element_keys(),
        cell_keys(),
        impact_keys(),
        blast_keys(),
        drive_keys(),
        support_keys([
            "wall.kind",
            "wall.material",
            "wall.cap_radius_mm",
            "wall.beta",
        ]),
        damping_keys(),
        preload_keys(),
        run_keys(),
        uncertainty_keys(),
    ]
    .concat()
}

#[rustfmt::skip] // one row per key
fn chain_keys() -> Vec<Key> {
    let rods = "Table 1 catalogue rods (fused quartz, 5 mm diameter) by length, top to bottom";
    let rod_lengths = "lengths of the Table 1 catalogue (woodpile::TABLE1_LENGTHS_MM)";
    let elements =
        "elements top to bottom: { rod_mm = L }, { kind = \"rod\", … }, { kind = \"sphere\", … }";
    let models = "cell model: Table 1 resonators, or one rigid body";
    vec![
        table_key("chain", "the column of elements, top to bottom"),
        Key::new("chain.rods_mm", KeyType::IntegerList, "mm", rod_lengths, rods).instead_of(&["chain.elements"]),
        list("chain.elements", "at least one entry", elements).instead_of(&["chain.rods_mm"]),
        named("chain.model", MODELS, Some(ModelSpec::Resonant.name()), models),
        float("chain.crossing_angle_deg", "deg", ANGLE, "angle between neighbouring rods").or(KeyDefault::Float(d::CROSSING_ANGLE_DEG)),
        list("chain.contact_beta", "one entry per contact", "beta set directly (1 = elements 1-2, N = wall)"),
        int("chain.contact_beta[].contact", "", "1..=N (N = the wall)", "contact number"),
        float("chain.contact_beta[].beta", "N/m^1.5", POSITIVE, "the contact's beta"),
    ]
}

#[rustfmt::skip] // one row per key
fn element_keys() -> Vec<Key> {
    let kind = "catalogue when rod_mm is given, else rod";
    vec![
        named("chain.elements[].kind", ELEMENT_KINDS, None, "what the element is").or(derived(kind)),
        int("chain.elements[].rod_mm", "mm", "a Table 1 length", "catalogue rod length"),
        named("chain.elements[].model", MODELS, None, "cell model of this rod").or(derived("chain.model")),
        float("chain.elements[].diameter_mm", "mm", POSITIVE, "diameter of a rod or sphere (a tube's outer one)").or(KeyDefault::Float(d::ROD_DIAMETER_MM)),
        float("chain.elements[].crossing_angle_deg", "deg", ANGLE, "angle to the rod above").or(derived("chain.crossing_angle_deg")),
        float("chain.elements[].inner_diameter_mm", "mm", "below diameter_mm", "inner diameter of a tube (none: a solid rod)"),
        float("chain.elements[].length_mm", "mm", POSITIVE, "length of a rod"),
        material("chain.elements[].material", d::ELEMENT_MATERIAL, "material of a rod or sphere"),
    ]
}

#[rustfmt::skip] // one row per key
fn cell_keys() -> Vec<Key> {
    let reduction = Some(ReductionSpec::PoleZero.name());
    vec![
        table_key("chain.elements[].cell", "unit cell of a rod (none: derived by beam theory)"),
        float("chain.elements[].cell.primary_mass_g", "g", POSITIVE, "primary mass M of a given cell"),
        list("chain.elements[].cell.resonators", "", "resonators of a given cell"),
        float("chain.elements[].cell.resonators[].mass_g", "g", POSITIVE, "auxiliary mass m_j"),
        float("chain.elements[].cell.resonators[].stiffness_kn_per_mm", "kN/mm", POSITIVE, "spring stiffness k_j"),
        int("chain.elements[].cell.modes", "", "1..=4", "resonators of a derived cell"),
        named("chain.elements[].cell.reduction", REDUCTIONS, reduction, "reduction of a derived cell"),
        int("chain.elements[].cell.fe_elements", "", "1..=64", "finite-element beam elements per half rod"),
    ]
}

#[rustfmt::skip] // one row per key
fn impact_keys() -> Vec<Key> {
    let kinds = "a striker, a blast, an actuator, or nothing";
    vec![
        table_key("excitation", "what drives the chain"),
        named("excitation.kind", EXCITATIONS, Some(ExcitationKind::Impact.name()), kinds),
        float("excitation.drop_height_m", "m", POSITIVE, "impact: drop height h, v0 = sqrt(2 g h)").or(KeyDefault::Float(d::DROP_HEIGHT_M)).instead_of(&["excitation.velocity_m_s"]),
        float("excitation.velocity_m_s", "m/s", POSITIVE, "impact: initial striker velocity").instead_of(&["excitation.drop_height_m"]),
        table_key("excitation.striker", "impact: the striker sphere"),
        float("excitation.striker.diameter_mm", "mm", POSITIVE, "striker diameter").or(KeyDefault::Float(d::STRIKER_DIAMETER_MM)),
        material("excitation.striker.material", d::STRIKER_MATERIAL, "striker material"),
        float("excitation.beta", "N/m^1.5", POSITIVE, "impact: striker-element 1 contact coefficient").or(derived("Hertz theory")),
    ]
}

#[rustfmt::skip] // one row per key
fn blast_keys() -> Vec<Key> {
    let profile = Some(ProfileKind::Friedlander.name());
    let shape = "blast: F0 (1 - t/Td) exp(-b t/Td), or a CSV table";
    vec![
        named("excitation.profile", PROFILES, profile, shape),
        float("excitation.peak_force_n", "N", POSITIVE, "blast: peak force F0").or(KeyDefault::Float(d::BLAST_PEAK_FORCE_N)),
        float("excitation.duration_s", "s", POSITIVE, "blast: positive phase Td").or(KeyDefault::Float(d::BLAST_DURATION_S)),
        float("excitation.decay", "", NON_NEGATIVE, "blast: decay b (1 = Friedlander, 0 = triangle)").or(KeyDefault::Float(d::BLAST_DECAY)),
        Key::new("excitation.file", KeyType::String, "", "a CSV file", "table profile or signal, relative to the scenario file"),
    ]
}

#[rustfmt::skip] // one row per key
fn drive_keys() -> Vec<Key> {
    let drives = "drive: a force (N) or a displacement (m, through the tip)";
    let ramp = "the signal's (woodpile::Signal::default_ramp_s)";
    [
        vec![
            named("excitation.drive", DRIVES, Some(DriveKind::Force.name()), drives),
            named("excitation.signal", SIGNALS, None, "drive: the signal"),
            float("excitation.amplitude", "N or m", "", "drive: amplitude (harmonic, chirp)"),
            float("excitation.frequency_hz", "Hz", POSITIVE, "drive: harmonic frequency"),
            float("excitation.start_hz", "Hz", POSITIVE, "drive: chirp from"),
            float("excitation.end_hz", "Hz", POSITIVE, "drive: chirp to"),
            float("excitation.sweep_duration_s", "s", POSITIVE, "drive: chirp over"),
            named("excitation.sweep", SWEEPS, Some(SweepSpec::Linear.name()), "drive: how a chirp sweeps"),
            float("excitation.ramp_s", "s", NON_NEGATIVE, "drive: sin^2 ramp (chirp: both ends)").or(derived(ramp)),
            table_key("excitation.tip", "drive: the actuator's tip, keys as in [wall]"),
        ],
        support_keys([
            "excitation.tip.kind",
            "excitation.tip.material",
            "excitation.tip.cap_radius_mm",
            "excitation.tip.beta",
        ]),
    ].concat()
}

/// The keys of a support (`[wall]`, a displacement actuator's tip): kind, material, cap radius
/// and beta.
#[rustfmt::skip] // one row per key
fn support_keys(names: [&'static str; 4]) -> Vec<Key> {
    let kinds = "a sensor with a spherical cap, a flat, a given beta, or free";
    let mut keys = vec![
        named(names[0], WALLS, None, kinds).or(derived("beta when beta is given, else cap")),
        material(names[1], d::WALL_MATERIAL, "material of the cap or flat"),
        float(names[2], "mm", POSITIVE, "cap radius R_c").or(KeyDefault::Float(d::WALL_CAP_RADIUS_MM)),
        float(names[3], "N/m^1.5", POSITIVE, "the contact's beta"),
    ];
    if names[0] == "wall.kind" { keys.insert(0, table_key("wall", "the support under the last element")); }
    keys
}

/// The keys of one contact's law: `[damping]` itself, `damping.striker`, `damping.wall`.
#[rustfmt::skip] // one row per key
fn law_keys(names: [&'static str; 3], default: KeyDefault) -> Vec<Key> {
    let restitution = "coefficient of restitution e (restitution, hunt-crossley)";
    vec![
        named(names[0], LAWS, None, "contact damping law").or(default),
        float(names[1], "", "0 < e <= 1", restitution),
        float(names[2], "s", POSITIVE, "dissipative time A (viscoelastic)"),
    ]
}

#[rustfmt::skip] // one row per key
fn damping_keys() -> Vec<Key> {
    let none = woodpile::Damping::default();
    let contact = || derived("damping.contact");
    let damping =
        "contact laws, resonator and on-site damping (docs/physics.md §14); none: lossless";
    let on_site = "on-site damping time tau of every mass (none: no on-site damping)";
    [
        vec![table_key("damping", damping)],
        law_keys(
            [
                "damping.contact",
                "damping.restitution",
                "damping.viscous_time_s",
            ],
            KeyDefault::Name(ContactLaw::None.name()),
        ),
        vec![table_key(
            "damping.striker",
            "the striker's or actuator's contact, when it differs",
        )],
        law_keys(
            [
                "damping.striker.contact",
                "damping.striker.restitution",
                "damping.striker.viscous_time_s",
            ],
            contact(),
        ),
        vec![table_key(
            "damping.wall",
            "the wall contact, when it differs",
        )],
        law_keys(
            [
                "damping.wall.contact",
                "damping.wall.restitution",
                "damping.wall.viscous_time_s",
            ],
            contact(),
        ),
        vec![
            Key::new("damping.allow_pull", KeyType::Bool, "", "", "may a damped contact pull near separation").or(KeyDefault::Bool(none.allow_pull)),
            float("damping.impact_speed_m_s", "m/s", POSITIVE, "Hunt-Crossley impact speed v_in").or(derived("the striker's speed")),
            float("damping.resonator_ratio", "", NON_NEGATIVE, "damping ratio zeta of every resonator").or(KeyDefault::Float(none.resonator_ratio)),
            list("damping.resonators", "", "damping ratio of single resonators"),
            int("damping.resonators[].element", "", "1..=N", "element, from 1 at the top"),
            int("damping.resonators[].resonator", "", "1.. (the element's resonators)", "resonator of that element, from 1"),
            float("damping.resonators[].ratio", "", NON_NEGATIVE, "its damping ratio zeta"),
            float("damping.on_site_time_s", "s", POSITIVE, on_site),
            float("damping.modal_ratio", "", NON_NEGATIVE, "damping ratio zeta of every elastic mode of a lattice's rods (lattices only)"),
        ],
    ].concat()
}

#[rustfmt::skip] // one row per key
fn preload_keys() -> Vec<Key> {
    let none = woodpile::Preload::default();
    let preload =
        "a static force on the top element and gravity (docs/physics.md §14); none: unloaded";
    vec![
        table_key("preload", preload),
        float("preload.force_n", "N", NON_NEGATIVE, "static force on the top element").or(KeyDefault::Float(none.force_n)),
        float("preload.gravity_m_s2", "m/s^2", NON_NEGATIVE, "gravity along the column").or(KeyDefault::Float(none.gravity_m_s2)),
    ]
}

#[rustfmt::skip] // one row per key
fn run_keys() -> Vec<Key> {
    let duration = format!(
        "the excitation's: {:e} s for an impact, {:e} s for a blast, a drive's from its signal",
        d::IMPACT_DURATION_S,
        d::BLAST_RUN_DURATION_S
    );
    let accuracy = "relative accuracy of every contact peak; woodpile chooses the integrator";
    let integrators = "fixed step (rk4) or adaptive with rtol/atol (dopri5)";
    vec![
        table_key("run", "duration, integrator and sampling"),
        float("run.duration_s", "s", POSITIVE, "simulated time").or(KeyDefault::Derived(duration)),
        float("run.peak_tolerance", "", "a small relative error", accuracy).instead_of(INTEGRATOR_KEYS),
        named("run.integrator", INTEGRATORS, Some(IntegratorKind::Rk4.name()), integrators).instead_of(PEAK_TOLERANCE),
        float("run.time_step_s", "s", "> 0 and below run.duration_s", "rk4 step").or(KeyDefault::Float(d::TIME_STEP_S)).instead_of(PEAK_TOLERANCE),
        float("run.rtol", "", "at least 1e-14", "dopri5 relative tolerance").or(KeyDefault::Float(d::RTOL)).instead_of(PEAK_TOLERANCE),
        float("run.atol", "m", POSITIVE, "dopri5 absolute tolerance").or(KeyDefault::Float(d::ATOL)).instead_of(PEAK_TOLERANCE),
        float("run.sample_interval_s", "s", "> 0 and at most run.duration_s", "uniform output grid").or(KeyDefault::Float(d::SAMPLE_INTERVAL_S)),
    ]
}

#[rustfmt::skip] // one row per key
fn uncertainty_keys() -> Vec<Key> {
    const DIST: &str = "{ sd = s } (normal, the key's unit), { relative_sd = r } or { uniform = [a, b] }";
    let dist = |name, unit, doc| Key::new(name, KeyType::Table, unit, DIST, doc);
    vec![
        table_key("uncertainty", "manufacturing scatter for --samples studies (docs/optimization.md); none: nominal values only"),
        int("uncertainty.samples", "", "at least 1", "samples per design").or(KeyDefault::Derived(d::UNCERTAINTY_SAMPLES.to_string())),
        int("uncertainty.seed", "", "0..2^32", "seed of the scrambled Sobol' points").or(KeyDefault::Derived(d::UNCERTAINTY_SEED.to_string())),
        dist("uncertainty.rod_length_mm", "mm", "length of each user rod, independently"),
        dist("uncertainty.crossing_angle_deg", "deg", "angle of each contact between rods, independently"),
        dist("uncertainty.youngs_modulus", "Pa", "Young's modulus of the elements' material"),
        dist("uncertainty.impact_velocity_m_s", "m/s", "the striker's impact velocity"),
        dist("uncertainty.restitution", "", "damping.restitution"),
        dist("uncertainty.viscous_time_s", "s", "damping.viscous_time_s"),
        dist("uncertainty.resonator_ratio", "", "damping.resonator_ratio"),
        dist("uncertainty.on_site_time_s", "s", "damping.on_site_time_s"),
    ]
}

/// A float as TOML: shortest round-trip digits, scientific notation for very small or large
/// magnitudes, always recognisable as a float.
pub(crate) fn toml_float(x: f64) -> String {
    if x.is_nan() {
        return "nan".into();
    }
    if x.is_infinite() {
        return if x > 0.0 { "inf" } else { "-inf" }.into();
    }
    let a = x.abs();
    if a == 0.0 || (1e-3..1e6).contains(&a) {
        let s = format!("{x}");
        if s.contains('.') {
            s
        } else {
            format!("{s}.0")
        }
    } else {
        format!("{x:e}")
    }
}
