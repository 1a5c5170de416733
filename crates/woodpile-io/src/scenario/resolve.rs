//! From a scenario to the library's model: every value checked under its scenario key.

use super::keys::toml_float as float;
use super::keys::{ANGLE, NON_NEGATIVE, POSITIVE};
use super::{
    CellSpec, ChainSpec, ContactLaw, DampingSpec, DriveKind, ElementKind, ElementSpec,
    ExcitationKind, ExcitationSpec, IntegratorKind, MaterialSpec, ProfileKind, Scenario,
    SignalKind, WallKind, WallSpec,
};
use crate::error::Error;
use crate::table::load_table;
use std::path::Path;
use woodpile::{
    BlastProfile, Body, Chain, ChainBuilder, ContactDamping, Damping, Drive, DriveQuantity,
    Element, Excitation, Material, Method, Preload, Resonator, ResonatorDamping, Rod, RunSettings,
    Signal, Striker, UnitCell, Wall,
};

/// Largest spherical-cap radius of a wall \[mm\]: beyond it the cap is a flat in all but name.
const MAX_CAP_RADIUS_MM: f64 = 1e6;
/// A scenario turned into what the library runs.
#[derive(Debug, Clone, PartialEq)]
pub struct Resolved {
    /// The chain with every contact coefficient computed.
    pub chain: Chain,
    /// The striker or the blast load.
    pub excitation: Excitation,
    /// Duration, integrator and sampling.
    pub settings: RunSettings,
    /// What is valid but probably not meant (e.g. a given cell whose mass is not the rod's),
    /// one sentence each, naming the key; front ends print them as warnings.
    pub warnings: Vec<String>,
}

/// A given cell whose total mass is further than this (relative) from the rod's ρ·A·L is
/// reported.
const MASS_MISMATCH_WARN: f64 = 0.01;

/// Refuses the first of `keys` (`modes`, `reduction`, `fe_elements`) that `spec` sets, as not
/// applicable `why`.
fn refuse_cell_keys(
    field: &dyn Fn(&str) -> String,
    spec: &CellSpec,
    keys: &[&str],
    why: &str,
) -> Result<(), Error> {
    let set = [
        ("modes", spec.modes.map(|l| l.to_string())),
        (
            "reduction",
            spec.reduction.map(|r| r.reduction().name().to_string()),
        ),
        ("fe_elements", spec.fe_elements.map(|n| n.to_string())),
    ];
    match set.iter().find(|(k, v)| keys.contains(k) && v.is_some()) {
        Some((k, Some(v))) => Err(not_applicable(&field(&format!("cell.{k}")), v, why)),
        _ => Ok(()),
    }
}

/// Reports a given cell whose total mass is more than [`MASS_MISMATCH_WARN`] off the element's
/// own (`what` says how that is computed).
fn warn_mass(warnings: &mut Vec<String>, key: &str, cell_kg: f64, body_kg: f64, what: &str) {
    let off = (cell_kg - body_kg) / body_kg;
    if off.abs() > MASS_MISMATCH_WARN {
        warnings.push(format!(
            "{key}: the cell's total mass {:.4} g is {:+.1} % off the element's {what} = {:.4} g; the run uses the cell's masses. For a rod, drop `cell` to derive it from the rod (docs/physics.md §13); otherwise correct the masses",
            cell_kg * 1e3,
            100.0 * off,
            body_kg * 1e3
        ));
    }
}

/// Checks that `value` is finite and > 0; the error names `field`.
fn positive(field: &str, value: f64) -> Result<f64, Error> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(
            field,
            float(value),
            format!("must be {POSITIVE}"),
        ))
    }
}

/// Checks that `value` is finite and >= 0; the error names `field`.
fn non_negative(field: &str, value: f64) -> Result<f64, Error> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(
            field,
            float(value),
            format!("must be {NON_NEGATIVE}"),
        ))
    }
}

/// A value that completion ([`Scenario::complete`]) writes wherever it applies: resolving reads it
/// from the completed scenario instead of applying the default a second time. Its absence names
/// the key (not reachable from a completed scenario).
fn completed<T: Clone>(field: &str, value: Option<&T>) -> Result<T, Error> {
    value
        .cloned()
        .ok_or_else(|| Error::invalid(field, "(missing)", "must be given"))
}

/// A key that does not apply to the chosen kind.
fn not_applicable(field: &str, value: impl ToString, why: &str) -> Error {
    Error::invalid(field, value, format!("not used {why}; remove it"))
}

/// Resolves a material spec; `field` is its key.
pub fn material(field: &str, spec: &MaterialSpec) -> Result<Material, Error> {
    match spec {
        MaterialSpec::Preset(name) => Material::preset(name).map_err(Error::at(field)),
        MaterialSpec::Custom(m) => {
            positive(&format!("{field}.youngs_modulus_pa"), m.youngs_modulus_pa)?;
            positive(&format!("{field}.density_kg_m3"), m.density_kg_m3)?;
            if !(m.poisson_ratio.is_finite() && m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5) {
                return Err(Error::invalid(
                    format!("{field}.poisson_ratio"),
                    m.poisson_ratio,
                    "must lie in (-1, 0.5)",
                ));
            }
            Ok(Material::new(
                &m.name,
                m.youngs_modulus_pa,
                m.poisson_ratio,
                m.density_kg_m3,
            )?)
        }
    }
}

/// A given cell (`primary_mass_g` \[g\] and its resonators).
fn cell(field: &str, primary_mass_g: f64, spec: &CellSpec) -> Result<UnitCell, Error> {
    positive(&format!("{field}.primary_mass_g"), primary_mass_g)?;
    let mut resonators = Vec::with_capacity(spec.resonators.len());
    for (j, r) in spec.resonators.iter().enumerate() {
        let f = format!("{field}.resonators[{j}]");
        positive(&format!("{f}.mass_g"), r.mass_g)?;
        positive(&format!("{f}.stiffness_kn_per_mm"), r.stiffness_kn_per_mm)?;
        resonators.push(Resonator {
            mass_kg: r.mass_g * 1e-3,
            stiffness_n_per_m: r.stiffness_kn_per_mm * 1e6,
        });
    }
    Ok(UnitCell::new(primary_mass_g * 1e-3, resonators)?)
}

/// Resolves one element; `key("rod_mm")` names its keys in errors (`key("")` the element);
/// what is valid but probably not meant is added to `warnings`.
pub fn resolve_element(
    e: &ElementSpec,
    key: &dyn Fn(&str) -> String,
    chain_model: woodpile::CellModel,
    warnings: &mut Vec<String>,
) -> Result<Element, Error> {
    let kind =
        match (e.kind, e.rod_mm) {
            (Some(k), _) => k,
            (None, Some(_)) => ElementKind::Catalogue,
            (None, None) => return Err(Error::invalid(
                key(""),
                "{}",
                "give `rod_mm = L` for a Table 1 rod, or `kind = \"rod\"` / `kind = \"sphere\"`",
            )),
        };
    let why = format!("with kind = \"{}\"", kind.name());
    let model = e.model.map(|m| m.cell_model()).unwrap_or(chain_model);
    let mut e = e.clone();
    e.complete();
    let e = &e;
    match kind {
        ElementKind::Catalogue => catalogue_element(e, key, model, &why),
        ElementKind::Rod => rod_element(e, key, model, warnings),
        ElementKind::Sphere => sphere_element(e, key, chain_model, &why, warnings),
    }
}

/// A Table 1 rod (`rod_mm`), refusing the keys of a user rod.
fn catalogue_element(
    e: &ElementSpec,
    field: &dyn Fn(&str) -> String,
    model: woodpile::CellModel,
    why: &str,
) -> Result<Element, Error> {
    let Some(l) = e.rod_mm else {
        return Err(Error::invalid(
            field("rod_mm"),
            "(missing)",
            "a catalogue element needs rod_mm",
        ));
    };
    if let Some(d) = e.diameter_mm {
        return Err(not_applicable(&field("diameter_mm"), d, why));
    }
    if let Some(d) = e.length_mm {
        return Err(not_applicable(&field("length_mm"), d, why));
    }
    if let Some(d) = e.inner_diameter_mm {
        return Err(not_applicable(&field("inner_diameter_mm"), d, why));
    }
    if e.material.is_some() {
        return Err(not_applicable(&field("material"), "…", why));
    }
    if e.cell.is_some() {
        return Err(not_applicable(&field("cell"), "{…}", why));
    }
    Element::table1_rod(l, model).map_err(Error::at(field("rod_mm")))
}

/// A user rod: its geometry, material and unit cell.
fn rod_element(
    e: &ElementSpec,
    field: &dyn Fn(&str) -> String,
    model: woodpile::CellModel,
    warnings: &mut Vec<String>,
) -> Result<Element, Error> {
    if let Some(l) = e.rod_mm {
        return Err(not_applicable(
            &field("rod_mm"),
            l,
            "with kind = \"rod\" (use length_mm and cell; or drop kind for a Table 1 rod)",
        ));
    }
    let diameter = positive(
        &field("diameter_mm"),
        completed(&field("diameter_mm"), e.diameter_mm.as_ref())?,
    )?;
    let Some(length) = e.length_mm else {
        return Err(Error::invalid(
            field("length_mm"),
            "(missing)",
            "a user rod needs length_mm",
        ));
    };
    let length = positive(&field("length_mm"), length)?;
    let inner = non_negative(
        &field("inner_diameter_mm"),
        e.inner_diameter_mm.unwrap_or(0.0),
    )?;
    if inner >= diameter {
        return Err(Error::invalid(
            field("inner_diameter_mm"),
            float(inner),
            format!(
                "must be smaller than {} ({})",
                field("diameter_mm"),
                float(diameter)
            ),
        ));
    }
    let mat = material(
        &field("material"),
        &completed(&field("material"), e.material.as_ref())?,
    )?;
    let c = rod_cell(e, field, (diameter, inner, length), &mat, warnings)?;
    let c = model.apply(c);
    Ok(Element {
        label: format!("rod{}mm", length),
        body: Body::Rod {
            diameter_m: diameter * 1e-3,
            length_m: length * 1e-3,
        },
        material: mat,
        cell: c,
    })
}

/// A user rod's unit cell: given (masses and springs, checked against the rod's mass), derived
/// by beam theory, or the finite-element rod. `size` is (diameter, inner diameter, length) \[mm\].
fn rod_cell(
    e: &ElementSpec,
    field: &dyn Fn(&str) -> String,
    size: (f64, f64, f64),
    mat: &Material,
    warnings: &mut Vec<String>,
) -> Result<UnitCell, Error> {
    let (diameter, inner, length) = size;
    let default_cell = CellSpec::default();
    let cell_spec = e.cell.as_ref().unwrap_or(&default_cell);
    Ok(match cell_spec.primary_mass_g {
        Some(primary_mass_g) => {
            refuse_cell_keys(
                field,
                cell_spec,
                &["modes", "reduction", "fe_elements"],
                "with a given cell (primary_mass_g): these derive a cell from the rod",
            )?;
            let given = cell(&field("cell"), primary_mass_g, cell_spec)?;
            let area = std::f64::consts::PI / 4.0 * (diameter.powi(2) - inner.powi(2));
            let rod_mass_kg = mat.density_kg_m3 * area * length * 1e-9;
            warn_mass(
                warnings,
                &field("cell"),
                given.total_mass_kg(),
                rod_mass_kg,
                "ρ·A·L",
            );
            given
        }
        None => {
            if !cell_spec.resonators.is_empty() {
                return Err(Error::invalid(field("cell.primary_mass_g"), "(missing)", "a given cell needs primary_mass_g with its resonators; or drop resonators to derive the cell from the rod"));
            }
            let rod = Rod::new(length * 1e-3, diameter * 1e-3, inner * 1e-3, mat.clone())?;
            // What is left to refuse: the rod's slenderness (its length), or the number of modes
            // or of elements.
            let at = |key: &str| {
                let key = field(key);
                let length_key = field("length_mm");
                move |e| match e {
                    woodpile::Error::InvalidParameter {
                        field: f, reason, ..
                    } if f == "rod.length_m" => Error::invalid(length_key, length, reason),
                    woodpile::Error::InvalidParameter { value, reason, .. } => {
                        Error::invalid(key, value, reason)
                    }
                    other => Error::Model(other),
                }
            };
            match cell_spec.fe_elements {
                Some(n) => {
                    refuse_cell_keys(
                        field,
                        cell_spec,
                        &["modes", "reduction"],
                        "with fe_elements (the finite-element rod keeps every mode)",
                    )?;
                    UnitCell::from_rod_fe(&rod, n).map_err(at("cell.fe_elements"))?
                }
                None => {
                    let reduction = cell_spec.reduction.unwrap_or_default().reduction();
                    UnitCell::from_rod(&rod, cell_spec.modes, reduction)
                        .map_err(at("cell.modes"))?
                }
            }
        }
    })
}

/// A sphere, with a given mass-in-mass cell when `cell` is set.
fn sphere_element(
    e: &ElementSpec,
    field: &dyn Fn(&str) -> String,
    chain_model: woodpile::CellModel,
    why: &str,
    warnings: &mut Vec<String>,
) -> Result<Element, Error> {
    if let Some(l) = e.rod_mm {
        return Err(not_applicable(&field("rod_mm"), l, why));
    }
    if let Some(l) = e.length_mm {
        return Err(not_applicable(&field("length_mm"), l, why));
    }
    if let Some(d) = e.inner_diameter_mm {
        return Err(not_applicable(&field("inner_diameter_mm"), d, why));
    }
    if let Some(m) = e.model {
        return Err(not_applicable(&field("model"), m.name(), why));
    }
    let Some(d) = e.diameter_mm else {
        return Err(Error::invalid(
            field("diameter_mm"),
            "(missing)",
            "a sphere needs diameter_mm",
        ));
    };
    let d = positive(&field("diameter_mm"), d)?;
    let mat = material(
        &field("material"),
        &completed(&field("material"), e.material.as_ref())?,
    )?;
    let mut sphere = Element::sphere(d * 1e-3, mat)?;
    if let Some(spec) = &e.cell {
        // A mass-in-mass sphere: a given cell (shell and internal resonators).
        let Some(primary_mass_g) = spec.primary_mass_g else {
            return Err(Error::invalid(
                field("cell.primary_mass_g"),
                "(missing)",
                "a sphere's cell is given: primary_mass_g and resonators (cells are derived for rods only)",
            ));
        };
        refuse_cell_keys(
            field,
            spec,
            &["modes", "reduction", "fe_elements"],
            "with kind = \"sphere\" (cells are derived for rods only)",
        )?;
        let given = cell(&field("cell"), primary_mass_g, spec)?;
        warn_mass(
            warnings,
            &field("cell"),
            given.total_mass_kg(),
            sphere.cell.total_mass_kg(),
            "ρπd³/6",
        );
        sphere.cell = chain_model.apply(given);
    }
    Ok(sphere)
}

/// Where the keys of a chain live in the file being resolved: the `[chain]` table of a
/// scenario ([`ChainKeys::SCENARIO`]) or the catalogue of an optimisation config's `[design]`
/// table. Errors name these keys directly, so nothing downstream rewrites a message.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ChainKeys {
    /// The Table 1 rod list (`chain.rods_mm`).
    pub rods_mm: &'static str,
    /// The general element list (`chain.elements`).
    pub elements: &'static str,
    /// The crossing angle (`chain.crossing_angle_deg`).
    pub crossing_angle_deg: &'static str,
}

impl ChainKeys {
    /// The keys of a scenario's `[chain]` table.
    pub const SCENARIO: ChainKeys = ChainKeys {
        rods_mm: "chain.rods_mm",
        elements: "chain.elements",
        crossing_angle_deg: "chain.crossing_angle_deg",
    };
}

/// Builds the chain, excitation and run settings of a scenario. `base_dir` is the directory
/// relative to which files named in the scenario (a blast table) are found.
///
/// Every invalid value gives an error naming its key (e.g. `chain.rods_mm[3]`), the value and
/// what would be valid.
pub fn resolve(scenario: &Scenario, base_dir: &Path) -> Result<Resolved, Error> {
    resolve_with_keys(scenario, base_dir, &ChainKeys::SCENARIO)
}

/// [`resolve`], naming the chain's keys as `keys` says (for a chain that comes from another
/// table of another file, such as an optimisation's catalogue).
pub fn resolve_with_keys(
    scenario: &Scenario,
    base_dir: &Path,
    keys: &ChainKeys,
) -> Result<Resolved, Error> {
    // Defaults are applied once, by completion; resolving checks and converts.
    let scenario = &scenario.complete();
    if let Some(u) = &scenario.uncertainty {
        u.check()?;
    }
    let mut warnings = Vec::new();
    let chain = resolve_chain(scenario, keys, &mut warnings)?;
    let excitation = resolve_excitation(scenario, &chain, base_dir)?;
    let settings = resolve_run(scenario)?;
    Ok(Resolved {
        chain,
        excitation,
        settings,
        warnings,
    })
}

fn resolve_chain(
    s: &Scenario,
    keys: &ChainKeys,
    warnings: &mut Vec<String>,
) -> Result<Chain, Error> {
    let c = &s.chain;
    let elements = chain_elements(c, keys, warnings)?;
    let n = elements.len();
    let angle = completed(keys.crossing_angle_deg, c.crossing_angle_deg.as_ref())?;
    if !(angle.is_finite() && angle > 0.0 && angle < 180.0) {
        return Err(Error::invalid(
            keys.crossing_angle_deg,
            angle,
            format!("must lie {ANGLE} (0 and 180 are parallel rods: a line contact)"),
        ));
    }
    if s.wall.effective_kind() == WallKind::Flat {
        if let Body::Rod { .. } = elements[n - 1].body {
            return Err(Error::invalid(
                "wall.kind",
                "\"flat\"",
                format!(
                    "element {n} is a rod, and a rod on a flat is a line contact, not a Hertz point contact; \
                     use kind = \"cap\" with cap_radius_mm, or kind = \"beta\" with beta = …"
                ),
            ));
        }
    }
    let mut builder = ChainBuilder::new(elements)
        .crossing_angle_rad(angle.to_radians())
        .wall(resolve_wall(&s.wall, "wall")?)
        .damping(resolve_damping(s)?)
        .preload(resolve_preload(s)?);
    builder = element_crossing_angles(c, keys, builder)?;
    // Indices, duplicates and values of the overrides are checked once, by the builder, under
    // their scenario keys.
    for o in &c.contact_beta {
        builder = builder.contact_beta(o.contact, o.beta);
    }
    builder.build().map_err(Error::at("chain"))
}

/// A chain's elements from `rods_mm` (Table 1 rods) or `elements` (the general form): exactly one
/// of them, not empty.
fn chain_elements(
    c: &ChainSpec,
    keys: &ChainKeys,
    warnings: &mut Vec<String>,
) -> Result<Vec<Element>, Error> {
    let model = c.model.unwrap_or_default().cell_model();
    let elements = match (&c.rods_mm, &c.elements) {
        (Some(_), Some(_)) => {
            return Err(Error::invalid(
                "chain",
                "both rods_mm and elements",
                "give either rods_mm (Table 1 rods) or elements (general form), not both",
            ))
        }
        (None, None) => {
            return Err(Error::invalid(
                "chain",
                "(no rods)",
                "give rods_mm = [80, 40, 20, …] or elements = [{ rod_mm = 40 }, …]",
            ))
        }
        (Some(rods), None) => rods
            .iter()
            .enumerate()
            .map(|(i, &l)| {
                Element::table1_rod(l, model).map_err(Error::at(format!("{}[{i}]", keys.rods_mm)))
            })
            .collect::<Result<Vec<_>, _>>()?,
        (None, Some(list)) => list
            .iter()
            .enumerate()
            .map(|(i, e)| {
                let list = keys.elements;
                let key = move |k: &str| match k {
                    "" => format!("{list}[{i}]"),
                    _ => format!("{list}[{i}].{k}"),
                };
                resolve_element(e, &key, model, warnings)
            })
            .collect::<Result<Vec<_>, _>>()?,
    };
    if elements.is_empty() {
        let key = if c.rods_mm.is_some() {
            keys.rods_mm
        } else {
            keys.elements
        };
        return Err(Error::invalid(
            key,
            "[]",
            "a chain needs at least one element",
        ));
    }
    Ok(elements)
}

/// The crossing angles given on elements (`elements[i].crossing_angle_deg`: with the element
/// above), checked and handed to the builder.
fn element_crossing_angles(
    c: &ChainSpec,
    keys: &ChainKeys,
    mut builder: ChainBuilder,
) -> Result<ChainBuilder, Error> {
    for (i, e) in c.elements.iter().flatten().enumerate() {
        let Some(a) = e.crossing_angle_deg else {
            continue;
        };
        let key = format!("{}[{i}].crossing_angle_deg", keys.elements);
        if i == 0 {
            return Err(Error::invalid(key, float(a), "the top element has no element above it; set chain.crossing_angle_deg or give the angle on the element below"));
        }
        if !(a.is_finite() && a > 0.0 && a < 180.0) {
            return Err(Error::invalid(
                key,
                float(a),
                format!("must lie {ANGLE} (0 and 180 are parallel rods: a line contact)"),
            ));
        }
        builder = builder.element_crossing_angle_rad(i, a.to_radians());
    }
    Ok(builder)
}

/// A support (`[wall]`, or a displacement actuator's tip); `key` names its table.
fn resolve_wall(w: &WallSpec, key: &str) -> Result<Wall, Error> {
    let kind = w.effective_kind();
    let given = if kind == WallKind::Beta {
        " (a support of given beta)"
    } else {
        ""
    };
    let why = format!("with {key}.kind = \"{}\"{given}", kind.name());
    let material_of = |w: &WallSpec| {
        let field = format!("{key}.material");
        material(&field, &completed(&field, w.material.as_ref())?)
    };
    if kind != WallKind::Cap {
        if let Some(r) = w.cap_radius_mm {
            return Err(not_applicable(&format!("{key}.cap_radius_mm"), r, &why));
        }
    }
    if matches!(kind, WallKind::Beta | WallKind::Free) && w.material.is_some() {
        return Err(not_applicable(&format!("{key}.material"), "…", &why));
    }
    if kind != WallKind::Beta {
        if let Some(b) = w.beta {
            return Err(Error::invalid(
                format!("{key}.beta"),
                b,
                format!("not used {why}; drop {key}.kind (or set it to \"beta\") to give the beta directly"),
            ));
        }
    }
    Ok(match kind {
        WallKind::Cap => Wall::Cap {
            material: material_of(w)?,
            radius_m: {
                let field = format!("{key}.cap_radius_mm");
                let radius_mm = positive(&field, completed(&field, w.cap_radius_mm.as_ref())?)?;
                if radius_mm > MAX_CAP_RADIUS_MM {
                    return Err(Error::invalid(
                        field,
                        format!("{radius_mm:e}"),
                        format!("at most {MAX_CAP_RADIUS_MM:e} mm (1 km): a cap this flat is a flat wall; use {key}.kind = \"flat\" (against a rod a line contact, so give {key}.beta)"),
                    ));
                }
                radius_mm * 1e-3
            },
        },
        WallKind::Flat => Wall::Flat {
            material: material_of(w)?,
        },
        WallKind::Beta => match w.beta {
            Some(b) => Wall::Beta(positive(&format!("{key}.beta"), b)?),
            None => {
                return Err(Error::invalid(
                    format!("{key}.beta"),
                    "(missing)",
                    format!("{key}.kind = \"beta\" needs beta = … [N/m^1.5]"),
                ))
            }
        },
        WallKind::Free => Wall::Free,
    })
}

/// Every key of `[excitation]` but `kind`, with its value as written (None: not given).
fn excitation_keys(x: &ExcitationSpec) -> [(&'static str, Option<String>); 19] {
    let f = |v: Option<f64>| v.map(|v| v.to_string());
    let table = |set: bool| set.then(|| "{…}".to_string());
    [
        ("drop_height_m", f(x.drop_height_m)),
        ("velocity_m_s", f(x.velocity_m_s)),
        ("striker", table(x.striker.is_some())),
        ("beta", f(x.beta)),
        (
            "profile",
            x.profile.map(|p| format!("{p:?}").to_lowercase()),
        ),
        ("peak_force_n", f(x.peak_force_n)),
        ("duration_s", f(x.duration_s)),
        ("decay", f(x.decay)),
        ("file", x.file.clone()),
        ("drive", x.drive.map(|d| d.name().to_string())),
        ("signal", x.signal.map(|d| d.name().to_string())),
        ("amplitude", f(x.amplitude)),
        ("frequency_hz", f(x.frequency_hz)),
        ("start_hz", f(x.start_hz)),
        ("end_hz", f(x.end_hz)),
        ("sweep_duration_s", f(x.sweep_duration_s)),
        ("sweep", x.sweep.map(|s| format!("{s:?}").to_lowercase())),
        ("ramp_s", f(x.ramp_s)),
        ("tip", table(x.tip.is_some())),
    ]
}

/// Refuses the first key of `[excitation]` that is given and not in `used`, as not used `why`.
pub(crate) fn refuse_excitation_keys(
    x: &ExcitationSpec,
    used: &[&str],
    why: &str,
) -> Result<(), Error> {
    match excitation_keys(x)
        .into_iter()
        .find(|(k, v)| v.is_some() && !used.contains(k))
    {
        Some((k, Some(v))) => Err(not_applicable(&format!("excitation.{k}"), v, why)),
        _ => Ok(()),
    }
}

/// A (time_s, `column`) table named by `excitation.file`.
fn excitation_table(
    x: &ExcitationSpec,
    base_dir: &Path,
    column: &str,
    needed_by: &str,
) -> Result<(Vec<f64>, Vec<f64>), Error> {
    let Some(file) = &x.file else {
        return Err(Error::invalid(
            "excitation.file",
            "(missing)",
            format!("{needed_by} needs file = \"load.csv\" (columns time_s, {column}; relative to the scenario file)"),
        ));
    };
    load_table(&base_dir.join(file), column).map_err(|e| match e {
        Error::Read { path, source } => Error::invalid(
            "excitation.file",
            format!("{file:?}"),
            format!("cannot read {}: {source}", path.display()),
        ),
        other => other,
    })
}

fn resolve_excitation(s: &Scenario, chain: &Chain, base_dir: &Path) -> Result<Excitation, Error> {
    let x = &s.excitation;
    let why = format!("with excitation.kind = \"{}\"", x.kind.name());
    match x.kind {
        ExcitationKind::Impact => {
            refuse_excitation_keys(
                x,
                &["drop_height_m", "velocity_m_s", "striker", "beta"],
                &why,
            )?;
            resolve_impact(x, chain)
        }
        ExcitationKind::Blast => {
            refuse_excitation_keys(x, &BLAST_KEYS, &why)?;
            Ok(Excitation::Blast(blast_profile_of(x, base_dir)?))
        }
        ExcitationKind::Drive => resolve_drive(x, chain, base_dir),
        ExcitationKind::Rest => {
            refuse_excitation_keys(x, &[], &format!("{why} (nothing drives the chain)"))?;
            Ok(Excitation::Rest)
        }
    }
}

/// The keys of a blast in `[excitation]` (besides `kind`).
pub(crate) const BLAST_KEYS: [&str; 5] = ["profile", "peak_force_n", "duration_s", "decay", "file"];

/// A blast's force history from `[excitation]` (a chain's or a lattice's): the Friedlander
/// keys or a table file relative to `base_dir`.
pub(crate) fn blast_profile_of(x: &ExcitationSpec, base_dir: &Path) -> Result<BlastProfile, Error> {
    let keys = BLAST_KEYS;
    Ok(match x.profile.unwrap_or_default() {
        ProfileKind::Friedlander => {
            refuse_excitation_keys(
                x,
                &keys[..4],
                "with excitation.profile = \"friedlander\" (set profile = \"table\")",
            )?;
            BlastProfile::Friedlander {
                peak_force_n: positive(
                    "excitation.peak_force_n",
                    completed("excitation.peak_force_n", x.peak_force_n.as_ref())?,
                )?,
                duration_s: positive(
                    "excitation.duration_s",
                    completed("excitation.duration_s", x.duration_s.as_ref())?,
                )?,
                decay: non_negative(
                    "excitation.decay",
                    completed("excitation.decay", x.decay.as_ref())?,
                )?,
            }
        }
        ProfileKind::Table => {
            refuse_excitation_keys(
                x,
                &["profile", "file"],
                "with excitation.profile = \"table\" (the table file gives the force)",
            )?;
            let (t, f) = excitation_table(x, base_dir, "force_n", "profile = \"table\"")?;
            BlastProfile::table(t, f)?
        }
    })
}

fn resolve_impact(x: &ExcitationSpec, chain: &Chain) -> Result<Excitation, Error> {
    let striker = striker_of(x.drop_height_m, x.velocity_m_s, x.striker.as_ref(), x.beta)?;
    // Fails early (as a usage error) when the striker cannot touch the top element.
    striker
        .contact_beta(chain)
        .map_err(Error::at("excitation.striker"))?;
    Ok(Excitation::Impact(striker))
}

/// The striker of a completed `[excitation]` (a chain's or a lattice's): its speed from
/// `velocity_m_s` or `drop_height_m` (not both), its sphere, and a given contact β.
pub(crate) fn striker_of(
    drop_height_m: Option<f64>,
    velocity_m_s: Option<f64>,
    striker: Option<&super::StrikerSpec>,
    beta: Option<f64>,
) -> Result<Striker, Error> {
    let velocity = match (drop_height_m, velocity_m_s) {
        (Some(h), Some(v)) => {
            return Err(Error::invalid(
                "excitation.velocity_m_s",
                v,
                format!("give either drop_height_m (here {h}) or velocity_m_s, not both"),
            ))
        }
        (_, Some(v)) => positive("excitation.velocity_m_s", v)?,
        (h, None) => {
            let field = "excitation.drop_height_m";
            woodpile::velocity_from_drop_height(positive(field, completed(field, h.as_ref())?)?)
        }
    };
    let st = completed("excitation.striker", striker)?;
    let field = "excitation.striker.diameter_mm";
    let diameter = positive(field, completed(field, st.diameter_mm.as_ref())?)?;
    let field = "excitation.striker.material";
    let mat = material(field, &completed(field, st.material.as_ref())?)?;
    let beta = beta.map(|b| positive("excitation.beta", b)).transpose()?;
    Ok(Striker {
        diameter_m: diameter * 1e-3,
        material: mat,
        velocity_m_s: velocity,
        beta_override: beta,
    })
}

/// The keys of a drive in `[excitation]` (besides `kind`).
pub(crate) const DRIVE_KEYS: [&str; 11] = [
    "drive",
    "signal",
    "ramp_s",
    "tip",
    "amplitude",
    "start_hz",
    "end_hz",
    "sweep_duration_s",
    "sweep",
    "frequency_hz",
    "file",
];

/// A drive's signal from `[excitation]` (a chain's or a lattice's): harmonic, chirp or a table
/// file relative to `base_dir`.
pub(crate) fn signal_of(x: &ExcitationSpec, base_dir: &Path) -> Result<Signal, Error> {
    const COMMON: [&str; 4] = ["drive", "signal", "ramp_s", "tip"];
    const CHIRP: [&str; 5] = [
        "amplitude",
        "start_hz",
        "end_hz",
        "sweep_duration_s",
        "sweep",
    ];
    let Some(kind) = x.signal else {
        return Err(Error::invalid(
            "excitation.signal",
            "(missing)",
            "a drive needs signal = \"harmonic\", \"chirp\" or \"table\"",
        ));
    };
    let why = format!("with excitation.signal = \"{}\"", kind.name());
    let need = |key: &str, v: Option<f64>| {
        v.ok_or_else(|| {
            Error::invalid(
                format!("excitation.{key}"),
                "(missing)",
                format!("signal = \"{}\" needs {key} = …", kind.name()),
            )
        })
    };
    let signal = match kind {
        SignalKind::Harmonic => {
            refuse_excitation_keys(
                x,
                &[&COMMON[..], &["amplitude", "frequency_hz"]].concat(),
                &why,
            )?;
            Signal::Harmonic {
                amplitude: need("amplitude", x.amplitude)?,
                frequency_hz: need("frequency_hz", x.frequency_hz)?,
            }
        }
        SignalKind::Chirp => {
            refuse_excitation_keys(x, &[&COMMON[..], &CHIRP].concat(), &why)?;
            Signal::Chirp {
                amplitude: need("amplitude", x.amplitude)?,
                start_hz: need("start_hz", x.start_hz)?,
                end_hz: need("end_hz", x.end_hz)?,
                duration_s: need("sweep_duration_s", x.sweep_duration_s)?,
                sweep: x.sweep.unwrap_or_default().sweep(),
            }
        }
        SignalKind::Table => {
            refuse_excitation_keys(x, &[&COMMON[..], &["file"]].concat(), &why)?;
            let (times_s, values) = excitation_table(x, base_dir, "value", "signal = \"table\"")?;
            Signal::Table { times_s, values }
        }
    };
    Ok(signal)
}

fn resolve_drive(x: &ExcitationSpec, chain: &Chain, base_dir: &Path) -> Result<Excitation, Error> {
    refuse_excitation_keys(x, &DRIVE_KEYS, "with excitation.kind = \"drive\"")?;
    let signal = signal_of(x, base_dir)?;
    let quantity = drive_quantity_of(x)?;
    if let DriveQuantity::Displacement { tip } = &quantity {
        // Fails early (as a usage error) when the tip cannot touch the top element.
        tip.beta_against(chain.top_surface(), &chain.elements()[0].material)
            .map_err(Error::at("excitation.tip"))?;
    }
    let drive = Drive {
        quantity,
        ramp_s: completed("excitation.ramp_s", x.ramp_s.as_ref())?,
        signal,
    };
    drive.validate()?;
    Ok(Excitation::Drive(drive))
}

/// What a drive prescribes (a chain's or a lattice's, completed `[excitation]`): a force, or a
/// displacement through `excitation.tip` (keys as in `[wall]`, not free).
pub(crate) fn drive_quantity_of(x: &ExcitationSpec) -> Result<DriveQuantity, Error> {
    Ok(match (x.drive.unwrap_or_default(), &x.tip) {
        (DriveKind::Force, Some(_)) => {
            return Err(not_applicable(
                "excitation.tip",
                "{…}",
                "with excitation.drive = \"force\" (the tip is a displacement actuator's)",
            ))
        }
        (DriveKind::Force, None) => DriveQuantity::Force,
        (DriveKind::Displacement, tip) => {
            let tip = resolve_wall(
                &completed("excitation.tip", tip.as_ref())?,
                "excitation.tip",
            )?;
            if tip == Wall::Free {
                return Err(Error::invalid(
                    "excitation.tip.kind",
                    "\"free\"",
                    "a displacement actuator pushes through its tip: give kind = \"cap\", \"flat\" or \"beta\"",
                ));
            }
            DriveQuantity::Displacement { tip }
        }
    })
}

/// One contact's law; `key` names its table (`damping`, `damping.striker`, `damping.wall`).
fn contact_law(
    key: &str,
    law: ContactLaw,
    restitution: Option<f64>,
    viscous_time_s: Option<f64>,
) -> Result<ContactDamping, Error> {
    let why = format!("with {key}.contact = \"{}\"", law.name());
    let need = |k: &str, v: Option<f64>| {
        v.ok_or_else(|| {
            Error::invalid(
                format!("{key}.{k}"),
                "(missing)",
                format!("{key}.contact = \"{}\" needs {k} = …", law.name()),
            )
        })
    };
    let refuse = |k: &str, v: Option<f64>| match v {
        Some(v) => Err(not_applicable(&format!("{key}.{k}"), float(v), &why)),
        None => Ok(()),
    };
    if matches!(law, ContactLaw::None | ContactLaw::Viscoelastic) {
        refuse("restitution", restitution)?;
    }
    if law != ContactLaw::Viscoelastic {
        refuse("viscous_time_s", viscous_time_s)?;
    }
    Ok(match law {
        ContactLaw::None => ContactDamping::None,
        ContactLaw::Restitution => ContactDamping::Restitution {
            coefficient: need("restitution", restitution)?,
        },
        ContactLaw::HuntCrossley => ContactDamping::HuntCrossley {
            restitution: need("restitution", restitution)?,
        },
        ContactLaw::Viscoelastic => ContactDamping::Viscoelastic {
            time_s: need("viscous_time_s", viscous_time_s)?,
        },
    })
}

/// `[damping]` (values are checked against the chain by the chain builder, under these keys).
fn resolve_damping(s: &Scenario) -> Result<Damping, Error> {
    let Some(d) = &s.damping else {
        return Ok(Damping::default());
    };
    if let Some(z) = d.modal_ratio {
        let why = "in a chain (it damps the modes of a lattice's rods; a chain's rods are damped by resonator_ratio)";
        return Err(not_applicable("damping.modal_ratio", float(z), why));
    }
    let x = &s.excitation;
    let has_striker = x.kind == ExcitationKind::Impact
        || (x.kind == ExcitationKind::Drive && x.drive == Some(DriveKind::Displacement));
    let has_wall = s.wall.effective_kind() != WallKind::Free;
    damping_of(d, has_striker, has_wall, x.kind == ExcitationKind::Impact)
}

/// A completed `[damping]` (a chain's or a lattice's; `modal_ratio` is left to the caller):
/// the contact laws, the striker's and wall's overrides (refused where there is no striker or
/// wall), the Hunt–Crossley impact speed (needed when nothing strikes, refused without a
/// Hunt–Crossley contact).
pub(crate) fn damping_of(
    d: &DampingSpec,
    has_striker: bool,
    has_wall: bool,
    struck: bool,
) -> Result<Damping, Error> {
    let law = completed("damping.contact", d.contact.as_ref())?;
    let contacts = contact_law("damping", law, d.restitution, d.viscous_time_s)?;
    let mut overrides = [None, None];
    for (slot, (name, spec, applies, why)) in [
        (
            "striker",
            &d.striker,
            has_striker,
            "without a striker or a displacement actuator",
        ),
        ("wall", &d.wall, has_wall, "with wall.kind = \"free\""),
    ]
    .into_iter()
    .enumerate()
    {
        let Some(c) = spec else { continue };
        let key = format!("damping.{name}");
        if !applies {
            return Err(not_applicable(&key, "{…}", why));
        }
        let law = completed(&format!("{key}.contact"), c.contact.as_ref())?;
        overrides[slot] = Some(contact_law(&key, law, c.restitution, c.viscous_time_s)?);
    }
    // Whether a contact is Hunt–Crossley (lossy: with e < 1, which needs v_in).
    let hunt = |lossy: bool| {
        let is = |l: &ContactDamping| match l {
            ContactDamping::HuntCrossley { restitution } => !lossy || *restitution < 1.0,
            _ => false,
        };
        is(&contacts) || overrides.iter().flatten().any(is)
    };
    match d.impact_speed_m_s {
        Some(v) if !hunt(false) => {
            let why = "without a hunt-crossley contact (it is that law's v_in)";
            return Err(not_applicable("damping.impact_speed_m_s", float(v), why));
        }
        // The core's rule (docs/physics.md §14), checked here to fail before the run.
        None if hunt(true) && !struck => {
            return Err(Error::invalid(
                "damping.impact_speed_m_s",
                "(missing)",
                "a hunt-crossley contact needs the impact speed v_in when there is no striker (whose speed is the default)",
            ));
        }
        _ => {}
    }
    Ok(Damping {
        contacts,
        striker: overrides[0],
        wall: overrides[1],
        allow_pull: completed("damping.allow_pull", d.allow_pull.as_ref())?,
        resonator_ratio: completed("damping.resonator_ratio", d.resonator_ratio.as_ref())?,
        resonator_overrides: d
            .resonators
            .iter()
            .map(|r| ResonatorDamping {
                element: r.element,
                resonator: r.resonator,
                ratio: r.ratio,
            })
            .collect(),
        on_site_time_s: d.on_site_time_s,
        impact_speed_m_s: d.impact_speed_m_s,
    })
}

/// `[preload]` (values are checked by the chain builder, under these keys).
fn resolve_preload(s: &Scenario) -> Result<Preload, Error> {
    let Some(p) = &s.preload else {
        return Ok(Preload::default());
    };
    Ok(Preload {
        force_n: completed("preload.force_n", p.force_n.as_ref())?,
        gravity_m_s2: completed("preload.gravity_m_s2", p.gravity_m_s2.as_ref())?,
    })
}

/// `[run]`. Positivity is checked here (naming NaN as the file writes it); how the step, the
/// sampling and the duration relate is checked once, by [`RunSettings::validate`].
fn resolve_run(s: &Scenario) -> Result<RunSettings, Error> {
    resolve_run_spec(&s.run)
}

/// `[run]` (every default filled in, or a peak tolerance given) as the core's settings.
pub(crate) fn resolve_run_spec(r: &super::RunSpec) -> Result<RunSettings, Error> {
    let get = |field: &str, v: Option<f64>| positive(field, completed(field, v.as_ref())?);
    let duration = get("run.duration_s", r.duration_s)?;
    let sample = get("run.sample_interval_s", r.sample_interval_s)?;
    let method = if let Some(tolerance) = r.peak_tolerance {
        let why = "with run.peak_tolerance (woodpile chooses the integrator for it)";
        if let Some(i) = r.integrator {
            return Err(not_applicable("run.integrator", i.name(), why));
        }
        for (key, v) in [
            ("run.time_step_s", r.time_step_s),
            ("run.rtol", r.rtol),
            ("run.atol", r.atol),
        ] {
            if let Some(v) = v {
                return Err(not_applicable(key, float(v), why));
            }
        }
        Method::for_peak_tolerance(tolerance)?
    } else {
        match completed("run.integrator", r.integrator.as_ref())? {
            IntegratorKind::Rk4 => {
                let why = "with run.integrator = \"rk4\" (a fixed step; set integrator = \"dopri5\" for tolerances)";
                for (key, v) in [("run.rtol", r.rtol), ("run.atol", r.atol)] {
                    if let Some(v) = v {
                        return Err(not_applicable(key, v, why));
                    }
                }
                Method::Rk4 {
                    time_step_s: get("run.time_step_s", r.time_step_s)?,
                }
            }
            IntegratorKind::Dopri5 => {
                if let Some(v) = r.time_step_s {
                    return Err(not_applicable(
                        "run.time_step_s",
                        v,
                        "with run.integrator = \"dopri5\" (adaptive; set rtol/atol)",
                    ));
                }
                Method::Dopri5 {
                    rtol: get("run.rtol", r.rtol)?,
                    atol: get("run.atol", r.atol)?,
                }
            }
        }
    };
    let settings = RunSettings {
        duration_s: duration,
        method,
        sample_interval_s: sample,
    };
    settings.validate()?;
    Ok(settings)
}
