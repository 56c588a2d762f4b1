//! A model with contacts behind one object-safe interface: the contact
//! runs (the decisions, the events, the run loop's walkers) are compiled
//! once per scalar, `N` and `K`, for [`Erased`], not once per model.
//! Every scene of `lagrange::models` with two coordinates and one contact
//! shares one copy of each method's loop.

use nalgebra::{RealField, SMatrix, SVector};

use super::{ContactLaw, Contacts};
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
    fn contact_laws(&self) -> [ContactLaw<S>; K];
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
    fn contact_laws(&self) -> [ContactLaw<L::Scalar>; K] {
        Contacts::contact_laws(self)
    }
}

/// A model with contacts, erased: the one model type the contact runs are
/// compiled for. Its contacts' names are the model's, kept as values
/// ([`names`](Self::names)); the `COORDINATES` and `CONTACTS` of its
/// `impl`s are blank.
pub struct Erased<'a, S: RealField + Copy, const N: usize, const K: usize> {
    model: &'a dyn DynContacts<S, N, K>,
    pub(crate) names: [&'static str; K],
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
        }
    }

    /// The contacts' names, in the order of the gaps.
    pub fn names(&self) -> &[&'static str; K] {
        &self.names
    }
}

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
    fn parameters_are_finite(&self) -> bool {
        self.model.parameters_are_finite()
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
    fn contact_laws(&self) -> [ContactLaw<S>; K] {
        self.model.contact_laws()
    }
}
