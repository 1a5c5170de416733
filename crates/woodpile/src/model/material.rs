//! Isotropic elastic materials and their named presets.

use crate::error::{require_positive, Error, Result};

/// An isotropic linear-elastic material.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Name (a preset name or the user's).
    pub name: String,
    /// Young's modulus E \[Pa\].
    pub youngs_modulus_pa: f64,
    /// Poisson's ratio ν [-], in (-1, 0.5).
    pub poisson_ratio: f64,
    /// Density ρ [kg/m³].
    pub density_kg_m3: f64,
}

/// Presets: (name, E \[Pa\], ν, ρ [kg/m³]). The first three are docs/physics.md §2; the others are
/// handbook values (e.g. the ASM/Matweb typical values for the named class of material).
const PRESETS: [(&str, f64, f64, f64); 7] = [
    ("fused-quartz", 72e9, 0.17, 2200.0),
    ("soda-lime-glass", 63e9, 0.22, 2500.0),
    ("stainless-steel", 200e9, 0.29, 8000.0),
    ("borosilicate-glass", 64e9, 0.20, 2230.0),
    ("steel", 210e9, 0.30, 7850.0),
    ("aluminium", 69e9, 0.33, 2700.0),
    ("brass", 100e9, 0.34, 8500.0),
];

impl Material {
    /// A user-defined material, validated.
    pub fn new(
        name: &str,
        youngs_modulus_pa: f64,
        poisson_ratio: f64,
        density_kg_m3: f64,
    ) -> Result<Self> {
        require_positive(
            &format!("material `{name}`.youngs_modulus_pa"),
            youngs_modulus_pa,
        )?;
        require_positive(&format!("material `{name}`.density_kg_m3"), density_kg_m3)?;
        if !(poisson_ratio.is_finite() && poisson_ratio > -1.0 && poisson_ratio < 0.5) {
            return Err(Error::invalid(
                format!("material `{name}`.poisson_ratio"),
                poisson_ratio,
                "must lie in (-1, 0.5)",
            ));
        }
        Ok(Material {
            name: name.to_string(),
            youngs_modulus_pa,
            poisson_ratio,
            density_kg_m3,
        })
    }

    /// A named preset: `fused-quartz`, `soda-lime-glass`, `stainless-steel`, `borosilicate-glass`,
    /// `steel`, `aluminium`, `brass`.
    pub fn preset(name: &str) -> Result<Self> {
        PRESETS
            .iter()
            .find(|p| p.0 == name)
            .map(|&(n, e, nu, rho)| Material {
                name: n.to_string(),
                youngs_modulus_pa: e,
                poisson_ratio: nu,
                density_kg_m3: rho,
            })
            .ok_or_else(|| Error::Unknown {
                what: "material",
                name: name.to_string(),
                valid: Self::preset_names().join(", "),
            })
    }

    /// Names of the presets.
    pub fn preset_names() -> Vec<&'static str> {
        PRESETS.iter().map(|p| p.0).collect()
    }

    /// Fused quartz, the paper's rods.
    pub fn fused_quartz() -> Self {
        Self::preset("fused-quartz").expect("preset exists")
    }

    /// Contact compliance (1 − ν²)/E [1/Pa].
    pub fn contact_compliance(&self) -> f64 {
        (1.0 - self.poisson_ratio * self.poisson_ratio) / self.youngs_modulus_pa
    }
}
