//! Forces that are not determined, chosen inside every friction cone
//! where a choice inside them exists: the least relative use of the cones
//! over the forces that give the same accelerations.
//!
//! Touching contacts whose rows are dependent leave their forces `λ`
//! undetermined along the null space `Z` of their responses (`M⁻¹ Dᵀ Z =
//! 0`: every `λ₀ + Z z` gives the same accelerations). Of those, a stuck
//! contact's friction is admissible where `|Fᵢ| ≤ μ_s Nᵢ` and every
//! normal force `Nᵢ ≥ 0`. The use of the cones is `ρ(z) = maxᵢ |Fᵢ| /
//! (μ_s Nᵢ)` over the stuck contacts, and `ρ* = inf_z ρ(z)` is the least
//! of it: an admissible distribution exists exactly where `ρ* ≤ 1`. For a
//! given `ρ`, the set `S(ρ) = {z : |Fᵢ| ≤ ρ μ_s Nᵢ, Nᵢ ≥ 0}` is a polyhedron
//! (planar friction: two half-spaces per cone, one per normal force),
//! empty below `ρ*`; so `ρ*` is found by bisection on the feasibility of
//! `S(ρ)`, to rounding.
//!
//! The forces taken are the given share `λ₀` (friction in proportion to
//! the cones, see `phase::share_friction`) where its own use `ρ₀` is at
//! most the target `ρ_t = (1 + ρ*)/2` (`ρ*` itself beyond 1), and
//! otherwise its projection onto `S(ρ_t)`: the nearest forces (in their
//! Euclidean norm) that use no cone more than halfway between the least
//! possible use and the limit. Then
//!
//! - every stuck contact keeps a margin `μ_s N − |F| ≥ (1 − ρ*) μ_s N / 2`,
//!   positive exactly while an admissible distribution exists, and
//!   reaching zero, at the contacts that limit it, exactly where none
//!   remains (the stick limit's event is located there, and only there);
//! - the choice is unique (a projection onto a convex set) and continuous in the state wherever `S(ρ_t)` has an
//!   interior (it moves with `ρ*` and the forces, and at the switch from
//!   `λ₀` to its projection `λ₀` lies on `S(ρ_t)`'s boundary); the forces
//!   stay bounded where the cones could squeeze the body without limit
//!   (a ladder wedged, `μ_w μ_f ≥ 1`), being the nearest to `λ₀`;
//! - where `λ₀` already qualifies (a crate on two corners, whose shares are
//!   one fraction of their cones, the least use), nothing is solved
//!   beyond one feasibility test, and the forces are `λ₀` bit for bit.
//!
//! A one-dimensional null space (two contacts of one planar body: a
//! ladder, a crate) is solved exactly, each half-space bounding an
//! interval; a larger one by Lemke's method on the projection's dual, `w
//! = d + C Cᵀ y` (`C z ≤ d` the polyhedron in orthonormal coordinates `z`
//! of the null space), whose matrix is positive semidefinite, so the
//! method finds the projection or proves the polyhedron empty. Contacts whose friction acts
//! in a plane (a disc, not two half-spaces) keep the proportional share.

use nalgebra::{DMatrix, DVector, RealField};

use super::ContactLaw;
use super::lcp::lemke;
use super::phase::Unknown;

/// One linear bound `c·z ≤ d₀ + ρ d₁` on the null-space coordinates, with
/// `c = c₀ + ρ c₁`: a side of a cone scaled by `ρ`, or a normal force's
/// sign (`c₁ = d₁ = 0`).
struct Bound<S: RealField + Copy> {
    c0: DVector<S>,
    c1: DVector<S>,
    d0: S,
    d1: S,
}

/// The forces of `first` moved along the null space of `responses` (the
/// `N × m` responses of the unknowns, column by column) to the choice
/// described in the module's docs, the nearest in the forces' Euclidean
/// norm; `first`
/// itself where it qualifies, or where nothing admissible can be solved.
pub(super) fn admissible<S: RealField + Copy>(
    responses: &DMatrix<S>,
    first: DVector<S>,
    unknowns: &[Unknown],
    laws: &[ContactLaw<S>],
) -> DVector<S> {
    if unknowns
        .iter()
        .any(|u| u.tangential && laws[u.contact].in_plane)
    {
        return first;
    }
    let m = unknowns.len();
    let zero = S::zero();
    let normal_index = |contact: usize| {
        unknowns
            .iter()
            .position(|u| u.contact == contact && !u.tangential)
    };
    // The share's own use of the cones (unbounded where a normal force
    // pulls, or friction acts without one).
    let infinite = S::one() / zero;
    let mut use0 = zero;
    for (c, u) in unknowns.iter().enumerate() {
        if !u.tangential {
            if first[c] < zero {
                use0 = infinite;
            }
            continue;
        }
        let normal = laws[u.contact]
            .normal
            .or_else(|| normal_index(u.contact).map(|k| first[k]))
            .unwrap_or(zero);
        let capacity = laws[u.contact].static_friction * normal;
        let size = first[c].abs();
        if size > zero {
            use0 = if capacity > zero {
                use0.max(size / capacity)
            } else {
                infinite
            };
        }
    }
    let one = S::one();
    let two = one + one;
    // Kept where `use0 ≤ ρ_t(ρ*)`, i.e. `ρ* ≥ ρ_t⁻¹(use0)`: where no
    // distribution uses the cones less than that.
    let threshold = if use0 <= one { two * use0 - one } else { use0 };
    let slack = nalgebra::convert::<f64, S>(1e-10);
    if threshold <= slack {
        return first;
    }
    let Some(basis) = null_space(responses, m) else {
        return first;
    };
    let k = basis.ncols();
    let mut bounds = Vec::new();
    for (c, u) in unknowns.iter().enumerate() {
        let row = basis.row(c).transpose();
        if !u.tangential {
            // −(λ₀ + Z z)ₙ ≤ 0.
            bounds.push(Bound {
                c0: -row,
                c1: DVector::zeros(k),
                d0: first[c],
                d1: zero,
            });
            continue;
        }
        let mu = laws[u.contact].static_friction;
        let (n_row, n0) = match (laws[u.contact].normal, normal_index(u.contact)) {
            (Some(given), _) => (DVector::zeros(k), given),
            (None, Some(n)) => (basis.row(n).transpose(), first[n]),
            (None, None) => (DVector::zeros(k), zero),
        };
        // ±F − ρ μ N ≤ 0, each side.
        for sign in [one, -one] {
            bounds.push(Bound {
                c0: &row * sign,
                c1: &n_row * (-mu),
                d0: -sign * first[c],
                d1: mu * n0,
            });
        }
    }
    let project = |rho: S| project(&bounds, k, rho);
    // ρ* by bisection between `lo` (S(lo) empty, or lo = 0) and `hi`
    // (S(hi) not): from below the threshold, or where the share itself
    // does not bound it, from the least power of two that is feasible.
    let mut hi = if threshold.is_finite() {
        threshold * (one - slack)
    } else {
        let mut hi = one;
        let most = nalgebra::convert::<f64, S>(1e12);
        while project(hi).is_none() {
            if hi > most {
                return first;
            }
            hi *= two;
        }
        hi
    };
    if project(hi).is_none() {
        return first;
    }
    let mut lo = zero;
    if project(zero).is_some() {
        hi = zero;
    }
    let eps = nalgebra::convert::<f64, S>(4.0) * S::default_epsilon();
    while hi - lo > eps * hi.max(one) {
        let mid = (lo + hi) / two;
        if project(mid).is_some() {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let target = if hi <= one { (one + hi) / two } else { hi };
    match project(target) {
        Some(z) => first + basis * z,
        None => first,
    }
}

/// An orthonormal basis of the null space of the `N × m` matrix
/// `responses` (as columns, `m × k`), from its singular values with the
/// tolerance of `least_solve`'s rank; `None` where it is trivial or a
/// value is not finite.
fn null_space<S: RealField + Copy>(responses: &DMatrix<S>, m: usize) -> Option<DMatrix<S>> {
    if !responses.iter().all(|x| x.is_finite()) {
        return None;
    }
    // Square, so that the decomposition gives every right singular vector.
    let rows = responses.nrows().max(m);
    let mut square = DMatrix::zeros(rows, m);
    square
        .view_mut((0, 0), (responses.nrows(), m))
        .copy_from(responses);
    let scale = square.iter().fold(S::zero(), |s, x| s.max(x.abs()));
    let eps = nalgebra::convert::<f64, S>(1e-12) * scale;
    let svd = square.svd(false, true);
    let v_t = svd.v_t?;
    let null: Vec<usize> = (0..m).filter(|&i| svd.singular_values[i] <= eps).collect();
    if null.is_empty() {
        return None;
    }
    Some(DMatrix::from_fn(m, null.len(), |r, c| v_t[(null[c], r)]))
}

/// The point of `S(ρ)` nearest the origin (in `k` orthonormal
/// coordinates of the null space), or `None` where `S(ρ)` is empty.
fn project<S: RealField + Copy>(bounds: &[Bound<S>], k: usize, rho: S) -> Option<DVector<S>> {
    let rows: Vec<(DVector<S>, S)> = bounds
        .iter()
        .map(|b| (&b.c0 + &b.c1 * rho, b.d0 + b.d1 * rho))
        .collect();
    let scale = rows
        .iter()
        .fold(S::zero(), |s, (c, d)| s.max(c.amax()).max(d.abs()));
    let tiny = nalgebra::convert::<f64, S>(1e-13) * scale;
    if k == 1 {
        // Each bound an end of an interval; the origin clamped into it.
        let (mut lo, mut hi) = (S::zero(), S::zero());
        let (mut has_lo, mut has_hi) = (false, false);
        for (c, d) in &rows {
            let (c, d) = (c[0], *d);
            if c.abs() <= tiny {
                if d < -tiny {
                    return None;
                }
            } else if c > S::zero() {
                let end = d / c;
                hi = if has_hi { hi.min(end) } else { end };
                has_hi = true;
            } else {
                let end = d / c;
                lo = if has_lo { lo.max(end) } else { end };
                has_lo = true;
            }
        }
        if has_lo && has_hi && lo > hi {
            return None;
        }
        let mut z = S::zero();
        if has_lo {
            z = z.max(lo);
        }
        if has_hi {
            z = z.min(hi);
        }
        return Some(DVector::from_element(1, z));
    }
    // The projection's dual: w = d + C Cᵀ y ≥ 0, y ≥ 0, yᵀ w = 0, and
    // z = −Cᵀ y (the basis orthonormal: the metric of the forces is the
    // coordinates' own).
    let c = DMatrix::from_fn(rows.len(), k, |r, j| rows[r].0[j]);
    let d = DVector::from_iterator(rows.len(), rows.iter().map(|(_, d)| *d));
    let ct = c.transpose();
    let y = lemke(&(&c * &ct), &d).ok()?;
    let z = -(&ct * y);
    let violation = (&c * &z - &d).max();
    (violation <= tiny).then_some(z)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two stuck contacts of one body that push along one direction and
    /// rub along another (`N × m` responses `[e₀, e₁, e₀, e₁]`): only the
    /// sums `N₁ + N₂` and `F₁ + F₂` are determined, a null space of two
    /// dimensions (load and friction both move between them), solved by
    /// Lemke's method.
    fn two_contacts(mu: f64) -> (DMatrix<f64>, [Unknown; 4], [ContactLaw<f64>; 2]) {
        let responses = DMatrix::from_row_slice(2, 4, &[1.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0]);
        let unknown = |contact, tangential| Unknown {
            contact,
            tangential,
            second: false,
        };
        let unknowns = [
            unknown(0, false),
            unknown(0, true),
            unknown(1, false),
            unknown(1, true),
        ];
        let law = ContactLaw::frictionless(0.0).with_friction(mu);
        (responses, unknowns, [law, law])
    }

    #[test]
    fn a_share_outside_a_cone_moves_to_the_nearest_using_them_halfway_from_the_least_to_the_limit()
    {
        let mu = 0.6;
        let (responses, unknowns, laws) = two_contacts(mu);
        // N = (1.5, 0.5), F = (0, 1): the second contact at 3.33 times its
        // cone; the least use is the sums' `1 / (0.6 × 2)`, so the target
        // is halfway from it to 1.
        let first = DVector::from_vec(vec![1.5, 0.0, 0.5, 1.0]);
        let least = 1.0 / (mu * 2.0);
        let target = (1.0 + least) / 2.0;
        let x = admissible(&responses, first.clone(), &unknowns, &laws);
        // The same accelerations: the sums to rounding.
        assert!((x[0] + x[2] - 2.0).abs() < 1e-14, "{x}");
        assert!((x[1] + x[3] - 1.0).abs() < 1e-14, "{x}");
        let uses = [x[1].abs() / (mu * x[0]), x[3].abs() / (mu * x[2])];
        for u in uses {
            assert!(u <= target * (1.0 + 1e-12), "{uses:?} beyond {target}");
        }
        // Nearest to the share: the contact it overloaded at the target's
        // bound exactly (the projection moves no further than it must).
        assert!((uses[1] - target).abs() < 1e-9, "{uses:?}, target {target}");
    }

    #[test]
    fn a_share_within_its_bound_is_kept_bit_for_bit_and_none_admissible_is_the_least_use() {
        let mu = 0.6;
        let (responses, unknowns, laws) = two_contacts(mu);
        // Each at 0.5 of its cone, the least use of the sums: kept.
        let even = DVector::from_vec(vec![1.0, 0.3, 1.0, 0.3]);
        assert_eq!(admissible(&responses, even.clone(), &unknowns, &laws), even);
        // Friction of 1.5 against cones of 1.2 in all: none admissible;
        // the forces use the cones as little as can be, 1.25 each.
        let beyond = DVector::from_vec(vec![1.5, 0.0, 0.5, 1.5]);
        let x = admissible(&responses, beyond, &unknowns, &laws);
        let uses = [x[1].abs() / (mu * x[0]), x[3].abs() / (mu * x[2])];
        for u in uses {
            assert!((u - 1.25).abs() < 1e-9, "{uses:?}");
        }
    }
}
