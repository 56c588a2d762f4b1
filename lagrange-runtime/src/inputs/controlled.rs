//! [`Controlled`]: a model with control inputs driven by a controller.

use core::cell::Cell;

use nalgebra::{ComplexField, SMatrix, SVector};

use super::Actuated;
use crate::constraints::{ConstraintSettings, Holonomic, Visitor};
use crate::Lagrangian;

/// A model whose `K` inputs are `controller(t, q, q̇)` at every evaluation:
/// the model is copied, its inputs set, and the evaluation delegated to the
/// copy. Build it with [`Actuated::with_controller`] and integrate it like
/// the model itself.
///
/// The controller is called once per right-hand side
/// ([`mass_matrix_and_forcing`](Lagrangian::mass_matrix_and_forcing); the
/// variational integrator, which asks for `∂L/∂q` and the non-conservative
/// forces apart, calls it twice per residual), and
/// [`controller_calls`](Self::controller_calls) counts the calls. Where it
/// returns a NaN or an infinity, the evaluation returns NaN, which the
/// integrators report as
/// [`NonFiniteValue::Inputs`](crate::NonFiniteValue::Inputs) at that `t`
/// and state; the inputs are never passed on.
///
/// What takes no `q̇` cannot call the controller: `mass_matrix` and
/// `momentum` need none (inputs are kept out of them), and
/// `potential_energy` is the model's with the inputs it holds (NaN unless
/// set by `with_inputs`): an input-dependent potential has no value
/// without the velocities the controller reads. The exact residual
/// Jacobians are not forwarded: they hold the inputs fixed, while `u`
/// depends on the state through the controller, so implicit methods take
/// finite differences, which see the controller too.
pub struct Controlled<'a, M, F, const K: usize> {
    model: &'a M,
    controller: F,
    calls: Cell<usize>,
}

impl<'a, M, F, const K: usize> Controlled<'a, M, F, K> {
    /// `model` driven by `controller`; [`Actuated::with_controller`] is the
    /// usual way to write it.
    pub fn new(model: &'a M, controller: F) -> Self {
        Self {
            model,
            controller,
            calls: Cell::new(0),
        }
    }

    /// How many times the controller was called so far (by every
    /// integration of this value).
    pub fn controller_calls(&self) -> usize {
        self.calls.get()
    }

    /// The model driven.
    pub fn model(&self) -> &'a M {
        self.model
    }
}

impl<M: Copy, F, const K: usize> Controlled<'_, M, F, K> {
    /// The model with the controller's inputs at `(t, q, q̇)`; `None` if
    /// they are not finite.
    fn driven<const N: usize>(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> Option<M>
    where
        M: Actuated<N, K>,
        F: Fn(M::Scalar, &SVector<M::Scalar, N>, &SVector<M::Scalar, N>) -> SVector<M::Scalar, K>,
    {
        self.calls.set(self.calls.get() + 1);
        let u = (self.controller)(t, q, qdot);
        if !u.iter().all(|x| x.is_finite()) {
            return None;
        }
        let mut model = *self.model;
        model.set_inputs(&u);
        Some(model)
    }
}

/// What an evaluation with non-finite inputs returns: NaN, never the inputs.
fn nan<S: nalgebra::RealField + Copy, const R: usize>() -> SVector<S, R> {
    SVector::from_element(nalgebra::convert::<f64, S>(f64::NAN))
}

impl<M, F, const N: usize, const K: usize> Lagrangian<N> for Controlled<'_, M, F, K>
where
    M: Actuated<N, K> + Copy,
    F: Fn(M::Scalar, &SVector<M::Scalar, N>, &SVector<M::Scalar, N>) -> SVector<M::Scalar, K>,
{
    type Scalar = M::Scalar;
    const COORDINATES: [&'static str; N] = M::COORDINATES;
    const CONSERVATIVE: bool = M::CONSERVATIVE;

    fn mass_matrix(&self, t: M::Scalar, q: &SVector<M::Scalar, N>) -> SMatrix<M::Scalar, N, N> {
        self.model.mass_matrix(t, q)
    }

    fn forcing(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> SVector<M::Scalar, N> {
        self.driven(t, q, qdot)
            .map_or_else(nan, |m| m.forcing(t, q, qdot))
    }

    fn mass_matrix_and_forcing(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> (SMatrix<M::Scalar, N, N>, SVector<M::Scalar, N>) {
        match self.driven(t, q, qdot) {
            Some(m) => m.mass_matrix_and_forcing(t, q, qdot),
            None => (self.model.mass_matrix(t, q), nan()),
        }
    }

    fn kinetic_energy(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> M::Scalar {
        self.driven(t, q, qdot)
            .map_or_else(|| nan::<_, 1>()[0], |m| m.kinetic_energy(t, q, qdot))
    }

    fn potential_energy(&self, t: M::Scalar, q: &SVector<M::Scalar, N>) -> M::Scalar {
        self.model.potential_energy(t, q)
    }

    fn energy(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> M::Scalar {
        self.driven(t, q, qdot)
            .map_or_else(|| nan::<_, 1>()[0], |m| m.energy(t, q, qdot))
    }

    fn momentum(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> Option<SVector<M::Scalar, N>> {
        self.model.momentum(t, q, qdot)
    }

    fn lagrangian_gradient(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> Option<SVector<M::Scalar, N>> {
        match self.driven(t, q, qdot) {
            Some(m) => m.lagrangian_gradient(t, q, qdot),
            None => Some(nan()),
        }
    }

    fn nonconservative_forces(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> Option<SVector<M::Scalar, N>> {
        if M::CONSERVATIVE {
            return Some(SVector::zeros());
        }
        match self.driven(t, q, qdot) {
            Some(m) => m.nonconservative_forces(t, q, qdot),
            None => Some(nan()),
        }
    }

    fn visit_constraints<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: Visitor<Self::Scalar, N>,
    {
        // The model's constraints, with this model's dynamics.
        self.model.visit_constraints(ThroughController {
            dynamics: self,
            visitor,
        })
    }

    fn parameters_are_finite(&self) -> bool {
        self.model.parameters_are_finite()
    }

    fn inputs_are_finite_at(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> bool {
        self.driven(t, q, qdot).is_some()
    }
}

/// A constrained model under a controller is constrained: its `φ`, `G`,
/// `φ̇` and `γ` are the model's (inputs are kept out of constraints), its
/// `M` and `f` go through the controller, so
/// `controlled.with_drift(..)` and `controlled.multipliers(..)` work as on
/// the model itself.
impl<M, F, const N: usize, const C: usize, const K: usize> Holonomic<N, C>
    for Controlled<'_, M, F, K>
where
    M: Actuated<N, K> + Holonomic<N, C> + Copy,
    F: Fn(M::Scalar, &SVector<M::Scalar, N>, &SVector<M::Scalar, N>) -> SVector<M::Scalar, K>,
{
    const CONSTRAINTS: [&'static str; C] = <M as Holonomic<N, C>>::CONSTRAINTS;

    fn constraints(&self, t: M::Scalar, q: &SVector<M::Scalar, N>) -> SVector<M::Scalar, C> {
        self.model.constraints(t, q)
    }

    fn constraint_jacobian(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
    ) -> SMatrix<M::Scalar, C, N> {
        self.model.constraint_jacobian(t, q)
    }

    fn constraint_velocities(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> SVector<M::Scalar, C> {
        self.model.constraint_velocities(t, q, qdot)
    }

    fn constraint_bias(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> SVector<M::Scalar, C> {
        self.model.constraint_bias(t, q, qdot)
    }

    fn constraint_settings(&self) -> ConstraintSettings<M::Scalar> {
        self.model.constraint_settings()
    }
}

/// The visitor that meets a controlled model's constraints: it hands its
/// own visitor the constraints (which hold no input) joined to the
/// controlled dynamics.
struct ThroughController<'b, L, V> {
    dynamics: &'b L,
    visitor: V,
}

impl<S, L, V, const N: usize> Visitor<S, N> for ThroughController<'_, L, V>
where
    S: nalgebra::RealField + Copy,
    L: Lagrangian<N, Scalar = S>,
    V: Visitor<S, N>,
{
    type Output = V::Output;

    fn visit<H, const C: usize>(self, constraints: &H) -> V::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let joined = WithConstraints::<L, H, C> {
            dynamics: self.dynamics,
            constraints,
        };
        self.visitor.visit::<_, C>(&joined)
    }
}

/// Dynamics from `L` (the controlled model), constraints from `H` (the
/// model itself): what a constrained integrator sees of a constrained model
/// under a controller. `constrained_system` is the trait's default, `M` and
/// `f` through the controller, `G` and `γ` from the model.
struct WithConstraints<'b, L, H: ?Sized, const C: usize> {
    dynamics: &'b L,
    constraints: &'b H,
}

impl<S, L, H, const N: usize, const C: usize> Lagrangian<N> for WithConstraints<'_, L, H, C>
where
    S: nalgebra::RealField + Copy,
    L: Lagrangian<N, Scalar = S>,
    H: Holonomic<N, C, Scalar = S> + ?Sized,
{
    type Scalar = S;
    const COORDINATES: [&'static str; N] = L::COORDINATES;
    const CONSERVATIVE: bool = L::CONSERVATIVE;

    fn mass_matrix(&self, t: S, q: &SVector<S, N>) -> SMatrix<S, N, N> {
        self.dynamics.mass_matrix(t, q)
    }
    fn forcing(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> SVector<S, N> {
        self.dynamics.forcing(t, q, qdot)
    }
    fn mass_matrix_and_forcing(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> (SMatrix<S, N, N>, SVector<S, N>) {
        self.dynamics.mass_matrix_and_forcing(t, q, qdot)
    }
    fn kinetic_energy(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> S {
        self.dynamics.kinetic_energy(t, q, qdot)
    }
    fn potential_energy(&self, t: S, q: &SVector<S, N>) -> S {
        self.dynamics.potential_energy(t, q)
    }
    fn energy(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> S {
        self.dynamics.energy(t, q, qdot)
    }
    fn momentum(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> Option<SVector<S, N>> {
        self.dynamics.momentum(t, q, qdot)
    }
    fn lagrangian_gradient(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> Option<SVector<S, N>> {
        self.dynamics.lagrangian_gradient(t, q, qdot)
    }
    fn nonconservative_forces(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> Option<SVector<S, N>> {
        self.dynamics.nonconservative_forces(t, q, qdot)
    }
    fn visit_constraints<V: Visitor<S, N>>(&self, visitor: V) -> Option<V::Output> {
        Some(visitor.visit::<Self, C>(self))
    }
    fn parameters_are_finite(&self) -> bool {
        self.dynamics.parameters_are_finite()
    }
    fn inputs_are_finite_at(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> bool {
        self.dynamics.inputs_are_finite_at(t, q, qdot)
    }
}

impl<S, L, H, const N: usize, const C: usize> Holonomic<N, C> for WithConstraints<'_, L, H, C>
where
    S: nalgebra::RealField + Copy,
    L: Lagrangian<N, Scalar = S>,
    H: Holonomic<N, C, Scalar = S> + ?Sized,
{
    const CONSTRAINTS: [&'static str; C] = H::CONSTRAINTS;

    fn constraints(&self, t: S, q: &SVector<S, N>) -> SVector<S, C> {
        self.constraints.constraints(t, q)
    }
    fn constraint_jacobian(&self, t: S, q: &SVector<S, N>) -> SMatrix<S, C, N> {
        self.constraints.constraint_jacobian(t, q)
    }
    fn constraint_velocities(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> SVector<S, C> {
        self.constraints.constraint_velocities(t, q, qdot)
    }
    fn constraint_bias(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> SVector<S, C> {
        self.constraints.constraint_bias(t, q, qdot)
    }
    fn constraint_settings(&self) -> ConstraintSettings<S> {
        self.constraints.constraint_settings()
    }
}
