//! What a layered model passes on beyond the [`Lagrangian`] trait itself,
//! its sized capabilities' own traits: [`Actuated`] under a layer that
//! keeps the inputs, [`ParameterDerivatives`] under any layer. (Holonomic's
//! is in `layer.rs`, with the joined model it needs.)

use nalgebra::{RealField, SMatrix, SVector};

use super::inputs::{Actuated, KeepsInputs};
use super::layer::{At, Layer, Layered};
use super::parameters::{Domain, ParameterDerivatives};

/// A layer that keeps the inputs passes the model's on.
impl<M, A, const N: usize, const K: usize> Actuated<N, K> for Layered<M, A>
where
    M: Actuated<N, K>,
    A: Layer<M, N> + KeepsInputs,
{
    const INPUTS: [&'static str; K] = M::INPUTS;

    #[inline]
    fn inputs(&self) -> SVector<Self::Scalar, K> {
        self.model().inputs()
    }

    #[inline]
    fn set_inputs(&mut self, u: &SVector<Self::Scalar, K>) {
        self.model_mut().set_inputs(u);
    }

    #[inline]
    fn input_jacobian(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SMatrix<Self::Scalar, N, K> {
        self.model().input_jacobian(t, q, qdot)
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
    const DOMAINS: [Domain; P] = M::DOMAINS;

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
