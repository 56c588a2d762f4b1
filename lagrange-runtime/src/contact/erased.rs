//! A model with contacts behind one object-safe interface: the contact
//! runs (the decisions, the events, the run loop's walkers) are compiled
//! once per scalar, `N` and `K`, for [`Erased`], not once per model.
//! Every scene of `lagrange::models` with two coordinates and one contact
//! shares one copy of each method's loop.

use nalgebra::{RealField, SMatrix, SVector};

use super::held::{Held, Read};
use super::{ContactLaw, Contacts};
use crate::error::{IntegrationError, NonFiniteValue};
use crate::model::Lagrangian;

/// What a contact run evaluates of a model, object-safe.
pub(crate) trait DynContacts<S: RealField + Copy, const N: usize, const K: usize>:
    Sync
{
    fn mass_matrix(&self, t: S, q: &SVector<S, N>) -> SMatrix<S, N, N>;
    fn forcing(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> SVector<S, N>;
    fn mass_matrix_and_forcing(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> (SMatrix<S, N, N>, SVector<S, N>);
    fn kinetic_energy(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> S;
    fn potential_energy(&self, t: S, q: &SVector<S, N>) -> S;
    fn parameters_are_finite(&self) -> bool;
    fn gaps(&self, t: S, q: &SVector<S, N>) -> SVector<S, K>;
    fn gap_jacobian(&self, t: S, q: &SVector<S, N>) -> SMatrix<S, K, N>;
    fn gap_velocities(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> SVector<S, K>;
    fn gap_bias(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> SVector<S, K>;
    fn slip_jacobian(&self, t: S, q: &SVector<S, N>) -> SMatrix<S, K, N>;
    fn slip_velocities(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> SVector<S, K>;
    fn slip_bias(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> SVector<S, K>;
    fn second_slip_jacobian(&self, t: S, q: &SVector<S, N>) -> SMatrix<S, K, N>;
    fn second_slip_velocities(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> SVector<S, K>;
    fn second_slip_bias(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> SVector<S, K>;
    fn contact_laws(&self) -> [ContactLaw<S>; K];
    /// The model's own constraints at `(t, q, q̇)`, with their residuals
    /// where asked; `None` for a model without.
    fn held(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
        residuals: bool,
    ) -> Option<Held<S>>;
    /// [`blame`](crate::dynamics::blame::blame) on the model itself: its
    /// inputs, which the erased model cannot hand a visitor.
    fn blame(
        &self,
        value: NonFiniteValue,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> NonFiniteValue;
}

impl<L, const N: usize, const K: usize> DynContacts<L::Scalar, N, K> for L
where
    L: Contacts<N, K> + Sync,
{
    fn mass_matrix(&self, t: L::Scalar, q: &SVector<L::Scalar, N>) -> SMatrix<L::Scalar, N, N> {
        Lagrangian::mass_matrix(self, t, q)
    }
    fn forcing(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> SVector<L::Scalar, N> {
        Lagrangian::forcing(self, t, q, qdot)
    }
    fn mass_matrix_and_forcing(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> (SMatrix<L::Scalar, N, N>, SVector<L::Scalar, N>) {
        Lagrangian::mass_matrix_and_forcing(self, t, q, qdot)
    }
    fn kinetic_energy(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> L::Scalar {
        Lagrangian::kinetic_energy(self, t, q, qdot)
    }
    fn potential_energy(&self, t: L::Scalar, q: &SVector<L::Scalar, N>) -> L::Scalar {
        Lagrangian::potential_energy(self, t, q)
    }
    fn parameters_are_finite(&self) -> bool {
        Lagrangian::parameters_are_finite(self)
    }
    fn gaps(&self, t: L::Scalar, q: &SVector<L::Scalar, N>) -> SVector<L::Scalar, K> {
        Contacts::gaps(self, t, q)
    }
    fn gap_jacobian(&self, t: L::Scalar, q: &SVector<L::Scalar, N>) -> SMatrix<L::Scalar, K, N> {
        Contacts::gap_jacobian(self, t, q)
    }
    fn gap_velocities(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> SVector<L::Scalar, K> {
        Contacts::gap_velocities(self, t, q, qdot)
    }
    fn gap_bias(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> SVector<L::Scalar, K> {
        Contacts::gap_bias(self, t, q, qdot)
    }
    fn slip_jacobian(&self, t: L::Scalar, q: &SVector<L::Scalar, N>) -> SMatrix<L::Scalar, K, N> {
        Contacts::slip_jacobian(self, t, q)
    }
    fn slip_velocities(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> SVector<L::Scalar, K> {
        Contacts::slip_velocities(self, t, q, qdot)
    }
    fn slip_bias(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> SVector<L::Scalar, K> {
        Contacts::slip_bias(self, t, q, qdot)
    }
    fn second_slip_jacobian(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
    ) -> SMatrix<L::Scalar, K, N> {
        Contacts::second_slip_jacobian(self, t, q)
    }
    fn second_slip_velocities(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> SVector<L::Scalar, K> {
        Contacts::second_slip_velocities(self, t, q, qdot)
    }
    fn second_slip_bias(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> SVector<L::Scalar, K> {
        Contacts::second_slip_bias(self, t, q, qdot)
    }
    fn contact_laws(&self) -> [ContactLaw<L::Scalar>; K] {
        Contacts::contact_laws(self)
    }
    fn held(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
        residuals: bool,
    ) -> Option<Held<L::Scalar>> {
        self.visit_constraints(Read {
            t,
            q,
            qdot,
            residuals,
        })
    }
    fn blame(
        &self,
        value: NonFiniteValue,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> NonFiniteValue {
        crate::dynamics::blame::blame(self, value, t, q, qdot)
    }
}

/// A model with contacts, erased: the one model type the contact runs are
/// compiled for. Its contacts' names are the model's, kept as values
/// ([`names`](Self::names)); the `COORDINATES` and `CONTACTS` of its
/// `impl`s are blank.
pub struct Erased<'a, S: RealField + Copy, const N: usize, const K: usize> {
    model: &'a dyn DynContacts<S, N, K>,
    pub(crate) names: [&'static str; K],
    /// Whether the model has constraints of its own.
    constrained: bool,
    /// Whether some contact's friction acts in a plane (its laws are the
    /// model's parameters', fixed while it is borrowed).
    planes: bool,
}

impl<S: RealField + Copy, const N: usize, const K: usize> Clone for Erased<'_, S, N, K> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S: RealField + Copy, const N: usize, const K: usize> Copy for Erased<'_, S, N, K> {}

impl<'a, S: RealField + Copy, const N: usize, const K: usize> Erased<'a, S, N, K> {
    pub(crate) fn new<L>(model: &'a L) -> Self
    where
        L: Contacts<N, K, Scalar = S> + Sync,
    {
        Self {
            model,
            names: L::CONTACTS,
            constrained: crate::model::constraints::is_constrained(model),
            planes: Contacts::contact_laws(model).iter().any(|law| law.in_plane),
        }
    }

    /// The model's own constraints at `(t, q, q̇)`, held throughout the
    /// run, with their residuals `φ` and `φ̇` where `residuals` asks; `None`
    /// for a model without.
    pub(crate) fn held(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
        residuals: bool,
    ) -> Option<Held<S>> {
        if self.constrained {
            self.model.held(t, q, qdot, residuals)
        } else {
            None
        }
    }

    /// Whether the model has constraints of its own.
    pub(crate) fn constrained(&self) -> bool {
        self.constrained
    }

    /// Whether some contact's friction acts in a plane.
    pub(crate) fn planes(&self) -> bool {
        self.planes
    }

    /// The contacts' names, in the order of the gaps.
    pub fn names(&self) -> &[&'static str; K] {
        &self.names
    }

    /// A non-finite `value` at `(t, q, q̇)` blamed on the model's inputs
    /// where they are to blame (see [`blame`](crate::dynamics::blame::blame)).
    pub(crate) fn blame(
        &self,
        value: NonFiniteValue,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> NonFiniteValue {
        self.model.blame(value, t, q, qdot)
    }
}

// Every method written out (the lint holds it so): a capability added to
// the contract is passed on here, or said not to be.
#[warn(clippy::missing_trait_methods)]
impl<S: RealField + Copy, const N: usize, const K: usize> Lagrangian<N> for Erased<'_, S, N, K> {
    type Scalar = S;
    const COORDINATES: [&'static str; N] = [""; N];

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
        self.model.kinetic_energy(t, q, qdot) + self.model.potential_energy(t, q)
    }
    fn parameters_are_finite(&self) -> bool {
        self.model.parameters_are_finite()
    }

    // Not passed on, each for its reason:

    /// None: the contact runs' implicit methods take differences (of the
    /// phase's forcing, which adds the contact forces to the model's).
    fn residual_jacobians(
        &self,
        _: S,
        _: &SVector<S, N>,
        _: &SVector<S, N>,
        _: &SVector<S, N>,
    ) -> Option<(SMatrix<S, N, N>, SMatrix<S, N, N>)> {
        None
    }
    /// None: the phase solves from `M` and `f` (a model's own solve, a
    /// tree's recursion, would give the same `q̈` without the contacts'
    /// forces, which the phase adds to `f`).
    fn accelerations(
        &self,
        _: S,
        _: &SVector<S, N>,
        _: &SVector<S, N>,
    ) -> Option<Result<SVector<S, N>, IntegrationError<S, N>>> {
        None
    }
    /// None: the variational method does not run contacts.
    fn momentum(&self, _: S, _: &SVector<S, N>, _: &SVector<S, N>) -> Option<SVector<S, N>> {
        None
    }
    /// None: the variational method does not run contacts.
    fn lagrangian_gradient(
        &self,
        _: S,
        _: &SVector<S, N>,
        _: &SVector<S, N>,
    ) -> Option<SVector<S, N>> {
        None
    }
    /// None: the variational method does not run contacts.
    fn nonconservative_forces(
        &self,
        _: S,
        _: &SVector<S, N>,
        _: &SVector<S, N>,
    ) -> Option<SVector<S, N>> {
        None
    }
    /// None: a contact run holds the model's own constraints itself,
    /// with the contacts (`contact/held.rs`): the run loop sees the
    /// phase's accelerations, which keep them.
    fn visit_constraints<V>(&self, _: V) -> Option<V::Output>
    where
        V: crate::model::constraints::Visitor<S, N>,
    {
        None
    }
    /// None: the model's inputs are checked before the erasure
    /// ([`Scene::new`](super::Scene::new)), and a non-finite value is
    /// blamed on them by the erased model itself (the visitor cannot pass
    /// through the object-safe interface).
    fn visit_inputs<V>(&self, _: V) -> Option<V::Output>
    where
        V: crate::model::inputs::Visitor<S, N>,
    {
        None
    }
    /// None: no contact run reads the model's `let`s.
    fn visit_lets<V>(&self, _: V) -> Option<V::Output>
    where
        V: crate::model::lets::Visitor<S, N>,
    {
        None
    }
}

impl<S: RealField + Copy, const N: usize, const K: usize> Contacts<N, K> for Erased<'_, S, N, K> {
    const CONTACTS: [&'static str; K] = [""; K];

    fn gaps(&self, t: S, q: &SVector<S, N>) -> SVector<S, K> {
        self.model.gaps(t, q)
    }
    fn gap_jacobian(&self, t: S, q: &SVector<S, N>) -> SMatrix<S, K, N> {
        self.model.gap_jacobian(t, q)
    }
    fn gap_velocities(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> SVector<S, K> {
        self.model.gap_velocities(t, q, qdot)
    }
    fn gap_bias(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> SVector<S, K> {
        self.model.gap_bias(t, q, qdot)
    }
    fn slip_jacobian(&self, t: S, q: &SVector<S, N>) -> SMatrix<S, K, N> {
        self.model.slip_jacobian(t, q)
    }
    fn slip_velocities(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> SVector<S, K> {
        self.model.slip_velocities(t, q, qdot)
    }
    fn slip_bias(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> SVector<S, K> {
        self.model.slip_bias(t, q, qdot)
    }
    fn second_slip_jacobian(&self, t: S, q: &SVector<S, N>) -> SMatrix<S, K, N> {
        self.model.second_slip_jacobian(t, q)
    }
    fn second_slip_velocities(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> SVector<S, K> {
        self.model.second_slip_velocities(t, q, qdot)
    }
    fn second_slip_bias(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> SVector<S, K> {
        self.model.second_slip_bias(t, q, qdot)
    }
    fn contact_laws(&self) -> [ContactLaw<S>; K] {
        self.model.contact_laws()
    }
}
