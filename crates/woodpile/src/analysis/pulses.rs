//! Pulses in force histories: when a wave arrives, how it splits into separated pulses, and how
//! much a frequency band carries against its neighbourhood. These measure the paper's qualitative
//! claims (docs/physics.md §9): a solitary wave in 20 mm chains, pulses split into groups in 40
//! and 80 mm chains, depleted negative-mass bands in the blast spectra.

use super::{contact_spectrum_map, SpectrumSettings};
use crate::error::Result;
use crate::record::Trajectory;

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
pub struct FirstTransit {
    /// A name for the chain (for tables).
    pub name: String,
    /// First arrival at contact 1 \[s\].
    pub arrival_top_s: f64,
    /// First arrival at the wall \[s\].
    pub arrival_wall_s: f64,
    /// Separated peaks at the wall within one transit time after the arrival.
    pub peaks: Vec<(f64, f64)>,
}

impl FirstTransit {
    /// The first transit of an impact run's wave at the wall; `name` labels it.
    pub fn of(name: &str, t: &Trajectory) -> Self {
        let n = t.n_elements;
        let wall = t.contact_force_n(n);
        let a1 = arrival_s(&t.times_s, &t.contact_force_n(1), 0.05).unwrap_or(0.0);
        let aw = arrival_s(&t.times_s, &wall, 0.05).unwrap_or(0.0);
        FirstTransit {
            name: name.to_string(),
            arrival_top_s: a1,
            arrival_wall_s: aw,
            peaks: separated_peaks(&t.times_s, &wall, aw, aw + (aw - a1), 0.05),
        }
    }

    /// Time between the two largest peaks \[s\].
    pub fn main_gap_s(&self) -> Option<f64> {
        let mut p = self.peaks.clone();
        p.sort_by(|a, b| b.1.total_cmp(&a.1));
        (p.len() >= 2).then(|| (p[1].0 - p[0].0).abs())
    }

    /// The second largest peak over the largest.
    pub fn second_ratio(&self) -> Option<f64> {
        let mut f: Vec<f64> = self.peaks.iter().map(|p| p.1).collect();
        f.sort_by(|a, b| b.total_cmp(a));
        (f.len() >= 2).then(|| f[1] / f[0])
    }
}

/// Mean spectral amplitude of the contacts 1..N inside `band` over that in the two flanking
/// intervals of half its width: < 1 where the band carries less than its neighbourhood.
pub fn band_contrast(t: &Trajectory, band: (f64, f64)) -> Result<f64> {
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
pub fn peak_layer_energy(t: &Trajectory, layer: usize) -> f64 {
    t.layer_energy_j(layer).into_iter().fold(0.0, f64::max)
}
