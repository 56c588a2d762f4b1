//! A stiff, nonlinear pendulum on a spring, with Jacobians derived by hand.

use lagrange_runtime::Lagrangian;
use lagrange_runtime::nalgebra::{Matrix2, Vector2};

/// A pendulum bob on a stiff, damped spring, in polar coordinates `(r, θ)`:
/// `T = ½ m (ṙ² + r² θ̇²)`, `V = −m g r cos θ + ½ k (r − l)²`, and a damper
/// `c` along the spring. Nonlinear, with a mass matrix that depends on `q`,
/// and stiff for large `k` (the spring vibrates at `√(k/m)`, the pendulum
/// swings at `≈ √(g/l)`).
///
/// Its exact residual Jacobians are written out by hand, and reported when
/// `exact_jacobians` is set.
pub struct ElasticPendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub k: f64,
    pub c: f64,
    pub exact_jacobians: bool,
}

impl Lagrangian<2> for ElasticPendulum {
    type Scalar = f64;
    const COORDINATES: [&'static str; 2] = ["r", "theta"];

    fn mass_matrix(&self, _t: f64, q: &Vector2<f64>) -> Matrix2<f64> {
        Matrix2::new(self.m, 0.0, 0.0, self.m * q[0] * q[0])
    }
    fn forcing(&self, _t: f64, q: &Vector2<f64>, qdot: &Vector2<f64>) -> Vector2<f64> {
        let (m, g) = (self.m, self.g);
        let ((r, th), (rd, thd)) = ((q[0], q[1]), (qdot[0], qdot[1]));
        Vector2::new(
            m * r * thd * thd + m * g * th.cos() - self.k * (r - self.l) - self.c * rd,
            -2.0 * m * r * rd * thd - m * g * r * th.sin(),
        )
    }
    fn kinetic_energy(&self, _t: f64, q: &Vector2<f64>, qdot: &Vector2<f64>) -> f64 {
        0.5 * self.m * (qdot[0] * qdot[0] + q[0] * q[0] * qdot[1] * qdot[1])
    }
    fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
        -self.m * self.g * q[0] * q[1].cos() + 0.5 * self.k * (q[0] - self.l).powi(2)
    }
    /// `r = M q̈ − f`: `r₁ = m r̈ − m r θ̇² − m g cos θ + k (r − l) + c ṙ`,
    /// `r₂ = m r² θ̈ + 2 m r ṙ θ̇ + m g r sin θ`.
    fn residual_jacobians(
        &self,
        _t: f64,
        q: &Vector2<f64>,
        qdot: &Vector2<f64>,
        qddot: &Vector2<f64>,
    ) -> Option<(Matrix2<f64>, Matrix2<f64>)> {
        if !self.exact_jacobians {
            return None;
        }
        let (m, g) = (self.m, self.g);
        let ((r, th), (rd, thd), thdd) = ((q[0], q[1]), (qdot[0], qdot[1]), qddot[1]);
        let d_q = Matrix2::new(
            self.k - m * thd * thd,
            m * g * th.sin(),
            2.0 * m * r * thdd + 2.0 * m * rd * thd + m * g * th.sin(),
            m * g * r * th.cos(),
        );
        let d_qdot = Matrix2::new(
            self.c,
            -2.0 * m * r * thd,
            2.0 * m * r * thd,
            2.0 * m * r * rd,
        );
        Some((d_q, d_qdot))
    }
}

impl ElasticPendulum {
    /// `m = l = 1`, `g = 9.81`, a spring `k = 1e4` (32× faster than the
    /// swing) damped by `c = 20`, Jacobians by finite differences.
    pub fn stiff() -> Self {
        Self {
            m: 1.0,
            l: 1.0,
            g: 9.81,
            k: 1e4,
            c: 20.0,
            exact_jacobians: false,
        }
    }

    /// Released at θ = 0.5 from rest with the spring at its static stretch.
    pub fn start(&self) -> (Vector2<f64>, Vector2<f64>) {
        let theta: f64 = 0.5;
        let r = self.l + self.m * self.g * theta.cos() / self.k;
        (Vector2::new(r, theta), Vector2::zeros())
    }
}
