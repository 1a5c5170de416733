//! `[uncertainty]` as a scenario file writes it ([`UncertaintySpec`]), and checked
//! ([`Uncertainty`]): the per-parameter distributions that `crate::uncertainty` draws from.

use crate::error::Error;
use serde::{Deserialize, Serialize};

/// One parameter's distribution: exactly one of its three keys.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DistributionSpec {
    /// Standard deviation of a normal about the nominal value, in the parameter's unit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sd: Option<f64>,
    /// Standard deviation of a normal about the nominal value, as a fraction of it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub relative_sd: Option<f64>,
    /// A uniform range `[a, b]`, a < b.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uniform: Option<[f64; 2]>,
}

/// A checked distribution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Distribution {
    /// Normal, nominal + sd·z.
    Normal {
        /// Standard deviation in the parameter's unit.
        sd: f64,
    },
    /// Normal, nominal·(1 + relative_sd·z).
    RelativeNormal {
        /// Standard deviation as a fraction of the nominal value.
        relative_sd: f64,
    },
    /// Uniform on [low, high].
    Uniform {
        /// Lower end.
        low: f64,
        /// Upper end.
        high: f64,
    },
}

impl Distribution {
    /// The value at unit-cube coordinate `u` (0 < u < 1) about `nominal`, by the inverse CDF.
    pub fn value(self, nominal: f64, u: f64) -> f64 {
        let z = || woodpile::uncertainty::standard_normal_quantile(u);
        match self {
            Distribution::Normal { sd } => nominal + sd * z(),
            Distribution::RelativeNormal { relative_sd } => nominal * (1.0 + relative_sd * z()),
            Distribution::Uniform { low, high } => low + (high - low) * u,
        }
    }
}

impl DistributionSpec {
    /// The distribution, or an error naming `key.sd`, `key.relative_sd` or `key.uniform`.
    pub fn check(&self, key: &str) -> Result<Distribution, Error> {
        const SD: &str = "a finite number >= 0";
        let given = [
            self.sd.is_some(),
            self.relative_sd.is_some(),
            self.uniform.is_some(),
        ];
        if given.iter().filter(|&&g| g).count() != 1 {
            return Err(Error::invalid(
                key,
                "{…}",
                "exactly one of { sd = s }, { relative_sd = r } or { uniform = [a, b] }",
            ));
        }
        if let Some(sd) = self.sd {
            if !(sd.is_finite() && sd >= 0.0) {
                return Err(Error::invalid(format!("{key}.sd"), sd, SD));
            }
            return Ok(Distribution::Normal { sd });
        }
        if let Some(relative_sd) = self.relative_sd {
            if !(relative_sd.is_finite() && relative_sd >= 0.0) {
                return Err(Error::invalid(
                    format!("{key}.relative_sd"),
                    relative_sd,
                    SD,
                ));
            }
            return Ok(Distribution::RelativeNormal { relative_sd });
        }
        let [low, high] = self.uniform.unwrap_or_default();
        if !(low.is_finite() && high.is_finite() && low < high) {
            return Err(Error::invalid(
                format!("{key}.uniform"),
                format!("[{low}, {high}]"),
                "[a, b] with finite a < b",
            ));
        }
        Ok(Distribution::Uniform { low, high })
    }
}

/// `[uncertainty]`, as written in the file.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UncertaintySpec {
    /// Samples per design (default [`woodpile::defaults::UNCERTAINTY_SAMPLES`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub samples: Option<usize>,
    /// Seed of the scrambled Sobol' points (default [`woodpile::defaults::UNCERTAINTY_SEED`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u32>,
    /// Length of each user rod (`kind = "rod"`), independently \[mm\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rod_length_mm: Option<DistributionSpec>,
    /// Angle between neighbouring rods, each contact independently \[deg\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crossing_angle_deg: Option<DistributionSpec>,
    /// Young's modulus of the elements' material, one draw per sample \[Pa\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub youngs_modulus: Option<DistributionSpec>,
    /// The striker's impact velocity \[m/s\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub impact_velocity_m_s: Option<DistributionSpec>,
    /// `damping.restitution`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub restitution: Option<DistributionSpec>,
    /// `damping.viscous_time_s` \[s\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub viscous_time_s: Option<DistributionSpec>,
    /// `damping.resonator_ratio`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub resonator_ratio: Option<DistributionSpec>,
    /// `damping.on_site_time_s` \[s\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub on_site_time_s: Option<DistributionSpec>,
}

/// A parameter that `[uncertainty]` can scatter, in the file's order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Parameter {
    /// `rod_length_mm`: one draw per rod.
    RodLength,
    /// `crossing_angle_deg`: one draw per contact between rods.
    CrossingAngle,
    /// `youngs_modulus`.
    YoungsModulus,
    /// `impact_velocity_m_s`.
    ImpactVelocity,
    /// `restitution`.
    Restitution,
    /// `viscous_time_s`.
    ViscousTime,
    /// `resonator_ratio`.
    ResonatorRatio,
    /// `on_site_time_s`.
    OnSiteTime,
}

impl Parameter {
    /// The key under `[uncertainty]`.
    pub const fn key(self) -> &'static str {
        match self {
            Parameter::RodLength => "rod_length_mm",
            Parameter::CrossingAngle => "crossing_angle_deg",
            Parameter::YoungsModulus => "youngs_modulus",
            Parameter::ImpactVelocity => "impact_velocity_m_s",
            Parameter::Restitution => "restitution",
            Parameter::ViscousTime => "viscous_time_s",
            Parameter::ResonatorRatio => "resonator_ratio",
            Parameter::OnSiteTime => "on_site_time_s",
        }
    }
}

/// A checked `[uncertainty]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Uncertainty {
    /// Samples per design (at least 1).
    pub samples: usize,
    /// Seed of the Sobol' points.
    pub seed: u32,
    /// The scattered parameters and their distributions, in the file's order.
    pub parameters: Vec<(Parameter, Distribution)>,
}

impl UncertaintySpec {
    /// Checks every key, naming it (`uncertainty.samples`, `uncertainty.rod_length_mm.sd`, …).
    pub fn check(&self) -> Result<Uncertainty, Error> {
        let samples = self
            .samples
            .unwrap_or(woodpile::defaults::UNCERTAINTY_SAMPLES);
        if samples == 0 {
            return Err(Error::invalid(
                "uncertainty.samples",
                samples,
                "at least 1 sample",
            ));
        }
        let given = [
            (Parameter::RodLength, &self.rod_length_mm),
            (Parameter::CrossingAngle, &self.crossing_angle_deg),
            (Parameter::YoungsModulus, &self.youngs_modulus),
            (Parameter::ImpactVelocity, &self.impact_velocity_m_s),
            (Parameter::Restitution, &self.restitution),
            (Parameter::ViscousTime, &self.viscous_time_s),
            (Parameter::ResonatorRatio, &self.resonator_ratio),
            (Parameter::OnSiteTime, &self.on_site_time_s),
        ];
        let mut parameters = Vec::new();
        for (p, spec) in given {
            if let Some(spec) = spec {
                parameters.push((p, spec.check(&format!("uncertainty.{}", p.key()))?));
            }
        }
        Ok(Uncertainty {
            samples,
            seed: self.seed.unwrap_or(woodpile::defaults::UNCERTAINTY_SEED),
            parameters,
        })
    }
}
