//! Effective-mass curves (paper Fig. 3) and the linear band structure of a homogeneous chain
//! (docs/physics.md §10).
//!
//! A homogeneous chain precompressed by a static force F_p has linearised contact stiffness
//! K_c = dF/dδ = (3/2) β^{2/3} F_p^{1/3}. A Bloch wave u_n ∝ e^{i(qna − ωt)} obeys
//!
//! ```text
//! 4 K_c sin²(qa/2) = ω² M_eff(ω),    i.e.  s(ω) := ω² M_eff(ω) / (4 K_c) = sin²(qa/2) ∈ [0, 1].
//! ```
//!
//! What is exactly true, and how the edges are found: every term of M_eff increases with ω, so
//! between consecutive local resonances ω_{j−1} < ω < ω_j (ω_0 = 0, ω_{l+1} = ∞) M_eff rises from
//! −∞ (or from M_total at ω = 0) to +∞ (or to M above the last pole), crossing zero once at the
//! free-cell resonance Ω_{j−1} (paper Eqs. 1, 2). Where M_eff > 0, s = ω² M_eff/(4K_c) is a
//! product of two increasing positive factors, so it rises from 0 to +∞ and crosses 1 exactly once,
//! at ω_c,j. Hence, in order of frequency:
//!
//! - pass band (Ω_{j−1}, ω_c,j) (with Ω_0 := 0), then
//! - gap (ω_c,j, Ω_j): s > 1 up to the pole ω_j, s < 0 (negative mass) from ω_j to Ω_j;
//! - above the last zero Ω_l one more pass band (Ω_l, ω_c,l+1) and a semi-infinite gap.
//!
//! So the upper edge of the j-th gap **is** the zero F_j = Ω_j/2π of M_eff (independent of K_c),
//! every negative-mass band [f_j, F_j] lies inside a gap, and the lower edges are roots of
//! s(ω) = 1, found by bisection in ω² on a bracket where s − 1 changes sign exactly once.

use crate::error::{require_positive, Error, Result};
use crate::math::Libm;
use crate::model::UnitCell;
use std::f64::consts::PI;

/// M_eff(ω)/M_total of one cell over a frequency grid, with its negative-mass bands.
#[derive(Debug, Clone, PartialEq)]
pub struct EffectiveMassCurve {
    /// Frequencies f \[Hz\].
    pub frequencies_hz: Vec<f64>,
    /// M_eff(2πf)/M_total [-] (±∞ exactly at a local resonance).
    pub normalised_mass: Vec<f64>,
    /// Total mass M + Σ m_j \[kg\].
    pub total_mass_kg: f64,
    /// Negative-effective-mass bands (f_j, F_j) \[Hz\] (of the undamped cell).
    pub negative_bands_hz: Vec<(f64, f64)>,
    /// Im M_eff(2πf)/M_total [-]: zero without resonator damping, ≤ 0 with it.
    pub normalised_loss: Vec<f64>,
}

impl EffectiveMassCurve {
    /// Evaluates the curve of `cell` at `frequencies_hz`.
    pub fn of(cell: &UnitCell, frequencies_hz: &[f64]) -> Self {
        let total = cell.total_mass_kg();
        EffectiveMassCurve {
            frequencies_hz: frequencies_hz.to_vec(),
            normalised_mass: frequencies_hz
                .iter()
                .map(|f| cell.effective_mass_kg(2.0 * PI * f) / total)
                .collect(),
            total_mass_kg: total,
            negative_bands_hz: cell.negative_mass_bands_hz(),
            normalised_loss: vec![0.0; frequencies_hz.len()],
        }
    }

    /// The curve with every resonator damped at ratio ζ (docs/physics.md §14): `normalised_mass`
    /// is Re M_eff/M_total and `normalised_loss` Im M_eff/M_total.
    pub fn damped(cell: &UnitCell, frequencies_hz: &[f64], ratio: f64) -> Result<Self> {
        crate::error::require_non_negative("resonator_ratio", ratio)?;
        let total = cell.total_mass_kg();
        let m: Vec<_> = frequencies_hz
            .iter()
            .map(|f| cell.damped_effective_mass_kg(2.0 * PI * f, ratio) / total)
            .collect();
        Ok(EffectiveMassCurve {
            frequencies_hz: frequencies_hz.to_vec(),
            normalised_mass: m.iter().map(|z| z.re).collect(),
            total_mass_kg: total,
            negative_bands_hz: cell.negative_mass_bands_hz(),
            normalised_loss: m.iter().map(|z| z.im).collect(),
        })
    }
}

/// `n` points evenly spaced from `start` to `end` inclusive.
pub fn linspace(start: f64, end: f64, n: usize) -> Vec<f64> {
    match n {
        0 => Vec::new(),
        1 => vec![start],
        _ => (0..n)
            .map(|i| start + (end - start) * i as f64 / (n - 1) as f64)
            .collect(),
    }
}

/// Linearised Hertz stiffness K_c = dF/dδ at a static force F_p: (3/2) β^{2/3} F_p^{1/3} [N/m].
pub fn contact_stiffness_n_per_m(beta: f64, precompression_n: f64) -> Result<f64> {
    require_positive("beta", beta)?;
    require_positive("precompression_n", precompression_n)?;
    Ok(1.5 * beta.libm_powf(2.0 / 3.0) * precompression_n.libm_cbrt())
}

/// Pass bands and band gaps of an infinite homogeneous chain of one cell.
#[derive(Debug, Clone, PartialEq)]
pub struct BandStructure {
    /// The cell.
    pub cell: UnitCell,
    /// Linearised contact stiffness K_c [N/m].
    pub contact_stiffness_n_per_m: f64,
    /// Pass bands [f_lo, f_hi] \[Hz\], ascending; the first starts at 0.
    pub pass_bands_hz: Vec<(f64, f64)>,
    /// Gaps (f_lo, f_hi) \[Hz\], ascending; the last is (cut-off, ∞).
    pub gaps_hz: Vec<(f64, f64)>,
}

impl BandStructure {
    /// Bands of a homogeneous chain of `cell` with contact coefficient β [N/m^1.5] at a static
    /// precompression F_p \[N\].
    pub fn homogeneous(cell: &UnitCell, beta: f64, precompression_n: f64) -> Result<Self> {
        let kc = contact_stiffness_n_per_m(beta, precompression_n)?;
        Self::with_stiffness(cell, kc)
    }

    /// Bands for a given linear contact stiffness K_c [N/m].
    pub fn with_stiffness(cell: &UnitCell, contact_stiffness_n_per_m: f64) -> Result<Self> {
        let kc = require_positive("contact_stiffness_n_per_m", contact_stiffness_n_per_m)?;
        let cell = UnitCell::new(cell.primary_mass_kg, cell.resonators.clone())?;
        let poles: Vec<f64> = cell
            .local_resonances_hz()
            .iter()
            .map(|f| (2.0 * PI * f).powi(2))
            .collect();
        let zeros: Vec<f64> = cell
            .free_resonances_hz()
            .iter()
            .map(|f| (2.0 * PI * f).powi(2))
            .collect();
        let s = |w2: f64| w2 * cell.effective_mass_kg(w2.sqrt()) / (4.0 * kc);
        let to_hz = |w2: f64| w2.sqrt() / (2.0 * PI);
        let mut pass = Vec::with_capacity(poles.len() + 1);
        let mut gaps = Vec::with_capacity(poles.len() + 1);
        let mut lower = 0.0; // Ω_{j−1}², where s = 0 and rises
        for j in 0..=poles.len() {
            let upper_bracket = poles.get(j).copied();
            let wc2 = crossing_of_one(&s, lower, upper_bracket).ok_or_else(|| {
                Error::invalid(
                    "band structure",
                    to_hz(lower),
                    "no band edge found above this frequency [Hz] (overflow?)",
                )
            })?;
            pass.push((to_hz(lower), to_hz(wc2)));
            match zeros.get(j) {
                Some(&z) => {
                    gaps.push((to_hz(wc2), to_hz(z)));
                    lower = z;
                }
                None => gaps.push((to_hz(wc2), f64::INFINITY)),
            }
        }
        Ok(BandStructure {
            cell,
            contact_stiffness_n_per_m: kc,
            pass_bands_hz: pass,
            gaps_hz: gaps,
        })
    }

    /// s(f) = ω² M_eff(ω)/(4 K_c) at f \[Hz\]: sin²(qa/2) inside a pass band.
    pub fn dispersion_ratio(&self, frequency_hz: f64) -> f64 {
        let w = 2.0 * PI * frequency_hz;
        w * w * self.cell.effective_mass_kg(w) / (4.0 * self.contact_stiffness_n_per_m)
    }

    /// Reduced Bloch wavenumber qa ∈ [0, π] at f \[Hz\], or None inside a gap.
    pub fn wavenumber(&self, frequency_hz: f64) -> Option<f64> {
        let s = self.dispersion_ratio(frequency_hz);
        (0.0..=1.0).contains(&s).then(|| 2.0 * s.sqrt().libm_asin())
    }

    /// Whether f \[Hz\] lies inside a gap (open intervals; edges are in the pass bands).
    pub fn in_gap(&self, frequency_hz: f64) -> bool {
        self.gaps_hz
            .iter()
            .any(|&(lo, hi)| frequency_hz > lo && frequency_hz < hi)
    }
}

/// The root in ω² of s(ω²) = 1 on (lo, hi) where s rises monotonically from s(lo) ≤ 1 to +∞ at
/// `hi` (a pole) or at infinity (hi = None: the bracket grows by doubling).
fn crossing_of_one(s: &dyn Fn(f64) -> f64, lo: f64, hi: Option<f64>) -> Option<f64> {
    let hi = match hi {
        Some(h) => h,
        None => {
            let mut h = if lo > 0.0 { 2.0 * lo } else { 1.0 };
            let mut tries = 0;
            while s(h) < 1.0 {
                h *= 2.0;
                tries += 1;
                if tries > 2000 || !h.is_finite() {
                    return None;
                }
            }
            h
        }
    };
    // Below the crossing s < 1 (including s = +0 at a zero of M_eff).
    Some(crate::root::bisect(lo, hi, |w| s(w) < 1.0))
}

/// The negative-effective-mass bands to mark on a chain's spectra \[Hz\], ascending: those of its
/// cells when it has at most two different cells; none with more (their bands would cover the
/// whole axis, and a chain of many kinds has no common band: paper §5).
pub fn chain_bands_hz<'a>(cells: impl IntoIterator<Item = &'a UnitCell>) -> Vec<(f64, f64)> {
    let mut distinct: Vec<&UnitCell> = Vec::new();
    for c in cells {
        if !distinct.contains(&c) {
            distinct.push(c);
        }
    }
    if distinct.len() > 2 {
        return Vec::new();
    }
    let mut bands: Vec<(f64, f64)> = distinct
        .iter()
        .flat_map(|c| c.negative_mass_bands_hz())
        .collect();
    bands.sort_by(|a, b| a.0.total_cmp(&b.0));
    bands
}
