//! A pendulum on a free cart, with Jacobians derived by hand.

use lagrange_runtime::Lagrangian;
use lagrange_runtime::nalgebra::{Matrix2, Vector2};

/// A pendulum (bob `m_p`, rod `l`) hanging from a cart (`m_c`) that slides
/// freely along `x`; `θ` from the downward vertical. The mass matrix
///
/// ```text
/// M(θ) = [[m_c + m_p,     m_p l cos θ],
///         [m_p l cos θ,   m_p l²     ]]
/// ```
///
/// depends on the configuration, so the Hamiltonian is not separable.
/// `T` is quadratic in `q̇` and nothing depends on `t`: the system is
/// reversible under `q̇ → −q̇` and conserves energy; `x` is cyclic, so it is
/// integrable (one degree of freedom once `p_x` is fixed).
///
/// With `exact_jacobians` it provides `residual_jacobians`, derived by hand.
pub struct CartPole {
    pub m_cart: f64,
    pub m_bob: f64,
    pub l: f64,
    pub g: f64,
    pub exact_jacobians: bool,
}

impl CartPole {
    /// Unit masses and rod, Earth's gravity.
    pub fn new(exact_jacobians: bool) -> Self {
        Self {
            m_cart: 1.0,
            m_bob: 1.0,
            l: 1.0,
            g: 9.81,
            exact_jacobians,
        }
    }
}

impl Lagrangian<2> for CartPole {
    type Scalar = f64;
    const COORDINATES: [&'static str; 2] = ["x", "theta"];

    fn mass_matrix(&self, _t: f64, q: &Vector2<f64>) -> Matrix2<f64> {
        let coupling = self.m_bob * self.l * q[1].cos();
        Matrix2::new(
            self.m_cart + self.m_bob,
            coupling,
            coupling,
            self.m_bob * self.l * self.l,
        )
    }
    fn forcing(&self, _t: f64, q: &Vector2<f64>, qdot: &Vector2<f64>) -> Vector2<f64> {
        let (s, ml) = (q[1].sin(), self.m_bob * self.l);
        Vector2::new(ml * s * qdot[1] * qdot[1], -ml * self.g * s)
    }
    fn kinetic_energy(&self, t: f64, q: &Vector2<f64>, qdot: &Vector2<f64>) -> f64 {
        0.5 * (qdot.transpose() * self.mass_matrix(t, q) * qdot)[0]
    }
    fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
        -self.m_bob * self.g * self.l * q[1].cos()
    }
    /// `r = M q̈ − f`: only `θ` and `θ̇` appear in it.
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
        let ((s, c), ml) = (q[1].sin_cos(), self.m_bob * self.l);
        let dr_dtheta = Vector2::new(
            -ml * s * qddot[1] - ml * c * qdot[1] * qdot[1],
            -ml * s * qddot[0] + ml * self.g * c,
        );
        let dr_dq = Matrix2::from_columns(&[Vector2::zeros(), dr_dtheta]);
        let dr_dthetadot = Vector2::new(-2.0 * ml * s * qdot[1], 0.0);
        let dr_dqdot = Matrix2::from_columns(&[Vector2::zeros(), dr_dthetadot]);
        Some((dr_dq, dr_dqdot))
    }
}
