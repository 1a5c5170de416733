//! What every section of the report shares: the loads and where figures go ([`Setup`]), one
//! simulated chain with its figures ([`Case`]), the paper's numbers as data ([`PaperValue`]) and
//! the comparison table they go into ([`Comparison`]).

use crate::Error;
use crate::Progress;
use std::path::{Path, PathBuf};
use woodpile::analysis::{energy_map, force_map, Spectrum, SpectrumSettings};
use woodpile::{BlastProfile, Chain, Excitation, RunSettings, RunSummary, Striker, Trajectory};
use woodpile_plot as plot;

/// Number of rods in every chain of the paper.
pub const CHAIN_LENGTH: usize = 20;

/// What every run of the report shares: the command's choices, where figures go, the loads.
pub struct Setup<'a> {
    /// The output directory (`--out`).
    pub out: PathBuf,
    /// `--quick`: small GAs and a 2 × 2 blast sweep.
    pub quick: bool,
    /// Seed of the GAs.
    pub seed: u64,
    /// Worker threads (0: one per core).
    pub threads: usize,
    /// Progress: a bar on a terminal, a line per stage otherwise.
    pub bar: &'a dyn Progress,
    /// `OUT/figures`.
    pub figs: PathBuf,
    /// The paper's impact.
    pub impact: Excitation,
    /// Run settings of the impact.
    pub impact_settings: RunSettings,
    /// The impact in words.
    pub impact_text: String,
    /// The default blast.
    pub blast: Excitation,
    /// Run settings of the blast.
    pub blast_settings: RunSettings,
    /// The blast in words.
    pub blast_text: String,
    /// Highest frequency of the spectra \[Hz\].
    pub max_hz: f64,
}

impl<'a> Setup<'a> {
    /// The paper's loads with the defaults of docs/physics.md, figures into `out/figures`.
    pub fn new(
        out: PathBuf,
        quick: bool,
        seed: u64,
        threads: usize,
        bar: &'a dyn Progress,
    ) -> Self {
        let striker = Striker::paper();
        let (f0, td) = match BlastProfile::paper() {
            BlastProfile::Friedlander {
                peak_force_n,
                duration_s,
                ..
            } => (peak_force_n, duration_s),
            BlastProfile::Table { .. } => (f64::NAN, f64::NAN),
        };
        Setup {
            figs: out.join("figures"),
            out,
            quick,
            seed,
            threads,
            bar,
            impact_text: format!(
                "impact of a {} mm glass sphere at {:.2} m/s",
                striker.diameter_m * 1e3,
                striker.velocity_m_s
            ),
            impact: Excitation::Impact(striker),
            impact_settings: RunSettings::paper_impact(),
            blast: Excitation::Blast(BlastProfile::paper()),
            blast_settings: RunSettings::paper_blast(),
            blast_text: format!("Friedlander blast {f0} N / {} ms", td * 1e3),
            max_hz: 80e3,
        }
    }

    /// `OUT/figures/NAME`: a figure's stem.
    pub fn fig(&self, name: &str) -> PathBuf {
        self.figs.join(name)
    }
}

/// One run of the study, kept with its trajectory for the figures.
#[derive(Debug, Clone)]
pub struct Case {
    /// Short name, e.g. `20 mm`.
    pub name: String,
    /// Title part naming the chain, e.g. `20 × 20 mm rods (resonant)`.
    pub chain_title: String,
    /// The chain.
    pub chain: Chain,
    /// Its figures of merit.
    pub summary: RunSummary,
    /// Its trajectory on the sample grid.
    pub trajectory: Trajectory,
    /// The chain's negative-mass bands to mark ([`woodpile::analysis::chain_bands_hz`]).
    pub bands: Vec<(f64, f64)>,
    /// Its figures, each the files of one plot.
    pub files: Vec<Vec<PathBuf>>,
}

impl Case {
    /// Runs `chain` (`name`, titled `chain_title`) under `excitation`; its figures are drawn
    /// into [`Case::files`] afterwards.
    pub fn simulate(
        name: &str,
        chain_title: &str,
        chain: Chain,
        excitation: &Excitation,
        settings: &RunSettings,
    ) -> Result<Case, Error> {
        let mut trajectory = Trajectory::default();
        let summary = woodpile::simulate(&chain, excitation, settings, &mut trajectory)?;
        let bands = woodpile::analysis::chain_bands_hz(chain.elements().iter().map(|e| &e.cell));
        Ok(Case {
            name: name.to_string(),
            chain_title: chain_title.to_string(),
            chain,
            summary,
            trajectory,
            bands,
            files: Vec::new(),
        })
    }

    /// Draws the force map and the energy map (`STEM_force_map`, `STEM_energy_map`); `contact0`
    /// names what drives the run (`striker`, `load`).
    pub fn draw_maps(&mut self, title: &str, contact0: &str, stem: &Path) -> Result<(), Error> {
        let t = &self.trajectory;
        let with = |suffix: &str| {
            let mut s = stem.as_os_str().to_owned();
            s.push(suffix);
            PathBuf::from(s)
        };
        self.files.push(plot::force_map(
            &force_map(t)?,
            title,
            Some(contact0),
            &with("_force_map"),
        )?);
        self.files.push(plot::energy_map(
            &energy_map(t)?,
            title,
            Some(contact0),
            &with("_energy_map"),
        )?);
        Ok(())
    }

    /// Draws the spectra of contact 1, the middle contact and the wall, the chain's bands shaded.
    pub fn draw_spectra(&mut self, title: &str, max_hz: f64, stem: &Path) -> Result<(), Error> {
        let t = &self.trajectory;
        let n = t.n_elements;
        let dt = woodpile::analysis::sample_interval_s(t)?;
        let spectra = [
            (1, "contact 1 (incident)".to_string()),
            (n / 2, format!("contact {} (middle)", n / 2)),
            (n, format!("contact {n} (wall)")),
        ]
        .into_iter()
        .map(|(c, l)| Ok((l, Spectrum::of(&t.contact_force_n(c), dt, &FOURIER)?)))
        .collect::<Result<Vec<_>, woodpile::Error>>()?;
        let refs: Vec<(String, &Spectrum)> = spectra.iter().map(|(l, s)| (l.clone(), s)).collect();
        let files = plot::spectra(&refs, &self.bands, title, max_hz, stem)?;
        self.files.push(files);
        Ok(())
    }
}

/// The report's spectra: Fourier-transform magnitudes \[N/Hz\], comparable across record lengths.
pub const FOURIER: SpectrumSettings = SpectrumSettings {
    scaling: woodpile::analysis::Scaling::FourierMagnitude,
    window: woodpile::analysis::Window::Rectangular,
    padding: woodpile::analysis::Padding::None,
    remove_mean: false,
};

/// How a reference value is read and compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// A force \[N\], shown with one decimal; compared in percent of the paper's value.
    ForceN,
    /// A fraction, shown in percent with one decimal; compared in percentage points.
    Fraction,
    /// A dimensionless coefficient, shown with four decimals; compared in percent.
    Coefficient,
    /// A time \[s\], shown in ms; compared in percent.
    DurationS,
}

/// One number the paper reports (docs/physics.md §9), stated once; its text is derived from
/// the number ([`PaperValue::text`]), so the two cannot disagree.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperValue {
    /// What it is.
    pub what: &'static str,
    /// The value, in SI units (a fraction for percentages).
    pub value: f64,
    /// How to read and compare it.
    pub quantity: Quantity,
    /// Whether the paper gives it only approximately ("~70 %").
    pub approximate: bool,
}

impl PaperValue {
    /// A value the paper states exactly.
    pub const fn new(what: &'static str, value: f64, quantity: Quantity) -> Self {
        PaperValue {
            what,
            value,
            quantity,
            approximate: false,
        }
    }

    /// The value as the paper states it.
    pub fn text(&self) -> String {
        let number = match self.quantity {
            Quantity::ForceN => format!("{:.1} N", self.value),
            // "~70 %": an approximate value is stated to the percent.
            Quantity::Fraction if self.approximate => format!("{:.0} %", 100.0 * self.value),
            Quantity::Fraction => format!("{:.1} %", 100.0 * self.value),
            Quantity::Coefficient => format!("{:.4}", self.value),
            Quantity::DurationS => format!("{} ms", self.value * 1e3),
        };
        if self.approximate {
            format!("~{number}")
        } else {
            number
        }
    }

    /// A measured value in the same form as [`PaperValue::text`].
    pub fn format(&self, ours: f64) -> String {
        PaperValue {
            value: ours,
            approximate: false,
            ..*self
        }
        .text()
    }

    /// Our value against the paper's: percent of the paper's value, or percentage points for a
    /// fraction.
    pub fn difference(&self, ours: f64) -> String {
        match self.quantity {
            Quantity::Fraction => format!("{:+.1} pp", 100.0 * (ours - self.value)),
            _ => format!("{:+.1} %", 100.0 * (ours - self.value) / self.value),
        }
    }
}

/// The rows of the comparison table: quantity, the paper's value, ours, the difference, why
/// they differ.
#[derive(Debug, Default)]
pub struct Comparison {
    /// The rows so far.
    pub rows: Vec<Vec<String>>,
}

impl Comparison {
    /// A row as given.
    pub fn row(&mut self, what: &str, paper: String, ours: String, diff: String, why: &str) {
        let cells = [what.to_string(), paper, ours, diff, why.to_string()];
        self.rows.push(cells.to_vec());
    }

    /// A paper value beside ours (n/a when ours is not defined).
    pub fn value(&mut self, p: PaperValue, ours: f64, why: &str) {
        let (text, diff) = if ours.is_finite() {
            (p.format(ours), p.difference(ours))
        } else {
            ("n/a".to_string(), "–".to_string())
        };
        self.row(p.what, p.text(), text, diff, why);
    }
}

/// The transmission ratio, NaN (printed as such) when the run gives none.
pub fn ratio(s: &RunSummary) -> f64 {
    s.transmission_ratio.unwrap_or(f64::NAN)
}

/// A fraction in percent; n/a for a value that is not defined (NaN).
pub fn pct(x: f64) -> String {
    if !x.is_finite() {
        return "n/a".to_string();
    }
    format!("{:.1} %", 100.0 * x)
}

/// Rod lengths separated by spaces: `80 70 20`.
pub fn join_mm(rods: &[u32]) -> String {
    rods.iter()
        .map(u32::to_string)
        .collect::<Vec<_>>()
        .join(" ")
}

/// Mean rod length of the rods `range` of a chain (clamped to its length) \[mm\].
pub fn mean_length_mm(rods_mm: &[u32], range: std::ops::Range<usize>) -> f64 {
    let rods = &rods_mm[range.start.min(rods_mm.len())..range.end.min(rods_mm.len())];
    rods.iter().map(|&r| f64::from(r)).sum::<f64>() / rods.len().max(1) as f64
}

/// Where the energy of an impact sits at the end of the run: the layer holding the largest
/// share of the initial energy, and the striker's share.
pub fn energy_held_text(t: &Trajectory) -> String {
    let (Some(&e0), Some(&t_end)) = (t.total_energy_j().first(), t.times_s.last()) else {
        return "the energy's path through the chain".to_string();
    };
    if e0 <= 0.0 {
        return "the energy's path through the chain".to_string();
    }
    let last = |layer: usize| t.layer_energy_j(layer).last().copied().unwrap_or(0.0) / e0;
    let (layer, share) = (1..t.n_contacts())
        .map(|l| (l, last(l)))
        .fold((0, f64::NEG_INFINITY), |a, b| if b.1 > a.1 { b } else { a });
    format!(
        "at {:.1} ms the striker carries {:.1} % of the initial energy, and layer {layer}, the element holding most, {:.1} %",
        t_end * 1e3,
        100.0 * last(0),
        100.0 * share
    )
}
