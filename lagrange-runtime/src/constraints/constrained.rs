//! [`Constrained`]: a model with its constraint handling chosen for a run.

use nalgebra::{RealField, SMatrix, SVector};

use super::{ConstraintSettings, Drift, Holonomic, InitialConditions, Visitor};
use crate::Lagrangian;

/// A constrained model with its own [`ConstraintSettings`]: everything else
/// is the model's, by delegation. Build it with
/// [`Holonomic::with_drift`], [`Holonomic::with_initial_conditions`] or
/// [`Constrained::new`], and integrate it like the model itself:
///
/// ```text
/// let measured = Rk4::new(1e-3).integrate(&pendulum.with_drift(Drift::None), t0, q0, v0, &times)?;
/// let strict = pendulum.with_drift(Drift::Projection).initial_conditions(InitialConditions::Reject);
/// ```
///
/// (A model needs `lagrangian!` or a page of hand-written code; the
/// compiled example is on `lagrange::models::CartesianPendulum`.)
///
/// `S` is the model's scalar and `C` its number of constraints; both are
/// inferred.
#[derive(Debug)]
pub struct Constrained<'a, M: ?Sized, S, const C: usize> {
    model: &'a M,
    settings: ConstraintSettings<S>,
}

impl<M: ?Sized, S: Copy, const C: usize> Clone for Constrained<'_, M, S, C> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<M: ?Sized, S: Copy, const C: usize> Copy for Constrained<'_, M, S, C> {}

impl<'a, M: ?Sized, S: RealField + Copy, const C: usize> Constrained<'a, M, S, C> {
    /// `model` with the settings it has now (its
    /// [`constraint_settings`](Holonomic::constraint_settings)).
    pub fn new<const N: usize>(model: &'a M) -> Self
    where
        M: Holonomic<N, C, Scalar = S>,
    {
        Self {
            model,
            settings: model.constraint_settings(),
        }
    }

    /// The drift control for this run.
    pub fn drift(mut self, drift: Drift<S>) -> Self {
        self.settings.drift = drift;
        self
    }

    /// The rule for an inconsistent initial state.
    pub fn initial_conditions(mut self, initial: InitialConditions) -> Self {
        self.settings.initial = initial;
        self
    }

    /// The model wrapped.
    pub fn model(&self) -> &'a M {
        self.model
    }
}

impl<M, S, const N: usize, const C: usize> Lagrangian<N> for Constrained<'_, M, S, C>
where
    M: Holonomic<N, C, Scalar = S> + ?Sized,
    S: RealField + Copy,
{
    type Scalar = S;
    const COORDINATES: [&'static str; N] = M::COORDINATES;
    const CONSERVATIVE: bool = M::CONSERVATIVE;

    fn mass_matrix(&self, t: S, q: &SVector<S, N>) -> SMatrix<S, N, N> {
        self.model.mass_matrix(t, q)
    }
    fn forcing(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> SVector<S, N> {
        self.model.forcing(t, q, qdot)
    }
    fn mass_matrix_and_forcing(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> (SMatrix<S, N, N>, SVector<S, N>) {
        self.model.mass_matrix_and_forcing(t, q, qdot)
    }
    fn kinetic_energy(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> S {
        self.model.kinetic_energy(t, q, qdot)
    }
    fn potential_energy(&self, t: S, q: &SVector<S, N>) -> S {
        self.model.potential_energy(t, q)
    }
    fn energy(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> S {
        self.model.energy(t, q, qdot)
    }
    fn residual_jacobians(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
        qddot: &SVector<S, N>,
    ) -> Option<(SMatrix<S, N, N>, SMatrix<S, N, N>)> {
        self.model.residual_jacobians(t, q, qdot, qddot)
    }
    fn momentum(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> Option<SVector<S, N>> {
        self.model.momentum(t, q, qdot)
    }
    fn lagrangian_gradient(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> Option<SVector<S, N>> {
        self.model.lagrangian_gradient(t, q, qdot)
    }
    fn nonconservative_forces(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> Option<SVector<S, N>> {
        self.model.nonconservative_forces(t, q, qdot)
    }
    fn visit_constraints<V: Visitor<S, N>>(&self, visitor: V) -> Option<V::Output> {
        Some(visitor.visit::<Self, C>(self))
    }
    fn parameters_are_finite(&self) -> bool {
        self.model.parameters_are_finite()
    }
}

impl<M, S, const N: usize, const C: usize> Holonomic<N, C> for Constrained<'_, M, S, C>
where
    M: Holonomic<N, C, Scalar = S> + ?Sized,
    S: RealField + Copy,
{
    const CONSTRAINTS: [&'static str; C] = M::CONSTRAINTS;

    fn constraints(&self, t: S, q: &SVector<S, N>) -> SVector<S, C> {
        self.model.constraints(t, q)
    }
    fn constraint_jacobian(&self, t: S, q: &SVector<S, N>) -> SMatrix<S, C, N> {
        self.model.constraint_jacobian(t, q)
    }
    fn constraint_velocities(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> SVector<S, C> {
        self.model.constraint_velocities(t, q, qdot)
    }
    fn constraint_bias(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> SVector<S, C> {
        self.model.constraint_bias(t, q, qdot)
    }
    #[allow(clippy::type_complexity)]
    fn constrained_system(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> (
        SMatrix<S, N, N>,
        SVector<S, N>,
        SMatrix<S, C, N>,
        SVector<S, C>,
    ) {
        self.model.constrained_system(t, q, qdot)
    }
    fn constraint_settings(&self) -> ConstraintSettings<S> {
        self.settings
    }
}
