//! What is searched: N positions (a fixed number, or any number in a range), each filled from a
//! discrete catalogue of elements, under the designer's constraints; and the set of genomes that
//! meet them.

use super::error::OptimizeError;
use crate::error::{Error, Result};
use crate::excitation::{BlastProfile, Excitation, Striker};
use crate::model::{Body, CellModel, Chain, ChainBuilder, Element, Wall, TABLE1_LENGTHS_MM};
use crate::simulate::RunSettings;
use rand::Rng;

/// A design: the catalogue index of the element at each position, top to bottom. Its length is
/// the number of layers (fixed, or within [`DesignSpace::lengths`]).
pub type Genome = Vec<u8>;

/// Largest catalogue a [`Genome`] can index.
pub const MAX_CATALOGUE_LEN: usize = 256;

/// Most layers a design may have when the number of layers varies (`max_positions`): every
/// length of the range gets its own feasible set, so the range costs about max²/2 genes of
/// memory and set-up; a fixed number of layers has no such limit.
pub const MAX_VARIABLE_POSITIONS: usize = 1024;

/// Relative slack of the mass constraint, so that summing the same masses in another order
/// (one rounding per term) never turns a feasible design infeasible.
const MASS_SLACK: f64 = 1e-12;

/// Optional limits a designer puts on the chain. Indices are catalogue indices; positions count
/// from 0 at the top (with a variable number of layers a fixed position must exist in every
/// design: below [`DesignSpace::positions`], the fewest).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Constraints {
    /// Largest total mass of the chain \[kg\].
    pub max_total_mass_kg: Option<f64>,
    /// Positions whose element is fixed: (position, catalogue index).
    pub fixed: Vec<(usize, usize)>,
    /// Largest number of copies of a catalogue entry: (catalogue index, count).
    pub max_count: Vec<(usize, usize)>,
    /// Largest height of the stack \[m\] (the sum of the elements' diameters).
    pub max_stack_height_m: Option<f64>,
    /// Largest Hertz peak pressure of any contact of the structure \[Pa\]
    /// ([`super::DesignFigure::MaxContactPressure`]). Known only after a run: NSGA-II's
    /// constraint domination handles it; the breeder GA refuses it.
    pub max_contact_pressure_pa: Option<f64>,
}

/// The design space of an optimisation: N positions (or N in a range), a catalogue, how the
/// chain is held and loaded, how long it is run, and the constraints.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignSpace {
    /// Number of positions N (elements in the chain); with `max_positions`, the fewest.
    pub positions: usize,
    /// The most positions when the number of layers is part of the design (None: exactly
    /// `positions`).
    pub max_positions: Option<usize>,
    /// The elements a position can hold (at most [`MAX_CATALOGUE_LEN`]).
    pub catalogue: Vec<Element>,
    /// What the last element stands on.
    pub wall: Wall,
    /// Angle between the axes of neighbouring rods \[rad\].
    pub crossing_angle_rad: f64,
    /// The load.
    pub excitation: Excitation,
    /// Duration and integrator of every evaluation.
    pub settings: RunSettings,
    /// The designer's constraints.
    pub constraints: Constraints,
}

impl DesignSpace {
    /// The Table 1 rods 20, 30, …, 80 mm in the given model.
    pub fn table1_catalogue(model: CellModel) -> Vec<Element> {
        TABLE1_LENGTHS_MM
            .iter()
            .map(|&l| Element::table1_rod(l, model).expect("Table 1 length"))
            .collect()
    }

    /// `positions` Table 1 rods on the paper's sensor under `excitation`, with the docs/physics.md §8
    /// run settings for that excitation and no constraints.
    pub fn table1(positions: usize, model: CellModel, excitation: Excitation) -> Self {
        DesignSpace {
            positions,
            max_positions: None,
            catalogue: Self::table1_catalogue(model),
            wall: Wall::paper_sensor(),
            crossing_angle_rad: std::f64::consts::FRAC_PI_2,
            settings: RunSettings::paper_for(&excitation),
            excitation,
            constraints: Constraints::default(),
        }
    }

    /// The paper's impact problem (§4, docs/physics.md §9): 20 rods from Table 1, the glass striker
    /// dropped from 0.2 m, the steel sensor, 2 ms of RK4 at 0.1 µs.
    pub fn paper_impact(model: CellModel) -> Self {
        Self::table1(20, model, Excitation::Impact(Striker::paper()))
    }

    /// The paper's blast problem (§5): 20 rods, the Friedlander load of docs/physics.md §6, 3 ms.
    pub fn paper_blast(model: CellModel) -> Self {
        Self::table1(20, model, Excitation::Blast(BlastProfile::paper()))
    }

    /// The numbers of layers a design may have: `positions..=max_positions` (one number when
    /// `max_positions` is None).
    pub fn lengths(&self) -> std::ops::RangeInclusive<usize> {
        self.positions..=self.max_positions.unwrap_or(self.positions)
    }

    /// Whether the number of layers is part of the design (`max_positions` above `positions`).
    pub fn varies_in_length(&self) -> bool {
        self.max_positions.is_some_and(|m| m > self.positions)
    }

    /// The chain a genome describes.
    pub fn chain(&self, genome: &[u8]) -> Result<Chain> {
        let elements = genome
            .iter()
            .map(|&g| self.catalogue[usize::from(g)].clone())
            .collect();
        ChainBuilder::new(elements)
            .wall(self.wall.clone())
            .crossing_angle_rad(self.crossing_angle_rad)
            .build()
    }

    /// The labels of a genome's elements, top to bottom.
    pub fn labels(&self, genome: &[u8]) -> Vec<String> {
        genome
            .iter()
            .map(|&g| self.catalogue[usize::from(g)].label.clone())
            .collect()
    }

    /// Total mass of a genome's chain \[kg\], summed top to bottom.
    pub fn mass_kg(&self, genome: &[u8]) -> f64 {
        genome
            .iter()
            .map(|&g| self.catalogue[usize::from(g)].cell.total_mass_kg())
            .sum()
    }

    /// Height of a genome's stack \[m\]: the sum of its elements' diameters, top to bottom.
    pub fn height_m(&self, genome: &[u8]) -> f64 {
        genome
            .iter()
            .map(|&g| element_height_m(&self.catalogue[usize::from(g)]))
            .sum()
    }

    /// Checks every field and that some design meets the constraints.
    pub fn validate(&self) -> std::result::Result<(), OptimizeError> {
        FeasibleSet::new(self).map(|_| ())
    }
}

/// The genomes that meet a design space's constraints, checked to be non-empty; draws and
/// repairs genomes.
///
/// The number of layers is a genome's length: fixed, or any number in
/// [`DesignSpace::lengths`] (layers count from the top, where the load arrives, so a layer
/// keeps its place whatever the length). The lengths offered are those from the fewest up to
/// the last one some design meets the constraints at (a design with one free layer fewer is
/// lighter, lower and holds no more copies of anything, so the feasible lengths are a range
/// from the fewest).
///
/// Constraint handling is by **repair**: an operator's child that breaks a constraint is changed
/// minimally until it meets them all, so every evaluated genome is feasible. Fixed positions are
/// reset; an entry used more often than allowed has randomly chosen surplus copies moved to the
/// nearest catalogue index with room left; while the chain is too heavy, a random position is
/// moved to the heaviest lighter entry with room left. Each move strictly lowers the mass, and a
/// design where no move is possible is a lightest design (every lighter entry is full), which the
/// up-front check found to be light enough: repair always ends feasible. A genome longer than the
/// longest feasible length first loses its bottom layers; a shorter one than the fewest is
/// filled with the lightest design's elements.
#[derive(Debug, Clone, PartialEq)]
pub struct FeasibleSet {
    /// One set per number of layers, from the fewest up to the longest feasible.
    by_length: Vec<LengthSet>,
    /// The fewest layers.
    min_positions: usize,
}

impl FeasibleSet {
    /// Validates a design space and proves its constraints can be met.
    ///
    /// Errors: an invalid field ([`OptimizeError::Model`]; with a range of lengths: the most
    /// below the fewest, a fixed position not below the fewest) or constraints no design of the
    /// fewest layers meets ([`OptimizeError::Infeasible`], [`OptimizeError::TooHeavy`],
    /// [`OptimizeError::TooTall`], naming the conflicting numbers).
    pub fn new(space: &DesignSpace) -> std::result::Result<Self, OptimizeError> {
        let (min, max) = (
            space.positions,
            space.max_positions.unwrap_or(space.positions),
        );
        if max < min {
            return Err(Error::invalid(
                "design.positions.max",
                max,
                format!("must be at least design.positions.min = {min}"),
            )
            .into());
        }
        if space.max_positions.is_some() && max > MAX_VARIABLE_POSITIONS {
            return Err(Error::invalid(
                "design.positions.max",
                max,
                format!(
                    "a variable number of layers goes up to {MAX_VARIABLE_POSITIONS} (each \
                     length gets its own feasible set); give one number for longer chains"
                ),
            )
            .into());
        }
        if space.max_positions.is_some() {
            if let Some((k, &(pos, _))) =
                (space.constraints.fixed.iter().enumerate()).find(|(_, (p, _))| *p >= min)
            {
                return Err(Error::invalid(
                    format!("design.constraints.fixed[{k}].position"),
                    pos,
                    format!(
                        "with a variable number of layers a fixed position counts from the top \
                         and must exist in every design: 0..{min} (design.positions.min = {min})"
                    ),
                )
                .into());
            }
        }
        LengthSet::validate_space(&DesignSpace {
            positions: max,
            ..space.clone()
        })?;
        let mut by_length = Vec::with_capacity(max - min + 1);
        for n in min..=max {
            let at = DesignSpace {
                positions: n,
                max_positions: None,
                ..space.clone()
            };
            match LengthSet::new(&at) {
                Ok(set) => by_length.push(set),
                Err(
                    OptimizeError::Infeasible { .. }
                    | OptimizeError::TooHeavy { .. }
                    | OptimizeError::TooTall { .. },
                ) if n > min => break,
                Err(e) => return Err(e),
            }
        }
        Ok(FeasibleSet {
            by_length,
            min_positions: min,
        })
    }

    /// The numbers of layers a feasible design may have: from the fewest to the longest some
    /// design meets the constraints at.
    pub fn lengths(&self) -> std::ops::RangeInclusive<usize> {
        self.min_positions..=self.min_positions + self.by_length.len() - 1
    }

    /// Whether designs of different lengths are offered.
    pub fn varies_in_length(&self) -> bool {
        self.by_length.len() > 1
    }

    /// The set of genomes of `len` layers (clamped into [`FeasibleSet::lengths`]).
    fn at(&self, len: usize) -> &LengthSet {
        let k = len.saturating_sub(self.min_positions);
        &self.by_length[k.min(self.by_length.len() - 1)]
    }

    /// Number of catalogue entries.
    pub fn catalogue_len(&self) -> usize {
        self.by_length[0].masses_kg.len()
    }

    /// The positions of a genome of `len` layers not fixed by a constraint.
    pub fn free_positions(&self, len: usize) -> &[usize] {
        &self.at(len).free
    }

    /// The first position below every fixed one (0 when none is fixed): layers are inserted
    /// and removed only from here down, so fixed positions keep their elements.
    pub fn first_movable_position(&self) -> usize {
        let fixed = &self.by_length[0].fixed;
        fixed.iter().rposition(Option::is_some).map_or(0, |p| p + 1)
    }

    /// A lightest feasible design of the fewest layers (the witness of feasibility).
    pub fn lightest(&self) -> &[u8] {
        &self.by_length[0].lightest
    }

    /// Whether a genome has a length in [`FeasibleSet::lengths`], indexes the catalogue and
    /// meets every constraint.
    pub fn contains(&self, genome: &[u8]) -> bool {
        self.lengths().contains(&genome.len()) && self.at(genome.len()).contains(genome)
    }

    /// A random feasible genome: with a range of lengths, the number of layers uniform over
    /// [`FeasibleSet::lengths`]; each free gene uniform over the catalogue; then repaired.
    pub fn random(&self, rng: &mut impl Rng) -> Genome {
        let len = if self.varies_in_length() {
            rng.random_range(self.lengths())
        } else {
            self.min_positions
        };
        self.at(len).random(rng)
    }

    /// Changes a genome with genes inside the catalogue as little as the rules of
    /// [`FeasibleSet`] allow until it meets every constraint (its length brought into
    /// [`FeasibleSet::lengths`] first).
    pub fn repair(&self, genome: &mut Genome, rng: &mut impl Rng) {
        let lengths = self.lengths();
        if genome.len() > *lengths.end() {
            genome.truncate(*lengths.end());
        }
        if genome.len() < *lengths.start() {
            let fill = &self.lightest()[genome.len()..];
            genome.extend_from_slice(fill);
        }
        self.at(genome.len()).repair(genome, rng);
    }
}

/// The genomes of one length that meet a design space's constraints, checked to be non-empty
/// (one per number of layers of a [`FeasibleSet`]).
#[derive(Debug, Clone, PartialEq)]
struct LengthSet {
    positions: usize,
    masses_kg: Vec<f64>,
    caps: Vec<usize>,
    fixed: Vec<Option<u8>>,
    free: Vec<usize>,
    max_mass_kg: Option<f64>,
    heights_m: Vec<f64>,
    max_height_m: Option<f64>,
    lightest: Genome,
}

impl LengthSet {
    /// Validates a design space and proves its constraints can be met.
    ///
    /// Errors: an invalid field ([`OptimizeError::Model`]) or constraints no design meets
    /// ([`OptimizeError::Infeasible`], naming the conflicting numbers).
    fn new(space: &DesignSpace) -> std::result::Result<Self, OptimizeError> {
        let fixed = Self::fixed_positions(space)?;
        let caps = Self::count_caps(space)?;
        let max_mass_kg = match space.constraints.max_total_mass_kg {
            Some(m) if !(m.is_finite() && m > 0.0) => {
                return Err(Error::invalid(
                    "design.constraints.max_total_mass_kg",
                    m,
                    "must be a finite number > 0",
                )
                .into())
            }
            other => other,
        };
        let masses_kg: Vec<f64> = space
            .catalogue
            .iter()
            .map(|e| e.cell.total_mass_kg())
            .collect();
        let free: Vec<usize> = (0..space.positions)
            .filter(|&p| fixed[p].is_none())
            .collect();
        let room = Self::room_left(space, &fixed, &caps, free.len())?;
        let lightest = Self::lightest_design(&masses_kg, &fixed, &free, room.clone());
        if let Some(max) = max_mass_kg {
            let min = space.mass_kg(&lightest);
            if min > max * (1.0 + MASS_SLACK) {
                return Err(OptimizeError::TooHeavy {
                    max_total_mass_kg: max,
                    lightest_kg: min,
                    lightest: space.labels(&lightest).join(" "),
                });
            }
        }
        let heights_m: Vec<f64> = space.catalogue.iter().map(element_height_m).collect();
        let max_height_m = Self::positive_limit(
            "design.constraints.max_stack_height_m",
            space.constraints.max_stack_height_m,
        )?;
        Self::positive_limit(
            "design.constraints.max_contact_pressure_pa",
            space.constraints.max_contact_pressure_pa,
        )?;
        let mut set = LengthSet {
            positions: space.positions,
            masses_kg,
            caps,
            fixed,
            free,
            max_mass_kg,
            heights_m,
            max_height_m,
            lightest,
        };
        if let Some(max) = max_height_m {
            set.meet_the_height(space, max, room)?;
        }
        Ok(set)
    }

    /// Under a height limit `max` \[m\]: refuses a space whose lowest design stands taller, and
    /// makes the witness (`lightest`) one that meets both the height and the mass limit.
    fn meet_the_height(
        &mut self,
        space: &DesignSpace,
        max: f64,
        room: Vec<usize>,
    ) -> std::result::Result<(), OptimizeError> {
        let lowest = Self::lightest_design(&self.heights_m, &self.fixed, &self.free, room);
        let (low, light) = (self.height_m(&lowest), self.height_m(&self.lightest));
        if low > max * (1.0 + MASS_SLACK) {
            return Err(OptimizeError::TooTall {
                max_stack_height_m: max,
                lowest_m: low,
                lowest: space.labels(&lowest).join(" "),
            });
        }
        // The witness must meet both limits: the lightest design if it is low enough,
        // else one lightened from the lowest without exceeding the height, else one
        // lowered from the lightest without exceeding the mass.
        if light > max * (1.0 + MASS_SLACK) {
            let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(0);
            let mut found = None;
            for start in [lowest.clone(), self.lightest.clone()] {
                let mut g = start;
                let mut counts = self.counts(&g);
                self.shrink_both(&mut g, &mut counts, &mut rng);
                if self.contains(&g) {
                    found = Some(g);
                    break;
                }
            }
            match found {
                Some(g) => self.lightest = g,
                None => {
                    return Err(OptimizeError::Infeasible {
                        reason: format!(
                            "found no design meeting max_stack_height = {max} m and \
                             max_total_mass = {} kg together: the lightest ({}) stands {light} m, \
                             the lowest ({}, {low} m) weighs {} kg",
                            self.max_mass_kg.unwrap_or(f64::INFINITY),
                            space.labels(&self.lightest).join(" "),
                            space.labels(&lowest).join(" "),
                            space.mass_kg(&lowest),
                        ),
                    })
                }
            }
        }

        Ok(())
    }

    /// A limit that must be a finite number > 0 when given.
    fn positive_limit(
        field: &str,
        limit: Option<f64>,
    ) -> std::result::Result<Option<f64>, OptimizeError> {
        match limit {
            Some(m) if !(m.is_finite() && m > 0.0) => {
                Err(Error::invalid(field, m, "must be a finite number > 0").into())
            }
            other => Ok(other),
        }
    }

    /// The design space's own fields: positions, the catalogue (each entry on the wall), the
    /// excitation and the run settings, and one full chain.
    fn validate_space(space: &DesignSpace) -> std::result::Result<(), OptimizeError> {
        let n_cat = space.catalogue.len();
        if space.positions == 0 {
            return Err(Error::invalid("design.positions", 0, "must be at least 1").into());
        }
        if n_cat == 0 {
            return Err(
                Error::invalid("design.catalogue", "[]", "must hold at least one element").into(),
            );
        }
        if n_cat > MAX_CATALOGUE_LEN {
            return Err(Error::invalid(
                "design.catalogue",
                format!("{n_cat} entries"),
                format!("must hold at most {MAX_CATALOGUE_LEN} entries"),
            )
            .into());
        }
        space.excitation.validate()?;
        space.settings.validate()?;
        for (i, e) in space.catalogue.iter().enumerate() {
            ChainBuilder::new(vec![e.clone()])
                .wall(space.wall.clone())
                .build()
                .map_err(|err| match err {
                    Error::InvalidParameter {
                        field,
                        value,
                        reason,
                    } => Error::InvalidParameter {
                        field: field
                            .replace("chain.elements[0]", &format!("design.catalogue[{i}]")),
                        value,
                        reason,
                    },
                    other => other,
                })?;
        }
        // One full chain of the first entry checks the wall, angle and excitation together.
        space.chain(&vec![0; space.positions])?;

        Ok(())
    }

    /// The fixed element of each position (None: free), checked against the positions and the
    /// catalogue; a position fixed twice to different elements is infeasible.
    fn fixed_positions(space: &DesignSpace) -> std::result::Result<Vec<Option<u8>>, OptimizeError> {
        let (c, n_cat) = (&space.constraints, space.catalogue.len());
        let mut fixed = vec![None; space.positions];
        for (k, &(pos, idx)) in c.fixed.iter().enumerate() {
            let field = format!("design.constraints.fixed[{k}]");
            if pos >= space.positions {
                return Err(Error::invalid(
                    format!("{field}.position"),
                    pos,
                    format!("positions are 0..{} (0 = top)", space.positions),
                )
                .into());
            }
            if idx >= n_cat {
                return Err(Error::invalid(
                    format!("{field}.element"),
                    idx,
                    format!("catalogue indices are 0..{n_cat}"),
                )
                .into());
            }
            match fixed[pos] {
                Some(prev) if usize::from(prev) != idx => {
                    return Err(OptimizeError::Infeasible {
                        reason: format!(
                            "position {pos} is fixed to both `{}` and `{}`",
                            space.catalogue[usize::from(prev)].label,
                            space.catalogue[idx].label
                        ),
                    })
                }
                _ => fixed[pos] = Some(idx as u8),
            }
        }
        Ok(fixed)
    }

    /// The most copies of each catalogue entry a design may hold (usize::MAX: no limit).
    fn count_caps(space: &DesignSpace) -> std::result::Result<Vec<usize>, OptimizeError> {
        let (c, n_cat) = (&space.constraints, space.catalogue.len());
        let mut caps = vec![usize::MAX; n_cat];
        for (k, &(idx, count)) in c.max_count.iter().enumerate() {
            if idx >= n_cat {
                return Err(Error::invalid(
                    format!("design.constraints.max_count[{k}].element"),
                    idx,
                    format!("catalogue indices are 0..{n_cat}"),
                )
                .into());
            }
            caps[idx] = caps[idx].min(count);
        }
        Ok(caps)
    }

    /// The copies of each entry the free positions may still take once the fixed ones are
    /// placed; infeasible when the fixed copies exceed a cap or the room cannot fill `n_free`.
    fn room_left(
        space: &DesignSpace,
        fixed: &[Option<u8>],
        caps: &[usize],
        n_free: usize,
    ) -> std::result::Result<Vec<usize>, OptimizeError> {
        // Counts: the fixed copies must fit under the caps, and the room left must fill the rest.
        let mut room = caps.to_vec();
        for f in fixed.iter().flatten() {
            let e = usize::from(*f);
            if room[e] == 0 {
                let n_fixed = fixed.iter().flatten().filter(|&&x| x == *f).count();
                return Err(OptimizeError::Infeasible {
                    reason: format!(
                        "`{}` is fixed at {n_fixed} positions but allowed at most {} times",
                        space.catalogue[e].label, caps[e]
                    ),
                });
            }
            if room[e] != usize::MAX {
                room[e] -= 1;
            }
        }
        let total_room = room.iter().fold(0usize, |a, &r| a.saturating_add(r));
        if total_room < n_free {
            return Err(OptimizeError::Infeasible {
                reason: format!(
                    "the count limits leave room for {total_room} elements but {} positions are free",
                    n_free
                ),
            });
        }
        Ok(room)
    }

    /// The lightest design: the free positions filled with the lightest entries that have room.
    fn lightest_design(
        masses_kg: &[f64],
        fixed: &[Option<u8>],
        free: &[usize],
        room: Vec<usize>,
    ) -> Genome {
        let n_cat = masses_kg.len();
        let mut by_mass: Vec<usize> = (0..n_cat).collect();
        by_mass.sort_by(|&a, &b| masses_kg[a].total_cmp(&masses_kg[b]).then(a.cmp(&b)));
        let mut lightest: Genome = fixed.iter().map(|f| f.unwrap_or(0)).collect();
        let mut left = room;
        let mut next = by_mass.iter();
        let mut current = *next.next().expect("catalogue is not empty");
        for &p in free {
            while left[current] == 0 {
                current = *next.next().expect("room was checked");
            }
            lightest[p] = current as u8;
            if left[current] != usize::MAX {
                left[current] -= 1;
            }
        }
        lightest
    }

    fn mass_kg(&self, genome: &[u8]) -> f64 {
        genome.iter().map(|&g| self.masses_kg[usize::from(g)]).sum()
    }

    fn counts(&self, genome: &[u8]) -> Vec<usize> {
        let mut counts = vec![0; self.masses_kg.len()];
        for &g in genome {
            counts[usize::from(g)] += 1;
        }
        counts
    }

    /// Whether a genome has the right length, indexes the catalogue and meets every constraint.
    fn contains(&self, genome: &[u8]) -> bool {
        if genome.len() != self.positions
            || genome
                .iter()
                .any(|&g| usize::from(g) >= self.masses_kg.len())
        {
            return false;
        }
        if self
            .fixed
            .iter()
            .zip(genome)
            .any(|(f, &g)| f.is_some_and(|f| f != g))
        {
            return false;
        }
        if self
            .counts(genome)
            .iter()
            .zip(&self.caps)
            .any(|(n, cap)| n > cap)
        {
            return false;
        }
        let within = |limit: Option<f64>, total: f64| {
            limit.is_none_or(|max| total <= max * (1.0 + MASS_SLACK))
        };
        within(self.max_mass_kg, self.mass_kg(genome))
            && within(self.max_height_m, self.height_m(genome))
    }

    /// Height of a genome's stack \[m\].
    fn height_m(&self, genome: &[u8]) -> f64 {
        genome.iter().map(|&g| self.heights_m[usize::from(g)]).sum()
    }

    /// A random feasible genome: each free gene uniform over the catalogue, then repaired.
    fn random(&self, rng: &mut impl Rng) -> Genome {
        let n = self.masses_kg.len();
        let mut g: Genome = self.fixed.iter().map(|f| f.unwrap_or(0)).collect();
        for &p in &self.free {
            g[p] = rng.random_range(0..n) as u8;
        }
        self.repair(&mut g, rng);
        g
    }

    /// Changes a genome of the right length with genes inside the catalogue as little as the
    /// rules of [`FeasibleSet`] allow until it meets every constraint.
    fn repair(&self, genome: &mut [u8], rng: &mut impl Rng) {
        assert_eq!(genome.len(), self.positions, "genome length");
        for (g, f) in genome.iter_mut().zip(&self.fixed) {
            if let Some(f) = f {
                *g = *f;
            }
        }
        let n = self.masses_kg.len();
        let mut counts = self.counts(genome);
        for e in 0..n {
            if counts[e] <= self.caps[e] {
                continue;
            }
            let mut holders: Vec<usize> = self
                .free
                .iter()
                .copied()
                .filter(|&p| usize::from(genome[p]) == e)
                .collect();
            while counts[e] > self.caps[e] {
                let k = rng.random_range(0..holders.len());
                let p = holders.swap_remove(k);
                let to = nearest_with_room(e, &counts, &self.caps, rng)
                    .expect("room was checked in FeasibleSet::new");
                genome[p] = to as u8;
                counts[e] -= 1;
                counts[to] += 1;
            }
        }
        if self.max_height_m.is_none() {
            if !self.shrink(genome, &mut counts, &self.masses_kg, self.max_mass_kg, rng) {
                // A lightest multiset summed in another order: cannot exceed the limit unless
                // rounding differs; fall back on the checked witness.
                genome.copy_from_slice(&self.lightest);
            }
            return;
        }
        // Height, then mass, each move keeping the other limit where it can; the checked
        // witness where they do not settle.
        if !self.shrink_both(genome, &mut counts, rng) {
            genome.copy_from_slice(&self.lightest);
        }
    }

    /// Height, then mass, a few rounds, each move keeping the other sum within its limit where
    /// one can; whether the genome ends within both.
    fn shrink_both(&self, genome: &mut [u8], counts: &mut [usize], rng: &mut impl Rng) -> bool {
        let height = (&self.heights_m[..], self.max_height_m);
        let mass = (&self.masses_kg[..], self.max_mass_kg);
        for _ in 0..4 {
            self.shrink_within(genome, counts, height, Some(mass), rng);
            self.shrink_within(genome, counts, mass, Some(height), rng);
            if self.contains(genome) {
                return true;
            }
        }
        false
    }

    /// While the sum of `resource` over the genome exceeds `limit`, moves a random free position
    /// to the largest smaller entry with room (each move strictly lowers the sum). False when no
    /// move is left and the sum is still above the limit.
    fn shrink(
        &self,
        genome: &mut [u8],
        counts: &mut [usize],
        resource: &[f64],
        limit: Option<f64>,
        rng: &mut impl Rng,
    ) -> bool {
        self.shrink_within(genome, counts, (resource, limit), None, rng)
    }

    /// [`FeasibleSet::shrink`], moves restricted to those that keep the sum of `keep`'s
    /// resource within its limit (a move that breaks it is taken only when no other is left).
    fn shrink_within(
        &self,
        genome: &mut [u8],
        counts: &mut [usize],
        (resource, limit): (&[f64], Option<f64>),
        keep: Option<(&[f64], Option<f64>)>,
        rng: &mut impl Rng,
    ) -> bool {
        let Some(max) = limit else { return true };
        let n = resource.len();
        let limit = max * (1.0 + MASS_SLACK);
        let total =
            |genome: &[u8], r: &[f64]| -> f64 { genome.iter().map(|&g| r[usize::from(g)]).sum() };
        let kept = keep.and_then(|(r, l)| l.map(|l| (r, l * (1.0 + MASS_SLACK))));
        let mut sum = total(genome, resource);
        while sum > limit {
            let other = kept.map(|(r, _)| total(genome, r));
            let smaller = |p: &usize, counts: &[usize], strict: bool| {
                let g = usize::from(genome[*p]);
                let m = resource[g];
                (0..n)
                    .filter(|&j| resource[j] < m && counts[j] < self.caps[j])
                    .filter(|&j| match (strict, kept, other) {
                        (true, Some((r, l)), Some(o)) => o - r[g] + r[j] <= l,
                        _ => true,
                    })
                    .max_by(|&a, &b| resource[a].total_cmp(&resource[b]))
            };
            let pick = |strict: bool, counts: &[usize]| -> Vec<usize> {
                self.free
                    .iter()
                    .copied()
                    .filter(|p| smaller(p, counts, strict).is_some())
                    .collect()
            };
            let mut strict = kept.is_some();
            let mut movable = pick(strict, counts);
            if movable.is_empty() && strict {
                strict = false;
                movable = pick(false, counts);
            }
            if movable.is_empty() {
                return false;
            }
            let p = movable[rng.random_range(0..movable.len())];
            let to = smaller(&p, counts, strict).expect("movable");
            counts[usize::from(genome[p])] -= 1;
            counts[to] += 1;
            genome[p] = to as u8;
            sum = total(genome, resource);
        }
        true
    }
}

/// The catalogue index nearest to `e` (ties broken at random) whose count is below its cap.
fn nearest_with_room(
    e: usize,
    counts: &[usize],
    caps: &[usize],
    rng: &mut impl Rng,
) -> Option<usize> {
    let n = counts.len();
    for d in 1..n {
        let down = e.checked_sub(d).filter(|&j| counts[j] < caps[j]);
        let up = Some(e + d).filter(|&j| j < n && counts[j] < caps[j]);
        match (down, up) {
            (Some(a), Some(b)) => return Some(if rng.random_bool(0.5) { a } else { b }),
            (Some(a), None) | (None, Some(a)) => return Some(a),
            (None, None) => {}
        }
    }
    None
}

/// Height of one element along the chain axis \[m\]: its diameter.
pub fn element_height_m(element: &Element) -> f64 {
    match element.body {
        Body::Rod { diameter_m, .. } | Body::Sphere { diameter_m } => diameter_m,
    }
}
