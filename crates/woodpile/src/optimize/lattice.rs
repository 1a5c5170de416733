//! Design studies over lattices (docs/physics.md §16): the rod length of each layer and the
//! pitch chosen from lists of values, searched by the same [`Nsga2`](super::Nsga2) as chains
//! through [`GenomeSpace`].
//!
//! A genome is one choice index per layer (its rod length, top to bottom) and one for the
//! pitch, shared by every layer of more than one rod: L + 1 genes, gene k drawing from its own
//! number of choices (a layer with one length choice, or a pitch with one, is fixed). Every
//! design of the space is proven buildable when the space is made: longer rods only add
//! crossings and cover more of the impact point, the load points and the supports, so a lattice
//! of the shortest rods that builds with its load at a pitch proves every lattice at that pitch
//! ([`LatticeDesignSpace::validate`]). Any lattice excitation (an impact, a blast, a force or a
//! displacement drive) and lab physics load every design alike.
//! Mutation is the breeder GA's BGA step gene by gene in index units
//! ([`super::operators::mutate_choices`]); no repair is needed.
//!
//! Designs are evaluated in parallel on a rayon pool, one run each (lattices have no SIMD lanes
//! yet); each run is the scalar [`simulate_lattice`], so results do not depend on the thread
//! count.

use super::error::OptimizeError;
use super::figures::DesignFigure;
use super::nsga2::{thread_pool, GenomeSpace, MoIndividual};
use super::objective::StandardObjective;
use super::space::Genome;
use crate::error::Error;
use crate::model::{Lattice, LatticeBuilder, LatticeExcitation, LatticeLab};
use crate::ode::LatticeOde;
use crate::simulate::{simulate_lattice, RunSettings};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

/// Most choices of one gene (a genome holds bytes).
pub const MAX_LATTICE_CHOICES: usize = 256;

/// What varies in a lattice design study, and the fixed rest.
#[derive(Debug, Clone)]
pub struct LatticeDesignSpace {
    /// The base lattice: its layers (their `length_m` and, for layers of more than one rod,
    /// `pitch_m` are replaced by the design's), elements, supports and wall.
    pub base: LatticeBuilder,
    /// What loads every design: a striker at a point, or a blast or a drive on load points.
    pub excitation: LatticeExcitation,
    /// Its lab physics (contact laws, modal damping, a static load).
    pub lab: LatticeLab,
    /// How every design is run (peaks are tracked over every step whatever the sampling).
    pub settings: RunSettings,
    /// Rod length choices of each layer, top to bottom \[m\] (one value: the layer is fixed).
    pub lengths_m: Vec<Vec<f64>>,
    /// Pitch choices \[m\], every layer's of more than one rod (empty: each layer keeps its
    /// own; the pitch gene then has one choice).
    pub pitches_m: Vec<f64>,
}

impl LatticeDesignSpace {
    /// Number of choices of each gene: the layers' lengths, then the pitch.
    pub fn choice_counts(&self) -> Vec<usize> {
        self.lengths_m
            .iter()
            .map(Vec::len)
            .chain(std::iter::once(self.pitches_m.len().max(1)))
            .collect()
    }

    /// Number of designs in the space (saturating).
    pub fn size(&self) -> usize {
        self.choice_counts()
            .iter()
            .fold(1usize, |n, &c| n.saturating_mul(c))
    }

    /// The lattice builder of a design.
    pub fn builder(&self, genome: &[u8]) -> LatticeBuilder {
        let mut b = self.base.clone();
        let pitch = self.pitch_m(genome);
        for (k, layer) in b.layers.iter_mut().enumerate() {
            layer.length_m = self.lengths_m[k][usize::from(genome[k])];
            if let (true, Some(p)) = (layer.rods > 1, pitch) {
                layer.pitch_m = p;
            }
        }
        b
    }

    /// A design's pitch \[m\] (None: every layer keeps its own).
    pub fn pitch_m(&self, genome: &[u8]) -> Option<f64> {
        self.pitches_m
            .get(usize::from(genome[self.lengths_m.len()]))
            .copied()
    }

    /// The lattice of a design.
    pub fn lattice(&self, genome: &[u8]) -> crate::error::Result<Lattice> {
        self.builder(genome).build()
    }

    /// The design in words: lengths top to bottom and the pitch, in mm.
    pub fn label(&self, genome: &[u8]) -> String {
        let lengths: Vec<String> = (0..self.lengths_m.len())
            .map(|k| format!("{}", self.lengths_m[k][usize::from(genome[k])] * 1e3))
            .collect();
        match self.pitch_m(genome) {
            Some(p) => format!(
                "lengths_mm = [{}], pitch_mm = {}",
                lengths.join(", "),
                p * 1e3
            ),
            None => format!("lengths_mm = [{}]", lengths.join(", ")),
        }
    }

    /// Checks the choices (one list per layer, each of 1..=256 distinct positive values) and
    /// proves every design buildable: at each pitch, the lattice of every layer's shortest rods
    /// builds and the impact point lies on its top layer.
    pub fn validate(&self) -> Result<(), OptimizeError> {
        let layers = self.base.layers.len();
        if self.lengths_m.len() != layers {
            return Err(Error::invalid(
                "design.length_mm",
                format!("{} lists", self.lengths_m.len()),
                format!("one list of lengths per layer: {layers}"),
            )
            .into());
        }
        for (k, list) in self.lengths_m.iter().enumerate() {
            check_choices(&format!("design.length_mm[{k}]"), list)?;
        }
        if !self.pitches_m.is_empty() {
            check_choices("design.pitch_mm", &self.pitches_m)?;
        }
        let shortest: Vec<u8> = self
            .lengths_m
            .iter()
            .map(|l| index_of_min(l) as u8)
            .collect();
        for i in 0..self.pitches_m.len().max(1) {
            let mut genome = shortest.clone();
            genome.push(i as u8);
            let (field, value) = match self.pitch_m(&genome) {
                Some(p) => (format!("design.pitch_mm[{i}]"), format!("{}", p * 1e3)),
                None => ("design.length_mm".to_string(), "(the shortest)".to_string()),
            };
            let built = self
                .lattice(&genome)
                .and_then(|l| LatticeOde::build(&l, &self.excitation, &self.lab).map(|_| ()));
            if let Err(e) = built {
                return Err(Error::invalid(
                    field,
                    value,
                    format!(
                        "the lattice of the shortest rods ({}) cannot be built: {e}",
                        self.label(&genome)
                    ),
                )
                .into());
            }
        }
        Ok(())
    }
}

/// Checks a list of choices: 1..=[`MAX_LATTICE_CHOICES`] distinct finite positive values.
fn check_choices(field: &str, list: &[f64]) -> Result<(), OptimizeError> {
    let bad = |value: String, reason: &str| Err(Error::invalid(field, value, reason).into());
    if list.is_empty() || list.len() > MAX_LATTICE_CHOICES {
        return bad(format!("{} values", list.len()), "give 1 to 256 values");
    }
    if let Some(x) = list.iter().find(|x| !(x.is_finite() && **x > 0.0)) {
        return bad(
            format!("{}", x * 1e3),
            "every value must be a finite length > 0",
        );
    }
    if (1..list.len()).any(|k| list[..k].contains(&list[k])) {
        return bad(format!("{list:?}"), "list each value once");
    }
    Ok(())
}

fn index_of_min(list: &[f64]) -> usize {
    (0..list.len())
        .min_by(|&a, &b| list[a].total_cmp(&list[b]))
        .unwrap_or(0)
}

/// A lattice design study as NSGA-II searches it: the space, the objectives (the transmitted
/// peak force, `transmitted-force`, and the rods' mass, `total-mass`), and the worker pool.
pub struct LatticeDesigns {
    space: LatticeDesignSpace,
    objectives: Vec<DesignFigure>,
    pool: rayon::ThreadPool,
}

impl std::fmt::Debug for LatticeDesigns {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LatticeDesigns")
            .field("space", &self.space)
            .field("objectives", &self.objectives)
            .finish()
    }
}

/// The figures a lattice study can minimise.
pub const LATTICE_FIGURES: [DesignFigure; 2] = [
    DesignFigure::Run(StandardObjective::TransmittedForce),
    DesignFigure::TotalMass,
];

impl LatticeDesigns {
    /// Validates the space ([`LatticeDesignSpace::validate`]) and the objectives (each of
    /// [`LATTICE_FIGURES`], once) and starts `threads` workers (0: one per core).
    pub fn new(
        space: LatticeDesignSpace,
        objectives: Vec<DesignFigure>,
        threads: usize,
    ) -> Result<Self, OptimizeError> {
        if objectives.is_empty() {
            return Err(
                Error::invalid("ga.objectives", "[]", "give at least one objective").into(),
            );
        }
        for (k, f) in objectives.iter().enumerate() {
            if !LATTICE_FIGURES.contains(f) {
                return Err(Error::invalid(
                    format!("ga.objectives[{k}]"),
                    f.as_str(),
                    "a lattice study minimises transmitted-force or total-mass",
                )
                .into());
            }
            if objectives[..k].contains(f) {
                return Err(Error::invalid(
                    format!("ga.objectives[{k}]"),
                    f.as_str(),
                    "is listed twice; list each objective once",
                )
                .into());
            }
        }
        space.validate()?;
        let pool = thread_pool(threads)?;
        Ok(LatticeDesigns {
            space,
            objectives,
            pool,
        })
    }

    /// The space.
    pub fn space(&self) -> &LatticeDesignSpace {
        &self.space
    }

    /// The objectives, in order.
    pub fn objectives(&self) -> &[DesignFigure] {
        &self.objectives
    }

    /// Every design of the space, in lexicographic order of the genes.
    pub fn all_designs(&self) -> Vec<Genome> {
        let counts = self.space.choice_counts();
        let mut out = vec![Vec::new()];
        for &c in &counts {
            out = out
                .into_iter()
                .flat_map(|g: Genome| {
                    (0..c).map(move |i| {
                        let mut g = g.clone();
                        g.push(i as u8);
                        g
                    })
                })
                .collect();
        }
        out
    }

    /// One design's objectives: a run only where an objective needs one.
    fn evaluate_one(&self, genome: &[u8]) -> Result<MoIndividual, OptimizeError> {
        let failed = |source| OptimizeError::Simulation {
            design: self.space.label(genome),
            source,
        };
        let lattice = self.space.lattice(genome).map_err(failed)?;
        let transmitted = if self.objectives.iter().any(|f| f.needs_run()) {
            let mut ode = LatticeOde::build(&lattice, &self.space.excitation, &self.space.lab)
                .map_err(failed)?;
            let settings = RunSettings {
                sample_interval_s: self.space.settings.duration_s,
                ..self.space.settings
            };
            simulate_lattice(&mut ode, &settings)
                .map_err(failed)?
                .transmitted_peak_force_n
        } else {
            f64::NAN
        };
        let objectives = self
            .objectives
            .iter()
            .map(|f| match f {
                DesignFigure::TotalMass => lattice.mass_kg(),
                _ => transmitted,
            })
            .collect();
        Ok(MoIndividual {
            genome: genome.to_vec(),
            objectives,
            violation: 0.0,
        })
    }
}

impl GenomeSpace for LatticeDesigns {
    fn random(&self, rng: &mut ChaCha8Rng) -> Genome {
        self.space
            .choice_counts()
            .iter()
            .map(|&c| rng.random_range(0..c) as u8)
            .collect()
    }

    /// The BGA mutation gene by gene (default range: each gene's span); every design is
    /// feasible, so nothing is repaired.
    fn vary(&self, child: &mut Genome, range: Option<f64>, rng: &mut ChaCha8Rng) {
        super::operators::mutate_choices(child, &self.space.choice_counts(), range, rng);
    }

    fn contains(&self, genome: &[u8]) -> bool {
        let counts = self.space.choice_counts();
        genome.len() == counts.len()
            && genome
                .iter()
                .zip(&counts)
                .all(|(&g, &c)| usize::from(g) < c)
    }

    fn objective_count(&self) -> usize {
        self.objectives.len()
    }

    fn evaluate(&self, genomes: &[&[u8]]) -> Result<Vec<MoIndividual>, OptimizeError> {
        let results: Vec<Result<MoIndividual, OptimizeError>> = self
            .pool
            .install(|| genomes.par_iter().map(|g| self.evaluate_one(g)).collect());
        results.into_iter().collect()
    }
}
