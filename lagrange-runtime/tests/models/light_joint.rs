//! A linearized double pendulum with an ill-conditioned mass matrix.

use lagrange_runtime::Lagrangian;
use lagrange_runtime::nalgebra::{Matrix2, Vector2};

/// A double pendulum linearized about the bottom (unit rods, `g = 1`) whose
/// inner bob has mass `mu` and outer bob mass 1:
/// `M = [[1 + μ, 1], [1, 1]]`, `K = diag(1 + μ, 1)`. For small `μ` the
/// mass matrix has pivot ratio `(1 + μ)² / μ`: condition ~`4 / μ`, and a
/// fast kink mode of frequency ~`√(2 / μ)`.
pub struct LightJoint {
    pub mu: f64,
}

impl LightJoint {
    fn mass(&self) -> Matrix2<f64> {
        Matrix2::new(1.0 + self.mu, 1.0, 1.0, 1.0)
    }
    fn stiffness(&self) -> Matrix2<f64> {
        Matrix2::new(1.0 + self.mu, 0.0, 0.0, 1.0)
    }
}

impl Lagrangian<2> for LightJoint {
    type Scalar = f64;
    const COORDINATES: [&'static str; 2] = ["theta1", "theta2"];

    fn mass_matrix(&self, _t: f64, _q: &Vector2<f64>) -> Matrix2<f64> {
        self.mass()
    }
    fn forcing(&self, _t: f64, q: &Vector2<f64>, _qdot: &Vector2<f64>) -> Vector2<f64> {
        -(self.stiffness() * q)
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector2<f64>, qdot: &Vector2<f64>) -> f64 {
        0.5 * qdot.dot(&(self.mass() * qdot))
    }
    fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
        0.5 * q.dot(&(self.stiffness() * q))
    }
    fn momentum(&self, _t: f64, _q: &Vector2<f64>, qdot: &Vector2<f64>) -> Option<Vector2<f64>> {
        Some(self.mass() * qdot)
    }
    fn lagrangian_gradient(
        &self,
        _t: f64,
        q: &Vector2<f64>,
        _qdot: &Vector2<f64>,
    ) -> Option<Vector2<f64>> {
        Some(-(self.stiffness() * q))
    }
    fn nonconservative_forces(
        &self,
        _t: f64,
        _q: &Vector2<f64>,
        _qdot: &Vector2<f64>,
    ) -> Option<Vector2<f64>> {
        Some(Vector2::zeros())
    }
}
