//! Named `let`s: the intermediate quantities a model names (a bob's `x`
//! and `y`, a coupler's midpoint), evaluated at a state, for drawing,
//! export and fits of measured outputs.
//!
//! A model from `lagrangian!` names every scalar `let` it defines
//! (`LETS`, in the order written, an indexed `let x[i]` as `x[0]`,
//! `x[1]`, …) and evaluates them all at once; the runtime reaches them
//! through [`Lagrangian::visit_lets`], which hands a [`Visitor`] the model
//! as [`Lets<N, K>`] with its `K` known.

use nalgebra::{RealField, SVector};

use super::Lagrangian;

/// A model with `K` named `let`s.
pub trait Lets<const N: usize, const K: usize>: Lagrangian<N> {
    /// The names, in the order of [`lets`](Self::lets).
    const LETS: [&'static str; K];

    /// Every named `let` at `(t, q, q̇)`.
    fn lets(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> [Self::Scalar; K];
}

/// What the runtime does with a model's named `let`s, written once for
/// every number of them: [`Lagrangian::visit_lets`] calls
/// [`visit`](Visitor::visit) with the model and its `K`.
pub trait Visitor<S: RealField + Copy, const N: usize> {
    /// What the visit returns.
    type Output;

    /// Runs on a model with `K` named `let`s.
    fn visit<L, const K: usize>(self, model: &L) -> Self::Output
    where
        L: Lets<N, K, Scalar = S> + ?Sized;
}
