//! `woodpile report --out DIR [--quick] [--seed S] [--threads T]`: runs everything the paper's
//! figures and numbers need, draws every figure into `DIR/figures/` (PNG and SVG), and writes
//! `DIR/report.md` and a self-contained `DIR/report.html` (figures embedded as data URIs) with a
//! comparison table: each number the paper reports (docs/physics.md §9) beside ours.
//!
//! What runs (docs/physics.md defaults throughout):
//! - homogeneous 20-rod chains of 20, 40, 80 mm rods (resonant) and 20 mm (rigid) under the
//!   impact: force and energy maps, force histories, spectra, the separated pulses at the wall
//!   (paper Figs. 5 a–c, 6);
//! - the breeder GA for the least wall force under the impact, resonant and rigid (paper Fig. 5
//!   d, e): convergence, best chain, incident and transmitted force, restitution;
//! - the layer-by-layer protocol on the resonant optimum (paper Fig. 7 a, b);
//! - the Friedlander blast on 20, 40, 80 mm chains and the paper's blast-optimised chain: peak
//!   energy of the last layer, spectra against the negative-mass bands (paper Figs. 8, 9);
//! - the effective-mass curves of the catalogue (paper Fig. 3).
//!
//! The GA results, the only expensive part, are kept in `DIR/cache/` under a stable FNV-1a hash
//! of the tool version and the complete problem (config, GA settings, seed); a rerun reuses
//! them. Everything else is re-simulated (well under a second per run). `report.md` and
//! `report.html` are written under a temporary name and renamed, so a failed run never leaves a
//! half-written report.

use crate::commands::Context;
use crate::plot_cmd::plot_err;
use crate::plot_cmd::{cells_figures, objective_label};
use crate::CliError;
use base64::Engine as _;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::fs;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::time::Instant;
use woodpile::analysis::{
    contact_spectrum_map, energy_map, force_map, layer_by_layer, Spectrum, SpectrumSettings,
};
use woodpile::optimize::{BreederGa, GaState, Objective};
use woodpile::{
    simulate, BlastProfile, CellModel, Chain, ChainBuilder, Excitation, RunSettings, RunSummary,
    Striker, Trajectory, UnitCell,
};
use woodpile_io::atomic::write_atomic;
use woodpile_io::optimize::{fnv1a64, OptimizeConfig, Problem};
use woodpile_io::scenario::ModelSpec;
use woodpile_plot as plot;

/// Tag of the cache entries' format (part of every key).
const CACHE_FORMAT: &str = "woodpile-report-cache/1";

/// Arguments of `woodpile report`.
#[derive(Debug, Clone, clap::Args)]
pub struct Args {
    /// Output directory: report.md, report.html, figures/, cache/ (created; a directory that
    /// holds anything else than an earlier report is refused).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// A smaller version for CI: GA of population 20 × 10 generations (the figures keep their
    /// meaning; the optimum is not converged).
    #[arg(long)]
    pub quick: bool,
    /// Seed of both GAs.
    #[arg(long, value_name = "S", default_value_t = 1)]
    pub seed: u64,
    /// Worker threads (default: one per core). Does not change results.
    #[arg(long, value_name = "T", default_value_t = 0)]
    pub threads: usize,
    /// Allow more than 4 worker threads per core.
    #[arg(long)]
    pub allow_many_threads: bool,
}

// ---------------------------------------------------------------------------------------------
// The document: blocks rendered to Markdown and to HTML.

/// One block of the report.
#[derive(Debug, Clone)]
enum Block {
    /// Section heading (level 2 or 3) with its anchor.
    Heading(u8, String),
    /// Paragraph; `code` spans in backticks.
    Para(String),
    /// Bulleted list.
    List(Vec<String>),
    /// Table: header and rows.
    Table(Vec<String>, Vec<Vec<String>>),
    /// Figure: path relative to the report, caption.
    Figure(String, String),
    /// Preformatted text.
    Code(String),
}

/// The report being assembled, and the figures it names.
#[derive(Debug, Default)]
struct Doc {
    blocks: Vec<Block>,
    figures: usize,
}

impl Doc {
    fn h2(&mut self, t: impl Into<String>) {
        self.blocks.push(Block::Heading(2, t.into()));
    }
    fn h3(&mut self, t: impl Into<String>) {
        self.blocks.push(Block::Heading(3, t.into()));
    }
    fn p(&mut self, t: impl Into<String>) {
        self.blocks.push(Block::Para(t.into()));
    }
    fn list(&mut self, items: Vec<String>) {
        self.blocks.push(Block::List(items));
    }
    fn table(&mut self, header: &[&str], rows: Vec<Vec<String>>) {
        self.blocks.push(Block::Table(
            header.iter().map(|s| s.to_string()).collect(),
            rows,
        ));
    }
    fn code(&mut self, t: impl Into<String>) {
        self.blocks.push(Block::Code(t.into()));
    }
    /// A figure: `files` as returned by a plot function (the PNG is shown, the SVG linked).
    fn figure(&mut self, files: &[PathBuf], root: &Path, caption: impl Into<String>) {
        if let Some(png) = files
            .iter()
            .find(|f| f.extension().is_some_and(|e| e == "png"))
        {
            let rel = png.strip_prefix(root).unwrap_or(png);
            let rel = rel.to_string_lossy().replace('\\', "/");
            self.figures += 1;
            self.blocks.push(Block::Figure(
                rel,
                format!("Figure {}. {}", self.figures, caption.into()),
            ));
        }
    }

    fn anchor(title: &str) -> String {
        let mut a = String::new();
        for c in title.chars() {
            if c.is_ascii_alphanumeric() {
                a.push(c.to_ascii_lowercase());
            } else if !a.ends_with('-') && !a.is_empty() {
                a.push('-');
            }
        }
        a.trim_end_matches('-').to_string()
    }

    fn markdown(&self, title: &str) -> String {
        let mut s = format!("# {title}\n\n## Contents\n\n");
        for b in &self.blocks {
            if let Block::Heading(2, t) = b {
                let _ = writeln!(s, "- [{t}](#{})", Self::anchor(t));
            }
        }
        s.push('\n');
        for b in &self.blocks {
            match b {
                Block::Heading(l, t) => {
                    let _ = writeln!(s, "{} {t}\n", "#".repeat(usize::from(*l)));
                }
                Block::Para(t) => {
                    let _ = writeln!(s, "{t}\n");
                }
                Block::List(items) => {
                    for i in items {
                        let _ = writeln!(s, "- {i}");
                    }
                    s.push('\n');
                }
                Block::Table(h, rows) => {
                    let _ = writeln!(s, "| {} |", h.join(" | "));
                    let _ = writeln!(s, "|{}", " --- |".repeat(h.len()));
                    for r in rows {
                        let cells: Vec<String> = r.iter().map(|c| c.replace('|', "\\|")).collect();
                        let _ = writeln!(s, "| {} |", cells.join(" | "));
                    }
                    s.push('\n');
                }
                Block::Figure(path, caption) => {
                    let svg = path.trim_end_matches(".png").to_string() + ".svg";
                    let _ = writeln!(s, "![{caption}]({path})\n\n*{caption}* ([SVG]({svg}))\n");
                }
                Block::Code(t) => {
                    let _ = writeln!(s, "```\n{t}\n```\n");
                }
            }
        }
        s
    }

    fn html(&self, title: &str, root: &Path) -> Result<String, CliError> {
        let mut s =
            String::from("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n");
        let _ = writeln!(s, "<title>{}</title>", escape(title));
        s.push_str(STYLE);
        s.push_str("</head>\n<body>\n<nav>\n<h2>Contents</h2>\n<ol>\n");
        for b in &self.blocks {
            if let Block::Heading(2, t) = b {
                let _ = writeln!(
                    s,
                    "<li><a href=\"#{}\">{}</a></li>",
                    Self::anchor(t),
                    inline(t)
                );
            }
        }
        s.push_str("</ol>\n</nav>\n<main>\n");
        let _ = writeln!(s, "<h1>{}</h1>", escape(title));
        for b in &self.blocks {
            match b {
                Block::Heading(l, t) => {
                    let _ = writeln!(s, "<h{l} id=\"{}\">{}</h{l}>", Self::anchor(t), inline(t));
                }
                Block::Para(t) => {
                    let _ = writeln!(s, "<p>{}</p>", inline(t));
                }
                Block::List(items) => {
                    s.push_str("<ul>\n");
                    for i in items {
                        let _ = writeln!(s, "<li>{}</li>", inline(i));
                    }
                    s.push_str("</ul>\n");
                }
                Block::Table(h, rows) => {
                    s.push_str("<div class=\"table\"><table>\n<thead><tr>");
                    for c in h {
                        let _ = write!(s, "<th>{}</th>", inline(c));
                    }
                    s.push_str("</tr></thead>\n<tbody>\n");
                    for r in rows {
                        s.push_str("<tr>");
                        for c in r {
                            let _ = write!(s, "<td>{}</td>", inline(c));
                        }
                        s.push_str("</tr>\n");
                    }
                    s.push_str("</tbody></table></div>\n");
                }
                Block::Figure(path, caption) => {
                    let file = root.join(path);
                    let bytes = fs::read(&file).map_err(|e| CliError::Read {
                        path: file.clone(),
                        source: e,
                    })?;
                    let data = base64::engine::general_purpose::STANDARD.encode(bytes);
                    let _ = writeln!(
                        s,
                        "<figure data-file=\"{path}\"><img src=\"data:image/png;base64,{data}\" alt=\"{}\"><figcaption>{} <span class=\"file\">({path})</span></figcaption></figure>",
                        escape(caption),
                        inline(caption)
                    );
                }
                Block::Code(t) => {
                    let _ = writeln!(s, "<pre>{}</pre>", escape(t));
                }
            }
        }
        s.push_str("</main>\n</body>\n</html>\n");
        Ok(s)
    }
}

const STYLE: &str = "<style>
body { font-family: -apple-system, 'Segoe UI', Helvetica, Arial, sans-serif; margin: 0; color: #222; line-height: 1.5; }
nav { position: fixed; top: 0; left: 0; width: 16rem; height: 100vh; overflow-y: auto; background: #f4f5f7; border-right: 1px solid #ddd; padding: 1rem; box-sizing: border-box; font-size: 0.9rem; }
nav h2 { font-size: 1rem; margin-top: 0; }
nav ol { padding-left: 1.2rem; }
main { margin-left: 17rem; max-width: 70rem; padding: 1rem 2rem 4rem; }
h1 { border-bottom: 2px solid #2b5797; padding-bottom: .3rem; }
h2 { border-bottom: 1px solid #ccc; padding-bottom: .2rem; margin-top: 2.5rem; }
code, pre { font-family: 'DejaVu Sans Mono', Menlo, Consolas, monospace; background: #f1f1f1; border-radius: 3px; }
code { padding: 0 .25rem; }
pre { padding: .6rem; overflow-x: auto; }
div.table { overflow-x: auto; }
table { border-collapse: collapse; margin: 1rem 0; font-size: 0.9rem; }
th, td { border: 1px solid #ccc; padding: .3rem .6rem; text-align: left; vertical-align: top; }
th { background: #e8ecf3; }
tr:nth-child(even) td { background: #fafafa; }
figure { margin: 1.5rem 0; }
figure img { max-width: 100%; border: 1px solid #ddd; }
figcaption { font-size: 0.9rem; color: #444; }
figcaption .file { color: #888; }
@media (max-width: 60rem) { nav { position: static; width: auto; height: auto; } main { margin-left: 0; } }
</style>
";

fn escape(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Escapes and turns `code` spans into `<code>`.
fn inline(t: &str) -> String {
    escape(t)
        .split('`')
        .enumerate()
        .map(|(i, part)| {
            if i % 2 == 1 {
                format!("<code>{part}</code>")
            } else {
                part.to_string()
            }
        })
        .collect()
}

// ---------------------------------------------------------------------------------------------
// The cache: FNV-1a of the tool version, the entry kind and the complete inputs as JSON.

/// A GA result as kept in the cache.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct CachedGa {
    /// The key's text (tool version, format, inputs): checked on load against collisions.
    inputs: String,
    best_genome: Vec<u8>,
    best_objective: f64,
    history: Vec<woodpile::optimize::GenerationStats>,
    generations: usize,
    evaluations: u64,
    cache_hits: u64,
    elapsed_s: f64,
    stop_reason: String,
}

struct Cache {
    dir: PathBuf,
}

impl Cache {
    fn key_text(kind: &str, inputs: &impl Serialize) -> String {
        format!(
            "woodpile {} {CACHE_FORMAT} {kind}\n{}",
            env!("CARGO_PKG_VERSION"),
            serde_json::to_string(inputs).unwrap_or_default()
        )
    }

    fn file(&self, text: &str) -> (PathBuf, String) {
        let name = format!("{:016x}.json", fnv1a64(text.as_bytes()));
        (self.dir.join(&name), name)
    }

    /// The cached GA for these inputs, if an entry with exactly this key text exists.
    fn get(&self, text: &str) -> Option<CachedGa> {
        let (path, _) = self.file(text);
        let entry: CachedGa = serde_json::from_str(&fs::read_to_string(path).ok()?).ok()?;
        (entry.inputs == text).then_some(entry)
    }

    fn put(&self, entry: &CachedGa) -> Result<(), CliError> {
        let (path, name) = self.file(&entry.inputs);
        let json = serde_json::to_vec(entry).map_err(|e| CliError::Output {
            path,
            source: std::io::Error::other(e),
        })?;
        write_atomic(&self.dir, &name, &json)
    }
}

// ---------------------------------------------------------------------------------------------
// Measurements.

/// First time the force exceeds `frac` of its maximum \[s\].
pub fn arrival_s(times_s: &[f64], force_n: &[f64], frac: f64) -> Option<f64> {
    let max = force_n.iter().copied().fold(0.0, f64::max);
    (max > 0.0)
        .then(|| force_n.iter().position(|&f| f > frac * max))
        .flatten()
        .map(|i| times_s[i])
}

/// Separated peaks of a force history inside [t0, t1]: local maxima of at least `keep` times the
/// window's maximum, where two neighbouring maxima count as one unless the force between them
/// falls below half the smaller of the two. Returns (time \[s\], force \[N\]) of each peak.
pub fn separated_peaks(
    times_s: &[f64],
    force_n: &[f64],
    t0: f64,
    t1: f64,
    keep: f64,
) -> Vec<(f64, f64)> {
    let idx: Vec<usize> = (0..force_n.len())
        .filter(|&i| times_s[i] >= t0 && times_s[i] <= t1)
        .collect();
    let (Some(&first), Some(&last)) = (idx.first(), idx.last()) else {
        return Vec::new();
    };
    let max = idx.iter().map(|&i| force_n[i]).fold(0.0, f64::max);
    let mut kept: Vec<usize> = Vec::new();
    for i in first..=last {
        let f = force_n[i];
        let left = if i > first {
            force_n[i - 1]
        } else {
            f64::NEG_INFINITY
        };
        let right = if i < last {
            force_n[i + 1]
        } else {
            f64::NEG_INFINITY
        };
        if !(f >= keep * max && f > left && f >= right) {
            continue;
        }
        if let Some(&k) = kept.last() {
            let dip = force_n[k..=i].iter().copied().fold(f64::INFINITY, f64::min);
            if dip > 0.5 * force_n[k].min(f) {
                // Not separated: one peak, the larger.
                if f > force_n[k] {
                    *kept.last_mut().expect("non-empty") = i;
                }
                continue;
            }
        }
        kept.push(i);
    }
    kept.into_iter().map(|i| (times_s[i], force_n[i])).collect()
}

/// The transmitted wave of an impact at the wall during its first transit.
#[derive(Debug, Clone)]
struct WaveAtWall {
    name: String,
    /// First arrival at contact 1 and at the wall \[s\].
    arrival_top_s: f64,
    arrival_wall_s: f64,
    /// Separated peaks at the wall within one transit time after the arrival.
    peaks: Vec<(f64, f64)>,
}

impl WaveAtWall {
    fn of(name: &str, t: &Trajectory) -> Self {
        let n = t.n_elements;
        let wall = t.contact_force_n(n);
        let a1 = arrival_s(&t.times_s, &t.contact_force_n(1), 0.05).unwrap_or(0.0);
        let aw = arrival_s(&t.times_s, &wall, 0.05).unwrap_or(0.0);
        WaveAtWall {
            name: name.to_string(),
            arrival_top_s: a1,
            arrival_wall_s: aw,
            peaks: separated_peaks(&t.times_s, &wall, aw, aw + (aw - a1), 0.05),
        }
    }

    /// Time between the two largest peaks \[s\].
    fn main_gap_s(&self) -> Option<f64> {
        let mut p = self.peaks.clone();
        p.sort_by(|a, b| b.1.total_cmp(&a.1));
        (p.len() >= 2).then(|| (p[1].0 - p[0].0).abs())
    }

    /// The second largest peak over the largest.
    fn second_ratio(&self) -> Option<f64> {
        let mut f: Vec<f64> = self.peaks.iter().map(|p| p.1).collect();
        f.sort_by(|a, b| b.total_cmp(a));
        (f.len() >= 2).then(|| f[1] / f[0])
    }
}

/// Mean spectral amplitude of the contacts 1..N inside `band` over that in the two flanking
/// intervals of half its width: < 1 where the band carries less than its neighbourhood.
fn band_contrast(t: &Trajectory, band: (f64, f64)) -> Result<f64, CliError> {
    let map = contact_spectrum_map(t, &SpectrumSettings::default())?;
    let f = &map.cols.values;
    let w = band.1 - band.0;
    let mean = |lo: f64, hi: f64| {
        let mut sum = 0.0;
        let mut n = 0usize;
        for row in 1..map.n_rows() {
            for (c, &fc) in f.iter().enumerate() {
                if fc >= lo && fc <= hi {
                    sum += map.at(row, c);
                    n += 1;
                }
            }
        }
        if n == 0 {
            f64::NAN
        } else {
            sum / n as f64
        }
    };
    let inside = mean(band.0, band.1);
    let flanks = 0.5 * (mean(band.0 - 0.5 * w, band.0) + mean(band.1, band.1 + 0.5 * w));
    Ok(inside / flanks)
}

/// Peak energy of layer `layer` over the run \[J\].
fn peak_layer_energy(t: &Trajectory, layer: usize) -> f64 {
    t.layer_energy_j(layer).into_iter().fold(0.0, f64::max)
}

fn mean_mm(rods: &[u32]) -> f64 {
    rods.iter().map(|&r| f64::from(r)).sum::<f64>() / rods.len().max(1) as f64
}

/// Fraction of interior positions whose rod is longer or shorter than both neighbours (1 for a
/// strictly alternating heavy/light chain).
fn alternation(rods: &[u32]) -> f64 {
    if rods.len() < 3 {
        return 0.0;
    }
    let n = rods
        .windows(3)
        .filter(|w| (w[1] > w[0] && w[1] > w[2]) || (w[1] < w[0] && w[1] < w[2]))
        .count();
    n as f64 / (rods.len() - 2) as f64
}

fn rods_mm(chain: &Chain) -> Vec<u32> {
    chain
        .elements()
        .iter()
        .map(|e| match e.body {
            woodpile::Body::Rod { length_m, .. } => (length_m * 1e3).round() as u32,
            woodpile::Body::Sphere { diameter_m } => (diameter_m * 1e3).round() as u32,
        })
        .collect()
}

/// The transmission ratio, NaN (printed as such) when the run gives none.
fn ratio(s: &RunSummary) -> f64 {
    s.transmission_ratio.unwrap_or(f64::NAN)
}

fn pct(x: f64) -> String {
    format!("{:.1} %", 100.0 * x)
}

fn rel_diff(ours: f64, paper: f64) -> String {
    format!("{:+.1} %", 100.0 * (ours - paper) / paper)
}

fn pp_diff(ours: f64, paper: f64) -> String {
    format!("{:+.1} pp", 100.0 * (ours - paper))
}

fn join_mm(rods: &[u32]) -> String {
    rods.iter()
        .map(u32::to_string)
        .collect::<Vec<_>>()
        .join(" ")
}

// ---------------------------------------------------------------------------------------------
// The runs.

/// One simulated chain with what the report needs of it.
struct Case {
    /// Short name, e.g. `20 mm`.
    name: String,
    /// File stem part, e.g. `20mm`.
    slug: String,
    /// Title part naming the chain, e.g. `20 × 20 mm rods (resonant)`.
    chain_title: String,
    chain: Chain,
    summary: RunSummary,
    trajectory: Trajectory,
    /// Negative-mass bands of the chain's cells (when it has at most two kinds).
    bands: Vec<(f64, f64)>,
}

fn homogeneous(length_mm: u32, model: CellModel) -> Result<Chain, CliError> {
    Ok(ChainBuilder::table1_rods(&[length_mm; 20], model)?.build()?)
}

fn simulate_case(
    name: &str,
    slug: &str,
    chain_title: &str,
    chain: Chain,
    excitation: &Excitation,
    settings: &RunSettings,
) -> Result<Case, CliError> {
    let mut trajectory = Trajectory::default();
    let summary = simulate(&chain, excitation, settings, &mut trajectory)?;
    let mut cells: Vec<&UnitCell> = Vec::new();
    for e in chain.elements() {
        if !cells.contains(&&e.cell) {
            cells.push(&e.cell);
        }
    }
    let bands = if cells.len() <= 2 {
        let mut b: Vec<(f64, f64)> = cells
            .iter()
            .flat_map(|c| c.negative_mass_bands_hz())
            .collect();
        b.sort_by(|a, b| a.0.total_cmp(&b.0));
        b
    } else {
        Vec::new()
    };
    Ok(Case {
        name: name.to_string(),
        slug: slug.to_string(),
        chain_title: chain_title.to_string(),
        chain,
        summary,
        trajectory,
        bands,
    })
}

/// Spectra of contact 1, the middle contact and the wall, with the chain's bands shaded.
fn draw_spectra(
    case: &Case,
    title: &str,
    max_hz: f64,
    stem: &Path,
) -> Result<Vec<PathBuf>, CliError> {
    let t = &case.trajectory;
    let n = t.n_elements;
    let dt = woodpile::analysis::sample_interval_s(t)?;
    let settings = SpectrumSettings::default();
    let spectra = [
        (1, "contact 1 (incident)".to_string()),
        (n / 2, format!("contact {} (middle)", n / 2)),
        (n, format!("contact {n} (wall)")),
    ]
    .into_iter()
    .map(|(c, l)| Ok((l, Spectrum::of(&t.contact_force_n(c), dt, &settings)?)))
    .collect::<Result<Vec<_>, woodpile::Error>>()?;
    let refs: Vec<(String, &Spectrum)> = spectra.iter().map(|(l, s)| (l.clone(), s)).collect();
    plot::spectra(&refs, &case.bands, title, max_hz, stem).map_err(plot_err)
}

/// A GA run (from the cache when it holds one for the same inputs).
struct GaRun {
    model: &'static str,
    chain: Chain,
    rods: Vec<u32>,
    cached: bool,
    result: CachedGa,
    population: usize,
    generations_limit: usize,
    stall: Option<usize>,
    objective: String,
    unit: String,
}

fn run_ga(
    model: ModelSpec,
    quick: bool,
    seed: u64,
    threads: usize,
    cache: &Cache,
    bar: &indicatif::ProgressBar,
) -> Result<GaRun, CliError> {
    let mut cfg = OptimizeConfig::builtin("paper-impact")?;
    cfg.design.model = Some(model);
    cfg.ga.seed = Some(seed);
    if quick {
        cfg.ga.population = Some(20);
        cfg.ga.generations = Some(10);
    }
    let problem = Problem::new(&cfg, Path::new("."), threads)?;
    let model_name = match model {
        ModelSpec::Resonant => "resonant",
        ModelSpec::Rigid => "rigid",
    };
    let key = Cache::key_text("ga", &problem.config);
    let objective = problem.objective;
    let (result, cached) = match cache.get(&key) {
        Some(entry) if entry.best_genome.len() == problem.space.positions => (entry, true),
        _ => {
            let ga = BreederGa::new(problem.space.clone(), Box::new(objective), problem.settings)
                .map_err(|e| CliError::invalid("ga", "(report)", e.to_string()))?;
            let total = problem.settings.generations;
            let unit = objective.unit().to_string();
            let mut observer = |s: &GaState| {
                bar.set_message(format!(
                    "{model_name} GA: generation {}/{total}, best {:.3} {unit}, {} evaluations",
                    s.generation,
                    s.best().objective,
                    s.evaluations
                ));
                ControlFlow::Continue(())
            };
            let outcome = ga
                .run(None, &AtomicBool::new(false), &mut observer)
                .map_err(|e| match e {
                    woodpile::optimize::OptimizeError::Simulation { source, .. } => {
                        CliError::Model(source)
                    }
                    other => CliError::invalid("ga", "(report)", other.to_string()),
                })?;
            let s = &outcome.state;
            let entry = CachedGa {
                inputs: key.clone(),
                best_genome: s.best().genome.clone(),
                best_objective: s.best().objective,
                history: s.history.clone(),
                generations: s.generation,
                evaluations: s.evaluations,
                cache_hits: s.cache_hits,
                elapsed_s: s.elapsed_s,
                stop_reason: format!("{:?}", outcome.reason),
            };
            cache.put(&entry)?;
            (entry, false)
        }
    };
    let chain = problem.space.chain(&result.best_genome)?;
    Ok(GaRun {
        model: model_name,
        rods: rods_mm(&chain),
        chain,
        cached,
        result,
        population: problem.settings.population,
        generations_limit: problem.settings.generations,
        stall: problem.settings.stall_generations,
        objective: objective.as_str().to_string(),
        unit: objective.unit().to_string(),
    })
}

// ---------------------------------------------------------------------------------------------
// The command.

/// Checks that `out` can hold the report: created if absent; an existing directory must be
/// empty or hold an earlier report.
fn prepare_out(out: &Path) -> Result<(), CliError> {
    let io = |e: std::io::Error| CliError::Output {
        path: out.to_path_buf(),
        source: e,
    };
    if out.exists() && !out.is_dir() {
        return Err(CliError::invalid(
            "--out",
            out.display(),
            "is a file, not a directory; choose a directory",
        ));
    }
    if out.is_dir() {
        let mut entries = fs::read_dir(out).map_err(io)?;
        let known = ["report.md", "report.html", "figures", "cache"];
        let earlier = known.iter().any(|k| out.join(k).exists());
        if entries.next().is_some() && !earlier {
            return Err(CliError::invalid(
                "--out",
                out.display(),
                "exists, is not empty and holds no earlier report: refusing to write into it; choose another --out",
            ));
        }
    }
    for d in [out.to_path_buf(), out.join("figures"), out.join("cache")] {
        fs::create_dir_all(&d).map_err(|e| CliError::Output { path: d, source: e })?;
    }
    // Prove the directory is writable before any work is done.
    write_atomic(out, ".write-test", b"")?;
    let _ = fs::remove_file(out.join(".write-test"));
    Ok(())
}

/// Runs `woodpile report`.
pub fn run(args: &Args, ctx: &Context) -> Result<(), CliError> {
    let started = Instant::now();
    woodpile_io::limits::check_threads("--threads", args.threads, args.allow_many_threads)?;
    prepare_out(&args.out)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads)
        .build()
        .map_err(|e| CliError::invalid("--threads", args.threads, e.to_string()))?;
    let bar = if ctx.quiet {
        indicatif::ProgressBar::hidden()
    } else {
        let bar = indicatif::ProgressBar::new(STEPS);
        if let Ok(style) = indicatif::ProgressStyle::with_template(
            "report {pos}/{len} [{bar:25}] {elapsed} | {msg}",
        ) {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.enable_steady_tick(std::time::Duration::from_millis(200));
        bar
    };
    let result = pool.install(|| build(args, &bar));
    bar.finish_and_clear();
    let (doc, summary) = result?;
    let title = "woodpile: reproduction of Kim, Yang et al. 2017 (impact and blast mitigation with locally resonant woodpiles)";
    let md = doc.markdown(title);
    let html = doc.html(title, &args.out)?;
    write_atomic(&args.out, "report.md", md.as_bytes())?;
    write_atomic(&args.out, "report.html", html.as_bytes())?;
    if !ctx.quiet {
        println!("{summary}");
        println!(
            "wrote {} figures, {} and {} in {:.1} s",
            doc.figures,
            args.out.join("report.md").display(),
            args.out.join("report.html").display(),
            started.elapsed().as_secs_f64()
        );
    }
    Ok(())
}

/// Progress steps: 4 impact chains, 2 GAs, optimum figures, protocol, 4 blast chains, cells.
const STEPS: u64 = 13;

/// Runs everything and assembles the document; returns it and a short text summary.
fn build(args: &Args, bar: &indicatif::ProgressBar) -> Result<(Doc, String), CliError> {
    let out = args.out.as_path();
    let figs = out.join("figures");
    let fig = |name: &str| figs.join(name);
    let cache = Cache {
        dir: out.join("cache"),
    };
    let mut doc = Doc::default();
    let impact = Excitation::Impact(Striker::paper());
    let impact_settings = RunSettings::paper_impact();
    let v0 = Striker::paper().velocity_m_s;
    let impact_text = format!("impact of a 10 mm glass sphere at {v0:.2} m/s");
    let blast = Excitation::Blast(BlastProfile::paper());
    let blast_settings = RunSettings::paper_blast();
    let blast_text = "Friedlander blast 200 N / 0.2 ms";
    let max_hz = 80e3;

    // --- Homogeneous chains under impact ---------------------------------------------------
    bar.set_message("homogeneous chains under impact");
    let specs = [
        (20, CellModel::Resonant, "20 mm", "20mm"),
        (40, CellModel::Resonant, "40 mm", "40mm"),
        (80, CellModel::Resonant, "80 mm", "80mm"),
        (20, CellModel::Rigid, "20 mm rigid", "20mm_rigid"),
    ];
    let impact_cases: Vec<(Case, Vec<Vec<PathBuf>>)> = specs
        .par_iter()
        .map(|&(l, model, name, slug)| {
            let model_name = if model == CellModel::Rigid {
                "rigid"
            } else {
                "resonant"
            };
            let chain_title = format!("20 × {l} mm rods ({model_name})");
            let case = simulate_case(
                name,
                slug,
                &chain_title,
                homogeneous(l, model)?,
                &impact,
                &impact_settings,
            )?;
            let title = format!("{chain_title}, {impact_text}");
            let t = &case.trajectory;
            let n = t.n_elements;
            let mut files = Vec::new();
            files.push(
                plot::force_map(
                    &force_map(t)?,
                    &title,
                    &fig(&format!("impact_{slug}_force_map")),
                )
                .map_err(plot_err)?,
            );
            files.push(
                plot::energy_map(
                    &energy_map(t)?,
                    &title,
                    &fig(&format!("impact_{slug}_energy_map")),
                )
                .map_err(plot_err)?,
            );
            let series = [
                (0, "contact 0 (striker)".to_string()),
                (1, "contact 1 (incident)".to_string()),
                (n / 2, format!("contact {} (middle)", n / 2)),
                (n, format!("contact {n} (wall)")),
            ]
            .map(|(c, l)| plot::Series::new(l, t.contact_force_n(c)));
            files.push(
                plot::force_histories(
                    &t.times_s,
                    &series,
                    &title,
                    &fig(&format!("impact_{slug}_force_histories")),
                )
                .map_err(plot_err)?,
            );
            files.push(draw_spectra(
                &case,
                &title,
                max_hz,
                &fig(&format!("impact_{slug}_spectra")),
            )?);
            bar.inc(1);
            Ok((case, files))
        })
        .collect::<Result<Vec<_>, CliError>>()?;
    let wall_series: Vec<plot::Series> = impact_cases
        .iter()
        .map(|(c, _)| {
            plot::Series::new(
                format!("{}: wall (contact 20)", c.name),
                c.trajectory.contact_force_n(c.trajectory.n_elements),
            )
        })
        .collect();
    let wall_compare = plot::force_histories(
        &impact_cases[0].0.trajectory.times_s,
        &wall_series,
        &format!("Wall force of homogeneous 20-rod chains, {impact_text}"),
        &fig("impact_homogeneous_wall_forces"),
    )
    .map_err(plot_err)?;

    // Pulses at the wall and at the middle contact, first transit only: up to the arrival of
    // the first pulse at the wall plus 0.6 ms.
    let waves: Vec<WaveAtWall> = impact_cases
        .iter()
        .map(|(c, _)| WaveAtWall::of(&c.name, &c.trajectory))
        .collect();

    // --- GA optimisations under impact ------------------------------------------------------
    bar.set_message("resonant GA");
    let ga_res = run_ga(
        ModelSpec::Resonant,
        args.quick,
        args.seed,
        args.threads,
        &cache,
        bar,
    )?;
    bar.inc(1);
    bar.set_message("rigid GA");
    let ga_rig = run_ga(
        ModelSpec::Rigid,
        args.quick,
        args.seed,
        args.threads,
        &cache,
        bar,
    )?;
    bar.inc(1);
    bar.set_message("figures of the optima");
    let optima: Vec<(Case, Vec<Vec<PathBuf>>)> = [&ga_res, &ga_rig]
        .par_iter()
        .map(|ga| {
            let chain_title = format!("GA optimum ({}): {}", ga.model, join_mm(&ga.rods));
            let case = simulate_case(
                &format!("{} optimum", ga.model),
                &format!("optimum_{}", ga.model),
                &chain_title,
                ga.chain.clone(),
                &impact,
                &impact_settings,
            )?;
            let short = format!("GA optimum, {} model, {impact_text}", ga.model);
            let t = &case.trajectory;
            let n = t.n_elements;
            let slug = &case.slug;
            let points: Vec<plot::ConvergencePoint> = ga
                .result
                .history
                .iter()
                .map(|h| plot::ConvergencePoint {
                    generation: h.generation,
                    best: h.best,
                    mean: h.mean,
                })
                .collect();
            let mut files = Vec::new();
            files.push(
                plot::convergence(
                    &points,
                    &objective_label(&ga.objective, &ga.unit),
                    &format!(
                        "Breeder GA, 20 rods, {} model, impact (population {}, seed {})",
                        ga.model, ga.population, args.seed
                    ),
                    &fig(&format!("{slug}_convergence")),
                )
                .map_err(plot_err)?,
            );
            files.push(
                plot::chain_picture(
                    &case.chain,
                    &format!("GA optimum, {} model, impact", ga.model),
                    &fig(&format!("{slug}_chain")),
                )
                .map_err(plot_err)?,
            );
            let series = [
                (1, "contact 1: incident".to_string()),
                (n, format!("contact {n}: transmitted (wall)")),
            ]
            .map(|(c, l)| plot::Series::new(l, t.contact_force_n(c)));
            files.push(
                plot::force_histories(&t.times_s, &series, &short, &fig(&format!("{slug}_forces")))
                    .map_err(plot_err)?,
            );
            files.push(
                plot::force_map(&force_map(t)?, &short, &fig(&format!("{slug}_force_map")))
                    .map_err(plot_err)?,
            );
            Ok((case, files))
        })
        .collect::<Result<Vec<_>, CliError>>()?;
    bar.inc(1);

    // --- Layer-by-layer protocol on the resonant optimum ------------------------------------
    bar.set_message("layer-by-layer protocol");
    let res_case = &optima[0].0;
    let protocol = layer_by_layer(&res_case.chain, &impact, &impact_settings)?;
    let ptitle = format!("Layer-by-layer protocol, resonant GA optimum, {impact_text}");
    let protocol_map_files =
        plot::protocol_map(&protocol.wall_force_map, &ptitle, &fig("protocol_map"))
            .map_err(plot_err)?;
    let full_peaks = res_case.summary.contact_peak_forces_n[1..].to_vec();
    let protocol_peak_files = plot::peaks_per_layer(
        &[
            plot::Series::new(
                "protocol: wall force of the first k rods on the sensor",
                protocol.peak_wall_force_n.clone(),
            ),
            plot::Series::new("full chain: peak of contact k", full_peaks.clone()),
        ],
        &ptitle,
        "peak force [N]",
        &fig("protocol_peaks"),
    )
    .map_err(plot_err)?;
    bar.inc(1);

    // --- Blast -----------------------------------------------------------------------------
    bar.set_message("blast cases");
    let blast_specs: Vec<(Vec<u32>, &str, &str, String)> = vec![
        (
            vec![20; 20],
            "20 mm",
            "20mm",
            "20 × 20 mm rods (resonant)".to_string(),
        ),
        (
            vec![40; 20],
            "40 mm",
            "40mm",
            "20 × 40 mm rods (resonant)".to_string(),
        ),
        (
            vec![80; 20],
            "80 mm",
            "80mm",
            "20 × 80 mm rods (resonant)".to_string(),
        ),
        (
            woodpile::PAPER_OPTIMIZED_CHAIN_MM.to_vec(),
            "paper optimum",
            "paper_optimum",
            "paper's blast-optimised chain (resonant)".to_string(),
        ),
    ];
    let blast_cases: Vec<(Case, Vec<Vec<PathBuf>>)> = blast_specs
        .par_iter()
        .map(|(rods, name, slug, chain_title)| {
            let chain = ChainBuilder::table1_rods(rods, CellModel::Resonant)?.build()?;
            let case = simulate_case(name, slug, chain_title, chain, &blast, &blast_settings)?;
            let title = format!("{chain_title}, {blast_text}");
            let t = &case.trajectory;
            let mut files = Vec::new();
            files.push(
                plot::force_map(
                    &force_map(t)?,
                    &title,
                    &fig(&format!("blast_{slug}_force_map")),
                )
                .map_err(plot_err)?,
            );
            files.push(
                plot::energy_map(
                    &energy_map(t)?,
                    &title,
                    &fig(&format!("blast_{slug}_energy_map")),
                )
                .map_err(plot_err)?,
            );
            files.push(
                plot::spectrum_map(
                    &contact_spectrum_map(t, &SpectrumSettings::default())?,
                    &title,
                    max_hz,
                    &fig(&format!("blast_{slug}_spectrum_map")),
                )
                .map_err(plot_err)?,
            );
            files.push(draw_spectra(
                &case,
                &title,
                max_hz,
                &fig(&format!("blast_{slug}_spectra")),
            )?);
            bar.inc(1);
            Ok((case, files))
        })
        .collect::<Result<Vec<_>, CliError>>()?;
    let mut blast_series = vec![plot::Series::new(
        "load (contact 0)",
        blast_cases[0].0.trajectory.contact_force_n(0),
    )];
    for (c, _) in &blast_cases {
        blast_series.push(plot::Series::new(
            format!("{}: wall", c.name),
            c.trajectory.contact_force_n(c.trajectory.n_elements),
        ));
    }
    let blast_compare = plot::force_histories(
        &blast_cases[0].0.trajectory.times_s,
        &blast_series,
        &format!("Blast load and wall forces of the 20-rod chains, {blast_text}"),
        &fig("blast_wall_forces"),
    )
    .map_err(plot_err)?;
    let e_ref = peak_layer_energy(&blast_cases[0].0.trajectory, 20);
    let blast_energy: Vec<(String, f64, f64)> = blast_cases
        .iter()
        .map(|(c, _)| {
            let e = peak_layer_energy(&c.trajectory, c.trajectory.n_elements);
            (c.name.clone(), e, e / e_ref)
        })
        .collect();
    // Band contrast: the homogeneous chains' negative-mass bands.
    let mut band_rows = Vec::new();
    for (c, _) in blast_cases.iter().take(3) {
        for &b in &c.bands {
            band_rows.push((c.name.clone(), b, band_contrast(&c.trajectory, b)?));
        }
    }

    // --- Effective mass --------------------------------------------------------------------
    bar.set_message("effective-mass curves");
    let cells_files = cells_figures(&figs)?;
    bar.inc(1);

    // --- The document ----------------------------------------------------------------------
    bar.set_message("writing the report");
    let elapsed = bar.elapsed().as_secs_f64();
    let cr = &optima[0].0.summary;
    let cg = &optima[1].0.summary;
    let restitution = |s: &RunSummary| s.restitution.map_or(f64::NAN, |r| r.coefficient);
    let better = 1.0 - ratio(cr) / ratio(cg);
    let first5 = mean_mm(&ga_res.rods[..5]);
    let last5 = mean_mm(&ga_res.rods[15..]);
    doc.h2("How this report was made");
    doc.p(format!(
        "Command: `woodpile report --out {}{} --seed {}` (woodpile {}), {}{}. Every number below was measured by this tool (the GA results possibly by an earlier run of the same command, kept in cache/); the model and its defaults are docs/physics.md's (rods of fused quartz with the paper's Table 1 unit cells, Hertz contacts, fixed-step RK4 with dt = 0.1 µs, samples every 1 µs).",
        out.display(),
        if args.quick { " --quick" } else { "" },
        args.seed,
        env!("CARGO_PKG_VERSION"),
        match (ga_res.cached, ga_rig.cached) {
            (true, true) => "both GA results reused from cache/",
            (false, false) => "both GAs run now",
            _ => "one GA result reused from cache/, one GA run now",
        },
        if args.quick {
            " — QUICK version: the GAs ran with population 20 × 10 generations and are not converged, so the optimisation numbers are not the full report's"
        } else {
            ""
        },
    ));
    doc.list(vec![
        format!("Impact: {impact_text} (dropped from 0.20 m), run 2 ms; wall = stainless-steel spherical cap of radius 5 mm (assumed, docs/physics.md §5)."),
        format!("Blast: {blast_text} (Friedlander positive phase, docs/physics.md §6, parameters chosen by docs/physics.md), run 3 ms."),
        format!(
            "GA (docs/physics.md §11): population {}, at most {} generations, stall limit {}, truncation 0.3, one elite, seed {}, objective: peak wall force.",
            ga_res.population,
            ga_res.generations_limit,
            ga_res.stall.map_or("none".to_string(), |s| s.to_string()),
            args.seed
        ),
        format!("Wall-clock time of the runs: {elapsed:.1} s."),
    ]);

    doc.h2("Comparison with the paper");
    doc.p("Each number the paper reports (docs/physics.md §9) beside ours. Differences in percent are relative to the paper's value; `pp` are percentage points.");
    let reason_constants = "the paper's wall and striker contact constants were lost: we use a 5 mm steel cap and a soda-lime sphere (docs/physics.md §2, §5)";
    let reason_ga = if args.quick {
        "quick GA (20 × 10), not converged; GA settings of the paper unknown"
    } else {
        "the paper's GA settings (population, generations, seed) are unknown; another optimum of a rugged landscape"
    };
    let mut rows: Vec<Vec<String>> = Vec::new();
    let mut row = |what: &str, paper: String, ours: String, diff: String, reason: &str| {
        rows.push(vec![
            what.to_string(),
            paper,
            ours,
            diff,
            reason.to_string(),
        ]);
    };
    row(
        "Resonant optimum: transmitted (wall) force",
        "28.5 N".into(),
        format!("{:.1} N", cr.transmitted_peak_force_n),
        rel_diff(cr.transmitted_peak_force_n, 28.5),
        &format!("{reason_ga}; {reason_constants}"),
    );
    row(
        "Resonant optimum: incident force (contact 1)",
        "159.6 N".into(),
        format!("{:.1} N", cr.incident_peak_force_n),
        rel_diff(cr.incident_peak_force_n, 159.6),
        "depends on the top rods the GA chose and on the striker contact (lost constant)",
    );
    row(
        "Resonant optimum: transmitted / incident",
        "17.9 %".into(),
        pct(ratio(cr)),
        pp_diff(ratio(cr), 0.179),
        reason_ga,
    );
    row(
        "Rigid optimum: transmitted (wall) force",
        "85.5 N".into(),
        format!("{:.1} N", cg.transmitted_peak_force_n),
        rel_diff(cg.transmitted_peak_force_n, 85.5),
        &format!("{reason_ga}; {reason_constants}"),
    );
    row(
        "Rigid optimum: incident force (contact 1)",
        "148.4 N".into(),
        format!("{:.1} N", cg.incident_peak_force_n),
        rel_diff(cg.incident_peak_force_n, 148.4),
        "depends on the top rods the GA chose and on the striker contact (lost constant)",
    );
    row(
        "Rigid optimum: transmitted / incident",
        "57.6 %".into(),
        pct(ratio(cg)),
        pp_diff(ratio(cg), 0.576),
        reason_ga,
    );
    row(
        "Resonant better than rigid (1 − ratio_res / ratio_rigid)",
        "68.9 %".into(),
        pct(better),
        pp_diff(better, 0.689),
        "follows from the two ratios",
    );
    row(
        "Striker restitution, resonant optimum",
        "0.2570".into(),
        format!("{:.4}", restitution(cr)),
        rel_diff(restitution(cr), 0.2570),
        "set by the top rods of the optimum (ours differ) and the striker contact",
    );
    row(
        "Striker restitution, rigid optimum",
        "0.4991".into(),
        format!("{:.4}", restitution(cg)),
        rel_diff(restitution(cg), 0.4991),
        "set by the top rods of the optimum (ours differ) and the striker contact",
    );
    row(
        "Resonant optimum: long rods on top, short at the bottom (mean of first / last five rods)",
        "80, 70 mm on top; 20–40 mm at the bottom".into(),
        format!("{first5:.0} mm / {last5:.0} mm"),
        "–".into(),
        "qualitative in the paper",
    );
    row(
        "Rigid optimum alternates heavy and light rods (share of rods longer or shorter than both neighbours)",
        "alternating".into(),
        format!("{:.0} %", 100.0 * alternation(&ga_rig.rods)),
        "–".into(),
        "qualitative in the paper",
    );
    for w in &waves[..3] {
        let paper = match w.name.as_str() {
            "20 mm" => "one solitary wave with a small oscillating tail",
            "40 mm" => "wave split into groups separated in time",
            _ => "two groups ~0.2 ms apart",
        };
        let ours = format!(
            "{} separated peak(s) at the wall in the first transit{}{}",
            w.peaks.len(),
            w.second_ratio().map_or(String::new(), |r| format!(
                "; second largest {:.0} % of the largest",
                100.0 * r
            )),
            w.main_gap_s()
                .map_or(String::new(), |g| format!(", {:.3} ms from it", g * 1e3))
        );
        let diff = if w.name == "80 mm" {
            w.main_gap_s().map_or("–".to_string(), |g| {
                format!("gap {}", rel_diff(g, 0.2e-3))
            })
        } else {
            "–".to_string()
        };
        row(
            &format!("Impact on 20 × {} rods: the wave arriving at the wall", w.name),
            paper.into(),
            ours,
            diff,
            "peaks of the wall force ≥ 5 % of its maximum within one transit time after the arrival, merged unless the force between them falls below half the smaller (see the homogeneous-chain section)",
        );
    }
    for (name, paper) in [("40 mm", 0.70), ("80 mm", 0.70), ("paper optimum", 0.083)] {
        if let Some((_, _, ratio)) = blast_energy.iter().find(|(n, _, _)| n == name) {
            row(
                &format!("Blast: peak transmitted energy (last layer), {name} chain / 20 mm chain"),
                if paper > 0.5 { "~70 %".into() } else { "8.3 %".into() },
                pct(*ratio),
                pp_diff(*ratio, paper),
                "F0, Td and the pulse shape of the paper's blast are unknown: docs/physics.md's Friedlander 200 N / 0.2 ms",
            );
        }
    }
    for (name, paper) in [
        ("20 mm", "38–55 kHz"),
        ("40 mm", "10–15 kHz"),
        ("80 mm", "2.7–3.9 and 15–20 kHz"),
    ] {
        let bands: Vec<String> = band_rows
            .iter()
            .filter(|(n, _, _)| n == name)
            .map(|(_, (lo, hi), c)| {
                format!(
                    "{:.1}–{:.1} kHz (spectral amplitude in the band {:.0} % of its flanks)",
                    lo * 1e-3,
                    hi * 1e-3,
                    100.0 * c
                )
            })
            .collect();
        row(
            &format!("Blast: low-energy band(s), {name} chain"),
            paper.into(),
            bands.join("; "),
            "edges within 1 kHz".into(),
            "the paper's bands are rounded; ours are the negative-mass bands of Table 1, the contrast is measured on the blast spectra of contacts 1..20",
        );
    }
    doc.table(
        &["quantity", "paper", "ours", "difference", "why they differ"],
        rows,
    );

    doc.h2("Homogeneous chains under impact (Figs. 5 a–c, 6)");
    doc.p("Twenty identical rods on the sensor, hit by the striker. The paper: 20 mm rods carry a solitary wave with a small oscillating tail (a nanopteron); 40 and 80 mm rods split the wave into groups separated in time (80 mm: two groups ~0.2 ms apart).");
    doc.p("Measured on the wall force, during the first transit only (from the wave's arrival at the wall, for as long as it took to get there from contact 1; later events include reflections): the separated peaks, i.e. local maxima of at least 5 % of the window's maximum, two neighbouring maxima counting as one unless the force between them falls below half the smaller one.");
    let mut prow = Vec::new();
    for (w, (c, _)) in waves.iter().zip(&impact_cases) {
        let peaks = w
            .peaks
            .iter()
            .map(|(t, f)| format!("{:.3} ms ({f:.1} N)", t * 1e3))
            .collect::<Vec<_>>()
            .join(", ");
        prow.push(vec![
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
        ]);
    }
    doc.table(
        &[
            "chain",
            "incident peak",
            "wall peak",
            "arrival at contact 1 → wall",
            "separated peaks at the wall (first transit)",
            "gap between the two largest",
        ],
        prow,
    );
    doc.figure(&wall_compare, out, "Wall force of the four homogeneous chains under the impact: the arrival and grouping of the transmitted wave.");
    for (c, files) in &impact_cases {
        doc.h3(format!("{} under impact", c.chain_title));
        let captions = [
            "contact force map (contact × time): the wave's path through the chain (Fig. 5 a–c).",
            "energy of each layer over the striker's initial energy (Fig. 6).",
            "force histories at the striker contact, contact 1, the middle contact and the wall.",
            "amplitude spectra of contact 1, the middle contact and the wall; the negative-effective-mass bands of the rods are shaded.",
        ];
        for (f, cap) in files.iter().zip(captions) {
            doc.figure(f, out, format!("{}, impact: {cap}", c.chain_title));
        }
    }

    doc.h2("Optimised chains under impact (Fig. 5 d, e)");
    doc.p(format!(
        "The breeder GA searched the 7^20 arrangements of Table 1 rods for the least peak wall force, once with resonant rods and once with rigid ones. Resonant optimum (top to bottom, mm): `{}`; rigid optimum: `{}`. The paper's resonant optimum puts long rods (80, 70 mm) at the top and short rods in a disordered pattern at the bottom; its rigid optimum alternates heavy and light rods.",
        join_mm(&ga_res.rods),
        join_mm(&ga_rig.rods)
    ));
    let mut grow = Vec::new();
    for (ga, (c, _)) in [&ga_res, &ga_rig].iter().zip(&optima) {
        grow.push(vec![
            ga.model.to_string(),
            join_mm(&ga.rods),
            format!("{:.2} N", c.summary.incident_peak_force_n),
            format!("{:.2} N", c.summary.transmitted_peak_force_n),
            pct(ratio(&c.summary)),
            format!("{:.4}", restitution(&c.summary)),
            format!(
                "{} generations, {} simulations, {:.1} s{}",
                ga.result.generations,
                ga.result.evaluations,
                ga.result.elapsed_s,
                if ga.cached { " (from cache)" } else { "" }
            ),
        ]);
    }
    doc.table(
        &[
            "model",
            "best chain (mm, top to bottom)",
            "incident",
            "transmitted",
            "ratio",
            "restitution",
            "search",
        ],
        grow,
    );
    for (ga, (_, files)) in [&ga_res, &ga_rig].iter().zip(&optima) {
        doc.h3(format!("{} optimum", ga.model));
        let captions = [
            "convergence of the breeder GA: best and mean peak wall force per generation.",
            "the best chain, rods to scale, top (striker) to bottom (sensor) (Fig. 5 d, e right).",
            "incident force (contact 1) and transmitted force (wall) of the best chain.",
            "contact force map of the best chain.",
        ];
        for (f, cap) in files.iter().zip(captions) {
            doc.figure(
                f,
                out,
                format!("GA optimum, {} model, impact: {cap}", ga.model),
            );
        }
    }

    doc.h2("Layer-by-layer protocol (Fig. 7 a, b)");
    let n = protocol.peak_wall_force_n.len();
    doc.p(format!(
        "The experiment's sensor sits under the last rod only, so the paper measured the sub-chains of the first k = 1..N rods one at a time. Emulated on the resonant GA optimum: the wall force of sub-chain k is the incident force at interface k. The k = {n} run is the full chain: its peak {:.3} N equals the full chain's wall force {:.3} N. Largest protocol peak: {:.1} N at k = {}; smallest: {:.1} N at k = {}.",
        protocol.peak_wall_force_n[n - 1],
        cr.transmitted_peak_force_n,
        protocol.peak_wall_force_n.iter().copied().fold(0.0, f64::max),
        1 + protocol.peak_wall_force_n.iter().enumerate().max_by(|a, b| a.1.total_cmp(b.1)).map_or(0, |p| p.0),
        protocol.peak_wall_force_n.iter().copied().fold(f64::INFINITY, f64::min),
        1 + protocol.peak_wall_force_n.iter().enumerate().min_by(|a, b| a.1.total_cmp(b.1)).map_or(0, |p| p.0),
    ));
    doc.figure(&protocol_map_files, out, "Layer-by-layer protocol on the resonant GA optimum under the impact: wall force of the first k rods on the sensor over time (Fig. 7 a).");
    doc.figure(&protocol_peak_files, out, "Layer-by-layer protocol on the resonant GA optimum under the impact: peak force per interface, protocol against the full chain's contact peaks (Fig. 7 b).");

    doc.h2("Blast (Figs. 8, 9)");
    doc.p(format!(
        "The {blast_text} load on the top rod of 20-rod resonant chains: homogeneous 20, 40, 80 mm and the paper's blast-optimised chain `{}`. The paper: peak transmitted energy (energy of the last layer) ~70 % of the 20 mm chain's for 40 and 80 mm rods, 8.3 % for the optimised chain; the spectra show low-energy bands at the negative-mass bands of the rods.",
        join_mm(&woodpile::PAPER_OPTIMIZED_CHAIN_MM)
    ));
    doc.table(
        &[
            "chain",
            "peak energy of layer 20",
            "relative to 20 mm",
            "wall peak force",
        ],
        blast_energy
            .iter()
            .zip(&blast_cases)
            .map(|((name, e, r), (c, _))| {
                vec![
                    name.clone(),
                    format!("{:.3e} J", e),
                    pct(*r),
                    format!("{:.2} N", c.summary.transmitted_peak_force_n),
                ]
            })
            .collect(),
    );
    doc.table(
        &[
            "chain",
            "negative-mass band",
            "mean amplitude in band / flanks",
        ],
        band_rows
            .iter()
            .map(|(name, (lo, hi), c)| {
                vec![
                    name.clone(),
                    format!("{:.2}–{:.2} kHz", lo * 1e-3, hi * 1e-3),
                    pct(*c),
                ]
            })
            .collect(),
    );
    doc.figure(
        &blast_compare,
        out,
        "The blast load (contact 0, Fig. 8) and the wall force of the four chains.",
    );
    for (c, files) in &blast_cases {
        doc.h3(format!("{} under the blast", c.chain_title));
        let captions = [
            "contact force map (Fig. 9 a, c, e, g).",
            "energy of each layer over the injected energy.",
            "spectrum map: force amplitude per contact and frequency (Fig. 9 b, d, f, h).",
            "amplitude spectra of contact 1, the middle contact and the wall, negative-mass bands shaded.",
        ];
        for (f, cap) in files.iter().zip(captions) {
            doc.figure(f, out, format!("{}, blast: {cap}", c.chain_title));
        }
    }

    doc.h2("Effective mass of the rods (Fig. 3)");
    doc.p("M_eff(ω)/M_total of the Table 1 unit cells (paper Eq. 3, 4): negative between each local resonance f_j and the next zero F_j (shaded).");
    let ef: Vec<PathBuf> = cells_files.clone();
    doc.figure(
        &ef[..2.min(ef.len())],
        out,
        "Effective mass of the 20, 30, 40 mm rods (one resonator each) (Fig. 3 a).",
    );
    if ef.len() > 2 {
        doc.figure(
            &ef[2..],
            out,
            "Effective mass of the 50–80 mm rods (two resonators each) (Fig. 3 b).",
        );
    }

    doc.h2("Reproducing and caching");
    doc.p("Every figure is also written as SVG beside its PNG in figures/. The GA results are kept in cache/ under an FNV-1a hash of the tool version and the complete problem (config, GA settings, seed); rerunning the same command reuses them. The simulations themselves take well under a second each and are re-run.");
    doc.code(format!(
        "woodpile report --out {}{} --seed {}",
        out.display(),
        if args.quick { " --quick" } else { "" },
        args.seed
    ));
    bar.inc(1);

    let summary = format!(
        "resonant optimum {:.2} N of {:.2} N ({}), rigid optimum {:.2} N of {:.2} N ({}); blast: 40 mm {}, 80 mm {}, paper optimum {} of the 20 mm chain's peak transmitted energy",
        cr.transmitted_peak_force_n,
        cr.incident_peak_force_n,
        pct(ratio(cr)),
        cg.transmitted_peak_force_n,
        cg.incident_peak_force_n,
        pct(ratio(cg)),
        pct(blast_energy[1].2),
        pct(blast_energy[2].2),
        pct(blast_energy[3].2),
    );
    Ok((doc, summary))
}
