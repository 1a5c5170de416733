//! What a run means: spectra, spatio-temporal maps, effective-mass curves, band gaps and the
//! paper's layer-by-layer protocol. Pure numbers: no plotting or file formats here.
//!
//! - [`Spectrum`] — one-sided amplitude spectrum of any uniformly sampled real signal, with a
//!   [`Window`] and zero [`Padding`]; [`contact_spectrum_map`] for every contact of a
//!   [`Trajectory`](crate::Trajectory) (paper Fig. 9 b, d, f, h).
//! - [`force_map`], [`energy_map`] — contact force (contact × time) and layer energy over the
//!   injected energy (layer × time) as [`Map2`] (paper Figs. 5, 6, 9 a, c, e, g).
//! - [`EffectiveMassCurve`] — M_eff(ω)/M_total of a unit cell with its negative-mass bands
//!   (paper Fig. 3); [`BandStructure`] — pass bands and gaps of a homogeneous chain from the
//!   linearised dispersion relation (docs/physics.md §10).
//! - [`layer_by_layer`] — the experimental protocol of paper §2 / Fig. 7: sub-chains of the
//!   first k elements on the sensor, k = 1..N.
//! - [`transmission()`] — the transmission spectrum of a preloaded chain driven by a small chirp,
//!   with the Bloch prediction for a homogeneous chain ([`TransmissionSpectrum`]) and the exact
//!   linear response of the finite chain ([`LinearChain`]).
//!
//! ```
//! use woodpile::analysis::{force_map, Spectrum, SpectrumSettings};
//! use woodpile::{simulate, CellModel, ChainBuilder, Excitation, RunSettings, Striker, Trajectory};
//!
//! let chain = ChainBuilder::table1_rods(&[40, 40, 40], CellModel::Resonant)?.build()?;
//! let settings = RunSettings { duration_s: 4e-4, ..RunSettings::paper_impact() };
//! let mut trajectory = Trajectory::default();
//! simulate(&chain, &Excitation::Impact(Striker::paper()), &settings, &mut trajectory)?;
//! let map = force_map(&trajectory)?;
//! assert_eq!((map.n_rows(), map.n_cols()), (4, 401));
//! let wall = Spectrum::of(&trajectory.contact_force_n(3), 1e-6, &SpectrumSettings::default())?;
//! assert!(wall.peak().1 > 0.0);
//! # Ok::<(), woodpile::Error>(())
//! ```
//!
//! ## References
//! - Kim, Yang et al., Int. J. Impact Eng. 2017: Figs. 3, 5, 6, 7, 9.
//! - F. J. Harris, Proc. IEEE 66 (1978) 51–83: windows.
//! - H. H. Huang, C. T. Sun, G. L. Huang, Int. J. Eng. Sci. 47 (2009) 610–617: negative
//!   effective mass and band gaps of mass-in-mass chains.

pub mod bands;
pub mod linear;
pub mod map;
pub mod protocol;
pub mod pulses;
pub mod spectrum;
pub mod transmission;

pub use crate::record::sample_interval_s;
pub use bands::{
    chain_bands_hz, contact_stiffness_n_per_m, linspace, BandStructure, EffectiveMassCurve,
};
pub use linear::{LinearChain, LinearResonator};
pub use map::{energy_map, force_map, injected_energy_j, Axis, Map2};
pub use protocol::{layer_by_layer, sub_chain, LayerByLayer};
pub use pulses::{arrival_s, band_contrast, peak_layer_energy, separated_peaks, FirstTransit};
pub use spectrum::{
    contact_spectrum_map, Padding, Scaling, Spectrum, SpectrumPlan, SpectrumSettings, Window,
};
pub use transmission::{
    homogeneous_prediction, transmission, EdgeComparison, EdgeRow, TransmissionSettings,
    TransmissionSpectrum,
};
