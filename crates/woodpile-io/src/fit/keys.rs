//! What a fitted parameter sets: a float key of the scenario (dotted, list entries indexed:
//! `chain.elements[2].diameter_mm`), a multiplicative scale of the contact coefficients β of
//! one type of contact, written into the scenario as explicit β (so that the fitted scenario runs
//! as it was fitted), or a scale of one material's Young's modulus, written as that material's
//! constants inline wherever the scenario uses it.

use crate::error::Error;
use crate::scenario::{
    key, material_of, resolve, CustomMaterial, ElementKind, ExcitationKind, KeyType, MaterialSpec,
    Scenario, WallKind,
};
use std::path::Path;
use toml::Value;
use woodpile::defaults;

/// The prefix of the contact scales: `contact_beta_scale.striker`, `.inner`, `.wall`.
pub const SCALE_PREFIX: &str = "contact_beta_scale";

/// The prefix of the modulus scales: `youngs_modulus_scale.MATERIAL` (a preset name or the
/// `name` of an inline material).
pub const MODULUS_PREFIX: &str = "youngs_modulus_scale";

/// Which contacts a scale multiplies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    /// The striker–element 1 contact (`excitation.beta`).
    Striker,
    /// Every contact between two elements (`chain.contact_beta`, contacts 1..N−1).
    Inner,
    /// The last element on the wall (`wall.beta`, or its `chain.contact_beta` entry).
    Wall,
}

/// What one parameter sets.
#[derive(Debug, Clone, PartialEq)]
pub enum Target {
    /// A float key of the scenario, by its path (`[name, index]` segments) and the keys it
    /// replaces.
    Key {
        /// The key as written.
        name: String,
        /// Its path: a table key and, for a list entry, the entry's index.
        path: Vec<(String, Option<usize>)>,
        /// Keys it replaces (`excitation.drop_height_m` for `excitation.velocity_m_s`).
        alternatives: Vec<String>,
    },
    /// A scale of a type of contact's β.
    Scale(Scale),
    /// A scale of the Young's modulus of the material of this name, wherever the scenario
    /// uses it (elements, striker, wall, an actuator's tip): their cells and contacts follow.
    Modulus(String),
}

impl Target {
    /// Parses the `key` of a parameter entry; `field` names it in errors.
    pub fn parse(name: &str, field: &str) -> Result<Self, Error> {
        if let Some(rest) = name
            .strip_prefix(SCALE_PREFIX)
            .and_then(|r| r.strip_prefix('.'))
        {
            let scale = match rest {
                "striker" => Scale::Striker,
                "inner" => Scale::Inner,
                "wall" => Scale::Wall,
                _ => {
                    return Err(Error::invalid(
                        field,
                        name,
                        format!("{SCALE_PREFIX} applies to striker, inner or wall"),
                    ))
                }
            };
            return Ok(Target::Scale(scale));
        }
        if let Some(material) = name
            .strip_prefix(MODULUS_PREFIX)
            .and_then(|r| r.strip_prefix('.'))
        {
            if material.is_empty() {
                return Err(Error::invalid(
                    field,
                    name,
                    format!("write {MODULUS_PREFIX}.MATERIAL, a preset name or an inline material's name"),
                ));
            }
            return Ok(Target::Modulus(material.to_string()));
        }
        let mut path = Vec::new();
        for part in name.split('.') {
            let (key, index) = match part.split_once('[') {
                Some((k, rest)) => {
                    let i = rest
                        .strip_suffix(']')
                        .and_then(|i| i.parse::<usize>().ok())
                        .ok_or_else(|| {
                            Error::invalid(
                                field,
                                name,
                                "a list entry is written LIST[INDEX], from 0",
                            )
                        })?;
                    (k, Some(i))
                }
                None => (part, None),
            };
            path.push((key.to_string(), index));
        }
        let generic: Vec<String> = path
            .iter()
            .map(|(k, i)| {
                if i.is_some() {
                    format!("{k}[]")
                } else {
                    k.clone()
                }
            })
            .collect();
        let Some(k) = key(&generic.join(".")) else {
            return Err(Error::invalid(
                field,
                name,
                format!("not a key of the scenario file, nor {SCALE_PREFIX}.striker|inner|wall or {MODULUS_PREFIX}.MATERIAL"),
            ));
        };
        if k.ty != KeyType::Float {
            return Err(Error::invalid(
                field,
                name,
                format!(
                    "is a {} key, not a number: only float keys (and {SCALE_PREFIX}.*) can be fitted",
                    k.ty.name()
                ),
            ));
        }
        Ok(Target::Key {
            name: name.to_string(),
            path,
            alternatives: k.alternatives.iter().map(|a| a.to_string()).collect(),
        })
    }

    /// Its value in `scenario` (defaults written out); a scale is 1.
    pub fn current(&self, scenario: &Scenario) -> Option<f64> {
        match self {
            Target::Scale(_) | Target::Modulus(_) => Some(1.0),
            Target::Key { path, .. } => {
                let v = Value::try_from(scenario.complete()).ok()?;
                let mut at = &v;
                for (k, i) in path {
                    at = at.get(k)?;
                    if let Some(i) = i {
                        at = at.get(*i)?;
                    }
                }
                at.as_float().or_else(|| at.as_integer().map(|i| i as f64))
            }
        }
    }
}

/// `scenario` with `values` applied to `targets` in order, the scales last (as explicit β of the
/// scenario with the keys applied). `dir` is where the scenario's own files are.
pub(super) fn apply(
    scenario: &Scenario,
    dir: &Path,
    targets: &[Target],
    values: &[f64],
) -> Result<Scenario, Error> {
    let mut doc =
        Value::try_from(scenario).map_err(|e| Error::invalid("scenario", "", e.to_string()))?;
    for (target, &v) in targets.iter().zip(values) {
        if let Target::Key {
            name,
            path,
            alternatives,
        } = target
        {
            set(&mut doc, path, v, name)?;
            for a in alternatives {
                remove(&mut doc, a);
            }
        }
    }
    let moduli: Vec<(&str, f64)> = targets
        .iter()
        .zip(values)
        .filter_map(|(t, &v)| match t {
            Target::Modulus(m) => Some((m.as_str(), v)),
            _ => None,
        })
        .collect();
    if !moduli.is_empty() {
        let mut typed = from_doc(&doc, "scenario")?;
        for (material, s) in moduli {
            scale_modulus(&mut typed, material, s)?;
        }
        doc = Value::try_from(&typed).map_err(|e| Error::invalid("scenario", "", e.to_string()))?;
    }
    let scales: Vec<(Scale, f64)> = targets
        .iter()
        .zip(values)
        .filter_map(|(t, &v)| match t {
            Target::Scale(s) => Some((*s, v)),
            _ => None,
        })
        .collect();
    if !scales.is_empty() {
        let keyed = from_doc(&doc, "scenario")?;
        let r = resolve(&keyed, dir)?;
        for (scale, s) in scales {
            scale_beta(&mut doc, scale, s, &r)?;
        }
    }
    from_doc(&doc, "scenario")
}

fn from_doc(doc: &Value, what: &str) -> Result<Scenario, Error> {
    doc.clone()
        .try_into()
        .map_err(|e: toml::de::Error| Error::invalid(what, "", e.to_string()))
}

/// Sets the float at `path` (creating missing tables; a list entry must exist).
fn set(doc: &mut Value, path: &[(String, Option<usize>)], v: f64, name: &str) -> Result<(), Error> {
    let mut at = doc;
    for (n, (k, i)) in path.iter().enumerate() {
        let table = at
            .as_table_mut()
            .ok_or_else(|| Error::invalid(name, v, format!("`{k}` is not inside a table")))?;
        let last = n + 1 == path.len() && i.is_none();
        if last {
            table.insert(k.clone(), Value::Float(v));
            return Ok(());
        }
        if i.is_some() && !table.contains_key(k) {
            // No list to index: say so (and, for a chain of rods, which list there is).
            let rods = table.get("rods_mm").and_then(Value::as_array).map(Vec::len);
            let reason = match (k.as_str(), rods) {
                ("elements", Some(n)) => format!("the chain is given as rods_mm ({n} Table 1 rods), which has no `elements` to index: to fit an element's keys, write the chain as `elements` of kind = \"rod\""),
                _ => format!("the scenario has no `{k}` list to index"),
            };
            return Err(Error::invalid(name, v, reason));
        }
        at = table
            .entry(k.clone())
            .or_insert_with(|| Value::Table(Default::default()));
        if let Some(i) = i {
            let len = at.as_array().map_or(0, Vec::len);
            at = at.get_mut(*i).ok_or_else(|| {
                Error::invalid(
                    name,
                    v,
                    format!("the scenario's `{k}` has {len} entries (indices 0..{len})"),
                )
            })?;
        }
    }
    Ok(())
}

/// Removes the dotted key `name` where present.
fn remove(doc: &mut Value, name: &str) {
    let parts: Vec<&str> = name.split('.').collect();
    let mut at = doc;
    for k in &parts[..parts.len() - 1] {
        match at.get_mut(*k) {
            Some(next) => at = next,
            None => return,
        }
    }
    if let Some(t) = at.as_table_mut() {
        t.remove(parts[parts.len() - 1]);
    }
}

/// Writes s × β (β as the scenario `r` has it) into the document for one type of contact.
fn scale_beta(
    doc: &mut Value,
    scale: Scale,
    s: f64,
    r: &crate::scenario::Resolved,
) -> Result<(), Error> {
    let key = |what: &str| format!("{SCALE_PREFIX}.{what}");
    let table = doc.as_table_mut().expect("a scenario is a table");
    let n = r.chain.len();
    match scale {
        Scale::Striker => {
            let woodpile::Excitation::Impact(striker) = &r.excitation else {
                return Err(Error::invalid(
                    key("striker"),
                    s,
                    "the scenario's excitation has no striker",
                ));
            };
            let beta = striker
                .contact_beta(&r.chain)
                .map_err(Error::at(key("striker")))?;
            let excitation = table
                .entry("excitation")
                .or_insert_with(|| Value::Table(Default::default()));
            if let Some(t) = excitation.as_table_mut() {
                t.insert("beta".into(), Value::Float(s * beta));
            }
        }
        Scale::Inner => {
            let mut entries = contact_entries(table, |c| c >= n);
            for (i, beta) in r.chain.inner_betas().iter().enumerate() {
                entries.push(beta_entry(i + 1, s * beta));
            }
            table_chain(table).insert("contact_beta".into(), Value::Array(entries));
        }
        Scale::Wall => {
            let beta = r.chain.wall_beta().ok_or_else(|| {
                Error::invalid(
                    key("wall"),
                    s,
                    "the scenario's chain has no wall (wall.kind = \"free\")",
                )
            })?;
            let mut entries = contact_entries(table, |c| c < n);
            let had_entry = entries.len() < contact_entries(table, |_| true).len();
            if had_entry {
                entries.push(beta_entry(n, s * beta));
                table_chain(table).insert("contact_beta".into(), Value::Array(entries));
            } else {
                let mut wall = toml::Table::new();
                wall.insert("kind".into(), Value::String("beta".into()));
                wall.insert("beta".into(), Value::Float(s * beta));
                table.insert("wall".into(), Value::Table(wall));
            }
        }
    }
    Ok(())
}

/// Multiplies the Young's modulus of every body of `scenario` made of `material` by `s`, writing
/// that material's constants inline there. Table 1 rods cannot follow (their cells are tabulated
/// for fused quartz), so scaling their material is refused, as is a name no body uses.
fn scale_modulus(scenario: &mut Scenario, material: &str, s: f64) -> Result<(), Error> {
    let key = format!("{MODULUS_PREFIX}.{material}");
    let chain = &mut scenario.chain;
    let catalogue = chain.rods_mm.as_ref().is_some_and(|r| !r.is_empty())
        || chain
            .elements
            .iter()
            .flatten()
            .any(|e| e.effective_kind() == ElementKind::Catalogue);
    if catalogue && material == defaults::ELEMENT_MATERIAL {
        return Err(Error::invalid(
            key,
            s,
            "the chain has Table 1 rods, whose cells are tabulated for the paper's fused quartz: give the rods as `kind = \"rod\"` elements (their cells follow the modulus)",
        ));
    }
    let mut slots: Vec<(String, &mut Option<MaterialSpec>, &str)> = Vec::new();
    for (i, e) in chain.elements.iter_mut().flatten().enumerate() {
        if e.effective_kind() != ElementKind::Catalogue {
            let field = format!("chain.elements[{i}].material");
            slots.push((field, &mut e.material, defaults::ELEMENT_MATERIAL));
        }
    }
    let x = &mut scenario.excitation;
    if x.kind == ExcitationKind::Impact {
        let striker = x.striker.get_or_insert_with(Default::default);
        slots.push((
            "excitation.striker.material".into(),
            &mut striker.material,
            defaults::STRIKER_MATERIAL,
        ));
    }
    if let Some(tip) = x
        .tip
        .as_mut()
        .filter(|t| t.effective_kind() != WallKind::Beta)
    {
        slots.push((
            "excitation.tip.material".into(),
            &mut tip.material,
            defaults::WALL_MATERIAL,
        ));
    }
    let wall = &mut scenario.wall;
    if matches!(wall.effective_kind(), WallKind::Cap | WallKind::Flat) {
        slots.push((
            "wall.material".into(),
            &mut wall.material,
            defaults::WALL_MATERIAL,
        ));
    }
    let (mut changed, mut others) = (0usize, Vec::new());
    for (field, slot, default) in slots {
        let spec = slot.clone().unwrap_or(MaterialSpec::preset(default));
        let m = material_of(&field, &spec)?;
        if m.name == material {
            *slot = Some(MaterialSpec::Custom(CustomMaterial {
                name: m.name,
                youngs_modulus_pa: s * m.youngs_modulus_pa,
                poisson_ratio: m.poisson_ratio,
                density_kg_m3: m.density_kg_m3,
            }));
            changed += 1;
        } else if !others.contains(&m.name) {
            others.push(m.name);
        }
    }
    if changed > 0 {
        return Ok(());
    }
    Err(Error::invalid(
        key,
        s,
        format!(
            "no body of the scenario is made of `{material}`; its materials: {}",
            others.join(", ")
        ),
    ))
}

fn table_chain(table: &mut toml::Table) -> &mut toml::Table {
    table
        .entry("chain")
        .or_insert_with(|| Value::Table(Default::default()))
        .as_table_mut()
        .expect("[chain] is a table")
}

/// The `chain.contact_beta` entries whose contact number satisfies `keep`.
fn contact_entries(table: &toml::Table, keep: impl Fn(usize) -> bool) -> Vec<Value> {
    table
        .get("chain")
        .and_then(|c| c.get("contact_beta"))
        .and_then(Value::as_array)
        .map(|a| {
            a.iter()
                .filter(|e| {
                    e.get("contact")
                        .and_then(Value::as_integer)
                        .is_some_and(|c| keep(c as usize))
                })
                .cloned()
                .collect()
        })
        .unwrap_or_default()
}

fn beta_entry(contact: usize, beta: f64) -> Value {
    let mut t = toml::Table::new();
    t.insert("contact".into(), Value::Integer(contact as i64));
    t.insert("beta".into(), Value::Float(beta));
    Value::Table(t)
}
