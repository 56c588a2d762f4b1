//! [`ParameterDerivatives<N, P>`]: a model's parameter scalars, read and
//! set by index, and its derivatives by them, for models written with
//! `#[lagrange(parameter_derivatives)]`. What forward sensitivities
//! ([`sensitivity`](crate::sensitivity)) and fits to measurements are built
//! on.

use nalgebra::{RealField, SMatrix, SVector};

use super::Lagrangian;
use super::layer::{At, Layer, Layered};

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

/// A layered model has its model's parameters: a controller replaying
/// recorded inputs (`model.with_controller(..)`) keeps them, and the
/// derivatives that depend on `q̇` are taken from the model the layer puts
/// at the state (its inputs set), as its forcing is.
impl<M, A, const N: usize, const P: usize> ParameterDerivatives<N, P> for Layered<M, A>
where
    M: ParameterDerivatives<N, P>,
    A: Layer<M, N>,
{
    const PARAMETERS: [&'static str; P] = M::PARAMETERS;

    fn parameter_values(&self) -> SVector<Self::Scalar, P> {
        self.model().parameter_values()
    }

    fn set_parameter_values(&mut self, values: &SVector<Self::Scalar, P>) {
        self.model_mut().set_parameter_values(values);
    }

    fn mass_matrix_parameter_derivatives(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
    ) -> [SMatrix<Self::Scalar, N, N>; P] {
        self.model().mass_matrix_parameter_derivatives(t, q)
    }

    fn forcing_parameter_jacobian(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SMatrix<Self::Scalar, N, P> {
        match self.layer().at(self.model(), t, q, qdot) {
            At::Model(m) => m.forcing_parameter_jacobian(t, q, qdot),
            At::Changed(m) => m.forcing_parameter_jacobian(t, q, qdot),
            At::NotFinite => not_finite(),
        }
    }

    fn residual_parameter_jacobian(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
        qddot: &SVector<Self::Scalar, N>,
    ) -> SMatrix<Self::Scalar, N, P> {
        match self.layer().at(self.model(), t, q, qdot) {
            At::Model(m) => m.residual_parameter_jacobian(t, q, qdot, qddot),
            At::Changed(m) => m.residual_parameter_jacobian(t, q, qdot, qddot),
            At::NotFinite => not_finite(),
        }
    }
}

/// NaN in every entry: where no model answers (a controller's NaN), which
/// the sensitivities report as a non-finite Jacobian.
fn not_finite<S: RealField + Copy, const R: usize, const C: usize>() -> SMatrix<S, R, C> {
    SMatrix::from_element(nalgebra::convert::<f64, S>(f64::NAN))
}
