//! How the state advances: explicit Runge–Kutta methods given as data (Butcher tableaux) and run
//! by one stage loop, with fixed steps or embedded error control, and dense output between steps.
//!
//! ## References
//! - W. Kutta, "Beitrag zur näherungsweisen Integration totaler Differentialgleichungen", 1901
//!   (the classical fourth-order method).
//! - J. R. Dormand, P. J. Prince, "A family of embedded Runge–Kutta formulae", J. Comput. Appl.
//!   Math. 6 (1980) 19–26 (DOPRI5).
//! - E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential Equations I*, 2nd ed.,
//!   Springer 1993, §II.4 (step-size control, initial step), §II.6 (dense output of DOPRI5) and
//!   §II.14 (Runge–Kutta–Nyström methods).
//! - J. R. Dormand, M. E. A. El-Mikkawy, P. J. Prince, "Families of Runge–Kutta–Nyström
//!   formulae", IMA J. Numer. Anal. 7 (1987) 235–250 (RKN6(4)6FM, [`Tableau::rkn64`]).

use crate::math::Libm;
mod control;
pub mod exponential;
mod kernels;
pub(crate) mod modal_graph;
pub(crate) mod modal_step;

pub(crate) use control::{StepControl, Verdict};
#[doc(hidden)]
pub use modal_graph::exact_modes_lattice_state;
#[doc(hidden)]
pub use modal_step::{exact_modes_observations, exact_modes_state};

pub(crate) use kernels::{attempt, missed_crossings, predict_crossings, rms, weighted_squares};

use crate::error::{require_positive, Error, Result};
use crate::real::MAX_LANES;

/// Largest |h ω| for which the classical RK4 method is stable on an undamped oscillation of
/// frequency ω: its stability region meets the imaginary axis at ±2√2 (Hairer & Wanner, *Solving
/// ODEs II*, §IV.2). A fixed step above 2√2/ω makes that oscillation grow without bound.
pub const RK4_STABILITY_LIMIT: f64 = 2.0 * std::f64::consts::SQRT_2;

/// A first-order ODE system y' = f(t, y). `rhs` takes `&mut self` so that a system can keep
/// per-evaluation quantities (our chain keeps its contact forces).
pub trait OdeSystem {
    /// Length of the state vector.
    fn dimension(&self) -> usize;
    /// Writes f(t, y) into `dydt`. Must not allocate.
    fn rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]);

    /// Number of switching functions g_j(y): where one changes sign the right-hand side is not
    /// smooth (a contact opens or closes). 0 (the default): none, and
    /// [`Method::Dopri5Events`] steps as [`Method::Dopri5`].
    fn switch_count(&self) -> usize {
        0
    }

    /// Writes the switching functions g_j(y) into `out` (length [`OdeSystem::switch_count`]).
    /// They must be linear and homogeneous in y (for the chain: the contacts' overlaps, differences
    /// of positions), so that `switches(f)` with f = dy/dt writes their rates dg_j/dt.
    fn switches(&self, _y: &[f64], _out: &mut [f64]) {}

    /// Some(n) when the state is y = [x | v] with n positions, x' = v, and v' = a(t, x) does not
    /// depend on v: the systems a Runge–Kutta–Nyström method ([`Method::Rkn64`]) can advance.
    /// None (the default): a general first-order system.
    fn second_order(&self) -> Option<usize> {
        None
    }
}

/// Continuous extension of a tableau for samples between steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DenseOutput {
    /// Cubic Hermite interpolation from y and f at both ends of the step (4th order in y).
    Hermite,
    /// The Dormand–Prince 5(4) continuous extension (Hairer et al. II.6) with its coefficients d_i.
    Dopri5([f64; 7]),
}

/// The velocity weights of a Runge–Kutta–Nyström method for y = [x | v], x'' = a(t, x). With
/// them a [`Tableau`]'s `a`, `b` and `error` act on the stage accelerations A_j = a(t + c_j h, X_j)
/// with a factor h²: X_i = x + c_i h v + h² Σ_j a_ij A_j, the new positions x + h v + h² Σ_j b_j A_j
/// and their error estimate h² Σ_j error_j A_j; the velocities take these weights with a factor h.
#[derive(Debug, Clone, PartialEq)]
pub struct NystromWeights {
    /// Velocity weights b'_j: v_new = v + h Σ_j b'_j A_j.
    pub b: Vec<f64>,
    /// Velocity error weights b'_j − b̂'_j of the embedded method.
    pub error: Vec<f64>,
}

/// An explicit Runge–Kutta method as data (Butcher tableau), or a Runge–Kutta–Nyström method
/// when `nystrom` holds its velocity weights.
#[derive(Debug, Clone, PartialEq)]
pub struct Tableau {
    /// Name, for reports.
    pub name: &'static str,
    /// The order that sets the step control (h ∝ err^{−1/order}) and the starting step: the
    /// solution's for RK4 and DOPRI5; for RKN 6(4), whose solution is of order 6, that of the
    /// leading term of its fourth-order embedded estimate, 5.
    pub order: u32,
    /// Nodes c_i.
    pub c: Vec<f64>,
    /// Coupling coefficients, row i holds a_{i,0..i}.
    pub a: Vec<Vec<f64>>,
    /// Weights b_i.
    pub b: Vec<f64>,
    /// Error weights b_i − b̂_i of the embedded method, if any.
    pub error: Option<Vec<f64>>,
    /// Whether the last stage is evaluated at the new solution (first same as last).
    pub fsal: bool,
    /// How to sample between steps.
    pub dense: DenseOutput,
    /// Some: a Runge–Kutta–Nyström method ([`NystromWeights`]).
    pub nystrom: Option<NystromWeights>,
}

impl Tableau {
    /// The classical fourth-order Runge–Kutta method (Kutta 1901), the paper's integrator.
    pub fn rk4() -> Self {
        Tableau {
            name: "rk4",
            order: 4,
            c: vec![0.0, 0.5, 0.5, 1.0],
            a: vec![vec![], vec![0.5], vec![0.0, 0.5], vec![0.0, 0.0, 1.0]],
            b: vec![1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
            error: None,
            fsal: false,
            dense: DenseOutput::Hermite,
            nystrom: None,
        }
    }

    /// Dormand–Prince 5(4) (Dormand & Prince 1980), FSAL, with its dense output.
    pub fn dopri5() -> Self {
        Tableau {
            name: "dopri5",
            order: 5,
            c: vec![0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0],
            a: vec![
                vec![],
                vec![1.0 / 5.0],
                vec![3.0 / 40.0, 9.0 / 40.0],
                vec![44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
                vec![
                    19372.0 / 6561.0,
                    -25360.0 / 2187.0,
                    64448.0 / 6561.0,
                    -212.0 / 729.0,
                ],
                vec![
                    9017.0 / 3168.0,
                    -355.0 / 33.0,
                    46732.0 / 5247.0,
                    49.0 / 176.0,
                    -5103.0 / 18656.0,
                ],
                vec![
                    35.0 / 384.0,
                    0.0,
                    500.0 / 1113.0,
                    125.0 / 192.0,
                    -2187.0 / 6784.0,
                    11.0 / 84.0,
                ],
            ],
            b: vec![
                35.0 / 384.0,
                0.0,
                500.0 / 1113.0,
                125.0 / 192.0,
                -2187.0 / 6784.0,
                11.0 / 84.0,
                0.0,
            ],
            error: Some(vec![
                71.0 / 57600.0,
                0.0,
                -71.0 / 16695.0,
                71.0 / 1920.0,
                -17253.0 / 339200.0,
                22.0 / 525.0,
                -1.0 / 40.0,
            ]),
            fsal: true,
            dense: DenseOutput::Dopri5([
                -12715105075.0 / 11282082432.0,
                0.0,
                87487479700.0 / 32700410799.0,
                -10690763975.0 / 1880347072.0,
                701980252875.0 / 199316789632.0,
                -1453857185.0 / 822651844.0,
                69997945.0 / 29380423.0,
            ]),
            nystrom: None,
        }
    }

    /// The Runge–Kutta–Nyström pair RKN6(4)6FM of Dormand, El-Mikkawy & Prince (1987) for
    /// x'' = a(t, x): six stages, the last at the new positions (first same as last), so five
    /// evaluations per step; positions and velocities of order 6, an embedded estimate of order 4.
    /// Samples between steps: cubic Hermite from (x, v) and (v, a) at both ends.
    pub fn rkn64() -> Self {
        // Positions: b_j, and the embedded b̂_j; velocities: b'_j and b̂'_j (Dormand, El-Mikkawy
        // & Prince 1987, Table 3). The last row of `a` is b (the FSAL stage is the new point).
        let b = [
            151.0 / 2142.0,
            5.0 / 116.0,
            385.0 / 1368.0,
            55.0 / 168.0,
            -6250.0 / 28101.0,
            0.0,
        ];
        let b_hat = [
            1349.0 / 157500.0,
            7873.0 / 50000.0,
            192199.0 / 900000.0,
            521683.0 / 2100000.0,
            -16.0 / 125.0,
            0.0,
        ];
        let bv = [
            151.0 / 2142.0,
            25.0 / 522.0,
            275.0 / 684.0,
            275.0 / 252.0,
            -78125.0 / 112404.0,
            1.0 / 12.0,
        ];
        let bv_hat = [
            1349.0 / 157500.0,
            7873.0 / 45000.0,
            27457.0 / 90000.0,
            521683.0 / 630000.0,
            -2.0 / 5.0,
            1.0 / 12.0,
        ];
        Tableau {
            name: "rkn64",
            order: 5,
            c: vec![0.0, 1.0 / 10.0, 3.0 / 10.0, 7.0 / 10.0, 17.0 / 25.0, 1.0],
            a: vec![
                vec![],
                vec![1.0 / 200.0],
                vec![-1.0 / 2200.0, 1.0 / 22.0],
                vec![637.0 / 6600.0, -7.0 / 110.0, 7.0 / 33.0],
                vec![
                    225437.0 / 1968750.0,
                    -30073.0 / 281250.0,
                    65569.0 / 281250.0,
                    -9367.0 / 984375.0,
                ],
                b[..5].to_vec(),
            ],
            b: b.to_vec(),
            error: Some(b.iter().zip(&b_hat).map(|(x, y)| x - y).collect()),
            fsal: true,
            dense: DenseOutput::Hermite,
            nystrom: Some(NystromWeights {
                b: bv.to_vec(),
                error: bv.iter().zip(&bv_hat).map(|(x, y)| x - y).collect(),
            }),
        }
    }

    /// Number of stages.
    pub fn stages(&self) -> usize {
        self.b.len()
    }
}

/// Envelope of the worst contact-peak error of Dormand–Prince with event-aware stepping
/// ([`Method::Dopri5Events`]) at relative tolerance rtol on the paper's runs,
/// e ≤ PEAK_ERROR_PREFACTOR · rtol^PEAK_ERROR_EXPONENT (docs/physics.md §8; measured at most
/// 2.88 rtol^0.75 over 48 runs, and the figures of merit at most 3.25 rtol^0.75 over 196 runs of
/// the paper's GA designs; plain Dormand–Prince stays below 0.75 rtol^0.6).
const PEAK_ERROR_PREFACTOR: f64 = 4.0;
/// See [`PEAK_ERROR_PREFACTOR`].
const PEAK_ERROR_EXPONENT: f64 = 0.75;
/// How far below a stated peak tolerance [`Method::for_peak_tolerance`] puts the envelope.
const PEAK_SAFETY_FACTOR: f64 = 3.0;
/// Envelope prefactor of [`Method::Rkn64`], e ≤ NYSTROM_PEAK_ERROR_PREFACTOR · rtol^0.75
/// (docs/physics.md §8; measured at most 1.26 rtol^0.75 over every contact of six impact runs,
/// resonant and rigid, at three striker speeds, and 0.56 rtol^0.75 on the figures of merit of 194
/// impact runs of the paper's GA designs, rtol 1e-5 … 3e-11).
const NYSTROM_PEAK_ERROR_PREFACTOR: f64 = 1.5;
/// A crossing [`Method::Rkn64`] lands on may lie up to this fraction of the step (its error
/// estimate does not see the last stage, so a kink late in a step goes unnoticed; bench/README.md).
pub(crate) const NYSTROM_LANDING_END: f64 = 0.999;

/// Envelope prefactor of [`Method::ExactModes`], e ≤ EXACT_MODES_PEAK_ERROR_PREFACTOR · rtol
/// (docs/physics.md §8; measured at most 1.12 rtol on the five-rod finite-element chain at rtol
/// 1e-5 … 1e-8, examples/exact_linear.rs; its error falls with rtol, not with rtol^0.75).
const EXACT_MODES_PEAK_ERROR_PREFACTOR: f64 = 1.3;
/// With a load or the lab physics (a blast, a drive, a column at rest, gravity, a preload) a
/// stated peak tolerance gives [`Method::ExactModes`] this fraction of itself as its rtol
/// (docs/physics.md §8). On the five-rod finite-element chain (examples/exact_loads.rs) the
/// worst peak was 22 rtol at rtol 1e-6 under a 10 N, 5 kHz force drive with no preload, whose
/// contacts open and close with the drive (13 rtol at 1e-7, under 7 at 1e-8 and 1e-9), and 12
/// rtol at rtol 2.6e-5 on the paper's impact under a 5 N preload and gravity, against at most
/// 1.12 rtol on the lossless impacts the other rule is calibrated on.
pub const EXACT_MODES_LOAD_RTOL_OF_TOLERANCE: f64 = 1e-2;

/// Whether [`Method::ExactModes`] can advance a chain's run (`ChainOde::fits_exact_modes`:
/// elastic contacts, undamped masses), and which peak-tolerance rule it takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExactModesFit {
    /// It cannot (damping).
    No,
    /// The paper's model under an impact (lossless, unloaded).
    Impact,
    /// A blast, a drive, a column at rest, or an impact under gravity or a preload
    /// ([`EXACT_MODES_LOAD_RTOL_OF_TOLERANCE`]).
    Loaded,
}

/// A stated peak tolerance chooses [`Method::ExactModes`] for an impact whose stiffest internal
/// frequency ([`crate::ode::ChainOde::stiffest_resonator`]) is above this \[rad/s\]
/// (docs/physics.md §8: there RKN 6(4)'s step is set by that mode's stability, not by the
/// contacts; below it RKN 6(4) is as fast).
pub const EXACT_MODES_ABOVE_RAD_S: f64 = 2.0 * std::f64::consts::PI * 300e3;

/// [`Method::Dopri5Events`] shortens a step to a predicted crossing only when it lies at least
/// this fraction of the step from either end: a kink that close to a step's end costs little
/// (its leading error term is δ^{3/2}), and a landed step's end, whose overlap is about zero,
/// must not trigger a second, tiny step (measured: 0.03 to 0.2 give the same accuracy,
/// bench/README.md, "Integrators: accuracy for the work").
pub(crate) const EVENT_LANDING_FRACTION: f64 = 0.1;

/// The integration method and its step control.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// Classical RK4 with a fixed step Δt \[s\].
    Rk4 {
        /// Time step Δt \[s\].
        time_step_s: f64,
    },
    /// Dormand–Prince 5(4) with error control: per component, the error must stay below
    /// atol·unit_i + rtol·|y_i| (units: see [`crate::ode::ChainOde::tolerance_units`]).
    Dopri5 {
        /// Relative tolerance.
        rtol: f64,
        /// Absolute tolerance [m for displacements].
        atol: f64,
    },
    /// [`Method::Dopri5`] with event-aware stepping: where the system's switching functions
    /// ([`OdeSystem::switches`]: the chain's contact overlaps) are predicted to change sign
    /// within the next step (a quadratic through the current value, its rate and the rate at the
    /// start of the last step), the step is shortened to end there, so that steps do not straddle
    /// the instants where a contact opens or closes and F = β δ₊^{3/2} is not smooth
    /// (docs/physics.md §8). A step shortened so is not used to adapt the step size.
    Dopri5Events {
        /// Relative tolerance.
        rtol: f64,
        /// Absolute tolerance [m for displacements].
        atol: f64,
    },
    /// The Runge–Kutta–Nyström pair RKN6(4) ([`Tableau::rkn64`]) for systems x'' = a(t, x)
    /// ([`OdeSystem::second_order`]: the paper's impact runs), event-aware as
    /// [`Method::Dopri5Events`], with two differences (docs/physics.md §8): a predicted crossing
    /// is landed on up to 0.999 of the step, past those within 0.1 of its start, and after an
    /// accepted step a crossing the prediction missed inside (0.1 h, 0.999 h) makes the step be
    /// retaken to end there. Its error estimate does not use the last stage, so without these a
    /// contact closing late in a step would go unnoticed.
    Rkn64 {
        /// Relative tolerance.
        rtol: f64,
        /// Absolute tolerance [m for displacements].
        atol: f64,
    },
    /// The linear vibrations integrated exactly (docs/physics.md §8, "Exact linear
    /// vibrations"): every element in its free–free modes ([`crate::ode::ChainOde`]'s cells
    /// diagonalised), advanced by the variation-of-constants formula with the contact forces
    /// replaced by their cubic through four Lobatto nodes, the collocation conditions solved on
    /// the primaries by fixed-point iteration; an embedded estimate (the cubic against its
    /// quadratic) on the primaries' positions and velocities controls the step, and a step in
    /// which a contact opens or closes is retaken to end there. Steps are set by the contacts,
    /// not by the stiffest mode. Impacts of the paper's model only (as [`Method::Rkn64`], and no
    /// blast); run by [`crate::simulate()`] (the lanes run it on the scalar path; an
    /// [`Integrator`] given it steps with [`Method::Rkn64`] at its tolerances).
    ExactModes {
        /// Relative tolerance.
        rtol: f64,
        /// Absolute tolerance [m for displacements].
        atol: f64,
    },
    /// A stated relative accuracy of every contact peak; woodpile chooses the method for the
    /// system ([`Method::resolve`]): [`Method::Rkn64`] where the acceleration does not depend on
    /// the velocity, [`Method::Dopri5Events`] otherwise, each at the rtol its calibrated
    /// envelope gives (docs/physics.md §8).
    PeakTolerance {
        /// Relative accuracy of every contact peak.
        peak_tolerance: f64,
    },
}

impl Method {
    /// The paper's integrator: RK4 at Δt = 0.1 µs (docs/physics.md §8).
    pub fn paper() -> Self {
        Method::Rk4 {
            time_step_s: crate::defaults::TIME_STEP_S,
        }
    }

    /// The integrator woodpile chooses for a stated accuracy of every contact peak: relative
    /// error at most `peak_tolerance` (docs/physics.md §8, "Accuracy instead of an integrator"),
    /// resolved for each system by [`Method::resolve`].
    pub fn for_peak_tolerance(peak_tolerance: f64) -> Result<Self> {
        check_peak_tolerance(peak_tolerance)?;
        Ok(Method::PeakTolerance { peak_tolerance })
    }

    /// The concrete method for a system: [`Method::PeakTolerance`] becomes [`Method::Rkn64`]
    /// when `second_order` (x'' = a(t, x), [`OdeSystem::second_order`]) and
    /// [`Method::Dopri5Events`] otherwise, at the rtol of their calibrated envelopes (atol =
    /// rtol · 1e-6); the other methods stay as they are.
    pub fn resolve(self, second_order: bool) -> Self {
        let Method::PeakTolerance { peak_tolerance } = self else {
            return self;
        };
        let prefactor = if second_order {
            NYSTROM_PEAK_ERROR_PREFACTOR
        } else {
            PEAK_ERROR_PREFACTOR
        };
        // Calibrated (examples/peak_tolerance.rs, docs/physics.md §8): the worst error of any
        // contact peak stays below prefactor · rtol^0.75 from rtol 1e-5 to 3e-11 (it falls slower
        // than rtol: a step landing near a contact's opening or closing still meets its kink; an
        // error test on the overlaps did not change that, bench/README.md). rtol is chosen so
        // that this envelope is PEAK_SAFETY_FACTOR times below the tolerance.
        let rtol = (peak_tolerance / (PEAK_SAFETY_FACTOR * prefactor))
            .libm_powf(1.0 / PEAK_ERROR_EXPONENT)
            .max(1e-13);
        let atol = rtol * 1e-6;
        if second_order {
            Method::Rkn64 { rtol, atol }
        } else {
            Method::Dopri5Events { rtol, atol }
        }
    }

    /// [`Method::resolve`] knowing whether the exact modal method can advance the run (`exact`)
    /// and the chain's stiffest internal frequency `stiffest_mode_rad_s`
    /// ([`crate::ode::ChainOde::stiffest_resonator`]; 0 without resonators): a stated peak
    /// tolerance on such a run whose cells vibrate above [`EXACT_MODES_ABOVE_RAD_S`]
    /// (finite-element rods) becomes [`Method::ExactModes`] at the rtol of its calibrated
    /// envelope (an impact's, or with a load [`EXACT_MODES_LOAD_RTOL_OF_TOLERANCE`] of the
    /// tolerance); otherwise as [`Method::resolve`].
    pub fn resolve_for_modes(
        self,
        second_order: bool,
        exact: ExactModesFit,
        stiffest_mode_rad_s: f64,
    ) -> Self {
        match self {
            Method::PeakTolerance { peak_tolerance }
                if exact != ExactModesFit::No && stiffest_mode_rad_s > EXACT_MODES_ABOVE_RAD_S =>
            {
                let rtol = match exact {
                    ExactModesFit::Loaded => peak_tolerance * EXACT_MODES_LOAD_RTOL_OF_TOLERANCE,
                    _ => peak_tolerance / (PEAK_SAFETY_FACTOR * EXACT_MODES_PEAK_ERROR_PREFACTOR),
                }
                .max(1e-13);
                Method::ExactModes {
                    rtol,
                    atol: rtol * 1e-6,
                }
            }
            _ => self.resolve(second_order),
        }
    }

    /// Whether the method needs x'' = a(t, x) ([`OdeSystem::second_order`]). (The exact modal
    /// method takes its own systems: elastic contacts, undamped masses.)
    pub fn needs_second_order(&self) -> bool {
        matches!(self, Method::Rkn64 { .. })
    }

    /// The relative accuracy of every contact peak this method is calibrated to meet: the stated
    /// one for [`Method::PeakTolerance`], the inverse of [`Method::resolve`]'s rule for
    /// [`Method::Dopri5Events`] and [`Method::Rkn64`]; None for the other methods, whose peak
    /// error has no calibrated bound (docs/physics.md §8).
    pub fn peak_tolerance(&self) -> Option<f64> {
        let envelope = |prefactor: f64, rtol: f64| {
            PEAK_SAFETY_FACTOR * prefactor * rtol.libm_powf(PEAK_ERROR_EXPONENT)
        };
        match *self {
            Method::PeakTolerance { peak_tolerance } => Some(peak_tolerance),
            Method::Dopri5Events { rtol, .. } => Some(envelope(PEAK_ERROR_PREFACTOR, rtol)),
            Method::Rkn64 { rtol, .. } => Some(envelope(NYSTROM_PEAK_ERROR_PREFACTOR, rtol)),
            Method::ExactModes { rtol, .. } => {
                Some(PEAK_SAFETY_FACTOR * EXACT_MODES_PEAK_ERROR_PREFACTOR * rtol)
            }
            Method::Rk4 { .. } | Method::Dopri5 { .. } => None,
        }
    }

    /// The tableau this method runs ([`Method::PeakTolerance`]: that of its choice for a
    /// first-order system; [`Method::resolve`] first).
    pub fn tableau(&self) -> Tableau {
        match self {
            Method::Rk4 { .. } => Tableau::rk4(),
            Method::Dopri5 { .. } | Method::Dopri5Events { .. } | Method::PeakTolerance { .. } => {
                Tableau::dopri5()
            }
            Method::Rkn64 { .. } | Method::ExactModes { .. } => Tableau::rkn64(),
        }
    }

    /// Whether the method steps with event landing ([`Method::Dopri5Events`], [`Method::Rkn64`]).
    pub fn event_aware(&self) -> bool {
        matches!(
            self,
            Method::Dopri5Events { .. } | Method::Rkn64 { .. } | Method::ExactModes { .. }
        )
    }

    /// Whether the method controls its step by an error estimate.
    pub fn adaptive(&self) -> bool {
        !matches!(self, Method::Rk4 { .. })
    }

    /// Validates the parameters against the run duration \[s\].
    pub fn validate(&self, duration_s: f64) -> Result<()> {
        match *self {
            Method::Rk4 { time_step_s } => {
                require_positive("run.time_step_s", time_step_s)?;
                if time_step_s >= duration_s {
                    return Err(Error::invalid(
                        "run.time_step_s",
                        time_step_s,
                        format!("must be smaller than run.duration_s = {duration_s}"),
                    ));
                }
            }
            Method::PeakTolerance { peak_tolerance } => check_peak_tolerance(peak_tolerance)?,
            Method::Dopri5 { rtol, atol }
            | Method::Dopri5Events { rtol, atol }
            | Method::Rkn64 { rtol, atol }
            | Method::ExactModes { rtol, atol } => {
                require_positive("run.rtol", rtol)?;
                require_positive("run.atol", atol)?;
                if rtol < 1e-14 {
                    return Err(Error::invalid(
                        "run.rtol",
                        rtol,
                        "must be at least 1e-14 (double precision)",
                    ));
                }
            }
        }
        Ok(())
    }
}

/// A peak tolerance must be a relative error in (0, 0.1).
fn check_peak_tolerance(peak_tolerance: f64) -> Result<()> {
    require_positive("run.peak_tolerance", peak_tolerance)?;
    if peak_tolerance >= 0.1 {
        return Err(Error::invalid(
            "run.peak_tolerance",
            peak_tolerance,
            "is a relative error: give a value below 0.1 (e.g. 1e-5)",
        ));
    }
    if peak_tolerance < MIN_PEAK_TOLERANCE {
        return Err(Error::invalid(
            "run.peak_tolerance",
            peak_tolerance,
            format!(
                "must be at least {MIN_PEAK_TOLERANCE:e}: a smaller one needs an rtol below the range its \
                 bound was calibrated on (down to 3e-11, docs/physics.md §8); for more accuracy give \
                 run.integrator and run.rtol instead"
            ),
        ));
    }
    Ok(())
}

/// The smallest stated peak tolerance: its rtol (`Method::resolve`) stays within the calibrated
/// range (rtol ≥ 3e-11) for impacts and blasts alike.
pub const MIN_PEAK_TOLERANCE: f64 = 2e-7;

/// Counters of the work an integration did.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct IntegratorStats {
    /// Accepted steps.
    pub steps: u64,
    /// Right-hand-side evaluations.
    pub rhs_evaluations: u64,
    /// Rejected (adaptive) steps.
    pub rejected_steps: u64,
}

/// Step control state.
#[derive(Debug, Clone)]
enum Control {
    Fixed {
        h: f64,
    },
    Adaptive {
        rtol: f64,
        atol: Vec<f64>,
        step: StepControl,
    },
}

/// Advances one ODE state step by step. Owns the state and every buffer: a step allocates nothing.
///
/// Invariant: after [`Integrator::new`] and after every [`Integrator::step`], the last call of
/// `rhs` was at the current (t, y). A system that caches per-evaluation quantities (contact forces)
/// can therefore be read right after a step at no extra cost.
#[derive(Debug, Clone)]
pub struct Integrator {
    tableau: Tableau,
    control: Control,
    t0: f64,
    t: f64,
    t_prev: f64,
    y: Vec<f64>,
    y_prev: Vec<f64>,
    /// Stage derivatives k_i of the last step; k[0] = f(t_prev, y_prev).
    k: Vec<Vec<f64>>,
    /// f(t, y) at the current point.
    f_now: Vec<f64>,
    stage: Vec<f64>,
    /// Embedded error estimate of the last attempt.
    error: Vec<f64>,
    stats: IntegratorStats,
    /// Event-aware stepping ([`Method::Dopri5Events`]); None: off.
    events: Option<Events>,
}

/// Buffers of event-aware stepping: the switching functions and their rates.
#[derive(Debug, Clone)]
struct Events {
    /// g(y) at the current point.
    g: Vec<f64>,
    /// dg/dt at the current point.
    rate: Vec<f64>,
    /// dg/dt at the start of the last step.
    rate_prev: Vec<f64>,
    /// g and dg/dt at the end of an attempted step ([`Method::Rkn64`]'s check for crossings).
    g_end: Vec<f64>,
    rate_end: Vec<f64>,
}

impl Integrator {
    /// Starts at (t0, y0). For an adaptive method, `tolerance_units` scales atol per component.
    /// [`Method::PeakTolerance`] is resolved for the system ([`Method::resolve`]).
    ///
    /// # Panics
    /// For [`Method::Rkn64`] on a system that is not [`OdeSystem::second_order`] (the runners
    /// check this first and report it as an error).
    pub fn new<S: OdeSystem>(
        method: Method,
        system: &mut S,
        t0: f64,
        y0: Vec<f64>,
        tolerance_units: &[f64],
        max_step_s: f64,
    ) -> Self {
        let second_order = system.second_order().is_some();
        let method = match method.resolve(second_order) {
            Method::ExactModes { rtol, atol } if second_order => Method::Rkn64 { rtol, atol },
            Method::ExactModes { rtol, atol } => Method::Dopri5Events { rtol, atol },
            other => other,
        };
        assert!(
            !method.needs_second_order() || system.second_order().is_some(),
            "{method:?} needs a system x'' = a(t, x)"
        );
        let tableau = method.tableau();
        let mut f_now = vec![0.0; y0.len()];
        system.rhs(t0, &y0, &mut f_now);
        let control = match method {
            Method::Rk4 { time_step_s } => Control::Fixed { h: time_step_s },
            Method::PeakTolerance { .. } | Method::ExactModes { .. } => {
                unreachable!("resolved above")
            }
            Method::Dopri5 { rtol, atol }
            | Method::Dopri5Events { rtol, atol }
            | Method::Rkn64 { rtol, atol } => {
                let atol: Vec<f64> = tolerance_units.iter().map(|u| atol * u).collect();
                let h = initial_step(
                    system,
                    t0,
                    &y0,
                    &f_now,
                    rtol,
                    &atol,
                    tableau.order,
                    max_step_s,
                );
                // `initial_step` evaluated the system elsewhere: restore the invariant.
                system.rhs(t0, &y0, &mut f_now);
                Control::Adaptive {
                    rtol,
                    atol,
                    step: StepControl::new(h),
                }
            }
        };
        let evals = match control {
            Control::Fixed { .. } => 1,
            Control::Adaptive { .. } => 3,
        };
        let mut integrator = Self::assemble(tableau, control, t0, y0, f_now, evals);
        let m = system.switch_count();
        if method.event_aware() && m > 0 {
            integrator.events = Some(Events {
                g: vec![0.0; m],
                rate: vec![0.0; m],
                rate_prev: vec![0.0; m],
                g_end: vec![0.0; m],
                rate_end: vec![0.0; m],
            });
        }
        integrator
    }

    /// Fixed steps of size h \[s\] with any tableau (e.g. to measure a method's order of accuracy).
    pub fn fixed_step<S: OdeSystem>(
        tableau: Tableau,
        h: f64,
        system: &mut S,
        t0: f64,
        y0: Vec<f64>,
    ) -> Self {
        let mut f_now = vec![0.0; y0.len()];
        system.rhs(t0, &y0, &mut f_now);
        Self::assemble(tableau, Control::Fixed { h }, t0, y0, f_now, 1)
    }

    fn assemble(
        tableau: Tableau,
        control: Control,
        t0: f64,
        y0: Vec<f64>,
        f_now: Vec<f64>,
        evals: u64,
    ) -> Self {
        let n = y0.len();
        Integrator {
            k: vec![vec![0.0; n]; tableau.stages()],
            tableau,
            control,
            t0,
            t: t0,
            t_prev: t0,
            y_prev: y0.clone(),
            y: y0,
            f_now,
            stage: vec![0.0; n],
            error: vec![0.0; n],
            stats: IntegratorStats {
                rhs_evaluations: evals,
                ..Default::default()
            },
            events: None,
        }
    }

    /// Current time \[s\].
    pub fn t(&self) -> f64 {
        self.t
    }

    /// Time at the start of the last step \[s\].
    pub fn t_prev(&self) -> f64 {
        self.t_prev
    }

    /// State at the start of the last step.
    pub fn y_prev(&self) -> &[f64] {
        &self.y_prev
    }

    /// Exchanges the state at the start of the last step with `buffer` (of the same length), so
    /// that a caller can keep it without a copy. Until the next step, [`Integrator::y_prev`] then
    /// holds `buffer`'s old contents and [`Integrator::interpolate`] is not valid.
    pub(crate) fn exchange_y_prev(&mut self, buffer: &mut Vec<f64>) {
        debug_assert_eq!(buffer.len(), self.y_prev.len());
        std::mem::swap(&mut self.y_prev, buffer);
    }

    /// Current state.
    pub fn y(&self) -> &[f64] {
        &self.y
    }

    /// Work counters.
    pub fn stats(&self) -> IntegratorStats {
        self.stats
    }

    /// Computes the stages of a step of size h from (t, y) into `self.k` and the new state into
    /// `self.stage` ([`kernels::attempt`]); the new point's derivative is left in `self.k[last]`
    /// for FSAL and Nyström tableaux (a Nyström step's error estimate is left in `self.error`).
    #[inline(always)]
    fn attempt<S: OdeSystem>(&mut self, system: &mut S, h: f64) {
        std::mem::swap(&mut self.k[0], &mut self.f_now);
        let t = self.t;
        kernels::attempt(
            &self.tableau,
            &self.y,
            &mut self.k,
            &mut self.stage,
            &mut self.error,
            h,
            #[inline(always)]
            move |c, stage, out| system.rhs(t + c * h, stage, out),
        );
        self.stats.rhs_evaluations += (self.tableau.stages() - 1) as u64;
    }

    /// Weighted RMS norm of the embedded error estimate (Hairer's sc_i = atol_i + rtol·max|y|).
    #[inline(always)]
    fn error_norm(&mut self, h: f64, rtol: f64, atol: &[f64]) -> f64 {
        let (tableau, k) = (&self.tableau, &self.k);
        kernels::weighted_squares(
            tableau,
            &mut self.error,
            k,
            h,
            &self.y,
            &self.stage,
            atol,
            rtol,
        );
        kernels::rms(&self.error, |square| square)
    }

    /// Accepts the attempted step: the new state becomes current and f at it is evaluated
    /// (or taken from the FSAL stage).
    #[inline(always)]
    fn accept<S: OdeSystem>(&mut self, system: &mut S, h: f64) {
        self.t_prev = self.t;
        self.t += h;
        std::mem::swap(&mut self.y_prev, &mut self.y);
        std::mem::swap(&mut self.y, &mut self.stage);
        if self.tableau.fsal {
            let last = self.tableau.stages() - 1;
            self.f_now.copy_from_slice(&self.k[last]);
        } else {
            system.rhs(self.t, &self.y, &mut self.f_now);
            self.stats.rhs_evaluations += 1;
        }
        self.stats.steps += 1;
    }

    /// Advances one accepted step, never beyond `t_end`. Returns the step taken \[s\].
    // The crate's `unsafe` (here, in the lanes' group runner and in the exact modal steppers'
    // `step`, [`exact_step_in_simd_build`]): calling the AVX2 build of the step after checking
    // the CPU has AVX2. It pays (bench/README.md: the step is measurably faster) and is safe to
    // keep because the claim `simd_step_bit_identical` checks each gives bit for bit the portable
    // results. (A closure handed to one shared AVX2 function was not inlined into it: the GA's
    // workload took twice the time.)
    #[allow(unsafe_code)]
    pub fn step<S: OdeSystem>(&mut self, system: &mut S, t_end: f64) -> Result<f64> {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2 (checked on the line above).
            return unsafe { self.step_avx2(system, t_end) };
        }
        self.step_portable(system, t_end)
    }

    /// The same step compiled with 256-bit vectors (no FMA contraction, so the results are bit
    /// for bit those of the portable path).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    #[allow(unsafe_code)]
    unsafe fn step_avx2<S: OdeSystem>(&mut self, system: &mut S, t_end: f64) -> Result<f64> {
        self.step_portable(system, t_end)
    }

    /// The same step without run-time SIMD dispatch: the reference the AVX2 build of
    /// [`Integrator::step`] is checked against (bit for bit).
    #[inline(always)]
    pub fn step_portable<S: OdeSystem>(&mut self, system: &mut S, t_end: f64) -> Result<f64> {
        match self.control {
            Control::Fixed { h } => {
                let t_next = fixed_step_end(self.t0, self.stats.steps, h, t_end);
                let h_step = t_next - self.t;
                self.attempt(system, h_step);
                self.accept(system, h_step);
                self.t = t_next;
                Ok(h_step)
            }
            Control::Adaptive { .. } => {
                // Move the control out (no allocation) so that `self` can be borrowed mutably.
                let mut control = std::mem::replace(&mut self.control, Control::Fixed { h: 0.0 });
                let result = match &mut control {
                    Control::Adaptive { rtol, atol, step } => {
                        self.adaptive_step(system, t_end, *rtol, atol, step)
                    }
                    Control::Fixed { .. } => unreachable!("matched above"),
                };
                self.control = control;
                result
            }
        }
    }

    /// Attempts steps from the current point until one is accepted ([`StepControl`] decides).
    #[inline(always)]
    fn adaptive_step<S: OdeSystem>(
        &mut self,
        system: &mut S,
        t_end: f64,
        rtol: f64,
        atol: &[f64],
        step: &mut StepControl,
    ) -> Result<f64> {
        let order = f64::from(self.tableau.order);
        let check_crossings = self.tableau.nystrom.is_some();
        loop {
            let h_try = step.propose(self.t, t_end)?;
            let predicted = if step.predicts() {
                self.predict_crossing(system, h_try)
            } else {
                None
            };
            let h_try = step.land(h_try, predicted);
            self.attempt(system, h_try);
            let err = self.error_norm(h_try, rtol, atol);
            let missed = if err <= 1.0 && check_crossings && !step.landing {
                self.missed_crossing(system, h_try)
            } else {
                None
            };
            match step.judge(h_try, err, missed, order, &mut self.stats) {
                Verdict::Accept => {
                    self.accept(system, h_try);
                    step.accepted(h_try, err, order);
                    return Ok(h_try);
                }
                // Restore the derivative at the current point and try again. The accepted
                // attempt's last stage (FSAL) is evaluated at the new point, which restores the
                // invariant that the last evaluation is at the current state.
                Verdict::Retry => std::mem::swap(&mut self.k[0], &mut self.f_now),
            }
        }
    }

    /// Event-aware stepping: the step to land on the first predicted sign change of a switching
    /// function within the next step of size h, if it lies inside the landing window
    /// ([`kernels::predict_crossings`]); None when events are off, before the first step, or
    /// when none is predicted there.
    fn predict_crossing<S: OdeSystem>(&mut self, system: &mut S, h: f64) -> Option<f64> {
        let ev = self.events.as_mut()?;
        let dt = self.t - self.t_prev;
        if self.stats.steps == 0 || dt <= 0.0 {
            return None;
        }
        // After a step, k[0] holds f at its start and f_now f at its end.
        system.switches(&self.y, &mut ev.g);
        system.switches(&self.f_now, &mut ev.rate);
        system.switches(&self.k[0], &mut ev.rate_prev);
        let rule = LandingRule::of(&self.tableau);
        let mut want = [false; MAX_LANES];
        want[0] = true;
        let (g, d, d_prev) = (&ev.g, &ev.rate, &ev.rate_prev);
        kernels::predict_crossings(
            g.len(),
            |s| g[s],
            |s| d[s],
            |s| d_prev[s],
            dt,
            h,
            want,
            rule,
        )[0]
    }

    /// [`Method::Rkn64`]'s check after an attempted step of size h (new state in `stage`, f there
    /// in k\[last\]): the first crossing inside it that no landing caught
    /// ([`kernels::missed_crossings`]).
    fn missed_crossing<S: OdeSystem>(&mut self, system: &mut S, h: f64) -> Option<f64> {
        let ev = self.events.as_mut()?;
        let last = self.k.len() - 1;
        system.switches(&self.y, &mut ev.g);
        system.switches(&self.stage, &mut ev.g_end);
        let changed = |(g0, g1): (&f64, &f64)| (*g0 > 0.0) != (*g1 > 0.0);
        if !ev.g.iter().zip(&ev.g_end).any(changed) {
            return None;
        }
        system.switches(&self.k[0], &mut ev.rate);
        system.switches(&self.k[last], &mut ev.rate_end);
        let mut check = [false; MAX_LANES];
        check[0] = true;
        let (g0, g1, d0, d1) = (&ev.g, &ev.g_end, &ev.rate, &ev.rate_end);
        let (g, d) = ((|s| g0[s], |s| g1[s]), (|s| d0[s], |s| d1[s]));
        kernels::missed_crossings(g0.len(), g, d, h, check)[0]
    }

    /// f(t, y) at the current point.
    pub(crate) fn f_now(&self) -> &[f64] {
        &self.f_now
    }

    /// The adaptive step controller; None for fixed steps.
    pub(crate) fn adaptive_control(&self) -> Option<StepControl> {
        match self.control {
            Control::Adaptive { step, .. } => Some(step),
            Control::Fixed { .. } => None,
        }
    }

    /// The solution at time t in [t_prev, t] of the last step, written into `out`.
    pub fn interpolate(&self, t: f64, out: &mut [f64]) {
        let h = self.t - self.t_prev;
        if h <= 0.0 || t >= self.t {
            out.copy_from_slice(&self.y);
            return;
        }
        let th = ((t - self.t_prev) / h).clamp(0.0, 1.0);
        let (y0, y1) = (&self.y_prev, &self.y);
        match self.tableau.dense {
            DenseOutput::Hermite => {
                let (f0, f1) = (&self.k[0], &self.f_now);
                let h00 = (1.0 + 2.0 * th) * (1.0 - th) * (1.0 - th);
                let h10 = th * (1.0 - th) * (1.0 - th);
                let h01 = th * th * (3.0 - 2.0 * th);
                let h11 = th * th * (th - 1.0);
                for i in 0..out.len() {
                    out[i] = h00 * y0[i] + h * h10 * f0[i] + h01 * y1[i] + h * h11 * f1[i];
                }
            }
            DenseOutput::Dopri5(d) => {
                let k = &self.k;
                for i in 0..out.len() {
                    let ydiff = y1[i] - y0[i];
                    let bspl = h * k[0][i] - ydiff;
                    let r4 = ydiff - h * k[6][i] - bspl;
                    let mut r5 = 0.0;
                    for (j, &dj) in d.iter().enumerate() {
                        r5 += dj * k[j][i];
                    }
                    r5 *= h;
                    out[i] =
                        y0[i] + th * (ydiff + (1.0 - th) * (bspl + th * (r4 + (1.0 - th) * r5)));
                }
            }
        }
    }
}

// Step-size control of Hairer's DOPRI5 code (Solving ODEs I, §IV.2): a PI controller on
// accepted steps, h_new = h · 0.9 · err^{−(1/q − 0.75 β)} · err_prev^{β} with β = 0.04, which
// damps the oscillation between accepted and rejected steps of the plain controller; after a
// rejection the step may not grow. Shared with the lanes of `crate::lanes`.
const PI_BETA: f64 = 0.04;

/// The `step` of an exact modal stepper over its `step_portable(&mut self, t_end)`: one
/// accepted step toward t_end, returning its size, run in the AVX2 build where the CPU has it, as
/// [`Integrator::step`] (the passes over the modes then run four modes per vector; no FMA
/// contraction, so the results are bit for bit the portable ones).
macro_rules! exact_step_in_simd_build {
    () => {
        /// One accepted step toward t_end; returns its size. Run in the AVX2 build where the CPU
        /// has it, as [`super::Integrator::step`] (bit for bit the portable one).
        #[allow(unsafe_code)]
        pub fn step(&mut self, t_end: f64) -> Result<f64> {
            #[cfg(target_arch = "x86_64")]
            if std::arch::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU supports AVX2 (checked on the line above).
                return unsafe { self.step_avx2(t_end) };
            }
            self.step_portable(t_end)
        }

        /// The same step compiled with 256-bit vectors.
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx2")]
        #[allow(unsafe_code)]
        unsafe fn step_avx2(&mut self, t_end: f64) -> Result<f64> {
            self.step_portable(t_end)
        }
    };
}
pub(crate) use exact_step_in_simd_build;

/// The next step after a step `h_try` accepted with error norm `err` (≤ 1); `h` is the step
/// the controller had proposed, `order` the tableau's.
pub(crate) fn next_step_after_accept(
    h: f64,
    h_try: f64,
    err: f64,
    err_prev: f64,
    order: f64,
    rejected_before: bool,
) -> f64 {
    let mut factor =
        0.9 * err.libm_powf(-(1.0 / order - 0.75 * PI_BETA)) * err_prev.libm_powf(PI_BETA);
    if !factor.is_finite() {
        factor = 5.0;
    }
    let grow = if rejected_before { 1.0 } else { 5.0 };
    h.max(h_try) * factor.clamp(0.2, grow)
}

/// Which predicted crossings a step lands on: DOPRI5's rule, or the wider one of a Nyström
/// tableau (whose error estimate does not see its last stage).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LandingRule {
    /// Whether crossings within [`EVENT_LANDING_FRACTION`] of the start are passed over (the
    /// one just landed on, whose overlap is about zero), so that a later one still counts.
    skip_near_start: bool,
    /// The latest fraction of the step a landing may end at.
    end: f64,
}

impl LandingRule {
    /// The rule of a tableau: [`Method::Rkn64`]'s for a Nyström tableau, else DOPRI5's.
    pub(crate) fn of(tableau: &Tableau) -> Self {
        if tableau.nystrom.is_some() {
            LandingRule {
                skip_near_start: true,
                end: NYSTROM_LANDING_END,
            }
        } else {
            LandingRule {
                skip_near_start: false,
                end: 1.0 - EVENT_LANDING_FRACTION,
            }
        }
    }

    /// Whether a predicted crossing at τ competes to be the first.
    #[inline(always)]
    pub(crate) fn counts(self, tau: f64, h: f64) -> bool {
        !self.skip_near_start || tau > EVENT_LANDING_FRACTION * h
    }

    /// The first predicted crossing τ if the step should be shortened to it: when it lies at
    /// least [`EVENT_LANDING_FRACTION`] h after the start and before `end` · h.
    #[inline(always)]
    pub(crate) fn window(self, first: Option<f64>, h: f64) -> Option<f64> {
        let tau = first?;
        (tau > EVENT_LANDING_FRACTION * h && tau < self.end * h).then_some(tau)
    }
}

/// For a switching function that changed sign over a step of size h: the zero of its cubic
/// Hermite interpolant if it lies in (0.1 h, 0.999 h) ([`kernels::missed_crossings`]).
#[inline(never)]
pub(crate) fn crossing_inside(g0: f64, d0: f64, g1: f64, d1: f64, h: f64) -> Option<f64> {
    let cubic = |th: f64| {
        let (u, w) = (1.0 - th, th);
        (1.0 + 2.0 * w) * u * u * g0 + h * w * u * u * d0 + w * w * (3.0 - 2.0 * w) * g1
            - h * w * w * u * d1
    };
    let tau = illinois(cubic, 1.0, g0, g1, 1e-6) * h;
    (tau > EVENT_LANDING_FRACTION * h && tau < NYSTROM_LANDING_END * h).then_some(tau)
}

/// The zero in (0, h) of q(τ) = g + τ (d + c τ), given q(h) = gh of the other sign than g:
/// bracketed regula falsi (Illinois), to 1e-6 h.
#[inline(never)]
pub(crate) fn crossing_root(g: f64, d: f64, c: f64, gh: f64, h: f64) -> f64 {
    illinois(|tau| g + tau * (d + c * tau), h, g, gh, 1e-6 * h)
}

/// Bracketed regula falsi (Illinois) for the zero of q in \[0, b\], given q(0) = qa and q(b) = qb
/// of opposite signs: the midpoint of the bracket once it is at most `tol` wide.
#[inline(always)]
fn illinois(q: impl Fn(f64) -> f64, b: f64, qa: f64, qb: f64, tol: f64) -> f64 {
    let (mut a, mut b, mut qa, mut qb) = (0.0_f64, b, qa, qb);
    let mut side = 0;
    for _ in 0..100 {
        if b - a <= tol {
            break;
        }
        let mut x = (a * qb - b * qa) / (qb - qa);
        if !(x > a && x < b) {
            x = 0.5 * (a + b);
        }
        let qx = q(x);
        if (qx > 0.0) == (qa > 0.0) {
            (a, qa) = (x, qx);
            if side == -1 {
                qb *= 0.5;
            }
            side = -1;
        } else {
            (b, qb) = (x, qx);
            if side == 1 {
                qa *= 0.5;
            }
            side = 1;
        }
    }
    0.5 * (a + b)
}

/// The step to retry with after `h_try` was rejected with error norm `err` (> 1).
pub(crate) fn next_step_after_reject(h_try: f64, err: f64, order: f64) -> f64 {
    let mut factor = 0.9 * err.libm_powf(-1.0 / order);
    if !factor.is_finite() {
        factor = 0.2;
    }
    h_try * factor.clamp(0.2, 0.9)
}

/// The end of fixed step number `steps_done + 1` from t0: t0 + (n+1) h computed by multiplication
/// (no drift), snapped to t_end when the remainder is a rounding error.
pub(crate) fn fixed_step_end(t0: f64, steps_done: u64, h: f64, t_end: f64) -> f64 {
    let t_next = t0 + (steps_done as f64 + 1.0) * h;
    if t_next > t_end || t_end - t_next < 1e-6 * h {
        t_end
    } else {
        t_next
    }
}

/// Smallest step allowed at time t of a run to t_end: below MIN_STEP_FRACTION of the run means
/// more than 1/MIN_STEP_FRACTION steps, a stiff system the tolerance cannot follow in time.
pub(crate) fn min_step_s(t: f64, t_end: f64) -> f64 {
    (1e-14 * t.abs()).max(crate::defaults::MIN_STEP_FRACTION * t_end.abs())
}

/// Hairer's starting step (Solving ODEs I, II.4): h0 from the sizes of y and f, refined by one
/// explicit Euler step's estimate of the second derivative. Evaluates the system twice.
#[allow(clippy::too_many_arguments)]
fn initial_step<S: OdeSystem>(
    system: &mut S,
    t0: f64,
    y0: &[f64],
    f0: &[f64],
    rtol: f64,
    atol: &[f64],
    order: u32,
    max_step_s: f64,
) -> f64 {
    let n = y0.len();
    let norm = |v: &dyn Fn(usize) -> f64| {
        ((0..n)
            .map(|i| {
                let sc = atol[i] + rtol * y0[i].abs();
                (v(i) / sc).powi(2)
            })
            .sum::<f64>()
            / n as f64)
            .sqrt()
    };
    let d0 = norm(&|i| y0[i]);
    let d1 = norm(&|i| f0[i]);
    let h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6 * max_step_s.min(1e-3)
    } else {
        0.01 * d0 / d1
    };
    let h0 = h0.min(max_step_s);
    let y1: Vec<f64> = (0..n).map(|i| y0[i] + h0 * f0[i]).collect();
    let mut f1 = vec![0.0; n];
    system.rhs(t0 + h0, &y1, &mut f1);
    let d2 = norm(&|i| f1[i] - f0[i]) / h0;
    let h1 = if d1.max(d2) <= 1e-15 {
        (h0 * 1e-3).max(1e-12)
    } else {
        (0.01 / d1.max(d2)).libm_powf(1.0 / f64::from(order + 1))
    };
    (100.0 * h0).min(h1).min(max_step_s)
}
