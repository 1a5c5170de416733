//! How the chain is loaded: a striker sphere hitting the top element, a prescribed blast force, an
//! actuator driving the top element with a signal (docs/physics.md §14), or nothing.

use crate::defaults;
use crate::error::{require_non_negative, require_positive, Error, Result};
use crate::math::Libm;
use crate::model::{hertz_beta, Chain, Material, Surface};

/// Standard gravity g [m/s²] used to turn a drop height into a velocity (docs/physics.md §2).
pub const STANDARD_GRAVITY_M_S2: f64 = defaults::GRAVITY_M_S2;

/// A sphere striking the top element; a body of the simulation with its own Hertz contact.
#[derive(Debug, Clone, PartialEq)]
pub struct Striker {
    /// Diameter \[m\].
    pub diameter_m: f64,
    /// Material.
    pub material: Material,
    /// Initial velocity v0 toward the chain [m/s].
    pub velocity_m_s: f64,
    /// Contact coefficient with the top element [N/m^1.5]; None = computed by Hertz theory.
    pub beta_override: Option<f64>,
}

impl Striker {
    /// The paper's striker: a 10 mm soda-lime glass sphere dropped from 0.20 m (docs/physics.md §2).
    pub fn paper() -> Self {
        Striker {
            diameter_m: defaults::STRIKER_DIAMETER_MM * 1e-3,
            material: Material::preset(defaults::STRIKER_MATERIAL).expect("preset exists"),
            velocity_m_s: velocity_from_drop_height(defaults::DROP_HEIGHT_M),
            beta_override: None,
        }
    }

    /// Mass ρ π d³/6 \[kg\].
    pub fn mass_kg(&self) -> f64 {
        self.material.density_kg_m3 * std::f64::consts::PI * self.diameter_m.powi(3) / 6.0
    }

    /// Contact coefficient with the top element of `chain` [N/m^1.5].
    pub fn contact_beta(&self, chain: &Chain) -> Result<f64> {
        match self.beta_override {
            Some(b) => require_positive("excitation.beta", b),
            None => hertz_beta(
                Surface::Sphere {
                    radius_m: 0.5 * self.diameter_m,
                },
                &self.material,
                chain.top_surface(),
                &chain.elements()[0].material,
            ),
        }
    }

    pub(crate) fn validate(&self) -> Result<()> {
        require_positive("excitation.striker.diameter_m", self.diameter_m)?;
        require_positive("excitation.velocity_m_s", self.velocity_m_s)?;
        Ok(())
    }
}

/// v0 = sqrt(2 g h) [m/s] for a drop height h \[m\].
pub fn velocity_from_drop_height(height_m: f64) -> f64 {
    (2.0 * STANDARD_GRAVITY_M_S2 * height_m).sqrt()
}

/// A prescribed force history F(t) on the top element \[N\].
#[derive(Debug, Clone, PartialEq)]
pub enum BlastProfile {
    /// Friedlander positive phase F0 (1 − t/Td) exp(−b t/Td) on [0, Td], zero after (docs/physics.md §6).
    Friedlander {
        /// Peak force F0 \[N\].
        peak_force_n: f64,
        /// Positive-phase duration Td \[s\].
        duration_s: f64,
        /// Decay parameter b [-] (1 = classic Friedlander, 0 = triangle).
        decay: f64,
    },
    /// A table (t_k, F_k), linearly interpolated, zero outside [t_0, t_last].
    Table {
        /// Times, strictly increasing \[s\].
        times_s: Vec<f64>,
        /// Forces \[N\].
        forces_n: Vec<f64>,
    },
}

impl BlastProfile {
    /// The default blast of docs/physics.md §6: F0 = 200 N, Td = 0.2 ms, b = 1.
    pub fn paper() -> Self {
        BlastProfile::Friedlander {
            peak_force_n: defaults::BLAST_PEAK_FORCE_N,
            duration_s: defaults::BLAST_DURATION_S,
            decay: defaults::BLAST_DECAY,
        }
    }

    /// A validated table profile.
    pub fn table(times_s: Vec<f64>, forces_n: Vec<f64>) -> Result<Self> {
        let p = BlastProfile::Table { times_s, forces_n };
        p.validate()?;
        Ok(p)
    }

    /// The largest force of the profile \[N\] (F0 for Friedlander, whose decay b ≥ 0; the
    /// largest |F_k| of a table).
    pub fn peak_force_n(&self) -> f64 {
        match self {
            BlastProfile::Friedlander { peak_force_n, .. } => peak_force_n.abs(),
            BlastProfile::Table { forces_n, .. } => {
                forces_n.iter().fold(0.0, |m: f64, f| m.max(f.abs()))
            }
        }
    }

    /// Force F(t) \[N\].
    #[inline]
    pub fn force_n(&self, t: f64) -> f64 {
        match self {
            BlastProfile::Friedlander {
                peak_force_n,
                duration_s,
                decay,
            } => {
                if (0.0..=*duration_s).contains(&t) {
                    let x = t / duration_s;
                    peak_force_n * (1.0 - x) * (-decay * x).libm_exp()
                } else {
                    0.0
                }
            }
            BlastProfile::Table { times_s, forces_n } => {
                let n = times_s.len();
                if t < times_s[0] || t > times_s[n - 1] {
                    return 0.0;
                }
                let k = times_s.partition_point(|&tk| tk <= t);
                if k >= n {
                    return forces_n[n - 1];
                }
                let (t0, t1) = (times_s[k - 1], times_s[k]);
                let (f0, f1) = (forces_n[k - 1], forces_n[k]);
                f0 + (f1 - f0) * (t - t0) / (t1 - t0)
            }
        }
    }

    /// Validates the parameters (fields named as in a scenario file).
    pub fn validate(&self) -> Result<()> {
        match self {
            BlastProfile::Friedlander {
                peak_force_n,
                duration_s,
                decay,
            } => {
                require_positive("excitation.peak_force_n", *peak_force_n)?;
                require_positive("excitation.duration_s", *duration_s)?;
                require_non_negative("excitation.decay", *decay)?;
            }
            BlastProfile::Table { times_s, forces_n } => {
                if times_s.len() < 2 || times_s.len() != forces_n.len() {
                    return Err(Error::invalid(
                        "excitation.table",
                        format!("{} times, {} forces", times_s.len(), forces_n.len()),
                        "needs at least two (t, F) rows",
                    ));
                }
                for (k, (&t, &f)) in times_s.iter().zip(forces_n).enumerate() {
                    if !t.is_finite() || !f.is_finite() {
                        return Err(Error::invalid(
                            format!("excitation.table row {}", k + 1),
                            format!("({t}, {f})"),
                            "time and force must be finite numbers",
                        ));
                    }
                    if k > 0 && t <= times_s[k - 1] {
                        return Err(Error::invalid(
                            format!("excitation.table row {} time", k + 1),
                            t,
                            format!(
                                "times must increase strictly (previous row has {})",
                                times_s[k - 1]
                            ),
                        ));
                    }
                }
            }
        }
        Ok(())
    }
}

/// What drives the chain.
#[derive(Debug, Clone, PartialEq)]
pub enum Excitation {
    /// A striker sphere with an initial velocity.
    Impact(Striker),
    /// A prescribed force on the top element.
    Blast(BlastProfile),
    /// An actuator driving the top element with a signal (a force, or a displacement through a
    /// Hertz contact).
    Drive(Drive),
    /// Nothing: the column is left at rest (with a preload, a check of its static equilibrium).
    Rest,
}

impl Excitation {
    /// Validates the parameters.
    pub fn validate(&self) -> Result<()> {
        match self {
            Excitation::Impact(s) => s.validate(),
            Excitation::Blast(b) => b.validate(),
            Excitation::Drive(d) => d.validate(),
            Excitation::Rest => Ok(()),
        }
    }

    /// Whether a run of `duration_s` with a fixed step `fixed_step_s` (None: an adaptive method)
    /// can mean anything under this excitation: a drive above the step's Nyquist frequency
    /// 1/(2h) is aliased by the integrator, and a blast whose force decays within one step (Td/(1 + b) < h) acts
    /// only at the stage evaluations of its first step: an impulse that does no work the energy
    /// audit can see. Each is refused naming its key and the run's.
    pub fn check_against_run(&self, fixed_step_s: Option<f64>) -> Result<()> {
        match self {
            Excitation::Drive(d) => {
                if let (Some((key, f)), Some(h)) = (d.signal.highest_frequency_hz(), fixed_step_s) {
                    if f * h >= 0.5 {
                        return Err(Error::invalid(
                            key,
                            f,
                            format!("above the Nyquist frequency 1/(2 run.time_step_s) = {:.4e} Hz of the step {h:e} s: the integrator cannot follow the drive; lower the frequency or the step (at least 20 steps a period: run.time_step_s ≤ {:.3e} s)", 0.5 / h, 0.05 / f),
                        ));
                    }
                }
                Ok(())
            }
            Excitation::Blast(BlastProfile::Friedlander {
                duration_s: td,
                decay,
                ..
            }) => match fixed_step_s {
                Some(h) if td / (1.0 + decay) < h => Err(Error::invalid(
                    "excitation.decay",
                    decay,
                    format!("the force would fall by 1/e within {:.3e} s, shorter than one step (run.time_step_s = {h:e} s): it would act only inside the first step, as an impulse whose work the energy balance cannot see; use decay ≤ {:.3e} or a smaller step", td / (1.0 + decay), (td / h - 1.0).max(0.0)),
                )),
                _ => Ok(()),
            },
            _ => Ok(()),
        }
    }

    /// A drive's ramp when it is longer than a run of `duration_s` (the drive then never reaches
    /// its amplitude: front ends warn, naming excitation.ramp_s).
    pub fn ramp_longer_than(&self, duration_s: f64) -> Option<f64> {
        match self {
            Excitation::Drive(d) if d.ramp_s > duration_s => Some(d.ramp_s),
            _ => None,
        }
    }

    /// The name used in files: `impact`, `blast`, `drive` or `rest`.
    pub fn kind_name(&self) -> &'static str {
        match self {
            Excitation::Impact(_) => "impact",
            Excitation::Blast(_) => "blast",
            Excitation::Drive(_) => "drive",
            Excitation::Rest => "rest",
        }
    }
}

/// One line saying what drives the chain, as front ends print it.
impl std::fmt::Display for Excitation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Excitation::Impact(st) => write!(
                f,
                "impact: {:.1} mm {} sphere ({:.4} g) at {:.4} m/s",
                st.diameter_m * 1e3,
                st.material.name,
                st.mass_kg() * 1e3,
                st.velocity_m_s
            ),
            Excitation::Blast(BlastProfile::Friedlander {
                peak_force_n,
                duration_s,
                decay,
            }) => write!(
                f,
                "blast: Friedlander F0 = {peak_force_n} N, Td = {duration_s:e} s, b = {decay}"
            ),
            Excitation::Blast(BlastProfile::Table { times_s, .. }) => {
                write!(f, "blast: table of {} points", times_s.len())
            }
            Excitation::Drive(d) => {
                let (what, unit) = match d.quantity {
                    DriveQuantity::Force => ("force", "N"),
                    DriveQuantity::Displacement { .. } => ("displacement", "m"),
                };
                write!(f, "drive ({what}): ")?;
                match &d.signal {
                    Signal::Harmonic {
                        amplitude,
                        frequency_hz,
                    } => write!(f, "harmonic {amplitude:e} {unit} at {frequency_hz} Hz")?,
                    Signal::Chirp {
                        amplitude,
                        start_hz,
                        end_hz,
                        duration_s,
                        sweep,
                    } => write!(
                        f,
                        "{} chirp {amplitude:e} {unit}, {start_hz} → {end_hz} Hz over {duration_s:e} s",
                        match sweep {
                            Sweep::Linear => "linear",
                            Sweep::Logarithmic => "logarithmic",
                        }
                    )?,
                    Signal::Table { times_s, .. } => write!(f, "table of {} points", times_s.len())?,
                }
                write!(f, ", ramp {:e} s", d.ramp_s)
            }
            Excitation::Rest => write!(f, "none: the column is left at rest"),
        }
    }
}

/// How a drive's frequency moves through a chirp.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Sweep {
    /// f(t) = f0 + (f1 − f0) t/T.
    #[default]
    Linear,
    /// f(t) = f0 (f1/f0)^{t/T}.
    Logarithmic,
}

/// The time history of a drive, before its ramp: a force \[N\] or a displacement \[m\].
#[derive(Debug, Clone, PartialEq)]
pub enum Signal {
    /// A sin(2π f t).
    Harmonic {
        /// Amplitude A (N or m).
        amplitude: f64,
        /// Frequency f \[Hz\].
        frequency_hz: f64,
    },
    /// A sin φ(t) on [0, T], zero after, with φ' = 2π f(t) sweeping f0 → f1.
    Chirp {
        /// Amplitude A (N or m).
        amplitude: f64,
        /// Start frequency f0 \[Hz\].
        start_hz: f64,
        /// End frequency f1 \[Hz\].
        end_hz: f64,
        /// Sweep duration T \[s\].
        duration_s: f64,
        /// Linear or logarithmic.
        sweep: Sweep,
    },
    /// A table (t_k, s_k), linearly interpolated, zero outside [t_0, t_last].
    Table {
        /// Times, strictly increasing \[s\].
        times_s: Vec<f64>,
        /// Values (N or m).
        values: Vec<f64>,
    },
}

impl Signal {
    /// The largest |value| the signal takes (N or m): its amplitude, or a table's largest entry.
    pub fn largest_abs(&self) -> f64 {
        match self {
            Signal::Harmonic { amplitude, .. } | Signal::Chirp { amplitude, .. } => amplitude.abs(),
            Signal::Table { values, .. } => values.iter().fold(0.0, |m, v| m.max(v.abs())),
        }
    }

    /// Value s(t) and rate ds/dt.
    pub fn value_and_rate(&self, t: f64) -> (f64, f64) {
        use std::f64::consts::TAU;
        match self {
            Signal::Harmonic {
                amplitude,
                frequency_hz,
            } => {
                let w = TAU * frequency_hz;
                let (s, c) = (w * t).libm_sin_cos();
                (amplitude * s, amplitude * w * c)
            }
            Signal::Chirp {
                amplitude,
                start_hz,
                end_hz,
                duration_s,
                sweep,
            } => {
                if !(0.0..=*duration_s).contains(&t) {
                    return (0.0, 0.0);
                }
                let (phase, f) = match sweep {
                    Sweep::Linear => {
                        let k = (end_hz - start_hz) / duration_s;
                        (TAU * (start_hz * t + 0.5 * k * t * t), start_hz + k * t)
                    }
                    Sweep::Logarithmic => {
                        let r = (end_hz / start_hz).libm_ln();
                        let g = (r * t / duration_s).libm_exp();
                        (TAU * start_hz * duration_s / r * (g - 1.0), start_hz * g)
                    }
                };
                let (s, c) = phase.libm_sin_cos();
                (amplitude * s, amplitude * TAU * f * c)
            }
            Signal::Table { times_s, values } => {
                let n = times_s.len();
                if t < times_s[0] || t > times_s[n - 1] {
                    return (0.0, 0.0);
                }
                let k = times_s.partition_point(|&tk| tk <= t).clamp(1, n - 1);
                let (t0, t1) = (times_s[k - 1], times_s[k]);
                let (v0, v1) = (values[k - 1], values[k]);
                let rate = (v1 - v0) / (t1 - t0);
                (v0 + rate * (t - t0), rate)
            }
        }
    }

    /// The ramp a signal gets when none is given: three periods for a harmonic signal, 5 % of the
    /// sweep at each end of a chirp, none for a table (docs/physics.md §14).
    pub fn default_ramp_s(&self) -> f64 {
        match self {
            Signal::Harmonic { frequency_hz, .. } => 3.0 / frequency_hz,
            Signal::Chirp { duration_s, .. } => 0.05 * duration_s,
            Signal::Table { .. } => 0.0,
        }
    }

    fn validate(&self) -> Result<()> {
        match self {
            Signal::Harmonic {
                amplitude,
                frequency_hz,
            } => {
                require_drive_amplitude(*amplitude)?;
                require_positive("excitation.frequency_hz", *frequency_hz)?;
            }
            Signal::Chirp {
                amplitude,
                start_hz,
                end_hz,
                duration_s,
                sweep,
            } => {
                require_drive_amplitude(*amplitude)?;
                require_positive("excitation.start_hz", *start_hz)?;
                require_positive("excitation.end_hz", *end_hz)?;
                require_positive("excitation.sweep_duration_s", *duration_s)?;
                if *sweep == Sweep::Logarithmic && start_hz == end_hz {
                    return Err(Error::invalid(
                        "excitation.end_hz",
                        end_hz,
                        "a logarithmic sweep needs end_hz different from start_hz (or use a harmonic signal)",
                    ));
                }
            }
            Signal::Table { times_s, values } => {
                BlastProfile::Table {
                    times_s: times_s.clone(),
                    forces_n: values.clone(),
                }
                .validate()?;
                if values.iter().all(|&v| v == 0.0) {
                    return Err(Error::invalid(
                        "excitation.table",
                        "all values 0",
                        NOTHING_DRIVEN,
                    ));
                }
            }
        }
        Ok(())
    }

    /// The highest frequency of a harmonic signal or a chirp \[Hz\] (None for a table).
    pub fn highest_frequency_hz(&self) -> Option<(&'static str, f64)> {
        match self {
            Signal::Harmonic { frequency_hz, .. } => {
                Some(("excitation.frequency_hz", *frequency_hz))
            }
            Signal::Chirp {
                start_hz, end_hz, ..
            } if start_hz > end_hz => Some(("excitation.start_hz", *start_hz)),
            Signal::Chirp { end_hz, .. } => Some(("excitation.end_hz", *end_hz)),
            Signal::Table { .. } => None,
        }
    }
}

const NOTHING_DRIVEN: &str = "a drive of amplitude 0 moves nothing, and every dynamic force (and ratio) of the run would be rounding noise; give a positive amplitude, or excitation.kind = \"rest\" for a chain left at rest";

fn require_drive_amplitude(amplitude: f64) -> Result<()> {
    require_non_negative("excitation.amplitude", amplitude)?;
    if amplitude == 0.0 {
        return Err(Error::invalid(
            "excitation.amplitude",
            amplitude,
            NOTHING_DRIVEN,
        ));
    }
    Ok(())
}

/// What an actuator prescribes.
#[derive(Debug, Clone, PartialEq)]
pub enum DriveQuantity {
    /// A force on the top element \[N\] (added to any preload force).
    Force,
    /// The displacement \[m\] of an actuator whose tip (a fixed-geometry support like the
    /// sensor) touches the top element through a Hertz contact; a preload is applied through it.
    Displacement {
        /// The actuator's tip.
        tip: crate::model::Wall,
    },
}

/// An actuator on the top element: s(t) r(t), with the smooth ramp
/// r(t) = sin²(π t / (2 T_r)) for t < T_r (and, for a chirp, the mirror image over its last T_r).
#[derive(Debug, Clone, PartialEq)]
pub struct Drive {
    /// Force or displacement.
    pub quantity: DriveQuantity,
    /// The signal.
    pub signal: Signal,
    /// Ramp time T_r \[s\] (0 = none).
    pub ramp_s: f64,
}

impl Drive {
    /// A force drive with the signal's default ramp.
    pub fn force(signal: Signal) -> Self {
        Drive {
            quantity: DriveQuantity::Force,
            ramp_s: signal.default_ramp_s(),
            signal,
        }
    }

    /// Value and rate of the ramped signal at t.
    #[inline]
    pub fn value_and_rate(&self, t: f64) -> (f64, f64) {
        let (s, ds) = self.signal.value_and_rate(t);
        let tr = self.ramp_s;
        if tr <= 0.0 {
            return (s, ds);
        }
        // Distance to the nearer ramped end: the start, and for a chirp also its end.
        let (tau, sign) = match &self.signal {
            Signal::Chirp { duration_s, .. } if t > duration_s - tr => (duration_s - t, -1.0),
            _ => (t, 1.0),
        };
        if tau >= tr || tau < 0.0 {
            return (s, ds);
        }
        let a = std::f64::consts::FRAC_PI_2 * tau / tr;
        let (sa, ca) = a.libm_sin_cos();
        let r = sa * sa;
        let dr = sign * 2.0 * sa * ca * std::f64::consts::FRAC_PI_2 / tr;
        (s * r, ds * r + s * dr)
    }

    /// Validates the fields (named as in a scenario's `[excitation]` table).
    pub fn validate(&self) -> Result<()> {
        self.signal.validate()?;
        require_non_negative("excitation.ramp_s", self.ramp_s)?;
        if let Signal::Chirp { duration_s, .. } = self.signal {
            if 2.0 * self.ramp_s > duration_s {
                return Err(Error::invalid(
                    "excitation.ramp_s",
                    self.ramp_s,
                    format!(
                        "a chirp is ramped at both ends: at most half its sweep ({duration_s} s)"
                    ),
                ));
            }
        }
        Ok(())
    }
}
