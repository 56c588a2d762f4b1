//! Linear oscillators with exact solutions: a coupled pair with a full mass
//! matrix, and a spring driven through its Lagrangian.

use lagrange_runtime::Lagrangian;
use lagrange_runtime::nalgebra::{Matrix2, RealField, SMatrix, Vector1, Vector2};

/// Two coordinates with a full, symmetric mass matrix `M = [[2, 1], [1, 2]]`
/// and stiffness `ω² M`, so `q̈ = -ω² q` exactly while the integrators still
/// have to solve a coupled `M q̈ = f`.
pub struct CoupledOscillator<S> {
    pub omega: S,
}

impl<S: RealField + Copy> CoupledOscillator<S> {
    fn mass() -> Matrix2<S> {
        let (one, two) = (S::one(), S::one() + S::one());
        Matrix2::new(two, one, one, two)
    }

    /// The exact state at `t` from `(q0, q̇0)` at `t = 0`.
    pub fn exact(&self, t: S, q0: Vector2<S>, qdot0: Vector2<S>) -> (Vector2<S>, Vector2<S>) {
        let (w, (s, c)) = (self.omega, (self.omega * t).sin_cos());
        (q0 * c + qdot0 * (s / w), qdot0 * c - q0 * (w * s))
    }
}

impl<S: RealField + Copy> Lagrangian<2> for CoupledOscillator<S> {
    type Scalar = S;
    const COORDINATES: [&'static str; 2] = ["x", "y"];

    fn mass_matrix(&self, _t: S, _q: &Vector2<S>) -> Matrix2<S> {
        Self::mass()
    }
    fn forcing(&self, _t: S, q: &Vector2<S>, _qdot: &Vector2<S>) -> Vector2<S> {
        Self::mass() * q * -(self.omega * self.omega)
    }
    fn kinetic_energy(&self, _t: S, _q: &Vector2<S>, qdot: &Vector2<S>) -> S {
        (qdot.transpose() * Self::mass() * qdot)[0] / (S::one() + S::one())
    }
    fn potential_energy(&self, _t: S, q: &Vector2<S>) -> S {
        (q.transpose() * Self::mass() * q)[0] * self.omega * self.omega / (S::one() + S::one())
    }
    fn parameters_are_finite(&self) -> bool {
        self.omega.is_finite()
    }
}

/// A unit spring shaken by a force in the Lagrangian itself:
/// `L = ½ ẋ² − ½ x² + F x cos(Ω t)`, explicitly time dependent.
pub struct DrivenOscillator {
    pub force: f64,
    pub omega: f64,
}

impl DrivenOscillator {
    /// The exact `(x, ẋ)` at `t` from rest at the origin (`Ω ≠ 1`).
    pub fn exact(&self, t: f64) -> (f64, f64) {
        let a = self.force / (1.0 - self.omega * self.omega);
        let x = a * ((self.omega * t).cos() - t.cos());
        let v = a * (t.sin() - self.omega * (self.omega * t).sin());
        (x, v)
    }
}

impl Lagrangian<1> for DrivenOscillator {
    type Scalar = f64;
    const COORDINATES: [&'static str; 1] = ["x"];

    fn mass_matrix(&self, _t: f64, _q: &Vector1<f64>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(1.0)
    }
    fn forcing(&self, t: f64, q: &Vector1<f64>, _qdot: &Vector1<f64>) -> Vector1<f64> {
        Vector1::new(-q[0] + self.force * (self.omega * t).cos())
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector1<f64>, qdot: &Vector1<f64>) -> f64 {
        0.5 * qdot[0] * qdot[0]
    }
    fn potential_energy(&self, t: f64, q: &Vector1<f64>) -> f64 {
        0.5 * q[0] * q[0] - self.force * q[0] * (self.omega * t).cos()
    }
    fn momentum(&self, _t: f64, _q: &Vector1<f64>, qdot: &Vector1<f64>) -> Option<Vector1<f64>> {
        Some(*qdot)
    }
    fn lagrangian_gradient(
        &self,
        t: f64,
        q: &Vector1<f64>,
        _qdot: &Vector1<f64>,
    ) -> Option<Vector1<f64>> {
        Some(Vector1::new(-q[0] + self.force * (self.omega * t).cos()))
    }
    fn nonconservative_forces(
        &self,
        _t: f64,
        _q: &Vector1<f64>,
        _qdot: &Vector1<f64>,
    ) -> Option<Vector1<f64>> {
        Some(Vector1::zeros())
    }
}
