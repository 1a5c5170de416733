//! Pareto fronts of minimisation problems: constraint domination, fast non-dominated sorting
//! and crowding distance (Deb et al. 2002), and the exact hypervolume.
//!
//! Every function takes objective vectors (all minimised) and, where constraints matter, a
//! violation per point (0 = feasible, > 0 = by how much a constraint is broken). Ties are broken
//! by index, so every result is deterministic.
//!
//! ## References
//! - K. Deb, A. Pratap, S. Agarwal, T. Meyarivan, "A fast and elitist multiobjective genetic
//!   algorithm: NSGA-II", IEEE Trans. Evol. Comput. 6 (2002) 182–197 (§III-A sorting, §III-B
//!   crowding distance, §VI constraint domination).
//! - L. While, P. Hingston, L. Barone, S. Huband, "A faster algorithm for calculating
//!   hypervolume", IEEE Trans. Evol. Comput. 10 (2006) 29–38 (hypervolume by slicing objectives).

use std::cmp::Ordering;

/// Whether `a` Pareto-dominates `b` (no worse in every objective, better in one).
pub fn dominates(a: &[f64], b: &[f64]) -> bool {
    let mut better = false;
    for (x, y) in a.iter().zip(b) {
        if x > y {
            return false;
        }
        if x < y {
            better = true;
        }
    }
    better
}

/// Constraint domination (Deb et al. 2002 §VI): a feasible point dominates an infeasible one;
/// of two infeasible points the smaller violation dominates; two feasible points compare by
/// Pareto domination.
pub fn constrained_dominates(a: &[f64], a_violation: f64, b: &[f64], b_violation: f64) -> bool {
    match (a_violation > 0.0, b_violation > 0.0) {
        (false, true) => true,
        (true, false) => false,
        (true, true) => a_violation < b_violation,
        (false, false) => dominates(a, b),
    }
}

/// Fast non-dominated sorting (Deb et al. 2002 §III-A) under constraint domination: the fronts,
/// best first, each a list of indices in ascending order.
pub fn non_dominated_fronts(points: &[Vec<f64>], violations: &[f64]) -> Vec<Vec<usize>> {
    let n = points.len();
    let mut dominated_by_count = vec![0usize; n];
    let mut dominates_list: Vec<Vec<usize>> = vec![Vec::new(); n];
    for i in 0..n {
        for j in (i + 1)..n {
            if constrained_dominates(&points[i], violations[i], &points[j], violations[j]) {
                dominates_list[i].push(j);
                dominated_by_count[j] += 1;
            } else if constrained_dominates(&points[j], violations[j], &points[i], violations[i]) {
                dominates_list[j].push(i);
                dominated_by_count[i] += 1;
            }
        }
    }
    let mut fronts = Vec::new();
    let mut current: Vec<usize> = (0..n).filter(|&i| dominated_by_count[i] == 0).collect();
    while !current.is_empty() {
        let mut next = Vec::new();
        for &i in &current {
            for &j in &dominates_list[i] {
                dominated_by_count[j] -= 1;
                if dominated_by_count[j] == 0 {
                    next.push(j);
                }
            }
        }
        next.sort_unstable();
        fronts.push(current);
        current = next;
    }
    fronts
}

/// Crowding distance of each point of one front (Deb et al. 2002 §III-B), in the front's
/// order: per objective, the points sorted by value (ties by index) get the normalised distance
/// between their neighbours; the two ends of any objective's range are infinite. An objective
/// with no range adds nothing.
// `k` indexes an objective within every point, not the list of points.
#[allow(clippy::needless_range_loop)]
pub fn crowding_distances(points: &[&[f64]]) -> Vec<f64> {
    let n = points.len();
    let mut distance = vec![0.0; n];
    if n == 0 {
        return distance;
    }
    let m = points[0].len();
    for k in 0..m {
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| points[a][k].total_cmp(&points[b][k]).then(a.cmp(&b)));
        let (lo, hi) = (points[order[0]][k], points[order[n - 1]][k]);
        distance[order[0]] = f64::INFINITY;
        distance[order[n - 1]] = f64::INFINITY;
        if hi <= lo {
            continue;
        }
        for w in 1..n.saturating_sub(1) {
            let gap = points[order[w + 1]][k] - points[order[w - 1]][k];
            distance[order[w]] += gap / (hi - lo);
        }
    }
    distance
}

/// The exact hypervolume dominated by `points` (minimisation) and bounded by `reference`: the
/// measure of { x : some point ≤ x < reference }. Points that do not lie strictly below the
/// reference in every objective add nothing. Computed by slicing along the last objective
/// (While et al. 2006), exact for any number of objectives; quadratic in the number of points
/// for two objectives after the sort, fine for fronts of hundreds.
pub fn hypervolume(points: &[Vec<f64>], reference: &[f64]) -> f64 {
    let inside: Vec<&[f64]> = points
        .iter()
        .map(Vec::as_slice)
        .filter(|p| p.iter().zip(reference).all(|(x, r)| x < r))
        .collect();
    volume(&inside, reference)
}

fn volume(points: &[&[f64]], reference: &[f64]) -> f64 {
    let d = reference.len();
    if points.is_empty() {
        return 0.0;
    }
    if d == 1 {
        let best = points.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
        return reference[0] - best;
    }
    if d == 2 {
        let mut sorted: Vec<&[f64]> = points.to_vec();
        sorted.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
        return strip_area(&sorted, reference);
    }
    let mut sorted: Vec<&[f64]> = points.to_vec();
    sorted.sort_by(|a, b| a[d - 1].total_cmp(&b[d - 1]));
    let lower = &reference[..d - 1];
    let mut total = 0.0;
    for k in 0..sorted.len() {
        let top = sorted.get(k + 1).map_or(reference[d - 1], |q| q[d - 1]);
        let depth = top - sorted[k][d - 1];
        if depth <= 0.0 {
            continue;
        }
        let slice: Vec<&[f64]> = sorted[..=k].iter().map(|p| &p[..d - 1]).collect();
        total += depth * volume(&slice, lower);
    }
    total
}

/// The area dominated by 2-D points sorted by the first objective, bounded by the reference.
fn strip_area(sorted: &[&[f64]], reference: &[f64]) -> f64 {
    let mut area = 0.0;
    let mut ceiling = reference[1];
    for p in sorted {
        if p[1] < ceiling {
            area += (reference[0] - p[0]) * (ceiling - p[1]);
            ceiling = p[1];
        }
    }
    area
}

/// Orders two (rank, crowding distance) pairs by NSGA-II's crowded comparison: lower rank first,
/// then larger distance.
pub fn crowded_order(a: (usize, f64), b: (usize, f64)) -> Ordering {
    a.0.cmp(&b.0).then(b.1.total_cmp(&a.1))
}
