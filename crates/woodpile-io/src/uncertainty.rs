//! `[uncertainty]`: the manufacturing scatter of a scenario, as per-parameter distributions.
//!
//! ```toml
//! [uncertainty]
//! samples = 32
//! seed = 0
//! rod_length_mm = { sd = 0.2 }              # each rod independently
//! crossing_angle_deg = { sd = 2.0 }         # each contact between rods
//! youngs_modulus = { relative_sd = 0.02 }   # the elements' material, one draw per sample
//! impact_velocity_m_s = { uniform = [1.8, 2.2] }
//! restitution = { uniform = [0.6, 0.8] }    # damping parameters
//! ```
//!
//! A distribution is exactly one of `sd` (normal about the nominal value, in the parameter's
//! unit), `relative_sd` (normal about the nominal value, a fraction of it) or `uniform = [a, b]`
//! (the nominal value is not used). [`UncertaintySpec::check`] refuses what means nothing, naming
//! the key: a negative or non-finite sd, an empty or reversed range, `samples = 0`; an unknown
//! parameter or distribution is refused when the file is read (its key is named by the parser).

use crate::error::Error;

pub use crate::scenario::scatter::{
    Distribution, DistributionSpec, Parameter, Uncertainty, UncertaintySpec,
};

/// One sample of a scenario: its drawn values and its complete scenario (no `[uncertainty]`).
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    /// The drawn values, one per [`Samples::columns`].
    pub values: Vec<f64>,
    /// The scenario with these values written in, every default written out.
    pub scenario: crate::scenario::Scenario,
}

/// The samples of a scenario under its `[uncertainty]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Samples {
    /// The name of each drawn value: `rod_length_mm[i]` (element i), `crossing_angle_deg[i]`
    /// (contact i, between elements i and i + 1), `youngs_modulus`, `impact_velocity_m_s`,
    /// `restitution`, ….
    pub columns: Vec<String>,
    /// Sample k is row k of the Sobol' points.
    pub samples: Vec<Sample>,
    /// The scenario key each column's value is written into (`chain.elements[0].length_mm`,
    /// `excitation.velocity_m_s`, `damping.restitution`; `.material` for the modulus, written
    /// into every element's material).
    pub writes: Vec<String>,
}

/// Where a drawn value goes in the scenario.
#[derive(Debug, Clone, Copy)]
enum Target {
    Length(usize),
    Angle(usize),
    Modulus,
    Velocity,
    Damping(Parameter),
}

/// The `samples` samples of `scenario` under `u` (its `[uncertainty]`, checked): the chain is
/// written as `chain.elements` (a `rods_mm` chain as its Table 1 elements, the same model), each
/// drawn value written into the key it scatters. Errors name the `[uncertainty]` key that does
/// not apply to this scenario, and why.
pub fn samples(scenario: &crate::scenario::Scenario, u: &Uncertainty) -> Result<Samples, Error> {
    samples_at(scenario, u, |dimensions| {
        woodpile::uncertainty::unit_cube(u.samples, dimensions, u.seed)
            .map_err(|e| Error::invalid("uncertainty", dimensions, e.to_string()))
    })
}

/// The samples of `scenario` under `u` at the unit-cube points `points(D)` returns for its D
/// drawn values (one row per sample, D coordinates each, strictly inside (0, 1)), e.g. a
/// Saltelli design (`crate::sensitivity`). [`samples`] is this at u's Sobol' points.
pub fn samples_at(
    scenario: &crate::scenario::Scenario,
    u: &Uncertainty,
    points: impl FnOnce(usize) -> Result<Vec<Vec<f64>>, Error>,
) -> Result<Samples, Error> {
    use crate::scenario::{ElementSpec, ExcitationKind};
    if u.parameters.is_empty() {
        return Err(Error::invalid(
            "uncertainty",
            "{}",
            "at least one scattered parameter (e.g. rod_length_mm = { sd = 0.2 }): with none, every sample is the nominal scenario, drawn again and again",
        ));
    }
    let mut base = scenario.complete();
    base.uncertainty = None;
    if let Some(rods) = base.chain.rods_mm.take() {
        base.chain.elements = Some(
            rods.into_iter()
                .map(|l| ElementSpec {
                    rod_mm: Some(l),
                    model: base.chain.model,
                    ..ElementSpec::default()
                })
                .collect(),
        );
    }
    let n = base.chain.elements.as_ref().map_or(0, Vec::len);
    let mut columns = Vec::new();
    let mut targets = Vec::new();
    for &(p, dist) in &u.parameters {
        let key = format!("uncertainty.{}", p.key());
        match p {
            Parameter::RodLength => {
                for i in 0..n {
                    columns.push(format!("rod_length_mm[{}]", i + 1));
                    targets.push((Target::Length(i), dist, key.clone()));
                }
            }
            Parameter::CrossingAngle => {
                for i in 1..n {
                    columns.push(format!("crossing_angle_deg[{i}]"));
                    targets.push((Target::Angle(i), dist, key.clone()));
                }
            }
            Parameter::YoungsModulus => {
                columns.push(p.key().into());
                targets.push((Target::Modulus, dist, key));
            }
            Parameter::ImpactVelocity => {
                if base.excitation.kind != ExcitationKind::Impact {
                    return Err(Error::invalid(
                        key,
                        "{…}",
                        "applies to an impact (excitation.kind = \"impact\")",
                    ));
                }
                columns.push(p.key().into());
                targets.push((Target::Velocity, dist, key));
            }
            _ => {
                if base.damping.is_none() {
                    return Err(Error::invalid(
                        key,
                        "{…}",
                        "scatters a [damping] key: give the scenario a [damping] table",
                    ));
                }
                columns.push(p.key().into());
                targets.push((Target::Damping(p), dist, key));
            }
        }
    }
    let points = points(targets.len())?;
    if let Some(row) = points.iter().find(|row| row.len() != targets.len()) {
        return Err(Error::invalid(
            "uncertainty",
            row.len(),
            format!(
                "{} coordinates per point, one per drawn value",
                targets.len()
            ),
        ));
    }
    let samples = draw(&base, &targets, &points)?;
    let writes = targets.iter().map(|(t, _, _)| t.writes()).collect();
    Ok(Samples {
        columns,
        samples,
        writes,
    })
}

/// Each row of `points` written into a copy of `base` at `targets`; a stop request ends the
/// drawing (many rows take seconds to build).
fn draw(
    base: &crate::scenario::Scenario,
    targets: &[(Target, Distribution, String)],
    points: &[Vec<f64>],
) -> Result<Vec<Sample>, Error> {
    points
        .iter()
        .map(|row| {
            if woodpile::interrupt::requested() {
                return Err(Error::Model(woodpile::Error::Interrupted { time_s: 0.0 }));
            }
            let mut s = base.clone();
            let values = targets
                .iter()
                .zip(row)
                .map(|((target, dist, key), &x)| apply(&mut s, *target, *dist, key, x))
                .collect::<Result<Vec<f64>, Error>>()?;
            Ok(Sample {
                values,
                scenario: s,
            })
        })
        .collect()
}

impl Target {
    /// The scenario key a drawn value is written into (see [`Samples::writes`]).
    fn writes(&self) -> String {
        match self {
            Target::Length(i) => format!("chain.elements[{i}].length_mm"),
            Target::Angle(i) => format!("chain.elements[{i}].crossing_angle_deg"),
            Target::Modulus => ".material".into(),
            Target::Velocity => "excitation.velocity_m_s".into(),
            Target::Damping(p) => format!("damping.{}", p.key()),
        }
    }
}

/// Resolves every sample's scenario (relative paths from `base_dir`), stopping at a stop
/// request. A sample refused for a key a drawn value was written into is named by the
/// `[uncertainty]` key that drew it, its column and row of `samples.csv`, and the value: the
/// distribution, not the scenario, is what to change (`rod_length_mm = { sd = 1e6 }` draws rods
/// of negative length).
pub fn resolve_samples(
    s: &Samples,
    base_dir: &std::path::Path,
) -> Result<Vec<crate::scenario::Resolved>, Error> {
    s.samples
        .iter()
        .enumerate()
        .map(|(k, sample)| {
            if woodpile::interrupt::requested() {
                return Err(Error::Model(woodpile::Error::Interrupted { time_s: 0.0 }));
            }
            crate::scenario::resolve(&sample.scenario, base_dir).map_err(|e| s.blame(k, e))
        })
        .collect()
}

/// The elements of `scenario`'s chain (its rods or elements; 1 when it names none).
pub fn chain_elements(scenario: &crate::scenario::Scenario) -> usize {
    let chain = scenario.complete().chain;
    chain
        .rods_mm
        .as_ref()
        .map(Vec::len)
        .or(chain.elements.as_ref().map(Vec::len))
        .unwrap_or(1)
        .max(1)
}

/// Refuses `samples` runs of `scenario` above the study limit unless `allow`
/// ([`crate::limits::check_study`]: every sample's scenario is built before the runs); `field`
/// names the number of samples as the front end spells it.
pub fn check_size(
    scenario: &crate::scenario::Scenario,
    samples: usize,
    field: &str,
    allow: bool,
) -> Result<(), Error> {
    let elements = chain_elements(scenario);
    crate::limits::check_study(field, &samples.to_string(), samples, elements, allow)
}

impl Samples {
    /// Sample `k`'s refusal `e` as the drawn value's, where `e` names a key a drawn value was
    /// written into; else `e` as it is.
    fn blame(&self, k: usize, e: Error) -> Error {
        let Some(field) = e.field().map(String::from) else {
            return e;
        };
        let hit = |w: &String| match w.strip_prefix('.') {
            Some(tail) => field.contains(&format!(".{tail}")),
            None => field == *w || field.starts_with(&format!("{w}.")),
        };
        let Some(j) = self.writes.iter().position(hit) else {
            return e;
        };
        let key = self.column_keys()[j];
        Error::invalid(
            format!("uncertainty.{key}"),
            format!(
                "{} = {} (row {} of samples.csv)",
                self.columns[j],
                self.samples[k].values[j],
                k + 1
            ),
            format!(
                "written into {field} = {}, which the scenario refuses: {} (a distribution that reaches such values must be narrowed)",
                e.value().unwrap_or_default(),
                e.reason()
            ),
        )
    }

    /// The `[uncertainty]` key each column draws (`rod_length_mm` for `rod_length_mm[3]`).
    pub fn column_keys(&self) -> Vec<&str> {
        self.columns
            .iter()
            .map(|c| c.split('[').next().unwrap_or(c))
            .collect()
    }
}

/// Writes the value of `dist` at `x` about the scenario's nominal value into `s`; returns it.
fn apply(
    s: &mut crate::scenario::Scenario,
    target: Target,
    dist: Distribution,
    key: &str,
    x: f64,
) -> Result<f64, Error> {
    use crate::scenario::{CustomMaterial, ElementKind, MaterialSpec};
    let chain_angle = s.chain.crossing_angle_deg;
    let elements = s.chain.elements.as_deref_mut().unwrap_or(&mut []);
    let needs = |what: &str| {
        Error::invalid(
            key,
            "{…}",
            format!("{what}; give the chain as elements of kind = \"rod\" (a Table 1 rod's cell is tabulated for its nominal rod)"),
        )
    };
    Ok(match target {
        Target::Length(i) => {
            let e = &mut elements[i];
            let (ElementKind::Rod, Some(nominal)) = (e.effective_kind(), e.length_mm) else {
                return Err(needs(&format!(
                    "scatters user rods' length_mm, and element {} is not one",
                    i + 1
                )));
            };
            let v = dist.value(nominal, x);
            e.length_mm = Some(v);
            v
        }
        Target::Angle(i) => {
            let e = &mut elements[i];
            let nominal = e.crossing_angle_deg.or(chain_angle).unwrap_or(90.0);
            let v = dist.value(nominal, x);
            e.crossing_angle_deg = Some(v);
            v
        }
        Target::Modulus => {
            let mut value = f64::NAN;
            for (i, e) in elements.iter_mut().enumerate() {
                if e.effective_kind() == ElementKind::Catalogue {
                    return Err(needs(&format!(
                        "scatters the elements' material, and element {} is a Table 1 rod",
                        i + 1
                    )));
                }
                let field = format!("chain.elements[{i}].material");
                let spec = e
                    .material
                    .clone()
                    .unwrap_or(MaterialSpec::preset(woodpile::defaults::ELEMENT_MATERIAL));
                let m = crate::scenario::material_of(&field, &spec)?;
                value = dist.value(m.youngs_modulus_pa, x);
                e.material = Some(MaterialSpec::Custom(CustomMaterial {
                    name: m.name,
                    youngs_modulus_pa: value,
                    poisson_ratio: m.poisson_ratio,
                    density_kg_m3: m.density_kg_m3,
                }));
            }
            value
        }
        Target::Velocity => {
            let x_spec = &mut s.excitation;
            let nominal = x_spec.velocity_m_s.unwrap_or_else(|| {
                woodpile::velocity_from_drop_height(
                    x_spec
                        .drop_height_m
                        .unwrap_or(woodpile::defaults::DROP_HEIGHT_M),
                )
            });
            let v = dist.value(nominal, x);
            x_spec.velocity_m_s = Some(v);
            x_spec.drop_height_m = None;
            v
        }
        Target::Damping(p) => {
            let d = s.damping.get_or_insert_with(Default::default);
            let slot = match p {
                Parameter::Restitution => &mut d.restitution,
                Parameter::ViscousTime => &mut d.viscous_time_s,
                Parameter::ResonatorRatio => &mut d.resonator_ratio,
                _ => &mut d.on_site_time_s,
            };
            let nominal = match (*slot, dist) {
                (Some(v), _) => v,
                (None, Distribution::Uniform { .. }) => f64::NAN,
                (None, _) => {
                    return Err(Error::invalid(
                        key,
                        "{…}",
                        format!("an sd needs a nominal value: give damping.{}", p.key()),
                    ))
                }
            };
            let v = dist.value(nominal, x);
            *slot = Some(v);
            v
        }
    })
}

/// The figures of merit of each sample, as the columns of `samples.csv` and the keys of
/// `summary.json` name them.
pub const FIGURES: [&str; 3] = [
    "transmitted_peak_force_n",
    "incident_peak_force_n",
    "transmission_ratio",
];

/// The figures of one run, in the order of [`FIGURES`]; None where a figure means nothing (a
/// transmission ratio of a wave that never reached the wall).
pub fn figures(run: &woodpile::RunSummary) -> [Option<f64>; 3] {
    [
        Some(run.transmitted_peak_force_n),
        Some(run.incident_peak_force_n),
        run.transmission_ratio,
    ]
}

/// The file of sample `index` (from 1) under `samples/`.
pub fn sample_file(index: usize) -> String {
    format!("{index:03}.toml")
}

/// The text of `samples.csv`: `sample` from 1, each drawn value, the [`FIGURES`] (an empty cell
/// where a figure means nothing). `runs[k]` is sample k's run.
pub fn samples_csv(s: &Samples, runs: &[woodpile::RunSummary]) -> String {
    let mut csv = String::from("sample");
    for c in s.columns.iter().map(String::as_str).chain(FIGURES) {
        csv += &format!(",{c}");
    }
    csv.push('\n');
    let cell = |x: Option<f64>| x.map(|v| format!("{v:e}")).unwrap_or_default();
    for (k, (sample, run)) in s.samples.iter().zip(runs).enumerate() {
        csv += &(k + 1).to_string();
        for v in sample.values.iter().map(|&v| Some(v)).chain(figures(run)) {
            csv += &format!(",{}", cell(v));
        }
        csv.push('\n');
    }
    csv
}

/// Writes a `--samples` study into `dir`: `samples.csv` (`sample` from 1, each drawn value, the
/// [`FIGURES`]; an empty cell where a figure means nothing), `samples/NNN.toml` (each sample's
/// complete scenario) and `summary.json` (per figure `mean`, `sd`, `quantiles`, `cvar_0.95`, or
/// `null` with the reason when some sample has no value). `runs[k]` is sample k's run.
pub fn write_samples(
    dir: &std::path::Path,
    u: &Uncertainty,
    s: &Samples,
    runs: &[woodpile::RunSummary],
) -> Result<(), Error> {
    use crate::atomic::{io_err, write_atomic};
    let sample_dir = dir.join("samples");
    std::fs::create_dir_all(&sample_dir).map_err(io_err(&sample_dir))?;
    let csv = samples_csv(s, runs);
    for (k, sample) in s.samples.iter().enumerate() {
        write_atomic(
            &sample_dir,
            &sample_file(k + 1),
            sample.scenario.to_toml().as_bytes(),
        )?;
    }
    write_atomic(dir, "samples.csv", csv.as_bytes())?;
    let mut per_figure = serde_json::Map::new();
    for (j, name) in FIGURES.iter().enumerate() {
        let values: Option<Vec<f64>> = runs.iter().map(|r| figures(r)[j]).collect();
        per_figure.insert(name.to_string(), summary_of(values, runs.len()));
    }
    let summary = serde_json::json!({
        "woodpile_version": crate::VERSION,
        "samples": u.samples,
        "seed": u.seed,
        "draws": "Owen-scrambled Sobol' points (sobol_burley), row = sample - 1; normals by Acklam's inverse CDF",
        "parameters": s.columns,
        "figures": per_figure,
    });
    let text = serde_json::to_string_pretty(&summary)
        .map_err(|e| Error::invalid("summary.json", "", e.to_string()))?;
    write_atomic(dir, "summary.json", text.as_bytes())
}

fn summary_of(values: Option<Vec<f64>>, n: usize) -> serde_json::Value {
    let Some(values) = values else {
        return serde_json::json!({
            "value": null,
            "reason": format!("not every one of the {n} samples has this figure (the wave did not reach the wall within the run): lengthen run.duration_s"),
        });
    };
    let st = woodpile::uncertainty::statistics(&values);
    let quantiles: serde_json::Map<String, serde_json::Value> = st
        .quantiles
        .iter()
        .map(|(p, q)| (p.to_string(), serde_json::json!(q)))
        .collect();
    serde_json::json!({
        "mean": st.mean,
        "sd": st.sd,
        "quantiles": quantiles,
        "cvar_0.95": st.cvar_95,
    })
}
