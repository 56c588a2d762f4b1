//! The linear algebra of the runtime, in one place. It knows matrices, not
//! models: the model's side of every solve is in
//! [`dynamics`](crate::dynamics).
//!
//! - [`mass`]: the mass matrix factored and `M q̈ = f` solved on the stack, `M` and `f` given (Cholesky as
//!   `LDLᵀ`, LU with partial pivoting as the fallback), with singular,
//!   indefinite and non-finite cases caught; from 32 coordinates, in place
//!   in an `M` the caller gives up (`acceleration`'s). Also the stack LU of
//!   the variational integrator's `N × N` Newton systems.
//! - `ldlt`: `M = L D Lᵀ` (Cholesky without square roots) written out for
//!   the hot path: inlined, one division per column, in place from 32
//!   coordinates; the row form and the substitutions also on SIMD lanes,
//!   for an [`Ensemble`](crate::ensemble::Ensemble).
//! - `schur`: the saddle-point system `M q̈ + Gᵀ λ = f`, `G q̈ = −γ` (one
//!   backward substitution with `M`'s factor), and the Schur complement
//!   `G M⁻¹ Gᵀ` judged for rank, which the projections onto the
//!   constraints share.
//! - `lu`: LU factors in storage allocated once per integration, real or
//!   complex, for the implicit Runge–Kutta methods' iteration matrices.
//! - `second_order`: the `2N × 2N` systems `(γ I − J) x = b` of those
//!   methods solved at size `N`, using `J = [[0, I], [∂q̈/∂q, ∂q̈/∂q̇]]`.
//!
//! - [`articulated`]: `M q̈ = f` in `O(N)` without `M`, for a model whose
//!   masses hang on a tree of increments (a chain or a tree of links): the
//!   articulated-body recursion, which the generated code calls.
//!
//! `mass` and `articulated` are public (`lagrange_runtime::linalg::mass`,
//! named for what they hold; the second reached by generated code); the
//! others are the runtime's own.

pub mod articulated;
pub(crate) mod ldlt;
pub(crate) mod lu;
pub mod mass;
pub(crate) mod schur;
pub(crate) mod second_order;

use nalgebra::SimdRealField;

/// Per lane, whether every entry of `parts` is finite: `x · 0` is zero just
/// where `x` is. (The lanes' mask; [`all_finite`] is the scalars' yes or
/// no.)
#[inline(always)]
pub(crate) fn finite_lanes<V: SimdRealField + Copy>(parts: &[&[V]]) -> V::SimdBool {
    // Four sums side by side: one would wait on each addition in turn.
    let zero = V::zero();
    let mut sums = [zero; 4];
    for part in parts {
        for (i, &v) in part.iter().enumerate() {
            sums[i % 4] += v * zero;
        }
    }
    ((sums[0] + sums[1]) + (sums[2] + sums[3])).simd_eq(zero)
}

/// Whether every value is finite, over a matrix's storage as a slice
/// (`m.as_slice()`): nalgebra's matrix iterator steps through columns and
/// strides per element, and took several times the work of the check
/// itself (at 64 coordinates, the two checks of `M` took nearly as long as its
/// factorization).
#[inline]
pub(crate) fn all_finite<S: nalgebra::RealField + Copy>(values: &[S]) -> bool {
    // Every value tested, without a branch per value (`&`, not `all`'s
    // `&&`): the tests become a few vector compares, where `all` is a
    // compare and a jump per value (issue 49).
    values.iter().fold(true, |finite, x| finite & x.is_finite())
}
