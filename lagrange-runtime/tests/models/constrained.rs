//! Models with holonomic constraints, written by hand as `lagrangian!`
//! will write them: `Holonomic<N, C>` and the one-line `visit_constraints`.

use lagrange_runtime::constraints::Visitor;
use lagrange_runtime::nalgebra::{
    Matrix1x2, Matrix2, Matrix2x3, Matrix3, RealField, SMatrix, SVector, Vector1, Vector2, Vector3,
};
use lagrange_runtime::{Holonomic, Lagrangian};

/// A bob of mass `m` on a rod of length `l`, in Cartesian coordinates
/// `(x, y)`, `y` up: `T = m/2 (ẋ² + ẏ²)`, `V = m g y`, held by the one
/// constraint `φ = x² + y² − l²`, so `G = 2 (x, y)` and
/// `γ = 2 (ẋ² + ẏ²)`. The rod pulls with `−Gᵀ λ = −2 λ (x, y)`: a tension
/// `T = 2 l λ`, which for the pendulum `θ = atan2(x, −y)` is
/// `m (g cos θ + l θ̇²)`.
pub struct CartesianPendulum<S> {
    pub m: S,
    pub l: S,
    pub g: S,
}

impl CartesianPendulum<f64> {
    /// Unit mass and rod, Earth's gravity.
    pub fn unit() -> Self {
        Self {
            m: 1.0,
            l: 1.0,
            g: 9.81,
        }
    }
}

impl<S: RealField + Copy> CartesianPendulum<S> {
    /// The state at angle `θ` from the downward vertical, turning at `θ̇`.
    pub fn state(&self, theta: S, theta_dot: S) -> (Vector2<S>, Vector2<S>) {
        let (s, c) = (theta.sin(), theta.cos());
        let l = self.l;
        (
            Vector2::new(l * s, -l * c),
            Vector2::new(l * c * theta_dot, l * s * theta_dot),
        )
    }

    /// `(θ, θ̇)` of a state on the constraint.
    pub fn angle(&self, q: &Vector2<S>, qdot: &Vector2<S>) -> (S, S) {
        let theta = q[0].atan2(-q[1]);
        let r2 = q.norm_squared();
        (theta, (q[0] * qdot[1] - q[1] * qdot[0]) / r2)
    }

    /// The rod's tension `m (g cos θ + l θ̇²)` of the pendulum at `(θ, θ̇)`.
    pub fn tension(&self, theta: S, theta_dot: S) -> S {
        self.m * (self.g * theta.cos() + self.l * theta_dot * theta_dot)
    }
}

impl<S: RealField + Copy> Lagrangian<2> for CartesianPendulum<S> {
    type Scalar = S;
    const COORDINATES: [&'static str; 2] = ["x", "y"];

    /// No forces but the potential's (the variational integrator asks).
    fn nonconservative_forces(
        &self,
        _t: S,
        _q: &lagrange_runtime::nalgebra::SVector<S, 2>,
        _qdot: &lagrange_runtime::nalgebra::SVector<S, 2>,
    ) -> Option<lagrange_runtime::nalgebra::SVector<S, 2>> {
        Some(lagrange_runtime::nalgebra::SVector::zeros())
    }

    fn mass_matrix(&self, _t: S, _q: &Vector2<S>) -> Matrix2<S> {
        Matrix2::identity() * self.m
    }
    fn forcing(&self, _t: S, _q: &Vector2<S>, _qdot: &Vector2<S>) -> Vector2<S> {
        Vector2::new(S::zero(), -self.m * self.g)
    }
    fn kinetic_energy(&self, _t: S, _q: &Vector2<S>, qdot: &Vector2<S>) -> S {
        self.m * qdot.norm_squared() / nalgebra_two()
    }
    fn potential_energy(&self, _t: S, q: &Vector2<S>) -> S {
        self.m * self.g * q[1]
    }
    fn momentum(&self, _t: S, _q: &Vector2<S>, qdot: &Vector2<S>) -> Option<Vector2<S>> {
        Some(qdot * self.m)
    }
    fn lagrangian_gradient(
        &self,
        _t: S,
        _q: &Vector2<S>,
        _qdot: &Vector2<S>,
    ) -> Option<Vector2<S>> {
        Some(Vector2::new(S::zero(), -self.m * self.g))
    }
    fn visit_constraints<V: Visitor<S, 2>>(&self, visitor: V) -> Option<V::Output> {
        Some(visitor.visit::<Self, 1>(self, Default::default()))
    }
}

impl<S: RealField + Copy> Holonomic<2, 1> for CartesianPendulum<S> {
    const CONSTRAINTS: [&'static str; 1] = ["rod"];

    fn constraints(&self, _t: S, q: &Vector2<S>) -> Vector1<S> {
        Vector1::new(q.norm_squared() - self.l * self.l)
    }
    fn constraint_jacobian(&self, _t: S, q: &Vector2<S>) -> Matrix1x2<S> {
        Matrix1x2::new(q[0] + q[0], q[1] + q[1])
    }
    fn constraint_velocities(&self, _t: S, q: &Vector2<S>, qdot: &Vector2<S>) -> Vector1<S> {
        Vector1::new(nalgebra_two::<S>() * q.dot(qdot))
    }
    fn constraint_bias(&self, _t: S, _q: &Vector2<S>, qdot: &Vector2<S>) -> Vector1<S> {
        Vector1::new(nalgebra_two::<S>() * qdot.norm_squared())
    }
}

fn nalgebra_two<S: RealField + Copy>() -> S {
    S::one() + S::one()
}

/// A unit mass free in `(x, y, z)`, held by two constraints that become
/// parallel at `t = 1`: `φ₁ = z` (the plane) and `φ₂ = z − (1 − t) y`. For
/// `t ≠ 1` they pin `y = z = 0` and `x` moves freely; at `t = 1` their
/// gradients `(0, 0, 1)` and `(0, t − 1, 1)` coincide, and `G M⁻¹ Gᵀ` is
/// singular: a dead centre in time.
pub struct ParallelAtOne;

impl Lagrangian<3> for ParallelAtOne {
    type Scalar = f64;
    const COORDINATES: [&'static str; 3] = ["x", "y", "z"];

    /// No forces but the potential's (the variational integrator asks).
    fn nonconservative_forces(
        &self,
        _t: f64,
        _q: &lagrange_runtime::nalgebra::SVector<f64, 3>,
        _qdot: &lagrange_runtime::nalgebra::SVector<f64, 3>,
    ) -> Option<lagrange_runtime::nalgebra::SVector<f64, 3>> {
        Some(lagrange_runtime::nalgebra::SVector::zeros())
    }

    fn mass_matrix(&self, _t: f64, _q: &Vector3<f64>) -> Matrix3<f64> {
        Matrix3::identity()
    }
    fn forcing(&self, _t: f64, _q: &Vector3<f64>, _qdot: &Vector3<f64>) -> Vector3<f64> {
        Vector3::zeros()
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector3<f64>, qdot: &Vector3<f64>) -> f64 {
        0.5 * qdot.norm_squared()
    }
    fn potential_energy(&self, _t: f64, _q: &Vector3<f64>) -> f64 {
        0.0
    }
    fn momentum(&self, _t: f64, _q: &Vector3<f64>, qdot: &Vector3<f64>) -> Option<Vector3<f64>> {
        Some(*qdot)
    }
    fn lagrangian_gradient(
        &self,
        _: f64,
        _: &Vector3<f64>,
        _: &Vector3<f64>,
    ) -> Option<Vector3<f64>> {
        Some(Vector3::zeros())
    }
    fn visit_constraints<V: Visitor<f64, 3>>(&self, visitor: V) -> Option<V::Output> {
        Some(visitor.visit::<Self, 2>(self, Default::default()))
    }
}

impl Holonomic<3, 2> for ParallelAtOne {
    const CONSTRAINTS: [&'static str; 2] = ["plane", "tilted plane"];

    fn constraints(&self, t: f64, q: &Vector3<f64>) -> SVector<f64, 2> {
        SVector::<f64, 2>::new(q[2], q[2] - (1.0 - t) * q[1])
    }
    fn constraint_jacobian(&self, t: f64, _q: &Vector3<f64>) -> Matrix2x3<f64> {
        Matrix2x3::new(0.0, 0.0, 1.0, 0.0, t - 1.0, 1.0)
    }
    fn constraint_velocities(
        &self,
        t: f64,
        q: &Vector3<f64>,
        qdot: &Vector3<f64>,
    ) -> SVector<f64, 2> {
        // d/dt (z − (1 − t) y) = ż − (1 − t) ẏ + y.
        SVector::<f64, 2>::new(qdot[2], qdot[2] - (1.0 - t) * qdot[1] + q[1])
    }
    fn constraint_bias(&self, _t: f64, _q: &Vector3<f64>, qdot: &Vector3<f64>) -> SVector<f64, 2> {
        // φ̈₂ = z̈ − (1 − t) ÿ + 2 ẏ.
        SVector::<f64, 2>::new(0.0, 2.0 * qdot[1])
    }
}

/// `φ = x²` on a unit mass in the plane at `x = 0`: satisfied, but its
/// gradient vanishes, so the constraint force is undetermined from the start.
pub struct VanishingGradient;

impl Lagrangian<2> for VanishingGradient {
    type Scalar = f64;
    const COORDINATES: [&'static str; 2] = ["x", "y"];

    /// No forces but the potential's (the variational integrator asks).
    fn nonconservative_forces(
        &self,
        _t: f64,
        _q: &lagrange_runtime::nalgebra::SVector<f64, 2>,
        _qdot: &lagrange_runtime::nalgebra::SVector<f64, 2>,
    ) -> Option<lagrange_runtime::nalgebra::SVector<f64, 2>> {
        Some(lagrange_runtime::nalgebra::SVector::zeros())
    }

    fn mass_matrix(&self, _t: f64, _q: &Vector2<f64>) -> Matrix2<f64> {
        Matrix2::identity()
    }
    fn forcing(&self, _t: f64, _q: &Vector2<f64>, _qdot: &Vector2<f64>) -> Vector2<f64> {
        Vector2::new(1.0, 0.0)
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector2<f64>, qdot: &Vector2<f64>) -> f64 {
        0.5 * qdot.norm_squared()
    }
    fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
        -q[0]
    }
    fn momentum(&self, _t: f64, _q: &Vector2<f64>, qdot: &Vector2<f64>) -> Option<Vector2<f64>> {
        Some(*qdot)
    }
    fn lagrangian_gradient(
        &self,
        _: f64,
        _: &Vector2<f64>,
        _: &Vector2<f64>,
    ) -> Option<Vector2<f64>> {
        Some(Vector2::new(1.0, 0.0))
    }
    fn visit_constraints<V: Visitor<f64, 2>>(&self, visitor: V) -> Option<V::Output> {
        Some(visitor.visit::<Self, 1>(self, Default::default()))
    }
}

impl Holonomic<2, 1> for VanishingGradient {
    const CONSTRAINTS: [&'static str; 1] = ["x squared"];

    fn constraints(&self, _t: f64, q: &Vector2<f64>) -> Vector1<f64> {
        Vector1::new(q[0] * q[0])
    }
    fn constraint_jacobian(&self, _t: f64, q: &Vector2<f64>) -> SMatrix<f64, 1, 2> {
        SMatrix::<f64, 1, 2>::new(2.0 * q[0], 0.0)
    }
    fn constraint_velocities(
        &self,
        _t: f64,
        q: &Vector2<f64>,
        qdot: &Vector2<f64>,
    ) -> Vector1<f64> {
        Vector1::new(2.0 * q[0] * qdot[0])
    }
    fn constraint_bias(&self, _t: f64, _q: &Vector2<f64>, qdot: &Vector2<f64>) -> Vector1<f64> {
        Vector1::new(2.0 * qdot[0] * qdot[0])
    }
}
