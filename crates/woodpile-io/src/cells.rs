//! The unit cell of a rod derived by beam theory (docs/physics.md §13), as `woodpile cells --rod
//! --json` prints it and the Python package returns it: one typed record, resolved exactly as a
//! scenario's `{ kind = "rod" }` element without a given cell.

use crate::error::Error;
use crate::scenario::{
    resolve_element, CellSpec, ElementKind, ElementSpec, MaterialSpec, ReductionSpec,
};
use serde::{Deserialize, Serialize};
use woodpile::BeamTheory;

/// What to derive: a rod and how to reduce it.
#[derive(Debug, Clone, PartialEq)]
pub struct RodRequest {
    /// Length \[mm\].
    pub length_mm: f64,
    /// Outer diameter \[mm\].
    pub diameter_mm: f64,
    /// Inner diameter of a tube \[mm\] (None: solid).
    pub inner_diameter_mm: Option<f64>,
    /// Material preset.
    pub material: String,
    /// Resonators (None: the default rule).
    pub modes: Option<usize>,
    /// The reduction.
    pub reduction: ReductionSpec,
}

/// A derived cell with the rod's own frequencies beside it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DerivedCell {
    /// Length \[mm\].
    pub length_mm: f64,
    /// Outer diameter \[mm\].
    pub diameter_mm: f64,
    /// Inner diameter \[mm\] (0: solid).
    pub inner_diameter_mm: f64,
    /// Material preset.
    pub material: String,
    /// `pole-zero` or `modal-mass`.
    pub reduction: String,
    /// ρ·A·L \[g\].
    pub total_mass_g: f64,
    /// Primary mass M \[g\].
    pub primary_mass_g: f64,
    /// The resonators.
    pub resonators: Vec<DerivedResonator>,
    /// Zeros of the cell's effective mass (its free resonances) \[kHz\].
    pub free_resonances_khz: Vec<f64>,
    /// The rod's symmetric free–free bending frequencies (Timoshenko) \[kHz\].
    pub rod_free_free_khz: Vec<f64>,
    /// The rod's centre-blocked frequencies (Timoshenko) \[kHz\].
    pub rod_centre_blocked_khz: Vec<f64>,
}

/// One resonator of a derived cell.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DerivedResonator {
    /// m_j \[g\].
    pub mass_g: f64,
    /// k_j \[kN/mm\].
    pub stiffness_kn_per_mm: f64,
    /// f_j = sqrt(k_j/m_j)/2π \[kHz\].
    pub frequency_khz: f64,
}

/// Derives the cell of `request`; `key("length_mm")` names a value in errors (a front end maps
/// the element keys to its own names: flags, keyword arguments).
pub fn derive(request: &RodRequest, key: &dyn Fn(&str) -> String) -> Result<DerivedCell, Error> {
    let spec = ElementSpec {
        kind: Some(ElementKind::Rod),
        length_mm: Some(request.length_mm),
        diameter_mm: Some(request.diameter_mm),
        inner_diameter_mm: request.inner_diameter_mm,
        material: Some(MaterialSpec::preset(&request.material)),
        cell: Some(CellSpec {
            modes: request.modes,
            reduction: Some(request.reduction),
            ..CellSpec::default()
        }),
        ..ElementSpec::default()
    };
    let element = resolve_element(&spec, key, woodpile::CellModel::Resonant, &mut Vec::new())?;
    let cell = &element.cell;
    let inner_mm = request.inner_diameter_mm.unwrap_or(0.0);
    let rod = woodpile::Rod::new(
        request.length_mm * 1e-3,
        request.diameter_mm * 1e-3,
        inner_mm * 1e-3,
        element.material.clone(),
    )?;
    let l = cell.resonators.len();
    let khz = |v: Vec<f64>| v.into_iter().map(|f| f * 1e-3).collect::<Vec<_>>();
    let t = BeamTheory::Timoshenko;
    Ok(DerivedCell {
        length_mm: request.length_mm,
        diameter_mm: request.diameter_mm,
        inner_diameter_mm: inner_mm,
        material: request.material.clone(),
        reduction: request.reduction.reduction().name().to_string(),
        total_mass_g: cell.total_mass_kg() * 1e3,
        primary_mass_g: cell.primary_mass_kg * 1e3,
        resonators: cell
            .resonators
            .iter()
            .map(|r| DerivedResonator {
                mass_g: r.mass_kg * 1e3,
                stiffness_kn_per_mm: r.stiffness_n_per_m * 1e-6,
                frequency_khz: r.angular_frequency() / (2.0 * std::f64::consts::PI) * 1e-3,
            })
            .collect(),
        free_resonances_khz: khz(cell.free_resonances_hz()),
        rod_free_free_khz: khz(rod.free_symmetric_frequencies_hz(t, l)?),
        rod_centre_blocked_khz: khz(rod.centre_blocked_frequencies_hz(t, l)?),
    })
}
