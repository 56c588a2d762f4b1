//! `f` through the mass matrix, for a kinetic energy quadratic in `q̇`.
//!
//! Written as `∂L/∂q − (∂p/∂q) q̇ − ∂p/∂t`, the velocity terms of `f` come
//! from two derivatives of `T` that cancel in part: for the pendulum chain
//! `∂T/∂θ_i` and `Σ_j ∂p_i/∂θ_j θ̇_j` both hold `θ̇_i θ̇_j` terms that are
//! equal and opposite, and the simplifier, seeing them in different
//! factored forms, keeps both (with the velocity sums only they use). When
//! `M` is free of `q̇`, `T = ½ q̇ᵀ M q̇ + bᵀ q̇ + T₀` (`b` and `T₀` are
//! `p` and `T` at rest), and
//!
//! ```text
//! f_i = Σ_{j<k} (∂_i M_jk − ∂_j M_ik − ∂_k M_ij) q̇_j q̇_k
//!     + Σ_j (½ ∂_i M_jj − ∂_j M_ij) q̇_j²                 (Christoffel symbols)
//!     + Σ_j (∂_i b_j − ∂_j b_i − ∂_t M_ij) q̇_j
//!     + ∂_i (T₀ − V) − ∂_t b_i
//! ```
//!
//! whose coefficients are sums of derivatives of the same nodes of `M`, so
//! what cancels is one node against its negative, which the simplifier
//! always sees: the chain's `f_i` comes out as the textbook's
//! `−l_i (g S_i sin θ_i + Σ_j S_max(i,j) l_j sin(θ_i − θ_j) θ̇_j²)`.

use crate::expr::{ExprId, Pool};
use crate::model::Symbols;
use std::collections::BTreeSet;

/// `f_i` without its non-conservative part, from `M`, the momenta
/// followed by `T`, and `V`; or `None` when `M` depends on
/// `q̇` (then `T` is not quadratic: the caller differentiates `L` and the
/// checks refuse the model), when
/// `T` at rest is not finite, or when the budget ran out.
///
/// Only the pairs `(j, k)` whose coefficient can be non-zero are visited:
/// those where `M_jk` depends on `q_i`, or `M_ik` on `q_j` (or `M_ij` on
/// `q_k`, the same pairs): work in proportion to the dependencies of `M`,
/// not to `n³`.
pub(super) fn conservative_forcing(
    pool: &mut Pool,
    s: &Symbols,
    mass: &[Vec<ExprId>],
    momenta_then_t: &[ExprId],
    v_pot: ExprId,
) -> Option<Vec<ExprId>> {
    let n = mass.len();
    if pool.exhausted() {
        return None;
    }
    let (q, v) = (&s.coordinates, &s.velocities);
    let velocities = Pool::symbol_set(v);
    let mut coordinate = vec![None; s.count()];
    for (k, x) in q.iter().enumerate() {
        coordinate[x.0 as usize] = Some(k);
    }
    // The coordinates each entry of M depends on; `by_coordinate[i]` the
    // entries (j ≤ k) that depend on q_i.
    let mut deps = vec![vec![Vec::new(); n]; n];
    let mut by_coordinate: Vec<Vec<(usize, usize)>> = vec![Vec::new(); n];
    for j in 0..n {
        for k in j..n {
            let m = mass[j][k];
            if pool.depends_on_any(m, &velocities) {
                return None;
            }
            let d: Vec<usize> = pool
                .dependencies(m)
                .filter_map(|x| coordinate[x.0 as usize])
                .collect();
            for &c in &d {
                by_coordinate[c].push((j, k));
            }
            deps[k][j] = d.clone();
            deps[j][k] = d;
        }
    }
    let mut rest = pool.at_zero(momenta_then_t, v);
    let t0 = rest.pop().expect("T is last");
    let b = rest;
    if pool.has_non_finite(t0) || b.iter().any(|&x| pool.has_non_finite(x)) {
        return None;
    }
    let rest = pool.sub(t0, v_pot);
    let half = pool.num(0.5);
    let mut forcing = Vec::with_capacity(n);
    for i in 0..n {
        if pool.exhausted() {
            return None;
        }
        let mut pairs: BTreeSet<(usize, usize)> = by_coordinate[i].iter().copied().collect();
        for (k, dk) in deps[i].iter().enumerate() {
            pairs.extend(dk.iter().map(|&j| (j.min(k), j.max(k))));
        }
        pool.charge(n as u64 + pairs.len() as u64);
        let mut terms = Vec::new();
        for (j, k) in pairs {
            let c = if j == k {
                let a = pool.diff(mass[j][j], q[i]);
                let a = pool.mul2(half, a);
                let d = pool.diff(mass[i][j], q[j]);
                pool.sub(a, d)
            } else {
                let a = pool.diff(mass[j][k], q[i]);
                let d1 = pool.diff(mass[i][k], q[j]);
                let d2 = pool.diff(mass[i][j], q[k]);
                let d = pool.add2(d1, d2);
                pool.sub(a, d)
            };
            if c != Pool::ZERO {
                let qd_j = pool.sym(v[j]);
                let qd_k = pool.sym(v[k]);
                terms.push(pool.mul(&[c, qd_j, qd_k]));
            }
        }
        for j in 0..n {
            let a = pool.diff(b[j], q[i]);
            let d = pool.diff(b[i], q[j]);
            let curl = pool.sub(a, d);
            let dt = pool.diff(mass[i][j], s.time);
            let c = pool.sub(curl, dt);
            if c != Pool::ZERO {
                let qd_j = pool.sym(v[j]);
                terms.push(pool.mul2(c, qd_j));
            }
        }
        terms.push(pool.diff(rest, q[i]));
        let bt = pool.diff(b[i], s.time);
        terms.push(pool.neg(bt));
        forcing.push(pool.add(&terms));
    }
    Some(forcing)
}
