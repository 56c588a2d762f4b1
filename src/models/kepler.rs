//! The Kepler problem: a unit mass around a fixed central mass, in Cartesian
//! and in polar coordinates. The same orbit is separable with a constant
//! mass matrix in one chart and not in the other, which is what tells the
//! symplectic methods from the merely symmetric ones. Every orbit here
//! starts at pericentre with semi-major axis 1: period `2π/√μ`, energy
//! `−μ/2`.

use crate::lagrangian;
use nalgebra::{RealField, Vector2};

lagrangian! {
    /// A unit mass around a fixed central mass `mu`, Cartesian: `M = I`, a
    /// separable Hamiltonian, and the angular momentum `x ẏ − y ẋ` a
    /// quadratic invariant. With exact Jacobians.
    #[lagrange(jacobians)]
    pub struct Kepler {
        coordinates: x, y;
        parameters: mu;
        kinetic: (dot(x)^2 + dot(y)^2)/2;
        potential: -mu/sqrt(x^2 + y^2);
    }
}

lagrangian! {
    /// The same orbit in polar coordinates: `M(q) = diag(1, r²)` depends on
    /// `q`, so the Hamiltonian is not separable; `φ` is cyclic, so its
    /// momentum `r² φ̇` is conserved. With exact Jacobians.
    #[lagrange(jacobians)]
    pub struct PolarKepler {
        coordinates: r, phi;
        parameters: mu;
        kinetic: (dot(r)^2 + r^2*dot(phi)^2)/2;
        potential: -mu/r;
    }
}

/// `r = 1 − e` and the speed there, `√(μ (1 + e)/(1 − e))`.
fn pericentre<S: RealField + Copy>(mu: S, e: S) -> (S, S) {
    let one = S::one();
    ((one - e), (mu * (one + e) / (one - e)).sqrt())
}

impl<S: RealField + Copy> Kepler<S> {
    /// `(q, q̇)` at pericentre of the orbit of eccentricity `e`.
    pub fn pericentre(&self, e: S) -> (Vector2<S>, Vector2<S>) {
        let (r, speed) = pericentre(self.mu, e);
        (Vector2::new(r, S::zero()), Vector2::new(S::zero(), speed))
    }

    /// `x ẏ − y ẋ`.
    pub fn angular_momentum(q: &Vector2<S>, qdot: &Vector2<S>) -> S {
        q[0] * qdot[1] - q[1] * qdot[0]
    }
}

impl<S: RealField + Copy> PolarKepler<S> {
    /// `(q, q̇)` at pericentre of the orbit of eccentricity `e`.
    pub fn pericentre(&self, e: S) -> (Vector2<S>, Vector2<S>) {
        let (r, speed) = pericentre(self.mu, e);
        (
            Vector2::new(r, S::zero()),
            Vector2::new(S::zero(), speed / r),
        )
    }

    /// `r² φ̇`, the momentum of the cyclic `φ`.
    pub fn angular_momentum(q: &Vector2<S>, qdot: &Vector2<S>) -> S {
        q[0] * q[0] * qdot[1]
    }
}
