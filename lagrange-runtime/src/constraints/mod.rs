//! Holonomic constraints: models in redundant coordinates, closed loops.
//!
//! A model written with a `constraints:` section implements [`Holonomic`]
//! besides [`Lagrangian`]: its constraints `φ(t, q) = 0`, their Jacobian
//! `G = ∂φ/∂q` and the bias `γ` with `φ̈ = G q̈ + γ`. The equations of motion
//! are then the saddle-point system
//!
//! ```text
//! M q̈ + Gᵀ λ = f,        G q̈ = −γ,
//! ```
//!
//! whose multipliers `λ` are the constraint forces, in the units of the
//! constraint (a constraint written in metres gives newtons).
//!
//! # How the integrators reach a model's constraints
//!
//! The integrators are generic over [`Lagrangian<N>`] alone, and the number
//! of constraints `C` is a second size that the trait cannot name. A
//! constrained model therefore overrides one provided method,
//! [`Lagrangian::visit_constraints`], which hands a [`Visitor`] the model as
//! a [`Holonomic<N, C>`] with its `C` known: statically dispatched, so the
//! constrained code is monomorphized for the model's own sizes and nothing
//! is allocated. `lagrangian!` writes that one line; a model in minimal
//! coordinates keeps the default (`None`) and pays nothing.

use nalgebra::{RealField, SMatrix, SVector};

use crate::Lagrangian;

/// A model with `C` holonomic constraints `φ(t, q) = 0` on its `N`
/// coordinates (`C < N`).
///
/// `lagrangian!` implements it for every model with a `constraints:`
/// section; the four required methods are generated from the constraints
/// symbolically.
pub trait Holonomic<const N: usize, const C: usize>: Lagrangian<N> {
    /// Names of the constraints, in the order of `φ`.
    const CONSTRAINTS: [&'static str; C];

    /// The constraint values `φ(t, q)`: zero on the constraint manifold.
    fn constraints(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
    ) -> SVector<Self::Scalar, C>;

    /// The constraint Jacobian `G(t, q) = ∂φ/∂q`, `C × N`.
    fn constraint_jacobian(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
    ) -> SMatrix<Self::Scalar, C, N>;

    /// The constraint velocities `φ̇ = G q̇ + ∂φ/∂t`: zero for a state on
    /// the manifold moving along it.
    fn constraint_velocities(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SVector<Self::Scalar, C>;

    /// The bias `γ(t, q, q̇)` with `φ̈ = G q̈ + γ`: the part of the constraint
    /// accelerations that does not depend on `q̈`.
    fn constraint_bias(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SVector<Self::Scalar, C>;

    /// `M`, `f`, `G` and `γ` together: generated models compute their
    /// shared subexpressions once. The constrained right-hand side calls
    /// this, once per evaluation.
    #[allow(clippy::type_complexity)]
    fn constrained_system(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> (
        SMatrix<Self::Scalar, N, N>,
        SVector<Self::Scalar, N>,
        SMatrix<Self::Scalar, C, N>,
        SVector<Self::Scalar, C>,
    ) {
        let (m, f) = self.mass_matrix_and_forcing(t, q, qdot);
        (
            m,
            f,
            self.constraint_jacobian(t, q),
            self.constraint_bias(t, q, qdot),
        )
    }
}

/// What the integrators do with a constrained model, written once for
/// every number of constraints: [`Lagrangian::visit_constraints`] calls
/// [`visit`](Visitor::visit) with the model and its `C`.
pub trait Visitor<S: RealField + Copy, const N: usize> {
    /// What the visit returns.
    type Output;

    /// Runs on a model with `C` constraints.
    fn visit<H, const C: usize>(self, model: &H) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized;
}
