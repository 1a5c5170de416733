//! The blast (paper Figs. 8, 9): the Friedlander load on homogeneous 20, 40, 80 mm resonant
//! chains and the paper's blast-optimised chain: the peak energy of the last layer against the
//! 20 mm chain's, and the spectra against the negative-mass bands.

use super::doc::Doc;
use super::study::FOURIER;
use super::study::{join_mm, pct, Case, Comparison, PaperValue, Quantity, Setup, CHAIN_LENGTH};
use crate::Error;
use rayon::prelude::*;
use std::path::PathBuf;
use woodpile::analysis::{band_contrast, contact_spectrum_map, peak_layer_energy};
use woodpile::{CellModel, Chain, ChainBuilder};
use woodpile_plot as plot;

/// Blast: peak transmitted energy of the 40 mm chain over the 20 mm chain's.
pub const BLAST_40MM: PaperValue = PaperValue {
    approximate: true,
    ..PaperValue::new(
        "Blast: peak transmitted energy (last layer), 40 mm chain / 20 mm chain",
        0.70,
        Quantity::Fraction,
    )
};
/// Blast: peak transmitted energy of the 80 mm chain over the 20 mm chain's.
pub const BLAST_80MM: PaperValue = PaperValue {
    approximate: true,
    ..PaperValue::new(
        "Blast: peak transmitted energy (last layer), 80 mm chain / 20 mm chain",
        0.70,
        Quantity::Fraction,
    )
};
/// Blast: peak transmitted energy of the paper's optimised chain over the 20 mm chain's.
pub const BLAST_OPTIMUM: PaperValue = PaperValue::new(
    "Blast: peak transmitted energy (last layer), paper optimum chain / 20 mm chain",
    0.083,
    Quantity::Fraction,
);
/// The paper's three blast ratios (40 mm, 80 mm, optimised chain over the 20 mm chain).
pub const BLAST_RATIOS: [PaperValue; 3] = [BLAST_40MM, BLAST_80MM, BLAST_OPTIMUM];

/// The low-energy bands the paper sees in the blast spectra, by rod length \[mm\] (as printed).
const BLAST_BANDS: [(u32, &str); 3] = [
    (20, "38–55 kHz"),
    (40, "10–15 kHz"),
    (80, "2.7–3.9 and 15–20 kHz"),
];

/// The chains: homogeneous 20, 40, 80 mm resonant chains, and the paper's blast-optimised chain
/// (`None`: [`woodpile::PAPER_OPTIMIZED_CHAIN_MM`]), with their names and file-name parts.
pub const BLAST_CHAINS: [(Option<u32>, &str, &str); 4] = [
    (Some(20), "20 mm", "20mm"),
    (Some(40), "40 mm", "40mm"),
    (Some(80), "80 mm", "80mm"),
    (None, "paper optimum", "paper_optimum"),
];

/// One of [`BLAST_CHAINS`], with the title part naming it.
pub fn blast_chain(rod_mm: Option<u32>) -> Result<(Chain, String), Error> {
    let (rods, title) = match rod_mm {
        Some(l) => (
            vec![l; CHAIN_LENGTH],
            format!("{CHAIN_LENGTH} × {l} mm rods (resonant)"),
        ),
        None => (
            woodpile::PAPER_OPTIMIZED_CHAIN_MM.to_vec(),
            "paper's blast-optimised chain (resonant)".to_string(),
        ),
    };
    let chain = ChainBuilder::table1_rods(&rods, CellModel::Resonant)?.build()?;
    Ok((chain, title))
}

/// What the blast runs give the report.
pub struct Blast {
    /// Each chain, with its figures.
    pub cases: Vec<Case>,
    /// The load and the wall forces compared.
    pub compare: Vec<PathBuf>,
    /// Peak energy of each chain's last layer \[J\].
    pub energy: Vec<f64>,
    /// (chain, negative-mass band \[Hz\], band contrast of its spectra).
    pub bands: Vec<(String, (f64, f64), f64)>,
}

/// Runs and draws one chain under the blast.
fn case(s: &Setup, (rod_mm, name, slug): (Option<u32>, &str, &str)) -> Result<Case, Error> {
    let (chain, chain_title) = blast_chain(rod_mm)?;
    let mut case = Case::simulate(name, &chain_title, chain, &s.blast, &s.blast_settings)?;
    let title = format!("{chain_title}, {}", s.blast_text);
    let fig = |what: &str| s.fig(&format!("blast_{slug}{what}"));
    case.draw_maps(&title, "load", &fig(""))?;
    let map = contact_spectrum_map(&case.trajectory, &FOURIER)?;
    let files = plot::spectrum_map(&map, &title, s.max_hz, Some("load"), &fig("_spectrum_map"))?;
    case.files.push(files);
    case.draw_spectra(&title, s.max_hz, &fig("_spectra"))?;
    s.bar.inc(1);
    Ok(case)
}

/// Runs the four chains under the blast and draws them.
pub fn run(s: &Setup) -> Result<Blast, Error> {
    let cases = BLAST_CHAINS
        .par_iter()
        .map(|&c| case(s, c))
        .collect::<Result<Vec<_>, Error>>()?;
    let wall = |c: &Case| c.trajectory.contact_force_n(c.trajectory.n_elements);
    let load = plot::Series::new("load (contact 0)", cases[0].trajectory.contact_force_n(0));
    let series: Vec<plot::Series> = std::iter::once(load)
        .chain(
            cases
                .iter()
                .map(|c| plot::Series::new(format!("{}: wall", c.name), wall(c))),
        )
        .collect();
    let compare = plot::force_histories(
        &cases[0].trajectory.times_s,
        &series,
        &format!(
            "Blast load and wall forces of the 20-rod chains, {}",
            s.blast_text
        ),
        &s.fig("blast_wall_forces"),
    )?;
    let energy = cases
        .iter()
        .map(|c| peak_layer_energy(&c.trajectory, c.trajectory.n_elements))
        .collect();
    // Band contrast: the homogeneous chains' negative-mass bands.
    let mut bands = Vec::new();
    for c in cases.iter().take(3) {
        for &b in &c.bands {
            bands.push((c.name.clone(), b, band_contrast(&c.trajectory, b)?));
        }
    }
    Ok(Blast {
        cases,
        compare,
        energy,
        bands,
    })
}

impl Blast {
    /// Peak energy of each chain's last layer over the 20 mm chain's.
    pub fn shares(&self) -> Vec<f64> {
        self.energy.iter().map(|e| e / self.energy[0]).collect()
    }

    /// Rows of the comparison table: the three energy ratios and the low-energy bands.
    pub fn compare(&self, table: &mut Comparison) {
        let why = "F0, Td and the pulse shape of the paper's blast are unknown: docs/physics.md §6's Friedlander 200 N / 0.2 ms";
        for (p, q) in BLAST_RATIOS.iter().zip(&self.shares()[1..]) {
            table.row(p.what, p.text(), pct(*q), p.difference(*q), why);
        }
        for (rod_mm, paper) in BLAST_BANDS {
            let name = format!("{rod_mm} mm");
            let bands: Vec<String> = self
                .bands_of(&name)
                .map(|((lo, hi), c)| {
                    format!(
                        "{:.1}–{:.1} kHz (spectral amplitude in the band {:.0} % of its flanks)",
                        lo * 1e-3,
                        hi * 1e-3,
                        100.0 * c
                    )
                })
                .collect();
            table.row(
                &format!("Blast: low-energy band(s), {name} chain"),
                paper.into(),
                bands.join("; "),
                "edges within 1 kHz".into(),
                "the paper's bands are rounded; ours are the negative-mass bands of Table 1, the contrast is measured on the blast spectra of contacts 1..20",
            );
        }
    }

    /// The bands of the chain named `name` and their contrast.
    fn bands_of<'a>(&'a self, name: &'a str) -> impl Iterator<Item = ((f64, f64), f64)> + 'a {
        self.bands
            .iter()
            .filter(move |(n, _, _)| n == name)
            .map(|&(_, band, contrast)| (band, contrast))
    }

    /// The section's opening: the energy and band tables and the wall forces.
    pub fn write_overview(&self, doc: &mut Doc, s: &Setup) {
        let paper = BLAST_RATIOS.map(|p| p.text());
        doc.h2("Blast (Figs. 8, 9)");
        doc.p(format!(
            "The {} load on the top rod of 20-rod resonant chains: homogeneous 20, 40, 80 mm and the paper's blast-optimised chain `{}`. The paper: peak transmitted energy (energy of the last layer) {} of the 20 mm chain's for 40 and 80 mm rods, {} for the optimised chain; the spectra show low-energy bands at the negative-mass bands of the rods.",
            s.blast_text,
            join_mm(&woodpile::PAPER_OPTIMIZED_CHAIN_MM),
            paper[0],
            paper[2],
        ));
        let energy_rows = self.cases.iter().zip(&self.energy).zip(self.shares());
        doc.table(
            &[
                "chain",
                "peak energy of layer 20",
                "relative to 20 mm",
                "wall peak force",
            ],
            energy_rows
                .map(|((c, e), share)| {
                    vec![
                        c.name.clone(),
                        format!("{e:.3e} J"),
                        pct(share),
                        format!("{:.2} N", c.summary.transmitted_peak_force_n),
                    ]
                })
                .collect(),
        );
        let band_rows = self.bands.iter().map(|(name, (lo, hi), c)| {
            let band = format!("{:.2}–{:.2} kHz", lo * 1e-3, hi * 1e-3);
            vec![name.clone(), band, pct(*c)]
        });
        doc.table(
            &[
                "chain",
                "negative-mass band",
                "mean amplitude in band / flanks",
            ],
            band_rows.collect(),
        );
        doc.figure(
            &self.compare,
            "The blast load (contact 0, Fig. 8) and the wall force of the four chains.",
        );
    }

    /// Each chain's figures under the blast.
    pub fn write_chains(&self, doc: &mut Doc) {
        let panels = [("a", "b"), ("c", "d"), ("e", "f"), ("g", "h")];
        for ((c, panels), share) in self.cases.iter().zip(panels).zip(self.shares()) {
            doc.h3(format!("{} under the blast", c.chain_title));
            let prefix = format!("{}, blast", c.chain_title);
            doc.figures(&c.files, &prefix, self.captions(c, panels, share));
        }
    }

    /// The captions of one chain's four figures (its panels of Fig. 9: force, spectrum).
    fn captions(
        &self,
        c: &Case,
        (force_panel, spectrum_panel): (&str, &str),
        share: f64,
    ) -> [String; 4] {
        let bands: Vec<String> = self
            .bands_of(&c.name)
            .map(|((lo, hi), contrast)| {
                format!(
                    "{:.1}–{:.1} kHz, {} ({})",
                    lo * 1e-3,
                    hi * 1e-3,
                    pct(contrast),
                    if contrast < 1.0 { "a dip" } else { "no dip" }
                )
            })
            .collect();
        let bands_text = if bands.is_empty() {
            "no common band: the rods' bands differ (the paper finds none in its optimised chain either)".to_string()
        } else {
            let paper: Vec<String> = BLAST_BANDS
                .iter()
                .map(|(rod_mm, band)| format!("{band} for {rod_mm} mm"))
                .collect();
            format!("the mean amplitude inside each shaded negative-mass band against its flanks: {} (the paper's low-energy bands: {} rods)", bands.join("; "), paper.join(", "))
        };
        let paper_waves = match force_panel {
            "a" => "the paper: at 20 mm the resonance (~55 kHz) changes little",
            "c" => "the paper: the 40 mm rods' resonance (~15 kHz) disintegrates the waves into modulated patterns",
            "e" => "the paper: the 80 mm rods' resonances (~4 and ~20 kHz) disintegrate the waves into modulated patterns",
            _ => "the paper: the optimised chain's wall force is blunted and low",
        };
        [
            format!("contact force over contact and time (Fig. 9 {force_panel}). What to see: the load's long pulse makes the top rods touch several times and launches several waves; {paper_waves}; the wall peak is {:.1} N.", c.summary.transmitted_peak_force_n),
            format!("energy of each layer as a share of the injected energy (the paper reads its peak transmitted energy from Fig. 9's colours). What to see: the last layer's peak energy is {} of the 20 mm chain's (table above).", pct(share)),
            format!("magnitude of the Fourier transform of each contact force |F̂(f)| [N/Hz] per contact and frequency (Fig. 9 {spectrum_panel}). What to see: {bands_text}."),
            "magnitude spectra of contact 1, the middle contact and the wall, negative-mass bands shaded (no panel in the paper; the same data as the map before it, on a line plot).".to_string(),
        ]
    }
}
