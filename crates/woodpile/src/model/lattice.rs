//! A woodpile lattice (docs/physics.md §16): layers of parallel rods, each layer's rods crossing
//! those of the layers above and below, every crossing a Hertz contact between crossed
//! cylinders, supports under the bottom layer.
//!
//! Geometry, top to bottom: layer 1's rods lie along x, and each further layer is turned by its
//! `angle_deg` (default 90) against the layer above, so that by default odd layers run along x
//! and even ones along y. Rod i (from 0) of a layer of n rods lies at the transverse coordinate
//! (i − (n − 1)/2)·pitch, its centre on the line through the origin normal to the rods, the
//! rods numbered toward +x (toward +y for rods along x). Two rods
//! of adjacent layers touch where their projections cross, if that point lies within both
//! lengths; the contact's point on each rod is its axial coordinate s (from the rod's centre,
//! along its axis). Every contact starts closed at zero overlap, as in a chain.
//!
//! Each rod moves vertically as the free–free finite-element Timoshenko beam of
//! [`FreeRodModes`] (rigid translation, rocking and bending); the striker and the supports are
//! those of a chain ([`crate::Striker`], the [`Wall`]'s law under each support).

use super::contact::{hertz_beta, Surface};
use super::fe_beam::FreeRodModes;
use super::material::Material;
use super::{Rod, Wall};
use crate::error::{Error, Result};
use crate::math::Libm;

/// One layer of parallel rods, as the user gives it.
#[derive(Debug, Clone, PartialEq)]
pub struct LayerSpec {
    /// Number of rods (≥ 1).
    pub rods: usize,
    /// Distance between neighbouring rods' axes \[m\] (more than the diameter).
    pub pitch_m: f64,
    /// Rod length \[m\].
    pub length_m: f64,
    /// Rod diameter \[m\].
    pub diameter_m: f64,
    /// Rod material.
    pub material: Material,
    /// Angle of this layer's rods to those of the layer above \[deg\] (not used for the top
    /// layer, whose rods lie along x).
    pub angle_deg: f64,
}

/// Per-rod overrides of one layer, for graded and staggered designs (`lengths_mm`,
/// `offsets_mm`): one entry per rod of the layer, rod 1 first.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RodOverrides {
    /// Each rod's length \[m\], instead of the layer's `length_m`.
    pub lengths_m: Option<Vec<f64>>,
    /// Each rod's shift along its own axis \[m\] (its centre moves from the line through the
    /// origin normal to the rods by this much along the rod).
    pub offsets_m: Option<Vec<f64>>,
}

/// Where the supports are.
#[derive(Debug, Clone, PartialEq)]
pub enum Supports {
    /// One under the centre of every bottom rod.
    Centres,
    /// At the given (x, y) points \[m\], each under some bottom rod.
    Points(Vec<[f64; 2]>),
}

/// One rod of a built lattice.
#[derive(Debug, Clone, PartialEq)]
pub struct LatticeRod {
    /// Layer, 1..=L from the top.
    pub layer: usize,
    /// Rod number in its layer, 1..=n.
    pub number: usize,
    /// Centre (x, y) \[m\].
    pub centre_m: [f64; 2],
    /// Unit vector along the axis.
    pub axis: [f64; 2],
    /// The rod's section, length and material.
    pub rod: Rod,
    /// Its free–free modes.
    pub modes: FreeRodModes,
}

impl LatticeRod {
    /// The point at axial coordinate s \[m\].
    pub fn point_m(&self, s_m: f64) -> [f64; 2] {
        [
            self.centre_m[0] + s_m * self.axis[0],
            self.centre_m[1] + s_m * self.axis[1],
        ]
    }

    /// (axial coordinate s, distance from the axis) of the point p, both \[m\].
    pub fn local_m(&self, p: [f64; 2]) -> (f64, f64) {
        let d = [p[0] - self.centre_m[0], p[1] - self.centre_m[1]];
        (
            d[0] * self.axis[0] + d[1] * self.axis[1],
            -d[0] * self.axis[1] + d[1] * self.axis[0],
        )
    }

    /// Its contact surface.
    pub fn surface(&self) -> Surface {
        Surface::Cylinder {
            radius_m: 0.5 * self.rod.outer_diameter_m,
            axis_angle_rad: self.axis[1].libm_atan2(self.axis[0]),
        }
    }

    /// Whether the point p lies on the rod seen from above (within its length and radius).
    fn covers(&self, p: [f64; 2]) -> Option<f64> {
        let (s, off) = self.local_m(p);
        let half = 0.5 * self.rod.length_m;
        let tolerance = 1e-12 * self.rod.length_m;
        (s.abs() <= half + tolerance && off.abs() <= 0.5 * self.rod.outer_diameter_m)
            .then_some(s.clamp(-half, half))
    }
}

/// A point on a rod: the rod's index in [`Lattice::rods`] and the axial coordinate s \[m\].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RodPoint {
    /// Index into [`Lattice::rods`].
    pub rod: usize,
    /// Axial coordinate from the rod's centre \[m\].
    pub s_m: f64,
}

/// A contact between two rods of adjacent layers, or a rod and a support.
#[derive(Debug, Clone, PartialEq)]
pub struct LatticeContact {
    /// The point on the upper rod.
    pub above: RodPoint,
    /// The point on the lower rod; None: a fixed support.
    pub below: Option<RodPoint>,
    /// Support number 1.. (for a support).
    pub support: Option<usize>,
    /// Contact coefficient β [N/m^1.5].
    pub beta: f64,
    /// Where it is, (x, y) \[m\].
    pub point_m: [f64; 2],
    /// The overlap beyond which the Hertz law is not physical (10 % of the smallest radius) \[m\].
    pub overlap_limit_m: f64,
}

/// A validated lattice: rods, crossings (layer by layer, by upper rod then lower rod), then
/// supports.
#[derive(Debug, Clone, PartialEq)]
pub struct Lattice {
    /// Every rod, layer by layer from the top, rod by rod.
    pub rods: Vec<LatticeRod>,
    /// Crossings then supports, in output order.
    pub contacts: Vec<LatticeContact>,
    /// Number of layers L.
    pub layers: usize,
    /// Finite elements per half rod.
    pub fe_elements: usize,
    /// `rod = { modes = l }`: every rod by its l lowest analytic bending modes (and the rigid
    /// ones) instead of the finite-element rod.
    pub bending_modes: Option<usize>,
}

/// Builds a [`Lattice`]; errors name the scenario keys (`lattice.layers[k].…`, `wall.supports`).
#[derive(Debug, Clone, PartialEq)]
pub struct LatticeBuilder {
    /// The layers, top to bottom.
    pub layers: Vec<LayerSpec>,
    /// Finite elements per half rod.
    pub fe_elements: usize,
    /// Where the supports are.
    pub supports: Supports,
    /// The law of every support (the chain's wall).
    pub wall: Wall,
    /// Per-rod overrides, layer by layer from the top (shorter than `layers`, or empty: none
    /// for the layers left out).
    pub overrides: Vec<RodOverrides>,
    /// `rod = { modes = l }`: every rod by its l lowest analytic free–free Timoshenko bending
    /// modes and its two rigid modes ([`FreeRodModes::analytic`]); None: the finite-element rod
    /// of `fe_elements` per half rod.
    pub bending_modes: Option<usize>,
}

impl LatticeBuilder {
    /// Layers on the paper's sensor, one support under every bottom rod's centre.
    pub fn new(layers: Vec<LayerSpec>, fe_elements: usize) -> Self {
        LatticeBuilder {
            layers,
            fe_elements,
            supports: Supports::Centres,
            wall: Wall::paper_sensor(),
            overrides: Vec::new(),
            bending_modes: None,
        }
    }

    /// Validates the geometry, finds every crossing and computes every β.
    pub fn build(&self) -> Result<Lattice> {
        if self.layers.is_empty() {
            return Err(Error::invalid(
                "lattice.layers",
                "[]",
                "give at least one layer",
            ));
        }
        let rods = self.rods()?;
        let mut contacts = Vec::new();
        for k in 1..self.layers.len() {
            let before = contacts.len();
            self.crossings(&rods, k, &mut contacts)?;
            if contacts.len() == before {
                return Err(Error::invalid(
                    format!("lattice.layers[{k}]"),
                    format!("{} rods", self.layers[k].rods),
                    format!("no rod of this layer crosses a rod of layer {k} above it within both lengths: the layers do not touch (check pitch_mm, length_mm and angle_deg)"),
                ));
            }
        }
        self.check_every_rod_touches(&rods, &contacts)?;
        self.support_contacts(&rods, &mut contacts)?;
        Ok(Lattice {
            rods,
            contacts,
            layers: self.layers.len(),
            fe_elements: self.fe_elements,
            bending_modes: self.bending_modes,
        })
    }

    fn rods(&self) -> Result<Vec<LatticeRod>> {
        let mut rods = Vec::new();
        let mut cache: Vec<(Rod, FreeRodModes)> = Vec::new();
        let mut angle_rad = 0.0_f64;
        for (k, layer) in self.layers.iter().enumerate() {
            let field = |f: &str| format!("lattice.layers[{k}].{f}");
            if layer.rods == 0 {
                return Err(Error::invalid(
                    field("rods"),
                    0,
                    "a layer has at least 1 rod",
                ));
            }
            require_positive_mm(&field("diameter_mm"), layer.diameter_m)?;
            if layer.rods > 1 && !(layer.pitch_m.is_finite() && layer.pitch_m > layer.diameter_m) {
                return Err(Error::invalid(
                    field("pitch_mm"),
                    layer.pitch_m * 1e3,
                    format!(
                        "the rods of a layer must not overlap: pitch_mm must exceed diameter_mm = {}",
                        layer.diameter_m * 1e3
                    ),
                ));
            }
            if k > 0 {
                let a = layer.angle_deg;
                let folded = a.rem_euclid(180.0);
                if !a.is_finite() || !(1.0..=179.0).contains(&folded) {
                    return Err(Error::invalid(
                        field("angle_deg"),
                        a,
                        "rods of adjacent layers must cross: the angle must differ from 0 and 180 by at least 1 deg (parallel cylinders touch along a line, not at a point)",
                    ));
                }
                angle_rad += a.to_radians();
            }
            let axis = [angle_rad.libm_cos(), angle_rad.libm_sin()];
            // The transverse direction, toward +x (toward +y for rods along x).
            let mut normal = [-axis[1], axis[0]];
            if normal[0] < -1e-12 || (normal[0].abs() <= 1e-12 && normal[1] < 0.0) {
                normal = [-normal[0], -normal[1]];
            }
            let (lengths, offsets) = self.layer_rods(k)?;
            for i in 0..layer.rods {
                let rod = Rod::new(lengths[i], layer.diameter_m, 0.0, layer.material.clone())
                    .map_err(|e| super::chain::prefix_field(e, &format!("lattice.layers[{k}].")))?;
                let modes = modes_of(&rod, self.fe_elements, self.bending_modes, &mut cache)?;
                let t = (i as f64 - 0.5 * (layer.rods as f64 - 1.0)) * layer.pitch_m;
                rods.push(LatticeRod {
                    layer: k + 1,
                    number: i + 1,
                    centre_m: [
                        t * normal[0] + offsets[i] * axis[0],
                        t * normal[1] + offsets[i] * axis[1],
                    ],
                    axis,
                    rod,
                    modes,
                });
            }
        }
        Ok(rods)
    }

    /// Each rod's length and offset along its axis in layer k (from 0) \[m\]: the layer's
    /// length and no offset, or the overrides, checked (one per rod, lengths finite and > 0,
    /// offsets finite).
    fn layer_rods(&self, k: usize) -> Result<(Vec<f64>, Vec<f64>)> {
        let layer = &self.layers[k];
        let n = layer.rods;
        let none = RodOverrides::default();
        let over = self.overrides.get(k).unwrap_or(&none);
        let key = |f: &str| format!("lattice.layers[{k}].{f}");
        let count = |f: &str, v: &[f64]| {
            if v.len() == n {
                Ok(())
            } else {
                Err(Error::invalid(
                    key(f),
                    format!("{} entries", v.len()),
                    format!("one entry per rod of the layer: {n} (rods = {n})"),
                ))
            }
        };
        let lengths = match &over.lengths_m {
            None => vec![require_positive_mm(&key("length_mm"), layer.length_m)?; n],
            Some(v) => {
                count("lengths_mm", v)?;
                for (i, &l) in v.iter().enumerate() {
                    if !(l.is_finite() && l > 0.0) {
                        return Err(Error::invalid(
                            key(&format!("lengths_mm[{i}]")),
                            l * 1e3,
                            "a rod's length must be a finite number of mm > 0",
                        ));
                    }
                }
                v.clone()
            }
        };
        let offsets = match &over.offsets_m {
            None => vec![0.0; n],
            Some(v) => {
                count("offsets_mm", v)?;
                if let Some(i) = v.iter().position(|o| !o.is_finite()) {
                    return Err(Error::invalid(
                        key(&format!("offsets_mm[{i}]")),
                        v[i] * 1e3,
                        "a rod's shift along its axis must be a finite number of mm",
                    ));
                }
                v.clone()
            }
        };
        Ok((lengths, offsets))
    }

    /// Refuses a rod that crosses no rod of the layers above or below (it would not be part of
    /// the lattice), naming the override that put it there, or its layer.
    fn check_every_rod_touches(
        &self,
        rods: &[LatticeRod],
        contacts: &[LatticeContact],
    ) -> Result<()> {
        if self.layers.len() < 2 {
            return Ok(());
        }
        let mut touches = vec![false; rods.len()];
        for c in contacts {
            touches[c.above.rod] = true;
            if let Some(b) = c.below {
                touches[b.rod] = true;
            }
        }
        let Some(r) = touches.iter().position(|t| !t) else {
            return Ok(());
        };
        let (k, i) = (rods[r].layer - 1, rods[r].number - 1);
        let over = self.overrides.get(k).cloned().unwrap_or_default();
        let what = format!(
            "rod {} of this layer crosses no rod of the layers above or below within both lengths, so it would not be part of the lattice: give it a length and offset that put it across a rod of an adjacent layer",
            i + 1
        );
        let key = format!("lattice.layers[{k}]");
        Err(match (over.offsets_m, over.lengths_m) {
            (Some(o), _) if o[i] != 0.0 => {
                Error::invalid(format!("{key}.offsets_mm[{i}]"), o[i] * 1e3, what)
            }
            (_, Some(l)) => Error::invalid(format!("{key}.lengths_mm[{i}]"), l[i] * 1e3, what),
            _ => Error::invalid(
                key,
                format!("rod {}", i + 1),
                format!("{what} (check pitch_mm and length_mm)"),
            ),
        })
    }

    /// The crossings of layer k (from 0) with layer k − 1 above it.
    fn crossings(
        &self,
        rods: &[LatticeRod],
        k: usize,
        contacts: &mut Vec<LatticeContact>,
    ) -> Result<()> {
        let upper: Vec<usize> = (0..rods.len()).filter(|&r| rods[r].layer == k).collect();
        let lower: Vec<usize> = (0..rods.len())
            .filter(|&r| rods[r].layer == k + 1)
            .collect();
        for &a in &upper {
            for &b in &lower {
                let (ra, rb) = (&rods[a], &rods[b]);
                // c_a + s a_a = c_b + u a_b.
                let det = ra.axis[0] * (-rb.axis[1]) - ra.axis[1] * (-rb.axis[0]);
                let d = [
                    rb.centre_m[0] - ra.centre_m[0],
                    rb.centre_m[1] - ra.centre_m[1],
                ];
                let s = (d[0] * (-rb.axis[1]) - d[1] * (-rb.axis[0])) / det;
                let point = ra.point_m(s);
                let (Some(s_a), Some(s_b)) = (ra.covers(point), rb.covers(point)) else {
                    continue;
                };
                let beta = hertz_beta(
                    ra.surface(),
                    &ra.rod.material,
                    rb.surface(),
                    &rb.rod.material,
                )
                .map_err(|e| super::chain::prefix_field(e, &format!("lattice.layers[{k}].")))?;
                contacts.push(LatticeContact {
                    above: RodPoint { rod: a, s_m: s_a },
                    below: Some(RodPoint { rod: b, s_m: s_b }),
                    support: None,
                    beta,
                    point_m: point,
                    overlap_limit_m: 0.05 * ra.rod.outer_diameter_m.min(rb.rod.outer_diameter_m),
                });
            }
        }
        Ok(())
    }

    fn support_contacts(
        &self,
        rods: &[LatticeRod],
        contacts: &mut Vec<LatticeContact>,
    ) -> Result<()> {
        let bottom: Vec<usize> = (0..rods.len())
            .filter(|&r| rods[r].layer == self.layers.len())
            .collect();
        let points: Vec<[f64; 2]> = match &self.supports {
            Supports::Centres => bottom.iter().map(|&r| rods[r].centre_m).collect(),
            Supports::Points(p) => p.clone(),
        };
        let cap_radius = match &self.wall {
            Wall::Cap { radius_m, .. } => *radius_m,
            _ => f64::INFINITY,
        };
        for (j, &p) in points.iter().enumerate() {
            let found = bottom
                .iter()
                .find_map(|&r| rods[r].covers(p).map(|s| (r, s)));
            let Some((r, s_m)) = found else {
                return Err(Error::invalid(
                    format!("wall.supports[{j}]"),
                    format!("{{ x_mm = {}, y_mm = {} }}", p[0] * 1e3, p[1] * 1e3),
                    format!("outside every rod of the bottom layer (layer {}): a support must lie under a bottom rod, within its length and radius", self.layers.len()),
                ));
            };
            let rod = &rods[r];
            let beta = self
                .wall
                .beta_against(rod.surface(), &rod.rod.material)?
                .ok_or_else(|| {
                    Error::invalid(
                        "wall.kind",
                        "free",
                        "a lattice stands on supports: give the wall a cap, a flat or a beta",
                    )
                })?;
            contacts.push(LatticeContact {
                above: RodPoint { rod: r, s_m },
                below: None,
                support: Some(j + 1),
                beta,
                point_m: rod.point_m(s_m),
                overlap_limit_m: 0.1 * (0.5 * rod.rod.outer_diameter_m).min(cap_radius),
            });
        }
        Ok(())
    }
}

impl Lattice {
    /// The top rod under the point p \[m\] and the point on it, or an error naming `field`.
    pub fn top_point(&self, p: [f64; 2], field: &str) -> Result<RodPoint> {
        self.rods
            .iter()
            .enumerate()
            .filter(|(_, r)| r.layer == 1)
            .find_map(|(i, r)| r.covers(p).map(|s_m| RodPoint { rod: i, s_m }))
            .ok_or_else(|| {
                Error::invalid(
                    field,
                    format!("[{}, {}]", p[0] * 1e3, p[1] * 1e3),
                    "the impact point (x, y in mm) lies on no rod of the top layer (within a rod's length and radius)",
                )
            })
    }

    /// Total mass of the rods \[kg\].
    pub fn mass_kg(&self) -> f64 {
        self.rods.iter().map(|r| r.rod.mass_kg()).sum()
    }

    /// The contacts that are supports.
    pub fn supports(&self) -> impl Iterator<Item = &LatticeContact> {
        self.contacts.iter().filter(|c| c.below.is_none())
    }
}

/// The free–free modes of `rod` (finite elements, or `bending` analytic modes), computed once
/// per distinct rod (identical rods share one eigenproblem).
fn modes_of(
    rod: &Rod,
    elements: usize,
    bending: Option<usize>,
    cache: &mut Vec<(Rod, FreeRodModes)>,
) -> Result<FreeRodModes> {
    if let Some((_, m)) = cache.iter().find(|(r, _)| r == rod) {
        return Ok(m.clone());
    }
    let modes = match bending {
        Some(l) => FreeRodModes::analytic(rod, l),
        None => FreeRodModes::new(rod, elements),
    }
    .map_err(|e| super::chain::prefix_field(e, "lattice."))?;
    cache.push((rod.clone(), modes.clone()));
    Ok(modes)
}

/// A length given in mm (`value_m` in metres) is finite and > 0; the error shows it in mm, as
/// the user wrote it.
fn require_positive_mm(field: &str, value_m: f64) -> Result<f64> {
    if value_m.is_finite() && value_m > 0.0 {
        Ok(value_m)
    } else {
        Err(Error::invalid(
            field,
            value_m * 1e3,
            "must be a finite number of mm > 0",
        ))
    }
}
