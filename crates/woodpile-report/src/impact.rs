//! Homogeneous chains under the impact (paper Figs. 5 a–c, 6): 20 rods of 20, 40, 80 mm
//! (resonant) and 20 mm (rigid), their maps, force histories and spectra, the wall forces
//! compared, and the first transit of each wave at the wall against what the paper says of it.

use super::doc::Doc;
use super::study::{energy_held_text, pct, ratio, Case, Comparison, PaperValue, Quantity, Setup};
use crate::Error;
use rayon::prelude::*;
use std::path::PathBuf;
use woodpile::analysis::FirstTransit;
use woodpile::{CellModel, ChainBuilder};
use woodpile_plot as plot;

/// The chains: rod length \[mm\] and cell model.
const CHAINS: [(u32, CellModel); 4] = [
    (20, CellModel::Resonant),
    (40, CellModel::Resonant),
    (80, CellModel::Resonant),
    (20, CellModel::Rigid),
];

/// What the paper says of the wave at the wall, by rod length \[mm\] (qualitative).
const WAVE_SHAPES: [(u32, &str); 3] = [
    (20, "one solitary wave with a small oscillating tail"),
    (40, "wave split into groups separated in time"),
    (80, "two groups ~0.2 ms apart"),
];

/// Impact on 80 mm rods: time between the two groups of the split wave.
pub const GAP_80MM: PaperValue = PaperValue::new(
    "Impact on 20 × 80 mm rods: time between the two pulse groups",
    0.2e-3,
    Quantity::DurationS,
);

/// The homogeneous chains under the impact.
pub struct Impact {
    /// Each chain, with its figures.
    pub cases: Vec<Case>,
    /// Wall forces of the chains compared.
    pub wall_compare: Vec<PathBuf>,
    /// First transit of each chain's wave at the wall.
    pub waves: Vec<FirstTransit>,
}

/// Runs and draws one homogeneous chain.
fn case(s: &Setup, rod_mm: u32, model: CellModel) -> Result<Case, Error> {
    let (model_name, suffix) = match model {
        CellModel::Rigid => ("rigid", "_rigid"),
        _ => ("resonant", ""),
    };
    let name = format!("{rod_mm} mm{}", suffix.replace('_', " "));
    let slug = format!("{rod_mm}mm{suffix}");
    let chain_title = format!("20 × {rod_mm} mm rods ({model_name})");
    let chain = ChainBuilder::table1_rods(&[rod_mm; 20], model)?.build()?;
    let mut case = Case::simulate(&name, &chain_title, chain, &s.impact, &s.impact_settings)?;
    let title = format!("{chain_title}, {}", s.impact_text);
    let fig = |what: &str| s.fig(&format!("impact_{slug}{what}"));
    case.draw_maps(&title, "striker", &fig(""))?;
    let t = &case.trajectory;
    let n = t.n_elements;
    let series = [
        (0, "contact 0 (striker)".to_string()),
        (1, "contact 1 (incident)".to_string()),
        (n / 2, format!("contact {} (middle)", n / 2)),
        (n, format!("contact {n} (wall)")),
    ]
    .map(|(c, l)| plot::Series::new(l, t.contact_force_n(c)));
    let histories = plot::force_histories(&t.times_s, &series, &title, &fig("_force_histories"))?;
    // The same, zoomed on the first arrivals (over 2 ms the pulses are slivers).
    let onset = plot::onset_window_s(&t.times_s, &series, 1.0)
        .unwrap_or((t.times_s[0], t.times_s[t.times_s.len() - 1]));
    let zoomed = plot::force_histories_between(
        &t.times_s,
        &series,
        &title,
        onset,
        &fig("_force_histories_onset"),
    )?;
    case.files.extend([histories, zoomed]);
    case.draw_spectra(&title, s.max_hz, &fig("_spectra"))?;
    s.bar.inc(1);
    Ok(case)
}

/// Runs the chains and draws their figures.
pub fn run(s: &Setup) -> Result<Impact, Error> {
    let cases = CHAINS
        .par_iter()
        .map(|&(rod_mm, model)| case(s, rod_mm, model))
        .collect::<Result<Vec<_>, Error>>()?;
    let wall_series: Vec<plot::Series> = cases
        .iter()
        .map(|c| {
            plot::Series::new(
                format!("{}: wall (contact 20)", c.name),
                c.trajectory.contact_force_n(c.trajectory.n_elements),
            )
        })
        .collect();
    let wall_compare = plot::force_histories(
        &cases[0].trajectory.times_s,
        &wall_series,
        &format!("Wall force of homogeneous 20-rod chains, {}", s.impact_text),
        &s.fig("impact_homogeneous_wall_forces"),
    )?;
    // Pulses at the wall and at the middle contact, first transit only: up to the arrival of
    // the first pulse at the wall plus 0.6 ms.
    let waves = cases
        .iter()
        .map(|c| FirstTransit::of(&c.name, &c.trajectory))
        .collect();
    Ok(Impact {
        cases,
        wall_compare,
        waves,
    })
}

impl Impact {
    /// Rows of the comparison table: the wave arriving at the wall.
    pub fn compare(&self, table: &mut Comparison) {
        for ((rod_mm, paper), w) in WAVE_SHAPES.iter().zip(&self.waves) {
            let ours = format!(
                "{} separated peak(s) at the wall in the first transit{}{}",
                w.peaks.len(),
                w.second_ratio().map_or(String::new(), |q| format!(
                    "; second largest {:.0} % of the largest",
                    100.0 * q
                )),
                w.main_gap_s()
                    .map_or(String::new(), |g| format!(", {:.3} ms from it", g * 1e3))
            );
            let diff = match (rod_mm, w.main_gap_s()) {
                (80, Some(g)) => format!("gap {}", GAP_80MM.difference(g)),
                _ => "–".to_string(),
            };
            table.row(
                &format!("Impact on 20 × {} rods: the wave arriving at the wall", w.name),
                (*paper).into(),
                ours,
                diff,
                "peaks of the wall force ≥ 5 % of its maximum within one transit time after the arrival, merged unless the force between them falls below half the smaller (see the homogeneous-chain section)",
            );
        }
    }

    /// The section: the table of first transits and every chain's figures.
    pub fn write(&self, doc: &mut Doc) {
        doc.h2("Homogeneous chains under impact (Fig. 5 a–c)");
        doc.p("Twenty identical rods on the sensor, hit by the striker. The paper: 20 mm rods carry a solitary wave with a small oscillating tail (a nanopteron); 40 and 80 mm rods split the wave into groups separated in time (80 mm: two groups ~0.2 ms apart).");
        doc.p("Measured on the wall force, during the first transit only (from the wave's arrival at the wall, for as long as it took to get there from contact 1; later events include reflections): the separated peaks, i.e. local maxima of at least 5 % of the window's maximum, two neighbouring maxima counting as one unless the force between them falls below half the smaller one.");
        let rows = self.waves.iter().zip(&self.cases).map(|(w, c)| {
            let peaks = w
                .peaks
                .iter()
                .map(|(t, f)| format!("{:.3} ms ({f:.1} N)", t * 1e3))
                .collect::<Vec<_>>()
                .join(", ");
            vec![
                w.name.clone(),
                format!("{:.1} N", c.summary.incident_peak_force_n),
                format!("{:.1} N", c.summary.transmitted_peak_force_n),
                format!(
                    "{:.3} → {:.3} ms",
                    w.arrival_top_s * 1e3,
                    w.arrival_wall_s * 1e3
                ),
                format!("{}: {peaks}", w.peaks.len()),
                w.main_gap_s()
                    .map_or("–".to_string(), |g| format!("{:.3} ms", g * 1e3)),
            ]
        });
        doc.table(
            &[
                "chain",
                "incident peak",
                "wall peak",
                "arrival at contact 1 → wall",
                "separated peaks at the wall (first transit)",
                "gap between the two largest",
            ],
            rows.collect(),
        );
        doc.figure(&self.wall_compare, "Wall force of the four homogeneous chains under the impact. What to see: when each wave arrives and how it is grouped (the table above counts the separated peaks of the first transit).");
        for ((c, w), (rod_mm, model)) in self.cases.iter().zip(&self.waves).zip(CHAINS) {
            doc.h3(format!("{} under impact", c.chain_title));
            let prefix = format!("{}, impact", c.chain_title);
            doc.figures(&c.files, &prefix, captions(c, w, rod_mm, model));
        }
    }
}

/// The captions of one chain's five figures.
fn captions(c: &Case, w: &FirstTransit, rod_mm: u32, model: CellModel) -> [String; 5] {
    let (panel, paper) = match (rod_mm, model) {
        (_, CellModel::Rigid) => (
            "no panel in the paper",
            "the reference for the resonant 20 mm chain",
        ),
        (20, _) => (
            "Fig. 5 a",
            "the paper's 20 mm chain carries one solitary wave with a small oscillating tail",
        ),
        (40, _) => (
            "Fig. 5 b",
            "the paper's 40 mm chain splits the wave into groups separated in time",
        ),
        (80, _) => (
            "Fig. 5 c",
            "the paper's 80 mm chain splits it into two groups ~0.2 ms apart",
        ),
        _ => (
            "no panel in the paper",
            "compare with the paper's 20, 40 and 80 mm chains",
        ),
    };
    [
        format!(
            "contact force over contact and time ({panel}). What to see: the pulse takes {:.3} ms from contact 1 to the wall and reaches it as {}; {paper}. Later traces are reflections from the wall and the striker.",
            (w.arrival_wall_s - w.arrival_top_s) * 1e3,
            pulses_text(w)
        ),
        format!(
            "energy of each layer as a share of the striker's initial energy (the paper draws this map for the optima only, Fig. 6). What to see: {}.",
            energy_held_text(&c.trajectory)
        ),
        "force at the striker contact, contact 1, the middle contact and the wall over the whole run (no panel in the paper). What to see: the first transit and the echoes that follow it.".to_string(),
        format!(
            "the same forces zoomed on the first arrivals. What to see: the incident peak {:.1} N against {:.1} N transmitted to the wall ({}); a wall force above the incident one is the wall's reflection adding to the arriving wave.",
            c.summary.incident_peak_force_n,
            c.summary.transmitted_peak_force_n,
            pct(ratio(&c.summary))
        ),
        "magnitude of the Fourier transform |F̂(f)| [N/Hz] of contact 1, the middle contact and the wall, the rods' negative-effective-mass bands shaded (no panel in the paper: its spectra, Fig. 9, are of the blast). What to see: how the wall's spectrum compares with contact 1's inside the shaded bands, where the chain carries no linear wave (docs/physics.md §3).".to_string(),
    ]
}

/// `one pulse` or `3 separated pulses, the two largest 0.156 ms apart`.
fn pulses_text(w: &FirstTransit) -> String {
    match (w.peaks.len(), w.main_gap_s()) {
        (0, _) => "no pulse above 5 % of its maximum".to_string(),
        (1, _) => "one pulse".to_string(),
        (n, Some(gap)) => format!(
            "{n} separated pulses, the two largest {:.3} ms apart",
            gap * 1e3
        ),
        (n, None) => format!("{n} separated pulses"),
    }
}
