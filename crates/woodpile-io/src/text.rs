//! The text summaries front ends show after a run: a chain's and a lattice's report, a samples
//! and a sensitivity study's, and the warnings that say when a figure means nothing (a drive that never reached its amplitude, a
//! wave that never arrived). `woodpile simulate` prints them; they name scenario keys, never a
//! command-line option.

use crate::lattice::ResolvedLattice;
use crate::rundir::{RunRecord, SummaryJson};
use crate::sensitivity::FigureIndices;
use crate::uncertainty::FIGURES;
use std::path::Path;
use woodpile::model::LatticeExcitation;
use woodpile::ode::LatticeOde;
use woodpile::simulate::LatticeRun;

/// The warnings of a chain's run whose figures mean less than they say: a drive's ramp longer
/// than the run, a wave that never reached the wall.
pub fn run_warnings(r: &RunRecord<'_>) -> Vec<String> {
    let duration_s = r.resolved.settings.duration_s;
    let mut warnings = Vec::new();
    if let Some(ramp) = r.resolved.excitation.ramp_longer_than(duration_s) {
        warnings.push(format!(
            "excitation.ramp_s = {ramp:e} s is longer than run.duration_s = {duration_s:e} s: the drive never reaches its amplitude, so its peaks and ratio describe the ramp (a harmonic drive's default ramp is three periods); shorten excitation.ramp_s or lengthen the run"
        ));
    }
    if !r.summary.wave_arrived {
        warnings.push(format!(
            "the wave did not reach the wall within run.duration_s = {duration_s:e} s (transmitted peak {:.3e} N, incident {:.3e} N): the transmitted force and the ratio mean nothing; increase run.duration_s",
            r.summary.transmitted_peak_force_n,
            r.summary.incident_peak_force_n
        ));
    }
    warnings
}

/// The warning of a lattice's run whose wave never reached the supports (none for a lattice
/// left at rest, which has no wave to wait for).
pub fn lattice_warnings(resolved: &ResolvedLattice, run: &LatticeRun) -> Vec<String> {
    if run.wave_arrived || left_at_rest(resolved) {
        return Vec::new();
    }
    vec![format!(
        "the wave did not reach the supports within run.duration_s = {:e} s (transmitted peak {:.3e} N, incident {:.3e} N): the transmitted force means nothing; increase run.duration_s",
        resolved.settings.duration_s,
        run.transmitted_peak_force_n,
        run.incident_peak_force_n
    )]
}

/// Whether the lattice is left at rest: it has no wave to wait for (its supports' peak is its
/// static load).
fn left_at_rest(resolved: &ResolvedLattice) -> bool {
    matches!(
        resolved.excitation,
        woodpile::model::LatticeExcitation::Rest { .. }
    )
}

/// The short report of a lattice's run that front ends show (`woodpile simulate` prints it).
pub fn lattice_run_summary(
    name: &str,
    resolved: &ResolvedLattice,
    ode: &LatticeOde,
    run: &LatticeRun,
    dir: &Path,
) -> String {
    let rods: usize = resolved.lattice.rods.len();
    let incident = match &resolved.excitation {
        LatticeExcitation::Impact { .. } => "peak of the striker's contact".to_string(),
        _ => format!(
            "peak of the sum of the {} load points",
            ode.incident_contacts().len()
        ),
    };
    let transmitted = if run.wave_arrived || left_at_rest(resolved) {
        format!(
            "{:.4} N   (peak of the sum of the supports)",
            run.transmitted_peak_force_n
        )
    } else {
        "none: the wave did not reach the supports within run.duration_s; increase it".to_string()
    };
    let mut text = format!(
        "scenario     {name}\nlattice      {} layers, {rods} rods, {} contacts ({} supports)\nexcitation   {}\nincident     {:.4} N   ({incident})\ntransmitted  {transmitted}\n",
        resolved.lattice.layers,
        run.contacts,
        run.supports.len(),
        match &resolved.excitation {
            LatticeExcitation::Rest { .. } =>
                "rest: the lattice is left alone (a check of its static equilibrium)".to_string(),
            x => x.as_chain_excitation().to_string(),
        },
        run.incident_peak_force_n + 0.0, // (no -0.0 where no load point is)
    );
    let e = &run.energy;
    if ode.has_lab() {
        if run.static_residual > 0.0 {
            let supports: f64 = run
                .supports
                .iter()
                .map(|&s| run.contact_static_forces_n[s])
                .sum();
            text += &format!(
                "static       supports carry {supports:.6} N (relative residual {:.1e})\n",
                run.static_residual
            );
        }
        if let Some(u) = run.actuator_rest_m {
            text += &format!("actuator     tips at rest at u* = {u:.6e} m (downward)\n");
        }
        text += &format!(
            "energy       E(0) {:.4e} J, work {:.4e} J, dissipated {:.4e} J; balance error {:.2e}\n",
            e.initial_j, e.input_work_j, e.dissipated_j, e.max_relative_error
        );
    } else {
        text += &format!(
            "energy       max relative error {:.2e}\n",
            e.max_relative_error
        );
    }
    text += &format!(
        "integrator   {} steps; {} samples\noutput       {}\n",
        run.stats.steps,
        run.times_s.len(),
        dir.display()
    );
    text
}

/// Most labels, or runs of equal labels, a `chain` line lists before it abbreviates.
const CHAIN_RUNS_SHOWN: usize = 24;

/// Element labels top to bottom; for a chain longer than [`CHAIN_RUNS_SHOWN`], runs of equal ones
/// as `80mm×40`, and when still too many the first and last runs around `… (N more runs) …`: one
/// line, however long the chain.
fn abbreviated_labels(labels: &[String]) -> String {
    if labels.len() <= CHAIN_RUNS_SHOWN {
        return labels.join(" ");
    }
    let mut runs: Vec<(&str, usize)> = Vec::new();
    for l in labels {
        match runs.last_mut() {
            Some((last, n)) if *last == l.as_str() => *n += 1,
            _ => runs.push((l.as_str(), 1)),
        }
    }
    let text = |r: &[(&str, usize)]| {
        r.iter()
            .map(|&(l, n)| {
                if n == 1 {
                    l.to_string()
                } else {
                    format!("{l}×{n}")
                }
            })
            .collect::<Vec<_>>()
            .join(" ")
    };
    if runs.len() <= CHAIN_RUNS_SHOWN {
        return text(&runs);
    }
    let (head, tail) = (CHAIN_RUNS_SHOWN * 2 / 3, CHAIN_RUNS_SHOWN / 3);
    format!(
        "{} … ({} more runs) … {}",
        text(&runs[..head]),
        runs.len() - head - tail,
        text(&runs[runs.len() - tail..])
    )
}

/// The short report of a chain's run that front ends show (`woodpile simulate` prints it).
pub fn run_summary(r: &RunRecord<'_>, dir: &Path) -> String {
    let s = SummaryJson::new(r);
    let chain = &r.resolved.chain;
    let mut o = String::new();
    let labels = abbreviated_labels(&s.chain_labels);
    o.push_str(&format!("scenario     {}\n", r.name));
    o.push_str(&format!(
        "chain        {} elements: {labels}\n",
        chain.len()
    ));
    o.push_str(&format!("excitation   {}\n", r.resolved.excitation));
    // Under a static load: totals, and the dynamic parts (total − static) beside them.
    let statics = &r.summary.static_contact_forces_n;
    let dynamic = |c: usize, total: f64| match statics.get(c) {
        Some(f) => format!(", dynamic {:.4} N (static {f:.4} N)", total - f),
        None => String::new(),
    };
    o.push_str(&format!(
        "incident     {:.4} N   (peak of contact 1{})\n",
        s.incident_peak_force_n,
        dynamic(1, s.incident_peak_force_n)
    ));
    o.push_str(&format!(
        "transmitted  {:.4} N   (peak of contact {}, the wall{})\n",
        s.transmitted_peak_force_n,
        s.n_elements,
        dynamic(s.n_elements, s.transmitted_peak_force_n)
    ));
    if let Some(u) = s.actuator_rest_m {
        o.push_str(&format!(
            "actuator     tip at rest at u* = {u:.6e} m (downward)\n"
        ));
    }
    match s.transmission_ratio {
        Some(r) => o.push_str(&format!("ratio        {r:.4}\n")),
        None if !s.wave_arrived => o.push_str(
            "ratio        none: the wave did not reach the wall within run.duration_s; increase it\n",
        ),
        None => o.push_str("ratio        none: the incident force is zero\n"),
    }
    match (s.restitution_coefficient, s.striker_separated) {
        (Some(e), _) => o.push_str(&format!("restitution  {e:.4}\n")),
        (None, Some(false)) => o.push_str(
            "restitution  none: the striker is still in contact or moving with the chain at the end; increase run.duration_s\n",
        ),
        _ => {}
    }
    o.push_str(&format!(
        "energy       initial {:.4e} J, final {:.4e} J, input work {:.4e} J, dissipated {:.4e} J, max relative error {:.2e}\n",
        s.energy.initial_j,
        s.energy.final_j,
        s.energy.input_work_j,
        r.summary.energy.dissipated_j,
        s.energy.max_relative_error
    ));
    o.push_str(&format!(
        "integrator   {}: {} steps, {} rhs evaluations, {} rejected; {} samples; {:.3} s wall time\n",
        s.integrator.method,
        s.integrator.steps,
        s.integrator.rhs_evaluations,
        s.integrator.rejected_steps,
        s.n_samples,
        s.wall_time_s
    ));
    o.push_str(&format!("output       {}\n", dir.display()));
    o
}

/// The report of K samples of a scenario's `[uncertainty]`: per figure its mean, sd, 0.95
/// quantile and CVaR.
pub fn samples_summary(
    dir: &Path,
    k: usize,
    elapsed: f64,
    runs: &[woodpile::RunSummary],
) -> String {
    let mut text = format!(
        "{k} samples in {elapsed:.2} s ({:.0} runs/s) -> {}\n",
        k as f64 / elapsed.max(1e-9),
        dir.display()
    );
    for (j, name) in FIGURES.iter().enumerate() {
        let values: Option<Vec<f64>> = runs
            .iter()
            .map(|r| crate::uncertainty::figures(r)[j])
            .collect();
        text += &match values {
            Some(v) => {
                let s = woodpile::uncertainty::statistics(&v);
                format!(
                    "  {name:<26} mean {:.6e}  sd {:.3e}  q0.95 {:.6e}  cvar_0.95 {:.6e}\n",
                    s.mean, s.sd, s.quantiles[4].1, s.cvar_95
                )
            }
            None => format!("  {name:<26} not every sample has one (see summary.json)\n"),
        };
    }
    text
}

/// The report of a sensitivity study: per figure, each parameter's S1 and ST with their
/// intervals.
pub fn sensitivity_summary(
    parameters: &[String],
    per_figure: &[(&'static str, FigureIndices)],
    rows: usize,
    elapsed: f64,
    dir: &Path,
) -> String {
    let mut text = format!(
        "{rows} runs in {elapsed:.2} s ({:.0} runs/s) -> {}\n",
        rows as f64 / elapsed.max(1e-9),
        dir.display()
    );
    for (figure, result) in per_figure {
        text += &format!("{figure}\n");
        match result {
            FigureIndices::Indices(s) => {
                for (p, i) in parameters.iter().zip(s) {
                    text += &format!(
                        "  {p:<22} S1 {:>9} ± {:<9}  ST {:>9} ± {}\n",
                        index(i.first_order),
                        index(i.first_order_conf),
                        index(i.total),
                        index(i.total_conf)
                    );
                }
            }
            FigureIndices::Meaningless(reason) => text += &format!("  no indices: {reason}\n"),
        }
    }
    text
}

/// An index as text: three decimals, or two significant digits below 1e-3 (so that a small
/// index is not shown as 0.000).
fn index(v: f64) -> String {
    if v != 0.0 && v.abs() < 1e-3 {
        format!("{v:.1e}")
    } else {
        format!("{v:.3}")
    }
}
