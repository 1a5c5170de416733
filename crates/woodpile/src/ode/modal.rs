//! The linear part of the chain in modal form (docs/physics.md §8, "Exact linear vibrations"):
//! each element — a primary mass M carrying resonators (m_j, k_j), a Table 1 cell or a
//! finite-element rod's Craig–Bampton cell — decomposed into its free–free modes, so that the
//! equations of motion read, per element,
//!
//! ```text
//! μ_k (c_k'' + Ω_k² c_k) = F_net(t),      x_primary = Σ_k c_k,
//! ```
//!
//! k = 0 the rigid mode (Ω_0 = 0, μ_0 = M + Σ m_j), k ≥ 1 the free cell's resonances Ω_k (the
//! zeros of M_eff, [`crate::UnitCell::free_resonances_hz`]), each mode scaled to unit amplitude
//! at the primary, with modal mass μ_k = M + Σ_j m_j u_jk² where u_jk = ω_j²/(ω_j² − Ω_k²) is
//! resonator j's amplitude in mode k. The contact forces act on the primaries only, so F_net is
//! all that couples the modes: the linear part is diagonal and can be integrated exactly.
//!
//! Each element's modes are [`ElementModes`] (`ode::element_modes`: Ω_k² from the secular
//! equation).
//!
//! Damped cells: on-site damping (every mass at 1/τ) keeps these modes, each decaying at 1/τ;
//! resonator dashpots do not, and such a cell is held in its complex modes
//! ([`DampedCell`]), each a damped oscillator whose weights B, A enter where 1/μ_k and 0 do here.

use super::damped_modes::{DampedCell, DampedResonator};
use super::element_modes::ElementModes;
use super::ChainOde;
use crate::error::Result;

/// Modes per primary padded to whole groups of four (the passes over the modes then run in
/// vectors with no remainder).
fn padded(modes: usize) -> usize {
    modes.div_ceil(4) * 4
}

/// The whole chain in modal form: every primary's modes (a striker: its rigid mode only), in
/// one flat list (each primary's padded to a multiple of four with massless modes at rest),
/// with the conversions to and from the chain's state.
#[derive(Debug, Clone)]
pub(crate) struct ModalChain {
    /// Per primary: its modes (shared by primaries of equal cells).
    pub elements: Vec<std::sync::Arc<ElementModes>>,
    /// Per primary: the range of its modes in the flat list (padding included).
    pub ranges: Vec<std::ops::Range<usize>>,
    /// Per primary: the range of its resonators in the chain's state.
    res_ranges: Vec<std::ops::Range<usize>>,
    /// Per primary: its distinct element (equal cells are one), whose modes are
    /// `kind_ranges[kind[i]]` of the per-mode lists below.
    pub kind: Vec<usize>,
    pub kind_ranges: Vec<std::ops::Range<usize>>,
    /// Per mode of a distinct element: the index of its frequency in
    /// [`ModalChain::frequencies`].
    pub frequency_index: Vec<usize>,
    /// The distinct (Ω \[rad/s\], damping rate 2γ \[1/s\]) of the chain (equal cells share
    /// theirs): on-site damping 1/τ acts on every mass of an element alike, so it damps each of
    /// its modes, the rigid one included, at 1/τ (mass-proportional damping keeps the modes).
    pub frequencies: Vec<(f64, f64)>,
    /// Per distinct element: its damping rate 1/τ \[1/s\] (0: undamped).
    pub kind_rate: Vec<f64>,
    /// Per mode of a distinct element: 1/μ_k \[1/kg\], μ_k \[kg\] and Ω_k² \[1/s²\].
    pub inv_modal_mass: Vec<f64>,
    pub modal_mass: Vec<f64>,
    pub omega2: Vec<f64>,
    /// Per mode of a distinct element: the weight A \[s/kg\] of its rate in the primary's
    /// displacement (0 but for a cell with dashpots, whose B is in `inv_modal_mass` and whose
    /// `modal_mass` is 0: its energy is not diagonal in the modes).
    pub a_weight: Vec<f64>,
    /// Per distinct element: its complex modes when its resonators have dashpots.
    pub damped: Vec<Option<std::sync::Arc<DampedCell>>>,
    /// Per distinct element: its primary's acceleration per newton of net force, Σ_k (B_k −
    /// 2γ_k A_k) (Σ 1/μ_k undamped) \[1/kg\].
    pub accel_per_newton: Vec<f64>,
}

/// A chain's cells: per primary its modes and its distinct element, per distinct element its
/// on-site rate and, with dashpots, its complex modes.
struct Cells {
    elements: Vec<std::sync::Arc<ElementModes>>,
    res_ranges: Vec<std::ops::Range<usize>>,
    kind: Vec<usize>,
    distinct: Vec<std::sync::Arc<ElementModes>>,
    kind_rate: Vec<f64>,
    damped: Vec<Option<std::sync::Arc<DampedCell>>>,
}

impl Cells {
    fn of(ode: &ChainOde) -> Result<Self> {
        let (p, eq) = (ode.eq.p, &ode.eq);
        let rate = |i: usize| eq.lab.as_ref().map_or(0.0, |l| l.on_site_rate[i]);
        let dashpot = |j: usize| eq.lab.as_ref().map_or(0.0, |l| l.res_damping[j]);
        let resonator = |j: usize| (ode.res_mass_kg[j], ode.res_stiffness[j], dashpot(j));
        let mut cells = Cells {
            elements: Vec::with_capacity(p),
            res_ranges: Vec::with_capacity(p),
            kind: Vec::with_capacity(p),
            distinct: Vec::new(),
            kind_rate: Vec::new(),
            damped: Vec::new(),
        };
        let mut start = 0;
        for i in 0..p {
            let end = start
                + eq.res_owner[start..]
                    .iter()
                    .take_while(|&&o| o == i)
                    .count();
            let cell: Vec<DampedResonator> = (start..end).map(resonator).collect();
            let known = (0..i).find(|&k| {
                let range = cells.res_ranges[k].clone();
                rate(k) == rate(i)
                    && ode.mass_kg[k] == ode.mass_kg[i]
                    && range.len() == cell.len()
                    && range.zip(&cell).all(|(j, c)| resonator(j) == *c)
            });
            match known {
                Some(k) => {
                    cells.elements.push(cells.elements[k].clone());
                    cells.kind.push(cells.kind[k]);
                }
                None => {
                    let undamped: Vec<(f64, f64)> = cell.iter().map(|r| (r.0, r.1)).collect();
                    let modes = std::sync::Arc::new(ElementModes::new(ode.mass_kg[i], &undamped)?);
                    let damped = if cell.iter().any(|r| r.2 > 0.0) {
                        let d = DampedCell::new(ode.mass_kg[i], &cell, rate(i), &modes)?;
                        Some(std::sync::Arc::new(d))
                    } else {
                        None
                    };
                    cells.kind.push(cells.distinct.len());
                    cells.distinct.push(modes.clone());
                    cells.kind_rate.push(rate(i));
                    cells.damped.push(damped);
                    cells.elements.push(modes);
                }
            }
            cells.res_ranges.push(start..end);
            start = end;
        }
        Ok(cells)
    }

    /// Number of modes of distinct element k.
    fn modes_of(&self, k: usize) -> usize {
        self.distinct[k].len()
    }
}

/// The per-mode lists of the distinct elements, built kind by kind.
#[derive(Default)]
struct ModeLists {
    frequencies: Vec<(f64, f64)>,
    frequency_index: Vec<usize>,
    inv_modal_mass: Vec<f64>,
    a_weight: Vec<f64>,
    force_accel: Vec<f64>,
    damped_mode: Vec<bool>,
}

impl ModeLists {
    /// Appends distinct element k's modes, padded to whole groups of four with modes of
    /// frequency 0 and no weight, which stay at rest.
    fn push_kind(&mut self, cells: &Cells, k: usize) {
        let e = &cells.distinct[k];
        let rate = cells.kind_rate[k];
        // (ω, 2γ, B, A) per mode.
        let modes: Vec<(f64, f64, f64, f64)> = match &cells.damped[k] {
            Some(d) => (0..d.len())
                .map(|m| (d.omega[m], d.rate[m], d.b[m], d.a[m]))
                .collect(),
            None => (e.omega.iter().zip(&e.modal_mass))
                .map(|(&w, &mu)| (w, rate, 1.0 / mu, 0.0))
                .collect(),
        };
        let padding = (modes.len()..padded(modes.len())).map(|_| (0.0, rate, 0.0, 0.0));
        for (w, r, b, a) in modes.into_iter().chain(padding) {
            let index = (self.frequencies.iter().position(|&f| f == (w, r))).unwrap_or_else(|| {
                self.frequencies.push((w, r));
                self.frequencies.len() - 1
            });
            self.frequency_index.push(index);
            self.inv_modal_mass.push(b);
            self.a_weight.push(a);
            self.force_accel.push(b - r * a);
            self.damped_mode.push(cells.damped[k].is_some());
        }
    }
}

impl ModalChain {
    /// The modal form of a compiled chain: its cells' modes, undamped or under on-site damping
    /// (the undamped modes, each decaying at 1/τ) or under resonator dashpots (the cell's
    /// complex modes, [`DampedCell`]).
    pub fn new(ode: &ChainOde) -> Result<Self> {
        let cells = Cells::of(ode)?;
        let (p, mut ranges, mut n) = (cells.elements.len(), Vec::new(), 0);
        for i in 0..p {
            let len = cells.modes_of(cells.kind[i]);
            ranges.push(n..n + padded(len));
            n += padded(len);
        }
        let mut lists = ModeLists::default();
        let mut kind_ranges = Vec::with_capacity(cells.distinct.len());
        for k in 0..cells.distinct.len() {
            let start = lists.frequency_index.len();
            lists.push_kind(&cells, k);
            kind_ranges.push(start..lists.frequency_index.len());
        }
        let accel_per_newton = kind_ranges
            .iter()
            .map(|r| r.clone().map(|m| lists.force_accel[m]).sum())
            .collect();
        let modal_mass = (lists.inv_modal_mass.iter())
            .zip(&lists.damped_mode)
            .map(|(&m, &damped)| if m == 0.0 || damped { 0.0 } else { 1.0 / m })
            .collect();
        let omega2 = (lists.frequency_index.iter())
            .map(|&u| lists.frequencies[u].0 * lists.frequencies[u].0)
            .collect();
        Ok(ModalChain {
            modal_mass,
            omega2,
            ranges,
            res_ranges: cells.res_ranges,
            kind: cells.kind,
            kind_ranges,
            frequency_index: lists.frequency_index,
            frequencies: lists.frequencies,
            kind_rate: cells.kind_rate,
            damped: cells.damped,
            accel_per_newton,
            a_weight: lists.a_weight,
            inv_modal_mass: lists.inv_modal_mass,
            elements: cells.elements,
        })
    }

    /// Primary i's distinct element's modes as groups of four of the per-mode lists.
    pub fn groups(&self, i: usize) -> std::ops::Range<usize> {
        let modes = &self.kind_ranges[self.kind[i]];
        modes.start / 4..modes.end / 4
    }

    /// Number of modes of the chain.
    pub fn n_modes(&self) -> usize {
        self.ranges.last().map_or(0, |r| r.end)
    }

    /// Modal amplitudes and rates (c, ċ) of the chain's state y = [x | w | v | ẇ | …].
    pub fn project_state(&self, y: &[f64], c: &mut [f64], cdot: &mut [f64]) {
        let p = self.ranges.len();
        let nd = p + self.res_ranges.last().map_or(0, |r| r.end);
        for (i, e) in self.elements.iter().enumerate() {
            let (res, start) = (self.res_ranges[i].clone(), self.ranges[i].start);
            let modes = start..start + e.len();
            let (ra, rb) = (p + res.start, p + res.end);
            if let Some(d) = &self.damped[self.kind[i]] {
                let (x, v) = (&y[ra..rb], &y[nd + ra..nd + rb]);
                d.project(
                    (y[i], y[nd + i]),
                    x,
                    v,
                    &mut c[modes.clone()],
                    &mut cdot[modes],
                );
                continue;
            }
            e.project(y[i], &y[ra..rb], &mut c[modes.clone()]);
            e.project(y[nd + i], &y[nd + ra..nd + rb], &mut cdot[modes]);
        }
    }
}

/// Each cell with resonator dashpots of `ode` at its state y: [`DampedCell::energy`]'s
/// (energy, dissipated power, damping acceleration) as run (the AVX2 build where the CPU has
/// it), then the portable build's: what the claim `simd_step_bit_identical` compares bit for
/// bit.
#[doc(hidden)]
pub fn damped_cell_energies(ode: &ChainOde, y: &[f64]) -> Result<Vec<[(f64, f64, f64); 2]>> {
    let modal = ModalChain::new(ode)?;
    let n = modal.n_modes();
    let (mut c, mut cdot) = (vec![0.0; n], vec![0.0; n]);
    modal.project_state(y, &mut c, &mut cdot);
    let cells = modal.ranges.iter().zip(&modal.kind);
    Ok(cells
        .filter_map(|(range, &kind)| {
            let (c, cdot) = (&c[range.clone()], &cdot[range.clone()]);
            let cell = modal.damped[kind].as_ref()?;
            Some([cell.energy(c, cdot), cell.energy_portable(c, cdot)])
        })
        .collect())
}
