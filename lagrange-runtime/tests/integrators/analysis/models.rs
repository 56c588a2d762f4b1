//! Hand-written models of the analysis tests, each for one way an
//! analysis must answer or refuse.

use lagrange_runtime::nalgebra::{Matrix2, SMatrix, SVector, Vector1, Vector2};
use lagrange_runtime::{Actuated, Lagrangian};

/// Implements the energies of a model whose energies the tests never read.
macro_rules! no_energies {
    ($n:literal) => {
        fn kinetic_energy(&self, _: f64, _: &SVector<f64, $n>, _: &SVector<f64, $n>) -> f64 {
            0.0
        }
        fn potential_energy(&self, _: f64, _: &SVector<f64, $n>) -> f64 {
            0.0
        }
    };
}

/// A unit mass on a saturating spring, `f = −atan(x)`: one equilibrium,
/// `x = 0`, but Newton's method overshoots it ever further from any guess
/// with `|x| > 1.39` (where `x − (1 + x²) atan x` is larger than `x` in
/// size), the textbook failure.
pub struct SaturatingSpring;

impl Lagrangian<1> for SaturatingSpring {
    type Scalar = f64;
    const COORDINATES: [&'static str; 1] = ["x"];
    fn mass_matrix(&self, _: f64, _: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(1.0)
    }
    fn forcing(&self, _: f64, q: &SVector<f64, 1>, _: &SVector<f64, 1>) -> SVector<f64, 1> {
        Vector1::new(-q[0].atan())
    }
    no_energies!(1);
}

/// A body of mass `m` falling in a uniform field, `f = −m g`: no
/// equilibrium at all, and `∂f/∂q = 0`.
pub struct Falling {
    pub m: f64,
    pub g: f64,
}

impl Lagrangian<1> for Falling {
    type Scalar = f64;
    const COORDINATES: [&'static str; 1] = ["y"];
    fn mass_matrix(&self, _: f64, _: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(self.m)
    }
    fn forcing(&self, _: f64, _: &SVector<f64, 1>, _: &SVector<f64, 1>) -> SVector<f64, 1> {
        Vector1::new(-self.m * self.g)
    }
    no_energies!(1);
}

/// A unit mass in the plane on an isotropic spring `k` with a circulatory
/// (follower-like) force `c (y, −x)`: `K = [[k, −c], [c, k]]` is not
/// symmetric, the origin is still an equilibrium, and there are no real
/// modes (the eigenvalues of `A` are `±√(−k ± i c)`: flutter).
pub struct Circulatory {
    pub k: f64,
    pub c: f64,
}

impl Lagrangian<2> for Circulatory {
    type Scalar = f64;
    const COORDINATES: [&'static str; 2] = ["x", "y"];
    fn mass_matrix(&self, _: f64, _: &SVector<f64, 2>) -> SMatrix<f64, 2, 2> {
        Matrix2::identity()
    }
    fn forcing(&self, _: f64, q: &SVector<f64, 2>, _: &SVector<f64, 2>) -> SVector<f64, 2> {
        Vector2::new(
            -self.k * q[0] + self.c * q[1],
            -self.k * q[1] - self.c * q[0],
        )
    }
    no_energies!(2);
}

/// A mass `m` on a spring `k` with a damper `c`, pushed by a force `u`
/// through a linkage that transmits `cos x` of it:
/// `m ẍ = −k x − c ẋ + u cos x`. So `∂f/∂u = cos x` depends on the state,
/// and `∂f/∂x = −k − u sin x` on the input. Exact Jacobians, by hand:
/// `∂r/∂x = k + u sin x`, `∂r/∂ẋ = c` (`M` is constant).
#[derive(Clone, Copy)]
pub struct PushedSpring {
    pub m: f64,
    pub k: f64,
    pub c: f64,
    pub u: f64,
}

impl Lagrangian<1> for PushedSpring {
    type Scalar = f64;
    const COORDINATES: [&'static str; 1] = ["x"];
    fn mass_matrix(&self, _: f64, _: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(self.m)
    }
    fn forcing(&self, _: f64, q: &SVector<f64, 1>, v: &SVector<f64, 1>) -> SVector<f64, 1> {
        Vector1::new(-self.k * q[0] - self.c * v[0] + self.u * q[0].cos())
    }
    fn residual_jacobians(
        &self,
        _: f64,
        q: &SVector<f64, 1>,
        _: &SVector<f64, 1>,
        _: &SVector<f64, 1>,
    ) -> Option<(SMatrix<f64, 1, 1>, SMatrix<f64, 1, 1>)> {
        Some((
            SMatrix::<f64, 1, 1>::new(self.k + self.u * q[0].sin()),
            SMatrix::<f64, 1, 1>::new(self.c),
        ))
    }
    no_energies!(1);
}

impl Actuated<1, 1> for PushedSpring {
    const INPUTS: [&'static str; 1] = ["u"];
    fn inputs(&self) -> SVector<f64, 1> {
        Vector1::new(self.u)
    }
    fn set_inputs(&mut self, u: &SVector<f64, 1>) {
        self.u = u[0];
    }
    fn input_jacobian(
        &self,
        _: f64,
        q: &SVector<f64, 1>,
        _: &SVector<f64, 1>,
    ) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(q[0].cos())
    }
}
