//! The breeder GA's operators (Mühlenbein & Schlierkamp-Voosen 1993), as plain functions of the
//! population and a random generator. None of them evaluates, prints or stops anything.

use super::space::{FeasibleSet, Genome};
use rand::Rng;

/// Number of parents that breed under truncation threshold T: ⌈T·μ⌉, at least 1, at most μ.
///
/// Truncation selection (Mühlenbein & Schlierkamp-Voosen 1993, §3): only the best T·100 % of a
/// population of size μ are parents, each equally likely.
pub fn truncation_pool(population: usize, truncation: f64) -> usize {
    ((truncation * population as f64).ceil() as usize).clamp(1, population)
}

/// Two parent ranks drawn uniformly from the best `pool` (distinct when pool ≥ 2).
pub fn select_parents(pool: usize, rng: &mut impl Rng) -> (usize, usize) {
    let a = rng.random_range(0..pool);
    if pool < 2 {
        return (a, a);
    }
    let mut b = rng.random_range(0..pool - 1);
    if b >= a {
        b += 1;
    }
    (a, b)
}

/// Discrete (gene-wise) recombination: each gene of the child comes from either parent with
/// probability ½ (Mühlenbein & Schlierkamp-Voosen 1993, §4.1 "discrete recombination").
///
/// Parents of different lengths are aligned at the top (layer k of one faces layer k of the
/// other, counted from where the load arrives): the layers both have are recombined as above,
/// the child takes either parent's length with probability ½, and its layers below the
/// shorter parent's last come from the longer parent. Parents of one length draw exactly as
/// without this rule.
pub fn recombine(a: &[u8], b: &[u8], rng: &mut impl Rng) -> Genome {
    let common = a.len().min(b.len());
    let mut child: Genome = a[..common]
        .iter()
        .zip(&b[..common])
        .map(|(&x, &y)| if rng.random_bool(0.5) { x } else { y })
        .collect();
    if a.len() != b.len() {
        let longer = if a.len() > b.len() { a } else { b };
        let len = if rng.random_bool(0.5) {
            a.len()
        } else {
            b.len()
        };
        child.extend_from_slice(&longer[common..len]);
    }
    child
}

/// The BGA mutation step δ = Σ_{k=0}^{15} α_k 2^{−k}, α_k = 1 with probability 1/16
/// (Mühlenbein & Schlierkamp-Voosen 1993, §4.2): small steps are common, large ones rare.
pub fn bga_delta(rng: &mut impl Rng) -> f64 {
    (0..16)
        .filter(|_| rng.random_bool(1.0 / 16.0))
        .map(|k| 0.5_f64.powi(k))
        .sum()
}

/// The BGA mutation for catalogue indices: each free gene is mutated with probability 1/n
/// (n = number of free positions) by ± round(range·δ) indices, at least one, the sign + or −
/// with probability ½, clamped to the catalogue 0..len. `range` is in index units.
///
/// When the number of layers is part of the design ([`FeasibleSet::varies_in_length`]), the
/// length then mutates with the same probability 1/n as a gene ([`mutate_length`]).
pub fn mutate(genome: &mut Genome, set: &FeasibleSet, range: f64, rng: &mut impl Rng) {
    mutate_genes(genome, set, range, rng);
    if set.varies_in_length() {
        let n = set.free_positions(genome.len()).len().max(1);
        if rng.random_bool(1.0 / n as f64) {
            mutate_length(genome, set, rng);
        }
    }
}

/// One layer more or fewer (probability ½ each, the only way open at either end of
/// [`FeasibleSet::lengths`]): a uniformly drawn catalogue entry inserted at, or the layer
/// removed from, a uniformly drawn position below every fixed one
/// ([`FeasibleSet::first_movable_position`]), so fixed layers keep their place.
pub fn mutate_length(genome: &mut Genome, set: &FeasibleSet, rng: &mut impl Rng) {
    let lengths = set.lengths();
    let len = genome.len();
    let first = set.first_movable_position().min(len);
    let grow = match (len < *lengths.end(), len > *lengths.start() && len > first) {
        (true, true) => rng.random_bool(0.5),
        (grow, shrink) if grow || shrink => grow,
        _ => return,
    };
    if grow {
        let at = rng.random_range(first..=len);
        let element = rng.random_range(0..set.catalogue_len()) as u8;
        genome.insert(at, element);
    } else {
        let at = rng.random_range(first..len);
        genome.remove(at);
    }
}

/// The gene part of [`mutate`].
fn mutate_genes(genome: &mut [u8], set: &FeasibleSet, range: f64, rng: &mut impl Rng) {
    let free = set.free_positions(genome.len());
    if free.is_empty() {
        return;
    }
    let p = 1.0 / free.len() as f64;
    let top = set.catalogue_len() - 1;
    let len = genome.len();
    for &pos in free.iter().filter(|&&p| p < len) {
        if !rng.random_bool(p) {
            continue;
        }
        let step = ((range * bga_delta(rng)).round() as usize).max(1);
        let g = usize::from(genome[pos]);
        let to = if rng.random_bool(0.5) {
            (g + step).min(top)
        } else {
            g.saturating_sub(step)
        };
        genome[pos] = to as u8;
    }
}

/// One child: two parents from the truncated pool of a population sorted best first,
/// recombined, mutated and repaired into the feasible set.
pub fn breed(
    sorted: &[&[u8]],
    pool: usize,
    set: &FeasibleSet,
    range: f64,
    rng: &mut impl Rng,
) -> Genome {
    let (a, b) = select_parents(pool, rng);
    let mut child = recombine(sorted[a], sorted[b], rng);
    mutate(&mut child, set, range, rng);
    set.repair(&mut child, rng);
    child
}

/// The BGA mutation for genes of different choice counts (a lattice's rod lengths and pitch):
/// each gene of more than one choice is mutated with probability 1/n (n = such genes) by
/// ± round(range·δ) indices, at least one, the sign + or − with probability ½, clamped to its
/// choices 0..count. `range` is in index units (None: each gene's span, count − 1).
pub fn mutate_choices(genome: &mut [u8], counts: &[usize], range: Option<f64>, rng: &mut impl Rng) {
    let free = counts.iter().filter(|&&c| c > 1).count();
    if free == 0 {
        return;
    }
    let p = 1.0 / free as f64;
    for (g, &count) in genome.iter_mut().zip(counts) {
        if count < 2 || !rng.random_bool(p) {
            continue;
        }
        let top = count - 1;
        let span = range.unwrap_or(top as f64);
        let step = ((span * bga_delta(rng)).round() as usize).max(1);
        let at = usize::from(*g);
        let to = if rng.random_bool(0.5) {
            (at + step).min(top)
        } else {
            at.saturating_sub(step)
        };
        *g = to as u8;
    }
}
