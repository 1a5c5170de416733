//! The rod itself as a Timoshenko finite-element beam (docs/physics.md §13), to check the
//! reduced cells of [`super::beam`] in time.
//!
//! By symmetry only the half rod from the centre (x = 0) to a free end (x = L/2) is modelled, with
//! `n` two-node Timoshenko elements (deflection w and rotation θ per node; the exact
//! shape-function element of Friedman and Kosmatka, free of shear locking, with consistent
//! translational and rotary mass). The contact acts on the centre node, whose rotation is zero by
//! symmetry.
//!
//! Seen from the centre, this linear model *is* a unit cell with one resonator per mode of the
//! rod with its centre held (a Craig–Bampton transformation that keeps every mode is exact): mode
//! j of the clamped half, mass-normalised (φᵀMφ = 1), has angular frequency ω_j and participation
//! L_j = φ_jᵀ M ψ for the rigid translation ψ, and carries the modal effective mass m_j = L_j²
//! (doubled for the two halves); the primary mass is the rest of ρ·A·L. So the finite-element rod
//! runs through the same equations of motion as any cell, with 2n resonators.

use super::beam::Rod;
use super::cell::{Resonator, UnitCell};
use super::free_rod::TimoshenkoMode;
use crate::error::{Error, Result};

/// The most elements per half rod (the generalized eigenproblem is dense: 2n unknowns).
pub const MAX_FE_ELEMENTS: usize = 64;

/// Stiffness and mass matrices (4 × 4, DOFs w₁ θ₁ w₂ θ₂) of one Timoshenko element of length h.
fn element_matrices(rod: &Rod, h: f64) -> ([[f64; 4]; 4], [[f64; 4]; 4]) {
    let e = rod.material.youngs_modulus_pa;
    let g = e / (2.0 * (1.0 + rod.material.poisson_ratio));
    let rho = rod.material.density_kg_m3;
    let (a, i) = (rod.area_m2(), rod.second_moment_m4());
    let ei = e * i;
    let phi = 12.0 * ei / (rod.shear_coefficient() * g * a * h * h);
    let c = ei / ((1.0 + phi) * h.powi(3));
    let (h2, p2) = (h * h, phi * phi);
    let k = [
        [12.0 * c, 6.0 * h * c, -12.0 * c, 6.0 * h * c],
        [
            6.0 * h * c,
            (4.0 + phi) * h2 * c,
            -6.0 * h * c,
            (2.0 - phi) * h2 * c,
        ],
        [-12.0 * c, -6.0 * h * c, 12.0 * c, -6.0 * h * c],
        [
            6.0 * h * c,
            (2.0 - phi) * h2 * c,
            -6.0 * h * c,
            (4.0 + phi) * h2 * c,
        ],
    ];
    let t = rho * a * h / (1.0 + phi).powi(2);
    let m11 = t * (13.0 / 35.0 + 7.0 * phi / 10.0 + p2 / 3.0);
    let m12 = t * (11.0 / 210.0 + 11.0 * phi / 120.0 + p2 / 24.0) * h;
    let m13 = t * (9.0 / 70.0 + 3.0 * phi / 10.0 + p2 / 6.0);
    let m14 = t * (13.0 / 420.0 + 3.0 * phi / 40.0 + p2 / 24.0) * h;
    let m22 = t * (1.0 / 105.0 + phi / 60.0 + p2 / 120.0) * h2;
    let m24 = t * (1.0 / 140.0 + phi / 60.0 + p2 / 120.0) * h2;
    let r = rho * i / ((1.0 + phi).powi(2) * h);
    let r11 = r * 6.0 / 5.0;
    let r12 = r * (1.0 / 10.0 - phi / 2.0) * h;
    let r22 = r * (2.0 / 15.0 + phi / 6.0 + p2 / 3.0) * h2;
    let r24 = r * (-1.0 / 30.0 - phi / 6.0 + p2 / 6.0) * h2;
    let m = [
        [m11 + r11, m12 + r12, m13 - r11, -m14 + r12],
        [m12 + r12, m22 + r22, m14 - r12, -m24 + r24],
        [m13 - r11, m14 - r12, m11 + r11, -m12 - r12],
        [-m14 + r12, -m24 + r24, -m12 - r12, m22 + r22],
    ];
    (k, m)
}

/// Cholesky factor L (lower, row-major n × n) of a symmetric positive-definite `a`.
fn cholesky(a: &[f64], n: usize) -> Option<Vec<f64>> {
    let mut l = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..=i {
            let s: f64 = (0..j).map(|k| l[i * n + k] * l[j * n + k]).sum();
            if i == j {
                let d = a[i * n + i] - s;
                if d <= 0.0 {
                    return None;
                }
                l[i * n + i] = d.sqrt();
            } else {
                l[i * n + j] = (a[i * n + j] - s) / l[j * n + j];
            }
        }
    }
    Some(l)
}

/// Eigenvalues and eigenvectors (columns of the returned row-major matrix) of a symmetric `a` by
/// cyclic Jacobi rotations, to machine precision.
fn jacobi_eigen(mut a: Vec<f64>, n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut v = vec![0.0; n * n];
    for i in 0..n {
        v[i * n + i] = 1.0;
    }
    for _sweep in 0..100 {
        let off: f64 = (0..n)
            .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i * n + j].powi(2))
            .sum();
        let diag: f64 = (0..n).map(|i| a[i * n + i].powi(2)).sum();
        if off <= 1e-30 * diag {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                let apq = a[p * n + q];
                if apq == 0.0 {
                    continue;
                }
                let theta = (a[q * n + q] - a[p * n + p]) / (2.0 * apq);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for k in 0..n {
                    let (akp, akq) = (a[k * n + p], a[k * n + q]);
                    a[k * n + p] = c * akp - s * akq;
                    a[k * n + q] = s * akp + c * akq;
                }
                for k in 0..n {
                    let (apk, aqk) = (a[p * n + k], a[q * n + k]);
                    a[p * n + k] = c * apk - s * aqk;
                    a[q * n + k] = s * apk + c * aqk;
                }
                for k in 0..n {
                    let (vkp, vkq) = (v[k * n + p], v[k * n + q]);
                    v[k * n + p] = c * vkp - s * vkq;
                    v[k * n + q] = s * vkp + c * vkq;
                }
            }
        }
    }
    ((0..n).map(|i| a[i * n + i]).collect(), v)
}

impl Rod {
    /// The modes of the finite-element rod with its centre held, ascending: (ω_j \[rad/s\],
    /// modal effective mass m_j \[kg\] of the whole rod). `elements` per half rod, 1..=64.
    pub fn fe_centre_blocked_modes(&self, elements: usize) -> Result<Vec<(f64, f64)>> {
        if !(1..=MAX_FE_ELEMENTS).contains(&elements) {
            return Err(Error::invalid(
                "rod.fe_elements",
                elements,
                format!("must be 1..={MAX_FE_ELEMENTS} elements per half rod"),
            ));
        }
        let h = 0.5 * self.length_m / elements as f64;
        let (ke, me) = element_matrices(self, h);
        // Assemble the half rod: DOFs (w_k, θ_k) of nodes 0..=n.
        let full = 2 * (elements + 1);
        let (mut k, mut m) = (vec![0.0; full * full], vec![0.0; full * full]);
        for el in 0..elements {
            let base = 2 * el;
            for r in 0..4 {
                for c in 0..4 {
                    k[(base + r) * full + base + c] += ke[r][c];
                    m[(base + r) * full + base + c] += me[r][c];
                }
            }
        }
        // M ψ for the rigid translation ψ (w = 1, θ = 0), then drop the held centre (w₀, θ₀).
        let m_psi: Vec<f64> = (0..full)
            .map(|r| (0..full).step_by(2).map(|c| m[r * full + c]).sum())
            .collect();
        let n = full - 2;
        let interior = |a: &[f64]| -> Vec<f64> {
            (0..n)
                .flat_map(|r| (0..n).map(move |c| (r, c)))
                .map(|(r, c)| a[(r + 2) * full + c + 2])
                .collect()
        };
        let (ki, mi) = (interior(&k), interior(&m));
        let l = cholesky(&mi, n).ok_or_else(|| {
            Error::invalid(
                "rod.fe_elements",
                elements,
                "the mass matrix is not positive definite",
            )
        })?;
        // A = L⁻¹ K L⁻ᵀ by forward substitution on the columns, then on the rows.
        let solve_lower = |b: &mut [f64], stride: usize, offset: usize| {
            for i in 0..n {
                let s: f64 = (0..i).map(|j| l[i * n + j] * b[j * stride + offset]).sum();
                b[i * stride + offset] = (b[i * stride + offset] - s) / l[i * n + i];
            }
        };
        let mut a = ki;
        for col in 0..n {
            solve_lower(&mut a, n, col);
        }
        let mut at: Vec<f64> = (0..n * n).map(|idx| a[(idx % n) * n + idx / n]).collect();
        for col in 0..n {
            solve_lower(&mut at, n, col);
        }
        let (values, vectors) = jacobi_eigen(at, n);
        // Mode j: φ = L⁻ᵀ y (mass-normalised); L_j = φᵀ (Mψ) = yᵀ (L⁻¹ Mψ).
        let mut r: Vec<f64> = m_psi[2..].to_vec();
        solve_lower(&mut r, 1, 0);
        let mut modes: Vec<(f64, f64)> = (0..n)
            .map(|j| {
                let participation: f64 = (0..n).map(|i| vectors[i * n + j] * r[i]).sum();
                (
                    values[j].max(0.0).sqrt(),
                    2.0 * participation * participation,
                )
            })
            .collect();
        modes.sort_by(|x, y| x.0.total_cmp(&y.0));
        Ok(modes)
    }
}

impl UnitCell {
    /// The finite-element rod (`elements` per half rod) as a cell: one resonator per mode of the
    /// rod with its centre held, with its modal effective mass; the primary mass is the rest of
    /// ρ·A·L (the mass that moves with the centre node).
    pub fn from_rod_fe(rod: &Rod, elements: usize) -> Result<Self> {
        let modes = rod.fe_centre_blocked_modes(elements)?;
        // A mode that does not move the centre (no effective mass) is not coupled to the contact.
        let negligible = 1e-12 * rod.mass_kg();
        let resonators: Vec<Resonator> = modes
            .iter()
            .filter(|&&(_, mass)| mass > negligible)
            .map(|&(omega, mass)| Resonator {
                mass_kg: mass,
                stiffness_n_per_m: mass * omega * omega,
            })
            .collect();
        let primary = rod.mass_kg() - resonators.iter().map(|r| r.mass_kg).sum::<f64>();
        UnitCell::new(primary, resonators)
    }
}

/// The free–free modes of the whole finite-element rod (docs/physics.md §16): `2n` elements
/// over the length (n per half, as for [`UnitCell::from_rod_fe`]), nodes at
/// s_k = −L/2 + k·h, mass-normalised (φᵀMφ = 1). Modes 0 and 1 are the rigid translation
/// (w = 1, θ = 0) and the rigid rocking (w = s, θ = 1), set exactly with ω = 0; every elastic
/// mode is made M-orthogonal to both, so that momentum and moment of momentum are carried by
/// the rigid modes alone.
#[derive(Debug, Clone, PartialEq)]
pub struct FreeRodModes {
    /// Rod length L \[m\].
    pub length_m: f64,
    /// Element length h = L / (2n) \[m\].
    pub element_m: f64,
    /// Shear parameter Φ = 12EI/(κGAh²) of the elements (it enters the shape functions).
    pub shear_parameter: f64,
    /// Angular frequency ω_j \[rad/s\] per mode, ascending (0 for the two rigid modes).
    pub omega_rad_s: Vec<f64>,
    /// Mode shapes: `shapes[j][2k]` = w of mode j at node k, `shapes[j][2k + 1]` = θ. For a rod
    /// of analytic modes ([`FreeRodModes::analytic`]) only the two rigid modes, on one element.
    pub shapes: Vec<Vec<f64>>,
    /// The analytic bending modes after the rigid ones ([`FreeRodModes::analytic`]); empty for
    /// the finite-element rod, whose modes are all in `shapes`.
    pub bending: Vec<TimoshenkoMode>,
    /// ψ_tᵀ M φ_j: the momentum per unit modal velocity [kg^½] (√m for mode 0, 0 otherwise).
    pub translation_participation: Vec<f64>,
    /// ψ_rᵀ M φ_j: the moment of momentum about the centre per unit modal velocity [kg^½ m].
    pub rocking_participation: Vec<f64>,
}

impl FreeRodModes {
    /// The free–free modes of `rod` with `elements` per half rod (1..=[`MAX_FE_ELEMENTS`]).
    pub fn new(rod: &Rod, elements: usize) -> Result<Self> {
        if !(1..=MAX_FE_ELEMENTS).contains(&elements) {
            return Err(Error::invalid(
                "rod.fe_elements",
                elements,
                format!("must be 1..={MAX_FE_ELEMENTS} elements per half rod"),
            ));
        }
        let count = 2 * elements;
        let h = rod.length_m / count as f64;
        let (k, m) = assemble(rod, h, count);
        let n = 2 * (count + 1);
        let l = cholesky(&m, n).ok_or_else(|| {
            Error::invalid(
                "rod.fe_elements",
                elements,
                "the mass matrix is not positive definite",
            )
        })?;
        let a = congruence(&l, &k, n);
        let (values, vectors) = jacobi_eigen(a, n);
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&x, &y| values[x].total_cmp(&values[y]));
        let node_s = |node: usize| -0.5 * rod.length_m + node as f64 * h;
        let translation: Vec<f64> = (0..n).map(|d| if d % 2 == 0 { 1.0 } else { 0.0 }).collect();
        let rocking: Vec<f64> = (0..n)
            .map(|d| if d % 2 == 0 { node_s(d / 2) } else { 1.0 })
            .collect();
        let mut shapes: Vec<Vec<f64>> = Vec::with_capacity(n);
        for rigid in [translation.clone(), rocking.clone()] {
            shapes.push(m_orthonormal(rigid, &shapes, &m, n));
        }
        let mut omega_rad_s = vec![0.0, 0.0];
        for &j in &order[2..] {
            // φ = L⁻ᵀ y.
            let mut phi: Vec<f64> = (0..n).map(|i| vectors[i * n + j]).collect();
            for i in (0..n).rev() {
                let s: f64 = (i + 1..n).map(|r| l[r * n + i] * phi[r]).sum();
                phi[i] = (phi[i] - s) / l[i * n + i];
            }
            omega_rad_s.push(values[j].max(0.0).sqrt());
            let phi = m_orthonormal(phi, &shapes[..2], &m, n);
            shapes.push(phi);
        }
        let largest = values[order[n - 1]];
        for &j in &order[..2] {
            if values[j].abs() > 1e-8 * largest {
                return Err(Error::invalid(
                    "rod.fe_elements",
                    elements,
                    format!(
                        "the free rod's two rigid modes were not found (eigenvalue {:e} against {largest:e})",
                        values[j]
                    ),
                ));
            }
        }
        let participation = |psi: &[f64]| -> Vec<f64> {
            let m_psi = mat_vec(&m, psi, n);
            shapes.iter().map(|phi| dot(phi, &m_psi)).collect()
        };
        Ok(FreeRodModes {
            length_m: rod.length_m,
            element_m: h,
            shear_parameter: shear_parameter(rod, h),
            translation_participation: participation(&translation),
            rocking_participation: participation(&rocking),
            omega_rad_s,
            shapes,
            bending: Vec::new(),
        })
    }

    /// The rod by its two rigid modes and its `count` lowest analytic free–free Timoshenko
    /// bending modes ([`Rod::free_free_modes`], docs/physics.md §16), mass-normalised against
    /// the continuous rod: no mesh, no eigenproblem. The rigid modes are those of
    /// [`FreeRodModes::new`] (w = 1/√m; w = s/√J, θ = 1/√J with J = ρAL³/12 + ρIL); the
    /// bending modes are orthogonal to them by the free ends and carry no momentum. Errors name
    /// `rod.modes` (at least 1, and no more than lie below the shear cutoff).
    pub fn analytic(rod: &Rod, count: usize) -> Result<Self> {
        if count == 0 {
            return Err(Error::invalid(
                "rod.modes",
                0,
                "at least 1 bending mode (the two rigid modes are always kept)",
            ));
        }
        let bending = rod.free_free_modes(count)?;
        let rho = rod.material.density_kg_m3;
        let half = 0.5 * rod.length_m;
        let mass = rod.mass_kg();
        let inertia =
            mass * rod.length_m.powi(2) / 12.0 + rho * rod.second_moment_m4() * rod.length_m;
        let (t, r) = (1.0 / mass.sqrt(), 1.0 / inertia.sqrt());
        let mut omega_rad_s = vec![0.0, 0.0];
        omega_rad_s.extend(bending.iter().map(|m| m.omega_rad_s));
        let modes = 2 + count;
        let unit = |j: usize, v: f64| (0..modes).map(|i| if i == j { v } else { 0.0 }).collect();
        Ok(FreeRodModes {
            length_m: rod.length_m,
            element_m: rod.length_m,
            shear_parameter: shear_parameter(rod, rod.length_m),
            omega_rad_s,
            shapes: vec![vec![t, 0.0, t, 0.0], vec![-half * r, r, half * r, r]],
            translation_participation: unit(0, mass.sqrt()),
            rocking_participation: unit(1, inertia.sqrt()),
            bending,
        })
    }

    /// The weights (element's first DOF index, [N_w1, N_θ1, N_w2, N_θ2]) that give the deflection
    /// w(s) at axial coordinate s ∈ [−L/2, L/2] from the nodal values: the Timoshenko element's
    /// own shape functions (those its matrices are built from), exact at the nodes.
    pub fn deflection_weights(&self, s_m: f64) -> (usize, [f64; 4]) {
        let count = self.shapes[0].len() / 2 - 1;
        let x = (s_m + 0.5 * self.length_m) / self.element_m;
        let el = (x.floor().max(0.0) as usize).min(count - 1);
        let xi = x - el as f64;
        let (p, h) = (self.shear_parameter, self.element_m);
        let c = 1.0 / (1.0 + p);
        let (xi2, xi3) = (xi * xi, xi * xi * xi);
        (
            2 * el,
            [
                c * (2.0 * xi3 - 3.0 * xi2 - p * xi + 1.0 + p),
                c * h * (xi3 - (2.0 + 0.5 * p) * xi2 + (1.0 + 0.5 * p) * xi),
                -c * (2.0 * xi3 - 3.0 * xi2 - p * xi),
                c * h * (xi3 - (1.0 - 0.5 * p) * xi2 - 0.5 * p * xi),
            ],
        )
    }

    /// The deflection of every mode at s: w(s) = Σ_j row_j q_j.
    pub fn modal_row(&self, s_m: f64) -> Vec<f64> {
        let (first, weights) = self.deflection_weights(s_m);
        self.shapes
            .iter()
            .map(|phi| (0..4).map(|k| weights[k] * phi[first + k]).sum())
            .chain(self.bending.iter().map(|m| m.deflection(s_m)))
            .collect()
    }
}

/// Φ = 12EI/(κGAh²) of an element of length h.
fn shear_parameter(rod: &Rod, h: f64) -> f64 {
    let e = rod.material.youngs_modulus_pa;
    let g = e / (2.0 * (1.0 + rod.material.poisson_ratio));
    12.0 * e * rod.second_moment_m4() / (rod.shear_coefficient() * g * rod.area_m2() * h * h)
}

/// K and M (row-major, 2(count + 1) square) of `count` elements of length h in a row.
fn assemble(rod: &Rod, h: f64, count: usize) -> (Vec<f64>, Vec<f64>) {
    let (ke, me) = element_matrices(rod, h);
    let full = 2 * (count + 1);
    let (mut k, mut m) = (vec![0.0; full * full], vec![0.0; full * full]);
    for el in 0..count {
        let base = 2 * el;
        for r in 0..4 {
            for c in 0..4 {
                k[(base + r) * full + base + c] += ke[r][c];
                m[(base + r) * full + base + c] += me[r][c];
            }
        }
    }
    (k, m)
}

/// L⁻¹ K L⁻ᵀ for the lower Cholesky factor L of M (all row-major n × n).
fn congruence(l: &[f64], k: &[f64], n: usize) -> Vec<f64> {
    let solve_lower = |b: &mut [f64], stride: usize, offset: usize| {
        for i in 0..n {
            let s: f64 = (0..i).map(|j| l[i * n + j] * b[j * stride + offset]).sum();
            b[i * stride + offset] = (b[i * stride + offset] - s) / l[i * n + i];
        }
    };
    let mut a = k.to_vec();
    for col in 0..n {
        solve_lower(&mut a, n, col);
    }
    let mut at: Vec<f64> = (0..n * n).map(|idx| a[(idx % n) * n + idx / n]).collect();
    for col in 0..n {
        solve_lower(&mut at, n, col);
    }
    // Symmetrise the round-off.
    for i in 0..n {
        for j in 0..i {
            let v = 0.5 * (at[i * n + j] + at[j * n + i]);
            at[i * n + j] = v;
            at[j * n + i] = v;
        }
    }
    at
}

fn mat_vec(a: &[f64], x: &[f64], n: usize) -> Vec<f64> {
    (0..n).map(|i| dot(&a[i * n..(i + 1) * n], x)).collect()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `v` made M-orthogonal to the (M-orthonormal) `basis` and normalised to vᵀMv = 1 (twice
/// Gram–Schmidt, so that the orthogonality holds to round-off).
fn m_orthonormal(mut v: Vec<f64>, basis: &[Vec<f64>], m: &[f64], n: usize) -> Vec<f64> {
    for _ in 0..2 {
        let mv = mat_vec(m, &v, n);
        for b in basis {
            let c = dot(b, &mv);
            v.iter_mut().zip(b).for_each(|(x, y)| *x -= c * y);
        }
    }
    let norm = dot(&v, &mat_vec(m, &v, n)).sqrt();
    v.iter_mut().for_each(|x| *x /= norm);
    v
}
