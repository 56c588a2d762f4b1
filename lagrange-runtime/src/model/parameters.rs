//! [`ParameterDerivatives<N, P>`]: a model's parameter scalars, read and
//! set by index, and its derivatives by them, for models written with
//! `#[lagrange(parameter_derivatives)]`. What forward sensitivities
//! ([`sensitivity`](crate::sensitivity)) and fits to measurements are built
//! on.

use nalgebra::{SMatrix, SVector};

use super::Lagrangian;

/// A model with its parameters' derivatives: `∂M/∂p`, `∂f/∂p` and the
/// residual's `∂r/∂p`, `P` the number of parameter scalars (an indexed
/// parameter `m[N]` counts `N`).
///
/// `lagrangian!` implements it for a model written with
/// `#[lagrange(parameter_derivatives)]`, each derivative derived at compile
/// time like `M` and `f` (the language reference, `lagrange::language`,
/// "Options"). A constrained model implements it too; the derivatives of
/// its constraints are the generated struct's inherent methods
/// (`constraint_parameter_jacobian` and its two siblings).
pub trait ParameterDerivatives<const N: usize, const P: usize>: Lagrangian<N> {
    /// The parameter scalars' names (`m1`, `l[0]`, …), the columns of the
    /// derivatives below: the generated struct's `PARAMETER_SCALARS`.
    const PARAMETERS: [&'static str; P];

    /// The parameter scalars' values, in the order of
    /// [`PARAMETERS`](Self::PARAMETERS).
    fn parameter_values(&self) -> SVector<Self::Scalar, P>;

    /// Sets every parameter scalar, in the order of
    /// [`PARAMETERS`](Self::PARAMETERS).
    fn set_parameter_values(&mut self, values: &SVector<Self::Scalar, P>);

    /// `∂M/∂p_k` at `(t, q)`, one `N × N` matrix per parameter scalar.
    fn mass_matrix_parameter_derivatives(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
    ) -> [SMatrix<Self::Scalar, N, N>; P];

    /// `∂f/∂p`, `N × P`, at `(t, q, q̇)`.
    fn forcing_parameter_jacobian(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SMatrix<Self::Scalar, N, P>;

    /// `∂r/∂p = (∂M/∂p) q̈ − ∂f/∂p`, `N × P`, of the residual
    /// `r = M(t, q) q̈ − f(t, q, q̇)`.
    fn residual_parameter_jacobian(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
        qddot: &SVector<Self::Scalar, N>,
    ) -> SMatrix<Self::Scalar, N, P>;

    /// The index of the parameter scalar named `name` (as
    /// [`PARAMETERS`](Self::PARAMETERS) writes it), if there is one.
    fn parameter_index(name: &str) -> Option<usize> {
        Self::PARAMETERS.iter().position(|p| *p == name)
    }
}
