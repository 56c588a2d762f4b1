//! Hand-written models shared by the runtime tests, each chosen for a known
//! exact solution or a known way of breaking.
#![allow(dead_code)]

use lagrange_runtime::nalgebra::{Matrix2, RealField, SMatrix, SVector, Vector1, Vector2};
use lagrange_runtime::Lagrangian;

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

/// Largest `|state - exact|` (max norm over `q` and `q̇`) over a trajectory of
/// the coupled oscillator started at `(q0, q̇0)` at `t = 0`.
pub fn max_error<S: RealField + Copy>(
    model: &CoupledOscillator<S>,
    trajectory: &lagrange_runtime::Trajectory<S, 2>,
    q0: SVector<S, 2>,
    qdot0: SVector<S, 2>,
) -> S {
    trajectory.iter().fold(S::zero(), |worst, s| {
        let (q, qdot) = model.exact(s.t, q0, qdot0);
        worst.max((s.q - q).amax()).max((s.qdot - qdot).amax())
    })
}
