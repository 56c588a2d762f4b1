//! Models that break on purpose: a mass that vanishes, a forcing that turns
//! NaN, a solution that blows up in finite time, a well with no discrete
//! solution for a long step.

use lagrange_runtime::Lagrangian;
use lagrange_runtime::nalgebra::{Matrix2, SMatrix, Vector1, Vector2};

/// Two unit springs; the second mass vanishes at `t_s` (its row of `M`
/// becomes zero), so `M q̈ = f` stops determining `ÿ` there.
pub struct InertiaVanishes {
    pub t_s: f64,
}

impl Lagrangian<2> for InertiaVanishes {
    type Scalar = f64;
    const COORDINATES: [&'static str; 2] = ["x", "y"];

    fn mass_matrix(&self, t: f64, _q: &Vector2<f64>) -> Matrix2<f64> {
        Matrix2::new(1.0, 0.0, 0.0, if t < self.t_s { 1.0 } else { 0.0 })
    }
    fn forcing(&self, _t: f64, q: &Vector2<f64>, _qdot: &Vector2<f64>) -> Vector2<f64> {
        -q
    }
    fn kinetic_energy(&self, t: f64, q: &Vector2<f64>, qdot: &Vector2<f64>) -> f64 {
        0.5 * (qdot.transpose() * self.mass_matrix(t, q) * qdot)[0]
    }
    fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
        0.5 * q.norm_squared()
    }
}

/// A unit spring whose forcing returns NaN after `t_star`, as a model with a
/// `sqrt` of a quantity that turns negative would.
pub struct ForcingBreaksDown {
    pub t_star: f64,
}

impl Lagrangian<1> for ForcingBreaksDown {
    type Scalar = f64;
    const COORDINATES: [&'static str; 1] = ["x"];

    fn mass_matrix(&self, _t: f64, _q: &Vector1<f64>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(1.0)
    }
    fn forcing(&self, t: f64, q: &Vector1<f64>, _qdot: &Vector1<f64>) -> Vector1<f64> {
        Vector1::new(-q[0] + (self.t_star - t).min(0.0).sqrt())
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector1<f64>, qdot: &Vector1<f64>) -> f64 {
        0.5 * qdot[0] * qdot[0]
    }
    fn potential_energy(&self, _t: f64, q: &Vector1<f64>) -> f64 {
        0.5 * q[0] * q[0]
    }
}

/// `q̈ = 2 q³` from `q = q̇ = 1`: the solution `q = 1 / (1 - t)` reaches
/// infinity at `t = 1`, in finite time.
pub struct BlowUp;

impl Lagrangian<1> for BlowUp {
    type Scalar = f64;
    const COORDINATES: [&'static str; 1] = ["q"];

    fn mass_matrix(&self, _t: f64, _q: &Vector1<f64>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(1.0)
    }
    fn forcing(&self, _t: f64, q: &Vector1<f64>, _qdot: &Vector1<f64>) -> Vector1<f64> {
        Vector1::new(2.0 * q[0].powi(3))
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector1<f64>, qdot: &Vector1<f64>) -> f64 {
        0.5 * qdot[0] * qdot[0]
    }
    fn potential_energy(&self, _t: f64, q: &Vector1<f64>) -> f64 {
        -0.5 * q[0].powi(4)
    }
}

/// `q̈ = e^q` (`L = ½ q̇² + e^q`): pushed ever harder the further it goes.
/// For a step `h` the discrete Euler–Lagrange residual
/// `r(v) = p − v + (h/2) e^{q + h v/2}` is convex in `v` with minimum
/// `p + (2/h)(1 + ln(h²/4) + q)`, positive for a large enough `h`: then the
/// discrete equations have no solution at all.
pub struct ExponentialWell;

impl Lagrangian<1> for ExponentialWell {
    type Scalar = f64;
    const COORDINATES: [&'static str; 1] = ["q"];

    fn mass_matrix(&self, _t: f64, _q: &Vector1<f64>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(1.0)
    }
    fn forcing(&self, _t: f64, q: &Vector1<f64>, _qdot: &Vector1<f64>) -> Vector1<f64> {
        Vector1::new(q[0].exp())
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector1<f64>, qdot: &Vector1<f64>) -> f64 {
        0.5 * qdot[0] * qdot[0]
    }
    fn potential_energy(&self, _t: f64, q: &Vector1<f64>) -> f64 {
        -q[0].exp()
    }
    fn momentum(&self, _t: f64, _q: &Vector1<f64>, qdot: &Vector1<f64>) -> Option<Vector1<f64>> {
        Some(*qdot)
    }
    fn lagrangian_gradient(
        &self,
        _t: f64,
        q: &Vector1<f64>,
        _qdot: &Vector1<f64>,
    ) -> Option<Vector1<f64>> {
        Some(Vector1::new(q[0].exp()))
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
