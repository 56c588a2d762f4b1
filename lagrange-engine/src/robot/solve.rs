//! `M x = b` solved by code emitted per robot: Featherstone's sparse
//! `Lᵀ D L` factorization of the joint-space inertia matrix ("Efficient
//! factorization of the joint-space inertia matrix", Proc. R. Soc. A,
//! 2005), unrolled over the robot's constant parent table.
//!
//! `M`'s entry `(i, j)` is zero unless one of the joints is an ancestor of
//! the other (branch-induced sparsity), and factoring from the leaves up,
//! `M = Lᵀ D L` with `L` unit lower triangular keeps exactly that pattern:
//! no fill-in. Row `k` only touches its ancestors, so the factorization
//! costs `Σ_k depth(k)²` multiply-adds and each substitution
//! `Σ_k depth(k)`, against `N³ / 6` for a dense Cholesky. Written as
//! straight-line code on traced scalars ([`super::trace`]), with every
//! index a constant, the loops over the parent table cost nothing at run
//! time. A floating base's six velocities are a chain of six at the root
//! (its block of `M` is dense), every joint below them.

use super::trace::{Trace, Val, ZERO};
use proc_macro2::TokenStream;
use quote::quote;

/// The ancestors of `k` by the parent table, nearest first (`k` excluded).
fn ancestors(parents: &[Option<usize>], k: usize) -> Vec<usize> {
    let mut out = Vec::new();
    let mut i = parents[k];
    while let Some(p) = i {
        out.push(p);
        i = parents[p];
    }
    out
}

/// The parent table in the velocities: a fixed base's joints as they are
/// (`None` for the base); on a floating base (`offset` 6), the base's six
/// velocities as a chain, then each joint under its parent, or under the
/// base's last velocity.
pub(super) fn parent_table(parents: &[Option<usize>], offset: usize) -> Vec<Option<usize>> {
    let base = (0..offset).map(|k| k.checked_sub(1));
    let joints = parents.iter().map(|p| match p {
        Some(p) => Some(p + offset),
        None => offset.checked_sub(1),
    });
    base.chain(joints).collect()
}

/// The traced solve: `M` read from `m[(i, j)]` at the entries the tree
/// leaves nonzero (the lower triangle, `j` an ancestor of `i` or `i`
/// itself), `b` from `b[i]`; returns `x` and the pivots `D`.
fn traced(t: &mut Trace, parents: &[Option<usize>]) -> (Vec<Val>, Vec<Val>) {
    let n = parents.len();
    let up: Vec<Vec<usize>> = (0..n).map(|k| ancestors(parents, k)).collect();
    let mut h = vec![vec![ZERO; n]; n];
    for i in 0..n {
        h[i][i] = t.input(quote!(m[(#i, #i)]));
        for &j in &up[i] {
            h[i][j] = t.input(quote!(m[(#i, #j)]));
        }
    }
    let mut b: Vec<Val> = (0..n).map(|i| t.input(quote!(b[#i]))).collect();
    // Factorization, leaves first: row k's pivot is final once all its
    // descendants (of higher index) have been folded into its ancestors.
    let mut inverse = vec![ZERO; n];
    for k in (0..n).rev() {
        inverse[k] = t.recip(h[k][k]);
        for (at, &i) in up[k].iter().enumerate() {
            let a = t.mul(h[k][i], inverse[k]);
            // H[i][j] -= a H[k][j] for j = i and i's ancestors (those of
            // k above i), read before row k's entries become L's.
            for &j in std::iter::once(&i).chain(&up[k][at + 1..]) {
                let p = t.mul(a, h[k][j]);
                h[i][j] = t.sub(h[i][j], p);
            }
            h[k][i] = a;
        }
    }
    // Lᵀ z = b, leaves first.
    for k in (0..n).rev() {
        for &i in &up[k] {
            let p = t.mul(h[k][i], b[k]);
            b[i] = t.sub(b[i], p);
        }
    }
    // y = D⁻¹ z, then L x = y, root first.
    let mut x = vec![ZERO; n];
    for k in 0..n {
        let mut v = t.mul(b[k], inverse[k]);
        for &i in &up[k] {
            let p = t.mul(h[k][i], x[i]);
            v = t.sub(v, p);
        }
        x[k] = v;
    }
    let d = (0..n).map(|k| h[k][k]).collect();
    (x, d)
}

/// The body of the generated `solve_*mass_matrix(&self, m, b) ->
/// Option<SVector>`: the unrolled factorization and substitutions, then
/// the runtime's check of the pivots and the result
/// (`lagrange_runtime::linalg::mass::checked_solution`, the test
/// `solve_mass_matrix` makes on Cholesky's pivots). Also returns the number of operations
/// written, for the docs and the tests of the code's size.
pub(super) fn emit(parents: &[Option<usize>]) -> (TokenStream, usize) {
    let n = parents.len();
    let mut t = Trace::default();
    let (x, d) = traced(&mut t, parents);
    let outputs: Vec<Val> = x.iter().chain(&d).copied().collect();
    let (body, outs) = t.emit(&outputs);
    let (xs, ds) = outs.split_at(n);
    let ops = t.len();
    let tokens = quote! {
        #body
        let d: [S; #n] = [#(#ds),*];
        let x = ::lagrange::nalgebra::SVector::<S, #n>::from_array_storage(
            ::lagrange::nalgebra::ArrayStorage([[#(#xs),*]])
        );
        ::lagrange::linalg::mass::checked_solution(&d, x)
    };
    (tokens, ops)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The traced solve against a dense solve on a tree's `M`: a random
    /// SPD matrix with the tree's sparsity.
    #[test]
    fn traced_solve_solves_a_tree() {
        // 0 ← 1 ← 2, 0 ← 3 ← 4, 3 ← 5; after a 2-chain base.
        let joints = [None, Some(0), Some(1), Some(0), Some(3), Some(3)];
        let parents = parent_table(&joints, 2);
        let n = parents.len();
        // M = Lᵀ D L from a chosen L with the tree's pattern.
        let mut l = vec![vec![0.0; n]; n];
        let mut seed = 7u64;
        let mut rand = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for k in 0..n {
            l[k][k] = 1.0;
            for i in ancestors(&parents, k) {
                l[k][i] = rand();
            }
        }
        let dd: Vec<f64> = (0..n).map(|k| 1.0 + k as f64).collect();
        let mut m = vec![vec![0.0; n]; n];
        for i in 0..n {
            for j in 0..n {
                m[i][j] = (0..n).map(|k| l[k][i] * dd[k] * l[k][j]).sum();
            }
        }
        let b: Vec<f64> = (0..n).map(|_| rand()).collect();
        let mut t = Trace::default();
        let (x, d) = traced(&mut t, &parents);
        // The inputs in the order `traced` made them.
        let mut inputs = Vec::new();
        for i in 0..n {
            inputs.push(m[i][i]);
            for j in ancestors(&parents, i) {
                inputs.push(m[i][j]);
            }
        }
        inputs.extend(&b);
        let values = t.eval(&inputs);
        for k in 0..n {
            let p = Trace::value(&values, d[k]);
            assert!((p - dd[k]).abs() < 1e-12, "pivot {k}: {p}");
        }
        for i in 0..n {
            let r: f64 = (0..n).map(|j| m[i][j] * Trace::value(&values, x[j])).sum();
            assert!((r - b[i]).abs() < 1e-12, "row {i}: {r} against {}", b[i]);
        }
    }
}
