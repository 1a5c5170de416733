//! A chain: an ordered column of elements (top to bottom), the contacts between neighbours and the
//! support at the bottom.

use super::cell::{CellModel, UnitCell};
use super::contact::{hertz_beta, Surface};
use super::lab::{Damping, Preload};
use super::material::Material;
use crate::error::{require_positive, Error, Result};

/// Diameter of the paper's rods \[m\].
pub const PAPER_ROD_DIAMETER_M: f64 = 5e-3;

/// The solid body of an element, which fixes its contact surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Body {
    /// A slender cylinder touching its neighbours at its centre.
    Rod {
        /// Diameter \[m\].
        diameter_m: f64,
        /// Length \[m\].
        length_m: f64,
    },
    /// A sphere.
    Sphere {
        /// Diameter \[m\].
        diameter_m: f64,
    },
}

/// One layer of the chain: a body, its material and its unit cell (dynamics).
#[derive(Debug, Clone, PartialEq)]
pub struct Element {
    /// Short label for tables and plots (e.g. `80mm`).
    pub label: String,
    /// Geometry.
    pub body: Body,
    /// Material (contact stiffness).
    pub material: Material,
    /// Inertia: primary mass and resonators.
    pub cell: UnitCell,
}

impl Element {
    /// A fused-quartz rod of the paper's Table 1 (diameter 5 mm), resonant or rigid.
    pub fn table1_rod(length_mm: u32, model: CellModel) -> Result<Self> {
        let cell = model.apply(UnitCell::table1(length_mm)?);
        Ok(Element {
            label: format!("{length_mm}mm"),
            body: Body::Rod {
                diameter_m: PAPER_ROD_DIAMETER_M,
                length_m: f64::from(length_mm) * 1e-3,
            },
            material: Material::fused_quartz(),
            cell,
        })
    }

    /// A rigid sphere of the given diameter and material (mass ρ·πd³/6).
    pub fn sphere(diameter_m: f64, material: Material) -> Result<Self> {
        require_positive("sphere.diameter_m", diameter_m)?;
        let mass = material.density_kg_m3 * std::f64::consts::PI * diameter_m.powi(3) / 6.0;
        Ok(Element {
            label: format!("sphere{:.1}mm", diameter_m * 1e3),
            body: Body::Sphere { diameter_m },
            material,
            cell: UnitCell::rigid_body(mass)?,
        })
    }

    /// The contact surface of this element; rods have their axis at `axis_angle_rad`.
    pub fn surface(&self, axis_angle_rad: f64) -> Surface {
        match self.body {
            Body::Rod { diameter_m, .. } => Surface::Cylinder {
                radius_m: 0.5 * diameter_m,
                axis_angle_rad,
            },
            Body::Sphere { diameter_m } => Surface::Sphere {
                radius_m: 0.5 * diameter_m,
            },
        }
    }

    fn validate(&self, i: usize) -> Result<()> {
        let field = |f: &str| format!("chain.elements[{i}].{f}");
        match self.body {
            Body::Rod {
                diameter_m,
                length_m,
            } => {
                require_positive(&field("diameter_m"), diameter_m)?;
                require_positive(&field("length_m"), length_m)?;
            }
            Body::Sphere { diameter_m } => {
                require_positive(&field("diameter_m"), diameter_m)?;
            }
        }
        UnitCell::new(self.cell.primary_mass_kg, self.cell.resonators.clone())
            .map_err(|e| prefix_field(e, &format!("chain.elements[{i}].")))?;
        Ok(())
    }
}

/// Prepends a path to the field of an [`Error::InvalidParameter`].
pub(crate) fn prefix_field(e: Error, prefix: &str) -> Error {
    match e {
        Error::InvalidParameter {
            field,
            value,
            reason,
        } => Error::InvalidParameter {
            field: format!("{prefix}{field}"),
            value,
            reason,
        },
        other => other,
    }
}

/// What the last element stands on.
#[derive(Debug, Clone, PartialEq)]
pub enum Wall {
    /// Nothing: the last element is free.
    Free,
    /// A fixed force sensor with a spherical cap of radius R_c \[m\] (docs/physics.md §2: steel, 5 mm).
    Cap {
        /// Material of the cap.
        material: Material,
        /// Cap radius R_c \[m\].
        radius_m: f64,
    },
    /// A fixed flat (only a point contact with a sphere).
    Flat {
        /// Material of the flat.
        material: Material,
    },
    /// A fixed support with a given contact coefficient β [N/m^1.5].
    Beta(f64),
}

impl Wall {
    /// β of this support touching `surface` of `material` [N/m^1.5] (None for a free end).
    pub fn beta_against(&self, surface: Surface, material: &Material) -> Result<Option<f64>> {
        Ok(match self {
            Wall::Free => None,
            Wall::Beta(b) => Some(require_positive("wall.beta", *b)?),
            Wall::Cap {
                material: m,
                radius_m,
            } => {
                require_positive("wall.cap_radius_m", *radius_m)?;
                let cap = Surface::Sphere {
                    radius_m: *radius_m,
                };
                Some(hertz_beta(surface, material, cap, m)?)
            }
            Wall::Flat { material: m } => Some(hertz_beta(surface, material, Surface::Flat, m)?),
        })
    }

    /// The paper's sensor: a stainless-steel spherical cap of radius 5 mm (docs/physics.md §2).
    pub fn paper_sensor() -> Self {
        Wall::Cap {
            material: Material::preset(crate::defaults::WALL_MATERIAL).expect("preset exists"),
            radius_m: crate::defaults::WALL_CAP_RADIUS_MM * 1e-3,
        }
    }
}

/// A validated chain with every contact coefficient computed.
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    elements: Vec<Element>,
    wall: Wall,
    /// β of contact i between element i and i+1 (paper contact i+1) [N/m^1.5].
    inner_betas: Vec<f64>,
    /// β of the wall contact (paper contact N), or None for a free end.
    wall_beta: Option<f64>,
    /// Largest physical overlap of each contact (paper contacts 1..=N) \[m\].
    overlap_limits_m: Vec<f64>,
    crossing_angle_rad: f64,
    damping: Damping,
    preload: Preload,
}

/// Builds a [`Chain`]: elements top to bottom, the wall, optional β overrides.
#[derive(Debug, Clone)]
pub struct ChainBuilder {
    elements: Vec<Element>,
    wall: Wall,
    crossing_angle_rad: f64,
    /// (element index from 0, angle to the element above \[rad\]).
    angle_overrides: Vec<(usize, f64)>,
    beta_overrides: Vec<(usize, f64)>,
    damping: Damping,
    preload: Preload,
}

impl ChainBuilder {
    /// A chain of these elements (top to bottom) on the paper's sensor, rods crossing at 90°.
    pub fn new(elements: Vec<Element>) -> Self {
        ChainBuilder {
            elements,
            wall: Wall::paper_sensor(),
            crossing_angle_rad: std::f64::consts::FRAC_PI_2,
            angle_overrides: Vec::new(),
            beta_overrides: Vec::new(),
            damping: Damping::default(),
            preload: Preload::default(),
        }
    }

    /// Dissipation (default: none, the paper's lossless model; docs/physics.md §14).
    pub fn damping(mut self, damping: Damping) -> Self {
        self.damping = damping;
        self
    }

    /// Static load: a force on the top element and gravity (default: none; docs/physics.md §14).
    pub fn preload(mut self, preload: Preload) -> Self {
        self.preload = preload;
        self
    }

    /// Table 1 rods by length \[mm\], top to bottom.
    pub fn table1_rods(lengths_mm: &[u32], model: CellModel) -> Result<Self> {
        let elements = lengths_mm
            .iter()
            .map(|&l| Element::table1_rod(l, model))
            .collect::<Result<Vec<_>>>()?;
        Ok(Self::new(elements))
    }

    /// The support at the bottom.
    pub fn wall(mut self, wall: Wall) -> Self {
        self.wall = wall;
        self
    }

    /// Angle between the axes of neighbouring rods \[rad\] (default π/2).
    pub fn crossing_angle_rad(mut self, angle: f64) -> Self {
        self.crossing_angle_rad = angle;
        self
    }

    /// The angle between the axis of element `element` (0-based, ≥ 1) and the axis of the element
    /// above it \[rad\], instead of [`ChainBuilder::crossing_angle_rad`] for that pair.
    pub fn element_crossing_angle_rad(mut self, element: usize, angle: f64) -> Self {
        self.angle_overrides.push((element, angle));
        self
    }

    /// Overrides β of paper contact `contact` (1 = element 1–element 2, …, N = wall) [N/m^1.5].
    pub fn contact_beta(mut self, contact: usize, beta: f64) -> Self {
        self.beta_overrides.push((contact, beta));
        self
    }

    /// Validates and computes the contact coefficients.
    pub fn build(self) -> Result<Chain> {
        self.validate()?;
        self.validate_beta_overrides()?;
        self.validate_angle_overrides()?;
        let (n, angle) = (self.elements.len(), self.crossing_angle_rad);
        let axis_rad = self.axes_rad();
        let overridden = |c: usize| self.beta_overrides.iter().find(|o| o.0 == c).map(|o| o.1);
        let surface = |i: usize| self.elements[i].surface(axis_rad[i]);
        let mut inner_betas = Vec::with_capacity(n.saturating_sub(1));
        let mut overlap_limits_m = Vec::with_capacity(n);
        for i in 0..n.saturating_sub(1) {
            let (s1, s2) = (surface(i), surface(i + 1));
            let beta = match overridden(i + 1) {
                Some(b) => b,
                None => hertz_beta(
                    s1,
                    &self.elements[i].material,
                    s2,
                    &self.elements[i + 1].material,
                )
                .map_err(|e| contact_context(e, i + 1))?,
            };
            inner_betas.push(beta);
            overlap_limits_m.push(0.1 * s1.smallest_radius_m().min(s2.smallest_radius_m()));
        }
        let last = surface(n - 1);
        let last_material = &self.elements[n - 1].material;
        // A wall whose β is overridden needs no contact geometry (e.g. a rod on a flat sensor
        // with a measured coefficient).
        let wall_beta = match overridden(n) {
            Some(b) if !matches!(self.wall, Wall::Free) => Some(b),
            _ => self
                .wall
                .beta_against(last, last_material)
                .map_err(|e| contact_context(e, n))?,
        };
        let wall_radius = match &self.wall {
            Wall::Cap { radius_m, .. } => *radius_m,
            _ => f64::INFINITY,
        };
        overlap_limits_m.push(0.1 * last.smallest_radius_m().min(wall_radius));
        Ok(Chain {
            elements: self.elements,
            wall: self.wall,
            inner_betas,
            wall_beta,
            overlap_limits_m,
            crossing_angle_rad: angle,
            damping: self.damping,
            preload: self.preload,
        })
    }

    /// The elements, damping, preload and crossing angle, each on its own.
    fn validate(&self) -> Result<()> {
        let n = self.elements.len();
        if n == 0 {
            return Err(Error::invalid(
                "chain.elements",
                "[]",
                "a chain needs at least one element",
            ));
        }
        for (i, e) in self.elements.iter().enumerate() {
            e.validate(i)?;
        }
        self.damping.validate(&resonator_counts(&self.elements))?;
        self.preload.validate()?;
        if !self.preload.is_none() && matches!(self.wall, Wall::Free) {
            return Err(Error::invalid(
                "preload",
                format!(
                    "force_n = {}, gravity_m_s2 = {}",
                    self.preload.force_n, self.preload.gravity_m_s2
                ),
                "a column with a free end has no static equilibrium: give it a wall, or no preload",
            ));
        }
        let angle = self.crossing_angle_rad;
        if !angle.is_finite() {
            return Err(Error::invalid(
                "chain.crossing_angle_deg",
                angle.to_degrees(),
                "must be finite",
            ));
        }
        Ok(())
    }

    /// Each contact-coefficient override: an existing contact (not the load, not a free end),
    /// β > 0, each contact once.
    fn validate_beta_overrides(&self) -> Result<()> {
        let n = self.elements.len();
        for (k, &(c, beta)) in self.beta_overrides.iter().enumerate() {
            let field = format!("chain.contact_beta[{k}]");
            if c == 0 {
                return Err(Error::invalid(
                    format!("{field}.contact"),
                    c,
                    "contact 0 is the striker or the load: set the striker's beta instead (excitation.beta)",
                ));
            }
            if c > n {
                return Err(Error::invalid(
                    format!("{field}.contact"),
                    c,
                    format!("contacts are numbered 1..={n} (1 = elements 1-2, {n} = the wall)"),
                ));
            }
            if c == n && matches!(self.wall, Wall::Free) {
                return Err(Error::invalid(
                    format!("{field}.contact"),
                    c,
                    "contact N is the wall, but the chain has a free end (wall.kind = \"free\")",
                ));
            }
            require_positive(&format!("{field}.beta"), beta)?;
            if let Some(j) = self.beta_overrides[..k].iter().position(|o| o.0 == c) {
                return Err(Error::invalid(
                    format!("{field}.contact"),
                    c,
                    format!(
                        "contact {c} is already set by chain.contact_beta[{j}] (beta = {:e}); give each contact once",
                        self.beta_overrides[j].1
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Each crossing-angle override: an element below another, a finite angle.
    fn validate_angle_overrides(&self) -> Result<()> {
        let n = self.elements.len();
        for &(i, a) in &self.angle_overrides {
            let field = format!("chain.elements[{i}].crossing_angle_deg");
            if i == 0 || i >= n {
                return Err(Error::invalid(
                    field,
                    a.to_degrees(),
                    format!(
                        "elements 1..={} have an element above them; element 0 is the top",
                        n.saturating_sub(1)
                    ),
                ));
            }
            if !a.is_finite() {
                return Err(Error::invalid(field, a.to_degrees(), "must be finite"));
            }
        }
        Ok(())
    }

    /// Each rod's axis from the top [rad]: element i is turned from element i − 1 by its own angle
    /// or the chain's. Written as angle · i plus the overrides' departures, so that a chain
    /// without overrides gets exactly the axes (and contact coefficients) it always had.
    fn axes_rad(&self) -> Vec<f64> {
        let (n, angle) = (self.elements.len(), self.crossing_angle_rad);
        let mut axis_rad: Vec<f64> = (0..n).map(|i| angle * i as f64).collect();
        let mut departure = 0.0;
        for (i, axis) in axis_rad.iter_mut().enumerate().skip(1) {
            if let Some(o) = self.angle_overrides.iter().rev().find(|o| o.0 == i) {
                departure += o.1 - angle;
            }
            *axis += departure;
        }
        axis_rad
    }
}

/// Resonators per element, top to bottom (what a [`Damping`] is checked against).
fn resonator_counts(elements: &[Element]) -> Vec<usize> {
    elements.iter().map(|e| e.cell.resonators.len()).collect()
}

fn contact_context(e: Error, contact: usize) -> Error {
    match e {
        Error::NotPointContact { what, reason } => Error::NotPointContact {
            what: format!("contact {contact} ({what})"),
            reason,
        },
        other => other,
    }
}

impl Chain {
    /// Number of elements N.
    pub fn len(&self) -> usize {
        self.elements.len()
    }

    /// Always false: a built chain has at least one element.
    pub fn is_empty(&self) -> bool {
        self.elements.is_empty()
    }

    /// The elements, top to bottom.
    pub fn elements(&self) -> &[Element] {
        &self.elements
    }

    /// The support.
    pub fn wall(&self) -> &Wall {
        &self.wall
    }

    /// Angle between neighbouring rods \[rad\].
    pub fn crossing_angle_rad(&self) -> f64 {
        self.crossing_angle_rad
    }

    /// β of paper contacts 1..N−1 (element i – element i+1) [N/m^1.5].
    pub fn inner_betas(&self) -> &[f64] {
        &self.inner_betas
    }

    /// β of the wall contact (paper contact N) [N/m^1.5], None for a free end.
    pub fn wall_beta(&self) -> Option<f64> {
        self.wall_beta
    }

    /// Largest physical overlap of paper contacts 1..=N \[m\] (10 % of the smallest radius).
    pub fn overlap_limits_m(&self) -> &[f64] {
        &self.overlap_limits_m
    }

    /// The contact surface of the top element (where a striker or load acts).
    pub fn top_surface(&self) -> Surface {
        self.elements[0].surface(0.0)
    }

    /// Total mass of the chain \[kg\].
    pub fn total_mass_kg(&self) -> f64 {
        self.elements.iter().map(|e| e.cell.total_mass_kg()).sum()
    }

    /// Dissipation.
    pub fn damping(&self) -> &Damping {
        &self.damping
    }

    /// Static load.
    pub fn preload(&self) -> &Preload {
        &self.preload
    }

    /// The same chain with other dissipation (validated).
    pub fn with_damping(mut self, damping: Damping) -> Result<Self> {
        damping.validate(&resonator_counts(&self.elements))?;
        self.damping = damping;
        Ok(self)
    }

    /// Static force carried by paper contacts 1..=N \[N\]: F_i = F_p + g Σ_{k ≤ i} M_k, with M_k
    /// the total mass of element k (all zero without a preload).
    pub fn static_contact_forces_n(&self) -> Vec<f64> {
        let mut carried = self.preload.force_n;
        self.elements
            .iter()
            .map(|e| {
                carried += self.preload.gravity_m_s2 * e.cell.total_mass_kg();
                carried
            })
            .collect()
    }
}
