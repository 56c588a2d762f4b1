//! Models, written out by hand with the optional methods `Variational` needs.

use lagrange_runtime::nalgebra::{Matrix1, Matrix2, Vector1, Vector2};
use lagrange_runtime::prelude::*;

/// A bob of mass `m` on a rod of length `l` in gravity `g`:
/// `L = ½ m l² θ̇² + m g l cos θ`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Pendulum {
    pub(super) m: f64,
    pub(super) l: f64,
    pub(super) g: f64,
}

impl Lagrangian<1> for Pendulum {
    type Scalar = f64;
    const COORDINATES: [&'static str; 1] = ["theta"];
    fn mass_matrix(&self, _t: f64, _q: &Vector1<f64>) -> Matrix1<f64> {
        Matrix1::new(self.m * self.l * self.l)
    }
    fn forcing(&self, _t: f64, q: &Vector1<f64>, _qd: &Vector1<f64>) -> Vector1<f64> {
        Vector1::new(-self.m * self.g * self.l * q[0].sin())
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector1<f64>, qd: &Vector1<f64>) -> f64 {
        0.5 * self.m * self.l * self.l * qd[0] * qd[0]
    }
    fn potential_energy(&self, _t: f64, q: &Vector1<f64>) -> f64 {
        -self.m * self.g * self.l * q[0].cos()
    }
    fn momentum(&self, _t: f64, _q: &Vector1<f64>, qd: &Vector1<f64>) -> Option<Vector1<f64>> {
        Some(Vector1::new(self.m * self.l * self.l * qd[0]))
    }
    fn lagrangian_gradient(
        &self,
        _t: f64,
        q: &Vector1<f64>,
        _qd: &Vector1<f64>,
    ) -> Option<Vector1<f64>> {
        Some(Vector1::new(-self.m * self.g * self.l * q[0].sin()))
    }
    fn nonconservative_forces(
        &self,
        _t: f64,
        _q: &Vector1<f64>,
        _qd: &Vector1<f64>,
    ) -> Option<Vector1<f64>> {
        Some(Vector1::zeros())
    }
    fn parameters_are_finite(&self) -> bool {
        [self.m, self.l, self.g].iter().all(|p| p.is_finite())
    }
}

/// A pendulum (bob `m`, rod `l`) hanging from a cart of mass `mc` on a
/// rail: `M(θ) = [[mc + m, m l cos θ], [m l cos θ, m l²]]` depends on the
/// configuration, and `f = (m l θ̇² sin θ, −m g l sin θ)`.
#[derive(Debug, Clone, Copy)]
pub(super) struct CartPendulum {
    pub(super) mc: f64,
    pub(super) m: f64,
    pub(super) l: f64,
    pub(super) g: f64,
}

impl CartPendulum {
    fn mass(&self, theta: f64) -> Matrix2<f64> {
        let coupling = self.m * self.l * theta.cos();
        Matrix2::new(
            self.mc + self.m,
            coupling,
            coupling,
            self.m * self.l * self.l,
        )
    }
}

impl Lagrangian<2> for CartPendulum {
    type Scalar = f64;
    const COORDINATES: [&'static str; 2] = ["x", "theta"];
    fn mass_matrix(&self, _t: f64, q: &Vector2<f64>) -> Matrix2<f64> {
        self.mass(q[1])
    }
    fn forcing(&self, _t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Vector2<f64> {
        let s = q[1].sin();
        Vector2::new(
            self.m * self.l * s * qd[1] * qd[1],
            -self.m * self.g * self.l * s,
        )
    }
    fn kinetic_energy(&self, _t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> f64 {
        0.5 * qd.dot(&(self.mass(q[1]) * qd))
    }
    fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
        -self.m * self.g * self.l * q[1].cos()
    }
    fn momentum(&self, _t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Option<Vector2<f64>> {
        Some(self.mass(q[1]) * qd)
    }
    fn lagrangian_gradient(
        &self,
        _t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
    ) -> Option<Vector2<f64>> {
        let s = q[1].sin();
        let dtheta = -self.m * self.l * s * (qd[0] * qd[1] + self.g);
        Some(Vector2::new(0.0, dtheta))
    }
    fn nonconservative_forces(
        &self,
        _t: f64,
        _q: &Vector2<f64>,
        _qd: &Vector2<f64>,
    ) -> Option<Vector2<f64>> {
        Some(Vector2::zeros())
    }
    fn parameters_are_finite(&self) -> bool {
        [self.mc, self.m, self.l, self.g]
            .iter()
            .all(|p| p.is_finite())
    }
}

/// A mass `m` on a spring `k` with a dashpot `c`: `Q = −c ẋ`.
#[derive(Debug, Clone, Copy)]
pub(super) struct DampedSpring {
    pub(super) m: f64,
    pub(super) k: f64,
    pub(super) c: f64,
}

impl Lagrangian<1> for DampedSpring {
    type Scalar = f64;
    const COORDINATES: [&'static str; 1] = ["x"];
    fn mass_matrix(&self, _t: f64, _q: &Vector1<f64>) -> Matrix1<f64> {
        Matrix1::new(self.m)
    }
    fn forcing(&self, _t: f64, q: &Vector1<f64>, qd: &Vector1<f64>) -> Vector1<f64> {
        Vector1::new(-self.k * q[0] - self.c * qd[0])
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector1<f64>, qd: &Vector1<f64>) -> f64 {
        0.5 * self.m * qd[0] * qd[0]
    }
    fn potential_energy(&self, _t: f64, q: &Vector1<f64>) -> f64 {
        0.5 * self.k * q[0] * q[0]
    }
    fn momentum(&self, _t: f64, _q: &Vector1<f64>, qd: &Vector1<f64>) -> Option<Vector1<f64>> {
        Some(Vector1::new(self.m * qd[0]))
    }
    fn lagrangian_gradient(
        &self,
        _t: f64,
        q: &Vector1<f64>,
        _qd: &Vector1<f64>,
    ) -> Option<Vector1<f64>> {
        Some(Vector1::new(-self.k * q[0]))
    }
    fn nonconservative_forces(
        &self,
        _t: f64,
        _q: &Vector1<f64>,
        qd: &Vector1<f64>,
    ) -> Option<Vector1<f64>> {
        Some(Vector1::new(-self.c * qd[0]))
    }
    fn parameters_are_finite(&self) -> bool {
        [self.m, self.k, self.c].iter().all(|p| p.is_finite())
    }
}

/// Two unit masses on unit rods in gravity `g` (the README's double
/// pendulum).
pub(super) struct DoublePendulum {
    pub(super) g: f64,
}

impl Lagrangian<2> for DoublePendulum {
    type Scalar = f64;
    const COORDINATES: [&'static str; 2] = ["theta1", "theta2"];
    fn mass_matrix(&self, _t: f64, q: &Vector2<f64>) -> Matrix2<f64> {
        let c = (q[0] - q[1]).cos();
        Matrix2::new(2.0, c, c, 1.0)
    }
    fn forcing(&self, _t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Vector2<f64> {
        let s = (q[0] - q[1]).sin();
        Vector2::new(
            -s * qd[1] * qd[1] - 2.0 * self.g * q[0].sin(),
            s * qd[0] * qd[0] - self.g * q[1].sin(),
        )
    }
    fn kinetic_energy(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> f64 {
        0.5 * qd.dot(&(self.mass_matrix(t, q) * qd))
    }
    fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
        -2.0 * self.g * q[0].cos() - self.g * q[1].cos()
    }
}
