//! The runs behind the report: every simulation and GA the paper's figures need, drawn into
//! figures/, with the GA results cached. Cases and reference values come from
//! `woodpile_io::study`; this module only runs and draws them.

use super::Args;
use crate::progress::Progress;
use crate::CliError;
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use woodpile::analysis::{
    band_contrast, contact_spectrum_map, energy_map, force_map, layer_by_layer, peak_layer_energy,
    FirstTransit, LayerByLayer, Spectrum, SpectrumSettings,
};
use woodpile::optimize::GaState;
use woodpile::{
    simulate, BlastProfile, CellModel, Chain, ChainBuilder, Excitation, RunSettings, RunSummary,
    Striker, Trajectory,
};
use woodpile_io::optimize::OptimizeConfig;
use woodpile_io::scenario::ModelSpec;
use woodpile_io::study::{self, simulate_case, Cache, Case, GaRun};
use woodpile_plot as plot;
use woodpile_plot::dirs::objective_label;

/// What every run of the report shares: the command's arguments, where figures go, the loads.
pub struct Setup<'a> {
    /// The command's arguments.
    pub args: &'a Args,
    /// Progress: a bar on a terminal, a line per stage otherwise.
    pub bar: &'a Progress,
    /// `OUT/figures`.
    pub figs: PathBuf,
    /// The GA cache in `OUT/cache`.
    pub cache: Cache,
    /// The paper's impact and its run settings.
    pub impact: Excitation,
    /// Run settings of the impact.
    pub impact_settings: RunSettings,
    /// The impact in words.
    pub impact_text: String,
    /// The default blast and its run settings.
    pub blast: Excitation,
    /// Run settings of the blast.
    pub blast_settings: RunSettings,
    /// The blast in words.
    pub blast_text: String,
    /// Highest frequency of the spectra \[Hz\].
    pub max_hz: f64,
}

impl<'a> Setup<'a> {
    /// The paper's loads with the defaults of docs/physics.md.
    pub fn new(args: &'a Args, bar: &'a Progress) -> Self {
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
            args,
            bar,
            figs: args.out.join("figures"),
            cache: Cache {
                dir: args.out.join("cache"),
            },
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

pub fn join_mm(rods: &[u32]) -> String {
    rods.iter()
        .map(u32::to_string)
        .collect::<Vec<_>>()
        .join(" ")
}

// ---------------------------------------------------------------------------------------------
// The runs.

fn homogeneous(length_mm: u32, model: CellModel) -> Result<Chain, CliError> {
    Ok(ChainBuilder::table1_rods(&[length_mm; 20], model)?.build()?)
}

/// The force map and the energy map of a run: `STEM_force_map` and `STEM_energy_map`;
/// `contact0` names what drives it (`striker`, `load`).
fn draw_maps(
    t: &Trajectory,
    title: &str,
    contact0: &str,
    stem: &Path,
) -> Result<Vec<Vec<PathBuf>>, CliError> {
    let with = |suffix: &str| {
        let mut s = stem.as_os_str().to_owned();
        s.push(suffix);
        PathBuf::from(s)
    };
    Ok(vec![
        plot::force_map(&force_map(t)?, title, Some(contact0), &with("_force_map"))?,
        plot::energy_map(&energy_map(t)?, title, Some(contact0), &with("_energy_map"))?,
    ])
}

/// Spectra of contact 1, the middle contact and the wall, with the chain's bands shaded.
/// The report's spectra: Fourier-transform magnitudes \[N/Hz\], comparable across record lengths.
const FOURIER: SpectrumSettings = SpectrumSettings {
    scaling: woodpile::analysis::Scaling::FourierMagnitude,
    window: woodpile::analysis::Window::Rectangular,
    padding: woodpile::analysis::Padding::None,
    remove_mean: false,
};

fn draw_spectra(
    case: &Case,
    title: &str,
    max_hz: f64,
    stem: &Path,
) -> Result<Vec<PathBuf>, CliError> {
    let t = &case.trajectory;
    let n = t.n_elements;
    let dt = woodpile::analysis::sample_interval_s(t)?;
    let settings = FOURIER;
    let spectra = [
        (1, "contact 1 (incident)".to_string()),
        (n / 2, format!("contact {} (middle)", n / 2)),
        (n, format!("contact {n} (wall)")),
    ]
    .into_iter()
    .map(|(c, l)| Ok((l, Spectrum::of(&t.contact_force_n(c), dt, &settings)?)))
    .collect::<Result<Vec<_>, woodpile::Error>>()?;
    let refs: Vec<(String, &Spectrum)> = spectra.iter().map(|(l, s)| (l.clone(), s)).collect();
    Ok(plot::spectra(&refs, &case.bands, title, max_hz, stem)?)
}

/// A GA of the report: from the cache or run now, with the progress bar's message.
fn run_ga(
    cfg: &OptimizeConfig,
    label: &'static str,
    threads: usize,
    cache: &Cache,
    bar: &Progress,
) -> Result<GaRun, CliError> {
    study::ga_run(
        cfg,
        label,
        threads,
        cache,
        &mut |s: &GaState, total: usize| {
            bar.detail(format!(
                "{label} GA: generation {}/{total}, best {:.3}, {} evaluations",
                s.generation,
                s.best().objective,
                s.ledger.evaluations
            ))
        },
    )
}

/// The homogeneous chains under the impact: their cases and figures, the wall forces compared,
/// and the first transit of each wave at the wall.
#[allow(clippy::type_complexity)]
pub fn impact_homogeneous(
    s: &Setup,
) -> Result<
    (
        Vec<(Case, Vec<Vec<PathBuf>>)>,
        Vec<PathBuf>,
        Vec<FirstTransit>,
    ),
    CliError,
> {
    let fig = |name: &str| s.figs.join(name);
    let (bar, max_hz) = (s.bar, s.max_hz);
    let (impact, impact_settings, impact_text) = (&s.impact, &s.impact_settings, &s.impact_text);
    let impact_cases: Vec<(Case, Vec<Vec<PathBuf>>)> = study::IMPACT_HOMOGENEOUS
        .par_iter()
        .map(|h| {
            let (l, model, name, slug) = (h.rod_mm, h.model, h.name, h.slug);
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
                impact,
                impact_settings,
            )?;
            let title = format!("{chain_title}, {impact_text}");
            let t = &case.trajectory;
            let n = t.n_elements;
            let mut files = draw_maps(t, &title, "striker", &fig(&format!("impact_{slug}")))?;
            let series = [
                (0, "contact 0 (striker)".to_string()),
                (1, "contact 1 (incident)".to_string()),
                (n / 2, format!("contact {} (middle)", n / 2)),
                (n, format!("contact {n} (wall)")),
            ]
            .map(|(c, l)| plot::Series::new(l, t.contact_force_n(c)));
            files.push(plot::force_histories(
                &t.times_s,
                &series,
                &title,
                &fig(&format!("impact_{slug}_force_histories")),
            )?);
            // The same, zoomed on the first arrivals (over 2 ms the pulses are slivers).
            let onset = plot::onset_window_s(&t.times_s, &series, 1.0)
                .unwrap_or((t.times_s[0], t.times_s[t.times_s.len() - 1]));
            files.push(plot::force_histories_between(
                &t.times_s,
                &series,
                &title,
                onset,
                &fig(&format!("impact_{slug}_force_histories_onset")),
            )?);
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
    )?;

    // Pulses at the wall and at the middle contact, first transit only: up to the arrival of
    // the first pulse at the wall plus 0.6 ms.
    let waves: Vec<FirstTransit> = impact_cases
        .iter()
        .map(|(c, _)| FirstTransit::of(&c.name, &c.trajectory))
        .collect();

    Ok((impact_cases, wall_compare, waves))
}

/// The resonant and rigid GAs and the figures of their optima.
#[allow(clippy::type_complexity)]
pub fn optima(s: &Setup) -> Result<(GaRun, GaRun, Vec<(Case, Vec<Vec<PathBuf>>)>), CliError> {
    let fig = |name: &str| s.figs.join(name);
    let bar = s.bar;
    let (impact, impact_settings, impact_text) = (&s.impact, &s.impact_settings, &s.impact_text);
    let (quick, seed, threads) = (s.args.quick, s.args.seed, s.args.threads);
    bar.stage("resonant GA");
    let cfg = study::ga_problem(ModelSpec::Resonant, seed, quick)?;
    let ga_res = run_ga(&cfg, "resonant", threads, &s.cache, bar)?;
    bar.inc(1);
    bar.stage("rigid GA");
    let cfg = study::ga_problem(ModelSpec::Rigid, seed, quick)?;
    let ga_rig = run_ga(&cfg, "rigid", threads, &s.cache, bar)?;
    bar.inc(1);
    bar.stage("figures of the optima");
    let optima: Vec<(Case, Vec<Vec<PathBuf>>)> = [&ga_res, &ga_rig]
        .par_iter()
        .map(|ga| {
            let chain_title = format!("GA optimum ({}): {}", ga.model, join_mm(&ga.rods));
            let case = simulate_case(
                &format!("{} optimum", ga.model),
                &format!("optimum_{}", ga.model),
                &chain_title,
                ga.chain.clone(),
                impact,
                impact_settings,
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
            files.push(plot::convergence(
                &points,
                &objective_label(&ga.objective, &ga.unit),
                &format!(
                    "Breeder GA, 20 rods, {} model, impact (population {}, seed {})",
                    ga.model, ga.population, s.args.seed
                ),
                &fig(&format!("{slug}_convergence")),
            )?);
            files.push(plot::chain_picture(
                &case.chain,
                &format!("GA optimum, {} model, impact", ga.model),
                Some("striker"),
                &fig(&format!("{slug}_chain")),
            )?);
            let series = [
                (1, "contact 1: incident".to_string()),
                (n, format!("contact {n}: transmitted (wall)")),
            ]
            .map(|(c, l)| plot::Series::new(l, t.contact_force_n(c)));
            files.push(plot::force_histories(
                &t.times_s,
                &series,
                &short,
                &fig(&format!("{slug}_forces")),
            )?);
            files.push(plot::force_map(
                &force_map(t)?,
                &short,
                Some("striker"),
                &fig(&format!("{slug}_force_map")),
            )?);
            // Paper Fig. 6 is the energy map of the two optima.
            files.push(plot::energy_map(
                &energy_map(t)?,
                &short,
                Some("striker"),
                &fig(&format!("{slug}_energy_map")),
            )?);
            Ok((case, files))
        })
        .collect::<Result<Vec<_>, CliError>>()?;
    bar.inc(1);
    Ok((ga_res, ga_rig, optima))
}

/// The layer-by-layer protocol on the resonant optimum, lossless and with [`stated_damping`],
/// and its two figures.
pub fn protocol(
    s: &Setup,
    res_case: &Case,
) -> Result<(LayerByLayer, LayerByLayer, Vec<PathBuf>, Vec<PathBuf>), CliError> {
    let fig = |name: &str| s.figs.join(name);
    let (impact, impact_settings, impact_text) = (&s.impact, &s.impact_settings, &s.impact_text);
    let protocol = layer_by_layer(&res_case.chain, impact, impact_settings)?;
    let damped_chain = res_case
        .chain
        .clone()
        .with_damping(study::stated_damping())?;
    let damped = layer_by_layer(&damped_chain, impact, impact_settings)?;
    let ptitle = format!("Layer-by-layer protocol, resonant GA optimum, {impact_text}");
    let protocol_map_files =
        plot::protocol_map(&protocol.wall_force_map, &ptitle, &fig("protocol_map"))?;
    let full_peaks = res_case.summary.contact_peak_forces_n[1..].to_vec();
    let protocol_peak_files = plot::peaks_per_layer(
        &[
            plot::Series::new(
                "protocol: wall force of the first k rods on the sensor",
                protocol.peak_wall_force_n.clone(),
            ),
            plot::Series::new("full chain: peak of contact k", full_peaks.clone()),
            plot::Series::new(
                "protocol with damping (e = 0.9, ζ = 0.01)",
                damped.peak_wall_force_n.clone(),
            ),
        ],
        &ptitle,
        "peak force [N]",
        &fig("protocol_peaks"),
    )?;
    Ok((protocol, damped, protocol_map_files, protocol_peak_files))
}

/// What the blast runs give the report.
pub struct BlastRuns {
    /// Each chain and its figures.
    pub cases: Vec<(Case, Vec<Vec<PathBuf>>)>,
    /// The load and the wall forces compared.
    pub compare: Vec<PathBuf>,
    /// (chain, peak energy of the last layer \[J\], relative to the 20 mm chain).
    pub energy: Vec<(String, f64, f64)>,
    /// (chain, negative-mass band \[Hz\], band contrast of its spectra).
    pub bands: Vec<(String, (f64, f64), f64)>,
    /// The paper's three blast ratios over a grid of Friedlander loads.
    pub sweep: study::BlastSweep,
    /// The sweep's figure (worst factor over F0 × Td).
    pub sweep_files: Vec<PathBuf>,
}

/// The blast on the homogeneous chains and the paper's blast-optimised chain.
pub fn blast(s: &Setup) -> Result<BlastRuns, CliError> {
    let fig = |name: &str| s.figs.join(name);
    let (bar, max_hz) = (s.bar, s.max_hz);
    let (blast, blast_settings, blast_text) = (&s.blast, &s.blast_settings, &s.blast_text);
    let blast_cases: Vec<(Case, Vec<Vec<PathBuf>>)> = study::BLAST_CHAINS
        .par_iter()
        .map(|&(rod_mm, name, slug)| {
            let (rods, chain_title) = match rod_mm {
                Some(l) => (
                    vec![l; study::CHAIN_LENGTH],
                    format!("{} × {l} mm rods (resonant)", study::CHAIN_LENGTH),
                ),
                None => (
                    woodpile::PAPER_OPTIMIZED_CHAIN_MM.to_vec(),
                    "paper's blast-optimised chain (resonant)".to_string(),
                ),
            };
            let chain_title = &chain_title;
            let chain = ChainBuilder::table1_rods(&rods, CellModel::Resonant)?.build()?;
            let case = simulate_case(name, slug, chain_title, chain, blast, blast_settings)?;
            let title = format!("{chain_title}, {blast_text}");
            let t = &case.trajectory;
            let mut files = draw_maps(t, &title, "load", &fig(&format!("blast_{slug}")))?;
            files.push(plot::spectrum_map(
                &contact_spectrum_map(t, &FOURIER)?,
                &title,
                max_hz,
                Some("load"),
                &fig(&format!("blast_{slug}_spectrum_map")),
            )?);
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
    )?;
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
    bar.stage("blast sweep (F0 × Td)");
    // The quick report checks only that the sweep is made: four loads.
    let (peaks, durations): (&[f64], &[f64]) = if s.args.quick {
        (&[100.0, 400.0], &[2e-4, 5e-4])
    } else {
        (&study::BLAST_SWEEP_PEAKS_N, &study::BLAST_SWEEP_DURATIONS_S)
    };
    let sweep = study::blast_sweep(peaks, durations, blast_settings)?;
    let map = sweep.worst_factor_map()?;
    let sweep_files = plot::Heatmap {
        x_scale: 1e3,
        x_label: "positive-phase duration Td [ms]".into(),
        y_label: "peak force F0 [N]".into(),
        value_label: "largest factor by which a blast ratio misses the paper's".into(),
        log_decades: Some(2.0),
        ..plot::Heatmap::new(
            &map,
            "Friedlander blast: how far the three energy ratios are from the paper's",
        )
    }
    .write(&fig("blast_sweep"))?;
    Ok(BlastRuns {
        cases: blast_cases,
        compare: blast_compare,
        energy: blast_energy,
        bands: band_rows,
        sweep,
        sweep_files,
    })
}

/// Everything the report's text needs from the runs.
pub struct Results {
    /// Homogeneous chains under the impact, with their figures.
    pub impact_cases: Vec<(Case, Vec<Vec<PathBuf>>)>,
    /// Wall forces of the homogeneous chains compared.
    pub wall_compare: Vec<PathBuf>,
    /// First transit of each homogeneous chain's wave at the wall.
    pub waves: Vec<FirstTransit>,
    /// The resonant GA.
    pub ga_res: GaRun,
    /// The rigid GA.
    pub ga_rig: GaRun,
    /// The two optima re-simulated, with their figures.
    pub optima: Vec<(Case, Vec<Vec<PathBuf>>)>,
    /// The layer-by-layer protocol on the resonant optimum.
    pub protocol: LayerByLayer,
    /// The same protocol with [`stated_damping`] (the paper's explanation of its measurements).
    pub protocol_damped: LayerByLayer,
    /// Its map.
    pub protocol_map_files: Vec<PathBuf>,
    /// Its peaks per layer.
    pub protocol_peak_files: Vec<PathBuf>,
    /// The blast runs.
    pub blast: BlastRuns,
    /// The GAs over derived cells (beyond the paper).
    pub fine: FineRuns,
    /// The transmission spectrum of the preloaded 80 mm chain and its figure.
    pub transmission: (woodpile::analysis::TransmissionSpectrum, Vec<PathBuf>),
    /// The effective-mass figures.
    pub cells_files: Vec<PathBuf>,
    /// Wall-clock time of the runs \[s\].
    pub elapsed: f64,
}

/// Beyond the paper: the resonant GA over rods with cells from beam theory, at the paper's seven
/// lengths and at every length 20–80 mm by 1 mm; their optima re-simulated, and the fine
/// optimum's chain picture.
pub struct FineRuns {
    /// The seven lengths, derived cells.
    pub seven: GaRun,
    /// Every length by 1 mm, derived cells.
    pub fine: GaRun,
    /// The two optima re-simulated under the paper's impact (seven, fine).
    pub summaries: [RunSummary; 2],
    /// The fine optimum's chain picture.
    pub files: Vec<PathBuf>,
}

/// Runs the two GAs over derived cells (docs/physics.md §13).
pub fn fine(s: &Setup) -> Result<FineRuns, CliError> {
    let (quick, seed, threads) = (s.args.quick, s.args.seed, s.args.threads);
    s.bar.stage("GA over derived cells, 7 lengths");
    let seven = run_ga(
        &study::derived_ga_problem(10.0, seed, quick)?,
        "derived, 7 lengths",
        threads,
        &s.cache,
        s.bar,
    )?;
    s.bar.inc(1);
    s.bar.stage("GA over derived cells, every length by 1 mm");
    let fine = run_ga(
        &study::derived_ga_problem(1.0, seed, quick)?,
        "derived, 1 mm steps",
        threads,
        &s.cache,
        s.bar,
    )?;
    s.bar.inc(1);
    let run = |ga: &GaRun| simulate(&ga.chain, &s.impact, &s.impact_settings, &mut ());
    let summaries = [run(&seven)?, run(&fine)?];
    let files = plot::chain_picture(
        &fine.chain,
        "GA optimum over rods of every length 20-80 mm (1 mm), cells from beam theory",
        Some("striker"),
        &s.figs.join("optimum_fine_chain"),
    )?;
    Ok(FineRuns {
        seven,
        fine,
        summaries,
        files,
    })
}

/// The transmission spectrum of twenty preloaded 80 mm rods ([`study::transmission_case`]) and
/// its figure.
pub fn transmission(
    s: &Setup,
) -> Result<(woodpile::analysis::TransmissionSpectrum, Vec<PathBuf>), CliError> {
    let (chain, settings) = study::transmission_case()?;
    let t = woodpile::analysis::transmission(&chain, &settings)?;
    let files = woodpile_plot::transmission(
        &t,
        woodpile::defaults::TRANSMISSION_STOP_DB,
        &format!(
            "Twenty 80 mm rods on the sensor, F_p = {} N, on-site τ = {} s",
            study::TRANSMISSION_PRELOAD_N,
            study::TRANSMISSION_ON_SITE_S
        ),
        &s.figs.join("transmission_80mm"),
    )?;
    Ok((t, files))
}
