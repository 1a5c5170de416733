//! # woodpile-report
//!
//! The paper's study as one report, used by `woodpile report --out DIR [--quick] [--seed S]
//! [--threads T]` (the command line owns the arguments, the output directory's policy and the
//! progress bar): [`build`] runs everything the paper's figures and numbers need, draws every
//! figure into `DIR/figures/` (PNG and SVG), and returns the document ([`Doc`]: `report.md` and a
//! self-contained `report.html`, figures embedded as SVG data URIs) with a comparison table: each
//! number the paper reports (docs/physics.md §9) beside ours.
//!
//! One module per section, each holding its runs, its figures, its text and the paper's numbers
//! it is compared with; this module runs them in order and assembles the document:
//! - `impact`: homogeneous 20-rod chains of 20, 40, 80 mm rods (resonant) and 20 mm (rigid)
//!   under the impact: force and energy maps, force histories, spectra, the separated pulses at
//!   the wall (paper Figs. 5 a–c, 6);
//! - `optima`: the breeder GA for the least wall force under the impact, resonant and rigid
//!   (paper Fig. 5 d, e): convergence, best chain, incident and transmitted force, restitution;
//! - `pareto`: NSGA-II's front of transmitted force against total mass over the same problem,
//!   the resonant optimum marked on it, and its hypervolume per generation (beyond the paper);
//! - `protocol`: the layer-by-layer protocol on the resonant optimum (paper Fig. 7 a, b);
//! - `blast`: the Friedlander blast on 20, 40, 80 mm chains and the paper's blast-optimised
//!   chain: peak energy of the last layer, spectra against the negative-mass bands (paper
//!   Figs. 8, 9); `sweep`: the same chains over a grid of blast loads;
//! - `fine`: the GA over rods of every length with cells from beam theory (beyond the paper);
//! - `transmission`: the transmission spectrum of preloaded 80 mm rods (beyond the paper);
//! - `calibration`: the scale of the paper's unstated striker constant that its incident force
//!   would need (beyond the paper);
//! - `cells`: the effective-mass curves of the catalogue (paper Fig. 3).
//!
//! `study` holds what the sections share (the loads, a simulated `study::Case`, the paper's
//! numbers as [`PaperValue`]s, the comparison table), `ga` the GA runs, `doc` the Markdown
//! and HTML. The GA results, the only expensive part, are kept in `DIR/cache/` under a stable
//! FNV-1a hash of the tool version and the complete problem (config, GA settings, seed); a rerun
//! reuses them. Everything else is re-simulated (well under a second per run). `report.md` and
//! `report.html` are written under a temporary name and renamed, so a failed run never leaves a
//! half-written report.

mod blast;
mod calibration;
mod cells;
mod doc;
mod fine;
mod ga;
mod impact;
mod optima;
mod pareto;
mod protocol;
mod study;
mod sweep;
mod transmission;

pub use blast::{BLAST_40MM, BLAST_80MM, BLAST_OPTIMUM};
pub use impact::GAP_80MM;
pub use optima::{
    RESONANT_ADVANTAGE, RESONANT_INCIDENT, RESONANT_RATIO, RESONANT_RESTITUTION,
    RESONANT_TRANSMITTED, RIGID_INCIDENT, RIGID_RATIO, RIGID_RESTITUTION, RIGID_TRANSMITTED,
};
pub use study::{PaperValue, Quantity};

pub use doc::Doc;
pub use study::Setup;
pub use woodpile_io::Error;

use study::{pct, ratio, Comparison};

/// Where the report shows how far it is (the command line's progress bar).
pub trait Progress: Sync {
    /// A new stage begins.
    fn stage(&self, stage: &str);
    /// A detail of the current stage.
    fn detail(&self, detail: &str);
    /// `n` steps of [`STEPS`] are done.
    fn inc(&self, n: u64);
    /// Time since the report began.
    fn elapsed(&self) -> std::time::Duration;
}

/// Progress steps: 4 impact chains, 2 GAs, optimum figures, the force–mass front, protocol,
/// 4 blast chains, 2 GAs over derived cells, the striker calibration, cells.
pub const STEPS: u64 = 17;

/// The report's title.
pub const TITLE: &str = "woodpile: reproduction of Kim, Yang et al. 2017 (impact and blast mitigation with locally resonant woodpiles)";

/// Runs every section, then writes them in order; returns the document and a short summary.
pub fn build(s: &Setup) -> Result<(Doc, String), Error> {
    let sections = Sections::run(s)?;
    s.bar.stage("writing the report");
    let elapsed = s.bar.elapsed().as_secs_f64();
    let doc = sections.write(s, elapsed);
    s.bar.inc(1);
    Ok((doc, sections.summary()))
}

/// The results of every section.
struct Sections {
    impact: impact::Impact,
    optima: optima::Optima,
    pareto: pareto::Front,
    protocol: protocol::Protocol,
    blast: blast::Blast,
    sweep: sweep::Sweep,
    fine: fine::Fine,
    transmission: transmission::Transmission,
    calibration: calibration::Calibration,
    cells: cells::Cells,
}

impl Sections {
    /// Runs the sections, each showing its stages and steps on the progress bar.
    fn run(s: &Setup) -> Result<Self, Error> {
        s.bar.stage("homogeneous chains under impact");
        let impact = impact::run(s)?;
        let optima = optima::run(s)?;
        let pareto = pareto::run(s, &optima.resonant)?;
        s.bar.stage("layer-by-layer protocol");
        let protocol = protocol::run(s, &optima)?;
        s.bar.inc(1);
        s.bar.stage("blast cases");
        let blast = blast::run(s)?;
        let sweep = sweep::run(s)?;
        let fine = fine::run(s)?;
        s.bar.stage("transmission spectrum");
        let transmission = transmission::run(s)?;
        s.bar.stage("striker constant");
        let calibration = calibration::run_all()?;
        s.bar.inc(1);
        let cells = cells::run(s)?;
        Ok(Sections {
            impact,
            optima,
            pareto,
            protocol,
            blast,
            sweep,
            fine,
            transmission,
            calibration,
            cells,
        })
    }

    /// The document: how it was made, the comparison with the paper, then each section.
    fn write(&self, s: &Setup, elapsed: f64) -> Doc {
        let mut doc = Doc::new(&s.out);
        let gas = [
            &self.optima.resonant,
            &self.optima.rigid,
            &self.fine.seven,
            &self.fine.fine,
        ];
        intro(&mut doc, s, gas, elapsed);
        let mut table = Comparison::default();
        self.optima.compare(s, &mut table);
        self.impact.compare(&mut table);
        self.blast.compare(&mut table);
        doc.h2("Comparison with the paper");
        doc.p("Each number the paper reports (docs/physics.md §9) beside ours. Differences in percent are relative to the paper's value; `pp` are percentage points.");
        doc.table(
            &["quantity", "paper", "ours", "difference", "why they differ"],
            table.rows,
        );
        self.impact.write(&mut doc);
        self.optima.write(&mut doc);
        self.protocol.write(&mut doc, &self.optima);
        self.pareto.write(&mut doc);
        self.blast.write_overview(&mut doc, s);
        self.sweep.write(&mut doc);
        self.blast.write_chains(&mut doc);
        self.fine.write(&mut doc, s, &self.optima);
        self.transmission.write(&mut doc);
        self.calibration.write(&mut doc);
        self.cells.write(&mut doc);
        doc.h2("Reproducing and caching");
        doc.p("Every figure is also written as SVG beside its PNG in figures/. The GA results are kept in cache/ under an FNV-1a hash of the tool version and the complete problem (config, GA settings, seed); rerunning the same command reuses them. The simulations themselves take well under a second each and are re-run.");
        doc.code(command(s));
        doc
    }

    /// The one-paragraph summary printed at the end of `woodpile report`.
    fn summary(&self) -> String {
        let (cr, cg) = (&self.optima.cases[0].summary, &self.optima.cases[1].summary);
        let shares = self.blast.shares();
        format!(
            "resonant optimum {:.2} N of {:.2} N ({}), rigid optimum {:.2} N of {:.2} N ({}); blast: 40 mm {}, 80 mm {}, paper optimum {} of the 20 mm chain's peak transmitted energy",
            cr.transmitted_peak_force_n,
            cr.incident_peak_force_n,
            pct(ratio(cr)),
            cg.transmitted_peak_force_n,
            cg.incident_peak_force_n,
            pct(ratio(cg)),
            pct(shares[1]),
            pct(shares[2]),
            pct(shares[3]),
        )
    }
}

/// The command that makes this report.
fn command(s: &Setup) -> String {
    let quick = if s.quick { " --quick" } else { "" };
    format!(
        "woodpile report --out {}{quick} --seed {}",
        s.out.display(),
        s.seed
    )
}

/// How the report was made: the command, the model, the loads and the GAs (resonant first).
fn intro(doc: &mut Doc, s: &Setup, gas: [&ga::GaRun; 4], elapsed: f64) {
    doc.h2("How this report was made");
    let cached = match gas.iter().filter(|g| g.cached).count() {
        4 => "all four GA results reused from cache/".to_string(),
        0 => "all four GAs run now".to_string(),
        k => format!("{k} of the four GA results reused from cache/, the others run now"),
    };
    doc.p(format!(
        "Command: `{}` (woodpile {}), {cached}{}. Every number below was measured by this tool (the GA results possibly by an earlier run of the same command, kept in cache/); the model and its defaults are docs/physics.md's (rods of fused quartz with the paper's Table 1 unit cells, Hertz contacts, fixed-step RK4 with dt = 0.1 µs, samples every 1 µs).",
        command(s),
        env!("CARGO_PKG_VERSION"),
        if s.quick {
            " — QUICK version: the GAs ran with population 10 × 5 generations and are not converged, so the optimisation numbers are not the full report's"
        } else {
            ""
        },
    ));
    let ga = gas[0];
    doc.list(vec![
        format!("Impact: {} (dropped from 0.20 m), run 2 ms; wall = stainless-steel spherical cap of radius 5 mm (assumed, docs/physics.md §5).", s.impact_text),
        format!("Blast: {} (Friedlander positive phase, docs/physics.md §6, parameters chosen by docs/physics.md), run 3 ms.", s.blast_text),
        format!(
            "GA (docs/physics.md §11): population {}, at most {} generations, stall limit {}, truncation 0.3, one elite, seed {}, objective: peak wall force.",
            ga.population,
            ga.generations_limit,
            ga.stall.map_or("none".to_string(), |s| s.to_string()),
            s.seed
        ),
        format!("Wall-clock time of the runs: {elapsed:.1} s."),
    ]);
}
