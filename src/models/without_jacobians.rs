//! A model seen without its exact Jacobians.

use lagrange_runtime::constraints::Visitor;
use lagrange_runtime::Lagrangian;
use nalgebra::{SMatrix, SVector};

/// `model` without its exact residual Jacobians: the implicit methods take
/// theirs by finite differences of the acceleration instead, the code path
/// of a model written without `#[lagrange(jacobians)]`. Everything else is
/// the model's own.
#[derive(Clone, Copy, Debug)]
pub struct WithoutJacobians<M>(pub M);

impl<M: Lagrangian<N>, const N: usize> Lagrangian<N> for WithoutJacobians<M> {
    type Scalar = M::Scalar;
    const COORDINATES: [&'static str; N] = M::COORDINATES;
    const CONSERVATIVE: bool = M::CONSERVATIVE;

    fn mass_matrix(&self, t: M::Scalar, q: &SVector<M::Scalar, N>) -> SMatrix<M::Scalar, N, N> {
        self.0.mass_matrix(t, q)
    }
    fn forcing(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> SVector<M::Scalar, N> {
        self.0.forcing(t, q, qdot)
    }
    fn mass_matrix_and_forcing(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> (SMatrix<M::Scalar, N, N>, SVector<M::Scalar, N>) {
        self.0.mass_matrix_and_forcing(t, q, qdot)
    }
    fn kinetic_energy(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> M::Scalar {
        self.0.kinetic_energy(t, q, qdot)
    }
    fn potential_energy(&self, t: M::Scalar, q: &SVector<M::Scalar, N>) -> M::Scalar {
        self.0.potential_energy(t, q)
    }
    fn energy(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> M::Scalar {
        self.0.energy(t, q, qdot)
    }
    fn momentum(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> Option<SVector<M::Scalar, N>> {
        self.0.momentum(t, q, qdot)
    }
    fn lagrangian_gradient(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> Option<SVector<M::Scalar, N>> {
        self.0.lagrangian_gradient(t, q, qdot)
    }
    fn nonconservative_forces(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> Option<SVector<M::Scalar, N>> {
        self.0.nonconservative_forces(t, q, qdot)
    }
    fn parameters_are_finite(&self) -> bool {
        self.0.parameters_are_finite()
    }
    /// The model's own constraints, if any: seen without Jacobians, a
    /// constrained model is still constrained.
    fn visit_constraints<V: Visitor<M::Scalar, N>>(&self, visitor: V) -> Option<V::Output> {
        self.0.visit_constraints(visitor)
    }
}
