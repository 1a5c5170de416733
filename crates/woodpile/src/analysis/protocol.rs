//! The paper's experimental protocol (§2, Fig. 7): the force sensor only sits under the last
//! element, so the experiment measured the sub-chains of the first k = 1, 2, …, N elements on the
//! sensor one at a time. The wall force of sub-chain k is the "incident force" at interface k of
//! the full chain (until the reflection from the missing rods below would arrive).

use super::map::{Axis, Map2};
use crate::error::{Error, Result};
use crate::excitation::Excitation;
use crate::model::{Chain, ChainBuilder, Wall};
use crate::record::EndForces;
use crate::simulate::{simulate, RunSettings, RunSummary};
use rayon::prelude::*;

/// The results of the layer-by-layer protocol.
#[derive(Debug, Clone, PartialEq)]
pub struct LayerByLayer {
    /// Wall force of sub-chain k (row k−1, k = 1..=N) over time \[s\] \[N\].
    pub wall_force_map: Map2,
    /// Peak wall force of each sub-chain \[N\] (refined between steps, as in [`RunSummary`]).
    pub peak_wall_force_n: Vec<f64>,
    /// Time of each peak \[s\].
    pub peak_time_s: Vec<f64>,
    /// The figures of merit of each sub-chain's run.
    pub summaries: Vec<RunSummary>,
}

/// The sub-chain of the first `k` elements of `chain` (1 ≤ k ≤ N) on the same wall: every contact
/// coefficient of the full chain is kept (including overrides); the wall contact is recomputed
/// for element k unless the full chain's wall coefficient was overridden, in which case the same
/// sensor coefficient is used.
pub fn sub_chain(chain: &Chain, k: usize) -> Result<Chain> {
    let n = chain.len();
    if k == 0 || k > n {
        return Err(Error::invalid(
            "sub-chain length k",
            k,
            format!("must be in 1..={n}"),
        ));
    }
    if matches!(chain.wall(), Wall::Free) {
        return Err(Error::invalid(
            "chain.wall",
            "free",
            "the layer-by-layer protocol measures the wall force: the chain needs a wall",
        ));
    }
    // The same dissipation and static load; resonator overrides of the elements kept.
    let mut damping = chain.damping().clone();
    damping.resonator_overrides.retain(|o| o.element <= k);
    let builder = |k: usize| {
        let mut b = ChainBuilder::new(chain.elements()[..k].to_vec())
            .wall(chain.wall().clone())
            .crossing_angle_rad(chain.crossing_angle_rad())
            .damping(damping.clone())
            .preload(*chain.preload());
        for (i, &beta) in chain.inner_betas()[..k - 1].iter().enumerate() {
            b = b.contact_beta(i + 1, beta);
        }
        b
    };
    // Was the full chain's wall coefficient set by hand? Then the sensor keeps it.
    let computed_wall = builder(n).build()?.wall_beta();
    let mut b = builder(k);
    if computed_wall != chain.wall_beta() {
        if let Some(beta) = chain.wall_beta() {
            b = b.contact_beta(k, beta);
        }
    }
    b.build()
}

/// Runs the sub-chains k = 1..=N of `chain` (in parallel; results in order of k) under the same
/// excitation and settings, and collects each wall force history and its peak.
pub fn layer_by_layer(
    chain: &Chain,
    excitation: &Excitation,
    settings: &RunSettings,
) -> Result<LayerByLayer> {
    let n = chain.len();
    let runs: Vec<(EndForces, RunSummary)> = (1..=n)
        .into_par_iter()
        .map(|k| {
            let sub = sub_chain(chain, k)?;
            let mut rec = EndForces::default();
            let summary = simulate(&sub, excitation, settings, &mut rec)?;
            Ok((rec, summary))
        })
        .collect::<Result<Vec<_>>>()?;
    let times = runs[0].0.times_s.clone();
    let mut data = Vec::with_capacity(n * times.len());
    for (rec, _) in &runs {
        data.extend_from_slice(&rec.wall_n);
    }
    let wall_force_map = Map2::new(
        Axis::new(
            "layers k on the sensor",
            "",
            (1..=n).map(|k| k as f64).collect(),
        ),
        Axis::new("time", "s", times),
        "wall force",
        "N",
        data,
    )?;
    let summaries: Vec<RunSummary> = runs.into_iter().map(|(_, s)| s).collect();
    Ok(LayerByLayer {
        wall_force_map,
        peak_wall_force_n: summaries
            .iter()
            .map(|s| s.transmitted_peak_force_n)
            .collect(),
        peak_time_s: summaries
            .iter()
            .map(|s| *s.contact_peak_times_s.last().expect("N + 1 contacts"))
            .collect(),
        summaries,
    })
}
