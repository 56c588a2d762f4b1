//! A borrowed model is a model: `&L` passes everything on to `L`, so that
//! a layer or a [`Stepper`](crate::stepper::Stepper) can own a reference where the
//! caller keeps the model (`(&model).with_drift(..)`).

use nalgebra::{SMatrix, SVector};

use super::Lagrangian;
use crate::model::constraints::{Holonomic, Visitor as ConstraintVisitor};
use crate::model::inputs::Visitor as InputVisitor;
use crate::model::lets::Visitor as LetVisitor;

#[warn(clippy::missing_trait_methods)]
impl<L: Lagrangian<N> + ?Sized, const N: usize> Lagrangian<N> for &L {
    type Scalar = L::Scalar;
    const COORDINATES: [&'static str; N] = L::COORDINATES;
    const HAS_CONTACTS: bool = L::HAS_CONTACTS;
    const SOLVES_ACCELERATIONS: bool = L::SOLVES_ACCELERATIONS;

    #[inline]
    fn mass_matrix(&self, t: L::Scalar, q: &SVector<L::Scalar, N>) -> SMatrix<L::Scalar, N, N> {
        (**self).mass_matrix(t, q)
    }
    #[inline]
    fn forcing(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> SVector<L::Scalar, N> {
        (**self).forcing(t, q, qdot)
    }
    #[inline]
    fn mass_matrix_and_forcing(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> (SMatrix<L::Scalar, N, N>, SVector<L::Scalar, N>) {
        (**self).mass_matrix_and_forcing(t, q, qdot)
    }
    #[inline]
    fn kinetic_energy(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> L::Scalar {
        (**self).kinetic_energy(t, q, qdot)
    }
    #[inline]
    fn potential_energy(&self, t: L::Scalar, q: &SVector<L::Scalar, N>) -> L::Scalar {
        (**self).potential_energy(t, q)
    }
    #[inline]
    fn energy(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> L::Scalar {
        (**self).energy(t, q, qdot)
    }
    #[inline]
    fn residual_jacobians(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
        qddot: &SVector<L::Scalar, N>,
    ) -> Option<(SMatrix<L::Scalar, N, N>, SMatrix<L::Scalar, N, N>)> {
        (**self).residual_jacobians(t, q, qdot, qddot)
    }
    #[allow(clippy::type_complexity)]
    #[inline]
    fn accelerations(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> Option<Result<SVector<L::Scalar, N>, crate::error::IntegrationError<L::Scalar, N>>> {
        (**self).accelerations(t, q, qdot)
    }
    #[inline]
    fn momentum(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> Option<SVector<L::Scalar, N>> {
        (**self).momentum(t, q, qdot)
    }
    #[inline]
    fn lagrangian_gradient(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> Option<SVector<L::Scalar, N>> {
        (**self).lagrangian_gradient(t, q, qdot)
    }
    #[inline]
    fn nonconservative_forces(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> Option<SVector<L::Scalar, N>> {
        (**self).nonconservative_forces(t, q, qdot)
    }
    #[inline]
    fn visit_constraints<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: ConstraintVisitor<L::Scalar, N>,
    {
        (**self).visit_constraints(visitor)
    }
    #[inline]
    fn visit_inputs<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: InputVisitor<L::Scalar, N>,
    {
        (**self).visit_inputs(visitor)
    }
    #[inline]
    fn visit_lets<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: LetVisitor<L::Scalar, N>,
    {
        (**self).visit_lets(visitor)
    }
    #[inline]
    fn parameters_are_finite(&self) -> bool {
        (**self).parameters_are_finite()
    }
}

impl<H: Holonomic<N, C> + ?Sized, const N: usize, const C: usize> Holonomic<N, C> for &H {
    const CONSTRAINTS: [&'static str; C] = H::CONSTRAINTS;

    #[inline]
    fn constraints(&self, t: H::Scalar, q: &SVector<H::Scalar, N>) -> SVector<H::Scalar, C> {
        (**self).constraints(t, q)
    }
    #[inline]
    fn constraint_jacobian(
        &self,
        t: H::Scalar,
        q: &SVector<H::Scalar, N>,
    ) -> SMatrix<H::Scalar, C, N> {
        (**self).constraint_jacobian(t, q)
    }
    #[inline]
    fn constraint_velocities(
        &self,
        t: H::Scalar,
        q: &SVector<H::Scalar, N>,
        qdot: &SVector<H::Scalar, N>,
    ) -> SVector<H::Scalar, C> {
        (**self).constraint_velocities(t, q, qdot)
    }
    #[inline]
    fn constraint_bias(
        &self,
        t: H::Scalar,
        q: &SVector<H::Scalar, N>,
        qdot: &SVector<H::Scalar, N>,
    ) -> SVector<H::Scalar, C> {
        (**self).constraint_bias(t, q, qdot)
    }
    #[inline]
    fn mass_regular_on_constraints_only(&self) -> bool {
        (**self).mass_regular_on_constraints_only()
    }
    #[inline]
    fn velocity_constraint_rows(&self) -> [bool; C] {
        (**self).velocity_constraint_rows()
    }
    #[inline]
    #[allow(clippy::type_complexity)]
    fn constrained_system(
        &self,
        t: H::Scalar,
        q: &SVector<H::Scalar, N>,
        qdot: &SVector<H::Scalar, N>,
    ) -> (
        SMatrix<H::Scalar, N, N>,
        SVector<H::Scalar, N>,
        SMatrix<H::Scalar, C, N>,
        SVector<H::Scalar, C>,
    ) {
        (**self).constrained_system(t, q, qdot)
    }
}
