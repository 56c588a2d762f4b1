//! A model with some of its optional methods hidden.

use lagrange_runtime::Lagrangian;
use lagrange_runtime::nalgebra::{SMatrix, SVector};

/// `inner` with some of the optional variational methods hidden, as a
/// hand-written model that skipped them would be.
pub struct Without<M> {
    pub inner: M,
    pub lacks_momentum: bool,
    pub lacks_gradient: bool,
    pub lacks_forces: bool,
}

impl<M: Lagrangian<N>, const N: usize> Lagrangian<N> for Without<M> {
    type Scalar = M::Scalar;
    const COORDINATES: [&'static str; N] = M::COORDINATES;

    fn mass_matrix(&self, t: M::Scalar, q: &SVector<M::Scalar, N>) -> SMatrix<M::Scalar, N, N> {
        self.inner.mass_matrix(t, q)
    }
    fn forcing(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> SVector<M::Scalar, N> {
        self.inner.forcing(t, q, qdot)
    }
    fn kinetic_energy(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> M::Scalar {
        self.inner.kinetic_energy(t, q, qdot)
    }
    fn potential_energy(&self, t: M::Scalar, q: &SVector<M::Scalar, N>) -> M::Scalar {
        self.inner.potential_energy(t, q)
    }
    fn momentum(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> Option<SVector<M::Scalar, N>> {
        self.inner
            .momentum(t, q, qdot)
            .filter(|_| !self.lacks_momentum)
    }
    fn lagrangian_gradient(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> Option<SVector<M::Scalar, N>> {
        self.inner
            .lagrangian_gradient(t, q, qdot)
            .filter(|_| !self.lacks_gradient)
    }
    fn nonconservative_forces(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> Option<SVector<M::Scalar, N>> {
        self.inner
            .nonconservative_forces(t, q, qdot)
            .filter(|_| !self.lacks_forces)
    }
}
