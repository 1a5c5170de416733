//! Writes a completed scenario as commented TOML (every key explicit).

use super::{
    CellSpec, ContactSpec, DampingSpec, ElementKind, ElementSpec, ExcitationKind, ExcitationSpec,
    MaterialSpec, ProfileKind, Scenario, SweepSpec, WallSpec,
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

/// Writes `key = value  # comment` for each given value.
fn keys(o: &mut String, lines: &[(&str, Option<String>, &str)]) {
    for (key, value, comment) in lines {
        if let Some(v) = value {
            commented(o, format!("{key} = {v}"), comment);
        }
    }
}

/// `{ key = value, … }` of the given values.
fn inline(items: &[(&str, Option<String>)]) -> String {
    let parts: Vec<String> = items
        .iter()
        .filter_map(|(k, v)| v.as_ref().map(|v| format!("{k} = {v}")))
        .collect();
    format!("{{ {} }}", parts.join(", "))
}

/// A support's keys and comments (`[wall]`, or an actuator's tip inline).
fn wall_keys(w: &WallSpec) -> [(&'static str, Option<String>, &'static str); 4] {
    let m = w.material.as_ref().map(material);
    let kinds =
        "\"cap\" (sensor with a spherical cap), \"flat\", \"beta\" (given beta) or \"free\"";
    [
        ("kind", Some(string(w.effective_kind().name())), kinds),
        ("material", m, "of the cap / flat"),
        ("cap_radius_mm", w.cap_radius_mm.map(float), "R_c"),
        ("beta", w.beta.map(float), "the contact's beta [N/m^1.5]"),
    ]
}

/// The drive keys of `[excitation]`.
fn drive(o: &mut String, x: &ExcitationSpec) {
    let name = |n: &str| Some(string(n));
    let f = |v: Option<f64>| v.map(float);
    let sweep = x.sweep.map(|w| match w {
        SweepSpec::Linear => string("linear"),
        SweepSpec::Logarithmic => string("logarithmic"),
    });
    let tip = (x.tip.as_ref()).map(|t| inline(&wall_keys(t).map(|(k, v, _)| (k, v))));
    let what = "N (force) or m (displacement)";
    let file = x.file.as_deref().map(string);
    let kinds = "\"force\" (N) or \"displacement\" (m, through the tip)";
    let signals = "\"harmonic\", \"chirp\" or \"table\" (CSV time_s,value)";
    keys(
        o,
        &[
            ("kind", name("drive"), "an actuator on the top element"),
            ("drive", x.drive.map(|d| string(d.name())), kinds),
            ("signal", x.signal.map(|k| string(k.name())), signals),
            ("amplitude", f(x.amplitude), what),
            ("frequency_hz", f(x.frequency_hz), "harmonic signal"),
            ("start_hz", f(x.start_hz), "chirp: from"),
            ("end_hz", f(x.end_hz), "chirp: to"),
            ("sweep_duration_s", f(x.sweep_duration_s), "chirp: over"),
            ("sweep", sweep, "\"linear\" or \"logarithmic\""),
            ("file", file, "CSV, relative to this file"),
            ("ramp_s", f(x.ramp_s), "sin^2 ramp (chirp: both ends)"),
            ("tip", tip, "the actuator's tip: keys as in [wall]"),
        ],
    );
}

/// The `[damping]` table.
fn damping(o: &mut String, d: &DampingSpec) {
    let law = |c: &Option<ContactSpec>| {
        c.map(|c| {
            inline(&[
                ("contact", c.contact.map(|l| string(l.name()))),
                ("restitution", c.restitution.map(float)),
                ("viscous_time_s", c.viscous_time_s.map(float)),
            ])
        })
    };
    let resonators = (!d.resonators.is_empty()).then(|| {
        let list: Vec<String> = (d.resonators.iter())
            .map(|r| {
                let (e, j, z) = (r.element, r.resonator, float(r.ratio));
                format!("{{ element = {e}, resonator = {j}, ratio = {z} }}")
            })
            .collect();
        format!("[{}]", list.join(", "))
    });
    let f = |v: Option<f64>| v.map(float);
    let laws = "\"none\", \"restitution\", \"hunt-crossley\" or \"viscoelastic\"";
    let pull = d.allow_pull.map(|p| p.to_string());
    let _ = writeln!(o, "\n[damping]");
    keys(
        o,
        &[
            ("contact", d.contact.map(|l| string(l.name())), laws),
            ("restitution", f(d.restitution), "coefficient e, 0 < e <= 1"),
            ("viscous_time_s", f(d.viscous_time_s), "dissipative time A"),
            ("striker", law(&d.striker), "striker's/actuator's contact"),
            ("wall", law(&d.wall), "the wall contact's law"),
            ("allow_pull", pull, "may a damped contact pull"),
            (
                "impact_speed_m_s",
                f(d.impact_speed_m_s),
                "Hunt-Crossley v_in",
            ),
            (
                "resonator_ratio",
                f(d.resonator_ratio),
                "every resonator's zeta",
            ),
            ("resonators", resonators, "zeta of single resonators"),
            ("on_site_time_s", f(d.on_site_time_s), "on-site time tau"),
        ],
    );
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
            commented(
                &mut o,
                "kind = \"impact\"".into(),
                "or \"blast\", \"drive\", \"rest\"",
            );
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
            commented(
                &mut o,
                "kind = \"blast\"".into(),
                "or \"impact\", \"drive\", \"rest\"",
            );
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
        ExcitationKind::Drive => drive(&mut o, x),
        ExcitationKind::Rest => commented(
            &mut o,
            "kind = \"rest\"".into(),
            "nothing drives the chain (with [preload]: its static equilibrium)",
        ),
    }

    // [wall], [damping], [preload]
    let _ = writeln!(o, "\n[wall]");
    keys(&mut o, &wall_keys(&s.wall));
    match &s.damping {
        Some(d) => damping(&mut o, d),
        None => {
            let _ = writeln!(o, "\n# [damping]: contact laws, resonator and on-site damping (docs/physics.md §14); none: lossless");
        }
    }
    match &s.preload {
        Some(p) => {
            let _ = writeln!(o, "\n[preload]");
            keys(
                &mut o,
                &[
                    (
                        "force_n",
                        p.force_n.map(float),
                        "static force on the top element [N]",
                    ),
                    (
                        "gravity_m_s2",
                        p.gravity_m_s2.map(float),
                        "gravity along the column [m/s^2]",
                    ),
                ],
            );
        }
        None => {
            let _ = writeln!(o, "\n# [preload]: force_n on the top element, gravity_m_s2 (docs/physics.md §14); none: unloaded");
        }
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
    if let Some(v) = r.peak_tolerance {
        commented(
            &mut o,
            format!("peak_tolerance = {}", float(v)),
            "relative accuracy of every contact peak; woodpile chooses the integrator",
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
