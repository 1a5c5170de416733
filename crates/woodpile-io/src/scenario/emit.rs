//! Writes a completed scenario as commented TOML (every key explicit).

use super::{
    CellSpec, ElementKind, ElementSpec, ExcitationKind, MaterialSpec, ProfileKind, Scenario,
    WallKind,
};
use std::fmt::Write;

/// A float as TOML: shortest round-trip digits, scientific notation for very small or large
/// magnitudes, always recognisable as a float.
pub(crate) fn float(x: f64) -> String {
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

fn string(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

fn material(m: &MaterialSpec) -> String {
    match m {
        MaterialSpec::Preset(name) => string(name),
        MaterialSpec::Custom(c) => format!(
            "{{ name = {}, youngs_modulus_pa = {}, poisson_ratio = {}, density_kg_m3 = {} }}",
            string(&c.name),
            float(c.youngs_modulus_pa),
            float(c.poisson_ratio),
            float(c.density_kg_m3)
        ),
    }
}

fn cell(c: &CellSpec) -> String {
    let mut parts = Vec::new();
    if let Some(m) = c.primary_mass_g {
        parts.push(format!("primary_mass_g = {}", float(m)));
        let res: Vec<String> = c
            .resonators
            .iter()
            .map(|r| {
                format!(
                    "{{ mass_g = {}, stiffness_kn_per_mm = {} }}",
                    float(r.mass_g),
                    float(r.stiffness_kn_per_mm)
                )
            })
            .collect();
        parts.push(format!("resonators = [{}]", res.join(", ")));
    }
    if let Some(l) = c.modes {
        parts.push(format!("modes = {l}"));
    }
    if let Some(r) = c.reduction {
        let name = r.reduction().name();
        parts.push(format!("reduction = {}", string(name)));
    }
    if let Some(n) = c.fe_elements {
        parts.push(format!("fe_elements = {n}"));
    }
    format!("{{ {} }}", parts.join(", "))
}

fn element(e: &ElementSpec) -> String {
    let mut parts = Vec::new();
    if let Some(k) = e.kind {
        if k != ElementKind::Catalogue || e.rod_mm.is_none() {
            parts.push(format!("kind = {}", string(k.name())));
        }
    }
    if let Some(l) = e.rod_mm {
        parts.push(format!("rod_mm = {l}"));
    }
    if let Some(d) = e.diameter_mm {
        parts.push(format!("diameter_mm = {}", float(d)));
    }
    if let Some(l) = e.length_mm {
        parts.push(format!("length_mm = {}", float(l)));
    }
    if let Some(d) = e.inner_diameter_mm {
        parts.push(format!("inner_diameter_mm = {}", float(d)));
    }
    if let Some(a) = e.crossing_angle_deg {
        parts.push(format!("crossing_angle_deg = {}", float(a)));
    }
    if let Some(m) = &e.material {
        parts.push(format!("material = {}", material(m)));
    }
    if let Some(m) = e.model {
        parts.push(format!("model = {}", string(m.name())));
    }
    if let Some(c) = &e.cell {
        parts.push(format!("cell = {}", cell(c)));
    }
    format!("{{ {} }}", parts.join(", "))
}

/// Pads `line` to a column and appends a comment.
fn commented(out: &mut String, line: String, comment: &str) {
    let _ = writeln!(out, "{line:<40} # {comment}");
}

/// The TOML text of a (completed) scenario.
pub(crate) fn to_toml(s: &Scenario) -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "# woodpile scenario: every key written out with its value (docs/physics.md's defaults unless set).\n\
         # Run it with `woodpile simulate THIS_FILE.toml --out DIR`."
    );
    if let Some(d) = &s.description {
        let _ = writeln!(o, "description = {}", string(d));
    }

    // [chain]
    let c = &s.chain;
    let _ = writeln!(o, "\n[chain]");
    if let Some(rods) = &c.rods_mm {
        let list: Vec<String> = rods.iter().map(u32::to_string).collect();
        let _ = writeln!(
            o,
            "# Table 1 catalogue rods (20, 30, 40, 50, 60, 70, 80 mm; fused quartz, 5 mm diameter), top to bottom.\n\
             # General form instead: elements = [{{ rod_mm = 40 }}, {{ kind = \"rod\", … }}, {{ kind = \"sphere\", … }}]"
        );
        let _ = writeln!(o, "rods_mm = [{}]", list.join(", "));
    }
    if let Some(elements) = &c.elements {
        let _ = writeln!(
            o,
            "# Elements top to bottom: {{ rod_mm = L }} (Table 1), {{ kind = \"rod\", diameter_mm, length_mm, material, cell }},\n\
             # {{ kind = \"sphere\", diameter_mm, material }}."
        );
        let _ = writeln!(o, "elements = [");
        for e in elements {
            let _ = writeln!(o, "    {},", element(e));
        }
        let _ = writeln!(o, "]");
    }
    if let Some(m) = c.model {
        commented(
            &mut o,
            format!("model = {}", string(m.name())),
            "\"resonant\" (Table 1 resonators) or \"rigid\" (one body)",
        );
    }
    if let Some(a) = c.crossing_angle_deg {
        commented(
            &mut o,
            format!("crossing_angle_deg = {}", float(a)),
            "angle between neighbouring rods",
        );
    }
    if c.contact_beta.is_empty() {
        let _ = writeln!(
            o,
            "# contact_beta = [{{ contact = 3, beta = 2.5e9 }}]  # set a contact's beta [N/m^1.5] (1 = elements 1-2, N = wall)"
        );
    } else {
        let list: Vec<String> = c
            .contact_beta
            .iter()
            .map(|b| format!("{{ contact = {}, beta = {} }}", b.contact, float(b.beta)))
            .collect();
        commented(
            &mut o,
            format!("contact_beta = [{}]", list.join(", ")),
            "beta [N/m^1.5] set directly (1 = elements 1-2, N = wall)",
        );
    }

    // [excitation]
    let x = &s.excitation;
    let _ = writeln!(o, "\n[excitation]");
    match x.kind {
        ExcitationKind::Impact => {
            commented(&mut o, "kind = \"impact\"".into(), "or \"blast\"");
            if let Some(h) = x.drop_height_m {
                commented(
                    &mut o,
                    format!("drop_height_m = {}", float(h)),
                    "v0 = sqrt(2 g h), g = 9.81 m/s^2; or velocity_m_s = …",
                );
            }
            if let Some(v) = x.velocity_m_s {
                commented(
                    &mut o,
                    format!("velocity_m_s = {}", float(v)),
                    "initial striker velocity; or drop_height_m = …",
                );
            }
            if let Some(st) = &x.striker {
                let mut parts = Vec::new();
                if let Some(d) = st.diameter_mm {
                    parts.push(format!("diameter_mm = {}", float(d)));
                }
                if let Some(m) = &st.material {
                    parts.push(format!("material = {}", material(m)));
                }
                commented(
                    &mut o,
                    format!("striker = {{ {} }}", parts.join(", ")),
                    "a sphere",
                );
            }
            match x.beta {
                Some(b) => commented(
                    &mut o,
                    format!("beta = {}", float(b)),
                    "striker-element 1 contact coefficient [N/m^1.5]",
                ),
                None => commented(
                    &mut o,
                    "# beta = 2.5683e9".into(),
                    "striker-element 1 contact [N/m^1.5]; default: exact Hertz theory",
                ),
            }
        }
        ExcitationKind::Blast => {
            commented(&mut o, "kind = \"blast\"".into(), "or \"impact\"");
            match x.profile.unwrap_or_default() {
                ProfileKind::Friedlander => {
                    commented(
                        &mut o,
                        "profile = \"friedlander\"".into(),
                        "F0 (1 - t/Td) exp(-b t/Td) on [0, Td]; or \"table\" with file = \"load.csv\"",
                    );
                }
                ProfileKind::Table => {
                    commented(
                        &mut o,
                        "profile = \"table\"".into(),
                        "CSV with header time_s,force_n; linear interpolation, zero outside",
                    );
                }
            }
            if let Some(v) = x.peak_force_n {
                commented(&mut o, format!("peak_force_n = {}", float(v)), "F0 [N]");
            }
            if let Some(v) = x.duration_s {
                commented(&mut o, format!("duration_s = {}", float(v)), "Td [s]");
            }
            if let Some(v) = x.decay {
                commented(
                    &mut o,
                    format!("decay = {}", float(v)),
                    "b (1 = Friedlander, 0 = triangle)",
                );
            }
            if let Some(f) = &x.file {
                commented(
                    &mut o,
                    format!("file = {}", string(f)),
                    "relative to this file's directory",
                );
            }
        }
    }

    // [wall]
    let w = &s.wall;
    let _ = writeln!(o, "\n[wall]");
    let kind = w.effective_kind();
    let kind_name = match kind {
        WallKind::Cap => "cap",
        WallKind::Flat => "flat",
        WallKind::Beta => "beta",
        WallKind::Free => "free",
    };
    commented(
        &mut o,
        format!("kind = {}", string(kind_name)),
        "\"cap\" (sensor with a spherical cap), \"flat\", \"beta\" (given beta) or \"free\"",
    );
    if let Some(m) = &w.material {
        commented(
            &mut o,
            format!("material = {}", material(m)),
            "of the cap / flat",
        );
    }
    if let Some(r) = w.cap_radius_mm {
        commented(&mut o, format!("cap_radius_mm = {}", float(r)), "R_c");
    }
    if let Some(b) = w.beta {
        commented(
            &mut o,
            format!("beta = {}", float(b)),
            "wall contact [N/m^1.5]",
        );
    }

    // [run]
    let r = &s.run;
    let _ = writeln!(o, "\n[run]");
    if let Some(d) = r.duration_s {
        commented(
            &mut o,
            format!("duration_s = {}", float(d)),
            "simulated time",
        );
    }
    if let Some(i) = r.integrator {
        commented(
            &mut o,
            format!("integrator = {}", string(i.name())),
            "\"rk4\" (fixed step) or \"dopri5\" (adaptive, rtol/atol)",
        );
    }
    if let Some(v) = r.time_step_s {
        commented(&mut o, format!("time_step_s = {}", float(v)), "rk4 step");
    }
    if let Some(v) = r.rtol {
        commented(
            &mut o,
            format!("rtol = {}", float(v)),
            "dopri5 relative tolerance",
        );
    }
    if let Some(v) = r.atol {
        commented(
            &mut o,
            format!("atol = {}", float(v)),
            "dopri5 absolute tolerance [m]",
        );
    }
    if let Some(v) = r.sample_interval_s {
        commented(
            &mut o,
            format!("sample_interval_s = {}", float(v)),
            "uniform output grid",
        );
    }
    o
}
