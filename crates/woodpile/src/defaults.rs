//! Every default of the model and of a run, stated once (docs/physics.md gives the reasons).
//!
//! The scenario format (`woodpile-io`), the command line and the Python package take their
//! defaults from here and nowhere else; the constructors of this crate
//! ([`crate::Striker::paper`], [`crate::BlastProfile::paper`], [`crate::RunSettings::paper_impact`],
//! [`crate::Wall::paper_sensor`], …) are built from the same constants.

/// Drop height h of the striker \[m\] (docs/physics.md §2): v0 = sqrt(2 g h).
pub const DROP_HEIGHT_M: f64 = 0.20;
/// Standard gravity g \[m/s²\] used to turn a drop height into an impact velocity.
pub const GRAVITY_M_S2: f64 = 9.81;
/// Striker sphere diameter \[mm\] (§2).
pub const STRIKER_DIAMETER_MM: f64 = 10.0;
/// Striker material preset (§2; the paper says "glass").
pub const STRIKER_MATERIAL: &str = "soda-lime-glass";
/// Friedlander peak force F0 \[N\] (§6; an assumption: the paper gives no number).
pub const BLAST_PEAK_FORCE_N: f64 = 200.0;
/// Friedlander positive-phase duration Td \[s\] (§6; an assumption).
pub const BLAST_DURATION_S: f64 = 2e-4;
/// Friedlander decay constant b (§6: 1 = classic Friedlander, 0 = triangle).
pub const BLAST_DECAY: f64 = 1.0;
/// Material preset of the sensor cap or flat under the chain (§2).
pub const WALL_MATERIAL: &str = "stainless-steel";
/// Radius of the sensor's spherical cap R_c \[mm\] (§2; an assumption).
pub const WALL_CAP_RADIUS_MM: f64 = 5.0;
/// Diameter of a user rod when none is given \[mm\] (the paper's rods).
pub const ROD_DIAMETER_MM: f64 = 5.0;
/// Material preset of a user rod or sphere when none is given (the paper's rods).
pub const ELEMENT_MATERIAL: &str = "fused-quartz";
/// A rod's derived unit cell gets one resonator per centre-blocked bending mode below this
/// frequency \[Hz\] (at least one, at most four; docs/physics.md §13). 38 kHz gives the paper's
/// choice for all seven Table 1 rods: one mode for 20–40 mm, two for 50–80 mm.
pub const CELL_MODE_CUTOFF_HZ: f64 = 38e3;
/// Angle between the axes of neighbouring rods \[deg\] (§1).
pub const CROSSING_ANGLE_DEG: f64 = 90.0;
/// Simulated time of an impact run \[s\] (§8).
pub const IMPACT_DURATION_S: f64 = 2e-3;
/// Simulated time of a blast run \[s\] (§8).
pub const BLAST_RUN_DURATION_S: f64 = 3e-3;
/// Fixed RK4 time step Δt \[s\] (§8: converges peak forces to ~1e-6).
pub const TIME_STEP_S: f64 = 1e-7;
/// Relative tolerance of the adaptive Dormand–Prince method.
pub const RTOL: f64 = 1e-9;
/// Absolute tolerance of the adaptive method \[m\] (displacements; velocities are scaled).
pub const ATOL: f64 = 1e-15;
/// Spacing of the uniform sample grid Δs \[s\] (§8).
pub const SAMPLE_INTERVAL_S: f64 = 1e-6;
/// Number of positions of the paper's design problem (§11).
pub const DESIGN_POSITIONS: usize = 20;
/// A transmitted peak below this fraction of the incident peak means the wave never reached the
/// wall within the run: the transmission ratio is then not reported (docs/physics.md §8).
pub const WAVE_ARRIVAL_FRACTION: f64 = 1e-3;
/// Smallest step of the adaptive integrator as a fraction of the run's end time: a step below it
/// (more than 1e10 steps for the run) is refused as [`crate::Error::StepSizeTooSmall`].
pub const MIN_STEP_FRACTION: f64 = 1e-10;
/// Most integration steps a run may take before it stops with [`crate::Error::TooManySteps`]
/// (a backstop for adaptive runs; front ends refuse fixed-step runs above it before starting).
pub const MAX_STEPS: u64 = 1_000_000_000;
/// Relative energy-balance error above which a run warns that it may be inaccurate.
pub const ENERGY_ERROR_WARN: f64 = 1e-4;
/// Relative energy-balance error above which a run is refused as inaccurate (unless the user
/// asks for its results anyway).
pub const ENERGY_ERROR_FAIL: f64 = 1e-2;

/// Transmission spectra (docs/physics.md §15): lowest frequency of the chirp \[Hz\].
pub const TRANSMISSION_START_HZ: f64 = 100.0;
/// Highest frequency of the chirp \[Hz\].
pub const TRANSMISSION_END_HZ: f64 = 30e3;
/// Frequency resolution \[Hz\] (the record lasts its inverse: 100 ms; with the measurement damping
/// every edge of 40-rod chains lands within 0.3 % of the linear prediction, docs/physics.md §15).
pub const TRANSMISSION_RESOLUTION_HZ: f64 = 10.0;
/// Chirp amplitude as a fraction of the static force on the top element: small enough that no
/// contact opens and the chain stays linear about its equilibrium.
pub const TRANSMISSION_RELATIVE_AMPLITUDE: f64 = 0.01;
/// Sample interval of the recorded forces \[s\] (Nyquist 100 kHz).
pub const TRANSMISSION_SAMPLE_INTERVAL_S: f64 = 5e-6;
/// On-site damping time τ \[s\] a chain without damping gets for its transmission measurement.
pub const TRANSMISSION_DAMPING_TIME_S: f64 = 0.02;
/// A frequency where the transmission is below this level \[dB\] is in a measured stop band.
pub const TRANSMISSION_STOP_DB: f64 = -20.0;

/// Longest rod, in diameters, whose cell is derived from beam theory (docs/physics.md §13): at
/// 10⁴ diameters a 5 mm fused-quartz rod (50 m) has its first bending mode at 6.4 mHz.
pub const ROD_MAX_SLENDERNESS: f64 = 1e4;
/// Design studies (`woodpile optimize` without `--paper-settings`): every contact peak within
/// this relative tolerance (bench/README.md: the paper's GA makes the same choices as at RK4
/// 0.1 µs, several times faster).
pub const STUDY_PEAK_TOLERANCE: f64 = 1e-5;
/// Design studies: the breeder GA screens new designs at this looser peak tolerance first
/// (docs/physics.md §11; a force objective).
pub const STUDY_SCREEN_PEAK_TOLERANCE: f64 = 3e-4;
/// Calibration (`fit`, docs/fit.md): number of starts (the initial values, then Sobol' points).
pub const FIT_STARTS: usize = 8;
/// Most residual evaluations of one start of a fit.
pub const FIT_MAX_EVALUATIONS: usize = 200;
/// Step of the fit's central-difference Jacobian as a fraction of a parameter's range: wide
/// enough to average over the kinks a contact opening or closing between RK4 stages puts into
/// the fixed-step model (the restitution law's δ^{1/4} makes them steep), narrow enough that the
/// O(h²) truncation stays below 1e-5 (measured in docs/fit.md).
pub const FIT_JACOBIAN_STEP: f64 = 1e-4;
/// Relative tolerance of a fit on the cost and the parameters (MINPACK's ftol, xtol).
pub const FIT_TOLERANCE: f64 = 1e-10;
/// |correlation| above which two fitted parameters are reported as not separable by the data.
pub const FIT_CORRELATION_WARN: f64 = 0.95;
/// The model is sampled this many times finer than the measurement's smallest time step and
/// interpolated onto the measured times.
pub const FIT_OVERSAMPLING: f64 = 4.0;

/// Base samples N of a sensitivity study (`woodpile sensitivity`): N·(G + 2) runs for G
/// scattered parameters; a power of two keeps the Sobol' points balanced.
pub const SENSITIVITY_BASE_SAMPLES: usize = 64;
/// Bootstrap resamples of a sensitivity study's confidence intervals (SALib's default).
pub const SENSITIVITY_RESAMPLES: usize = 100;
/// Confidence level of a sensitivity study's intervals (SALib's default).
pub const SENSITIVITY_CONFIDENCE: f64 = 0.95;
/// Samples of a scenario's `[uncertainty]` when `samples` is not given.
pub const UNCERTAINTY_SAMPLES: usize = 32;

/// Seed of the scrambled Sobol' points of `[uncertainty]` when `seed` is not given.
pub const UNCERTAINTY_SEED: u32 = 0;
