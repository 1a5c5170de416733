//! Who watches: recorders receive the state on the uniform sample grid.

use crate::error::{require_positive, Error, Result};

/// What a run is made of, given to a recorder before the first sample.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layout {
    /// Number of elements N.
    pub n_elements: usize,
    /// Whether layer 0 is a striker body (impact) rather than a load (blast).
    pub has_striker: bool,
    /// Number of samples the run will deliver.
    pub n_samples: usize,
}

impl Layout {
    /// Number of contacts 0..=N (= number of layers).
    pub fn n_contacts(&self) -> usize {
        self.n_elements + 1
    }
}

/// The observed state at one sample time. Contacts and layers use the paper's numbering:
/// contact 0 = striker–element 1 (or the load), contact N = element N – wall; layer 0 = striker.
#[derive(Debug, Clone, Copy)]
pub struct Sample<'a> {
    /// Time t \[s\].
    pub time_s: f64,
    /// Force of contacts 0..=N \[N\].
    pub contact_forces_n: &'a [f64],
    /// Energy of layers 0..=N \[J\].
    pub layer_energies_j: &'a [f64],
    /// The wall's half of the potential of contact N \[J\].
    pub wall_energy_j: f64,
    /// Work done by the external forces so far \[J\] (0 for an impact without a static load).
    pub input_work_j: f64,
    /// Energy dissipated so far \[J\] (0 without damping).
    pub dissipated_j: f64,
    /// Displacements u_1..u_N of the elements' primary masses \[m\].
    pub displacements_m: &'a [f64],
    /// Velocities of the elements' primary masses [m/s].
    pub velocities_m_s: &'a [f64],
    /// Striker position \[m\] and velocity [m/s] (impact only).
    pub striker: Option<(f64, f64)>,
}

impl Sample<'_> {
    /// Total energy of all bodies and contacts \[J\].
    pub fn total_energy_j(&self) -> f64 {
        self.layer_energies_j.iter().sum::<f64>() + self.wall_energy_j
    }
}

/// Receives samples from a run.
pub trait Recorder {
    /// Called once before the first sample.
    fn start(&mut self, _layout: &Layout) {}
    /// Called at every sample time, in order.
    fn record(&mut self, sample: &Sample<'_>);
}

/// Records nothing (figures of merit are still computed by the runner).
impl Recorder for () {
    fn record(&mut self, _sample: &Sample<'_>) {}
}

/// Records only the two ends of the chain: the force of contact 0 (the striker's, the load or an
/// actuator) and of contact N (the wall) at every sample, for analyses that need no more (the
/// layer-by-layer protocol, transmission spectra).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EndForces {
    /// Sample times \[s\].
    pub times_s: Vec<f64>,
    /// Force of contact 0 \[N\].
    pub load_n: Vec<f64>,
    /// Force of contact N \[N\].
    pub wall_n: Vec<f64>,
}

impl Recorder for EndForces {
    fn start(&mut self, layout: &Layout) {
        let n = layout.n_samples;
        *self = EndForces {
            times_s: Vec::with_capacity(n),
            load_n: Vec::with_capacity(n),
            wall_n: Vec::with_capacity(n),
        };
    }

    fn record(&mut self, s: &Sample<'_>) {
        let f = s.contact_forces_n;
        self.times_s.push(s.time_s);
        self.load_n.push(f[0]);
        self.wall_n.push(f[f.len() - 1]);
    }
}

/// Records everything on the sample grid, row-major (one row per sample).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Trajectory {
    /// Number of elements N.
    pub n_elements: usize,
    /// Sample times \[s\].
    pub times_s: Vec<f64>,
    /// Contact forces, rows of N+1 \[N\].
    pub contact_forces_n: Vec<f64>,
    /// Layer energies, rows of N+1 \[J\].
    pub layer_energies_j: Vec<f64>,
    /// Wall's share of the energy \[J\].
    pub wall_energy_j: Vec<f64>,
    /// Work done by the external forces \[J\].
    pub input_work_j: Vec<f64>,
    /// Energy dissipated \[J\].
    pub dissipated_j: Vec<f64>,
    /// Primary displacements, rows of N \[m\].
    pub displacements_m: Vec<f64>,
    /// Primary velocities, rows of N [m/s].
    pub velocities_m_s: Vec<f64>,
    /// Striker position \[m\] (empty for a blast).
    pub striker_position_m: Vec<f64>,
    /// Striker velocity [m/s] (empty for a blast).
    pub striker_velocity_m_s: Vec<f64>,
}

impl Trajectory {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.times_s.len()
    }

    /// Whether nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.times_s.is_empty()
    }

    /// Number of contacts (= layers) N + 1.
    pub fn n_contacts(&self) -> usize {
        self.n_elements + 1
    }

    /// Force history of one contact \[N\].
    pub fn contact_force_n(&self, contact: usize) -> Vec<f64> {
        self.contact_forces_n
            .chunks(self.n_contacts())
            .map(|row| row[contact])
            .collect()
    }

    /// Energy history of one layer \[J\].
    pub fn layer_energy_j(&self, layer: usize) -> Vec<f64> {
        self.layer_energies_j
            .chunks(self.n_contacts())
            .map(|row| row[layer])
            .collect()
    }

    /// Total energy (all layers and the wall's share) at each sample \[J\].
    pub fn total_energy_j(&self) -> Vec<f64> {
        self.layer_energies_j
            .chunks(self.n_contacts())
            .zip(&self.wall_energy_j)
            .map(|(row, w)| row.iter().sum::<f64>() + w)
            .collect()
    }
}

impl Recorder for Trajectory {
    fn start(&mut self, layout: &Layout) {
        let (n, c, s) = (layout.n_elements, layout.n_contacts(), layout.n_samples);
        *self = Trajectory {
            n_elements: n,
            times_s: Vec::with_capacity(s),
            contact_forces_n: Vec::with_capacity(s * c),
            layer_energies_j: Vec::with_capacity(s * c),
            wall_energy_j: Vec::with_capacity(s),
            input_work_j: Vec::with_capacity(s),
            dissipated_j: Vec::with_capacity(s),
            displacements_m: Vec::with_capacity(s * n),
            velocities_m_s: Vec::with_capacity(s * n),
            striker_position_m: Vec::new(),
            striker_velocity_m_s: Vec::new(),
        };
    }

    fn record(&mut self, s: &Sample<'_>) {
        self.times_s.push(s.time_s);
        self.contact_forces_n.extend_from_slice(s.contact_forces_n);
        self.layer_energies_j.extend_from_slice(s.layer_energies_j);
        self.wall_energy_j.push(s.wall_energy_j);
        self.input_work_j.push(s.input_work_j);
        self.dissipated_j.push(s.dissipated_j);
        self.displacements_m.extend_from_slice(s.displacements_m);
        self.velocities_m_s.extend_from_slice(s.velocities_m_s);
        if let Some((x, v)) = s.striker {
            self.striker_position_m.push(x);
            self.striker_velocity_m_s.push(v);
        }
    }
}

/// The uniform sample interval Δt of a trajectory \[s\] (checked to be uniform to 1e-6 relative).
pub fn sample_interval_s(trajectory: &Trajectory) -> Result<f64> {
    let t = &trajectory.times_s;
    if t.len() < 2 {
        return Err(Error::invalid(
            "trajectory.times_s length",
            t.len(),
            "needs at least 2 samples",
        ));
    }
    let dt = (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64;
    require_positive("trajectory sample interval", dt)?;
    for (k, w) in t.windows(2).enumerate() {
        if ((w[1] - w[0]) - dt).abs() > 1e-6 * dt {
            return Err(Error::invalid(
                format!("trajectory.times_s[{}]", k + 1),
                w[1],
                format!("samples must be uniformly spaced (Δt = {dt:e} s)"),
            ));
        }
    }
    Ok(dt)
}
