//! Models with unilateral contacts, written by hand (`Contacts<N, K>`):
//! a particle on a sphere, and a ladder between a floor and a wall.

use lagrange_runtime::Lagrangian;
use lagrange_runtime::contact::{ContactLaw, Contacts};
use lagrange_runtime::nalgebra::{Matrix2, SMatrix, SVector, Vector2, Vector3};

use super::CartesianPendulum;

/// A particle of unit mass outside a frictionless sphere (a circle in the
/// vertical plane) of radius `r` centred at the origin, in Cartesian
/// coordinates `(x, y)`, `y` up, under gravity `g`. The gap is the
/// distance from the surface, `√(x² + y²) − r`, so the multiplier is the
/// normal force in newtons.
pub struct OnSphere {
    pub r: f64,
    pub g: f64,
}

impl Lagrangian<2> for OnSphere {
    type Scalar = f64;
    const COORDINATES: [&'static str; 2] = ["x", "y"];
    fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 2>) -> Matrix2<f64> {
        Matrix2::identity()
    }
    fn forcing(&self, _t: f64, _q: &SVector<f64, 2>, _qd: &SVector<f64, 2>) -> Vector2<f64> {
        Vector2::new(0.0, -self.g)
    }
    fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 2>, qd: &SVector<f64, 2>) -> f64 {
        0.5 * qd.norm_squared()
    }
    fn potential_energy(&self, _t: f64, q: &SVector<f64, 2>) -> f64 {
        self.g * q[1]
    }
}

impl Contacts<2, 1> for OnSphere {
    const CONTACTS: [&'static str; 1] = ["sphere"];
    fn gaps(&self, _t: f64, q: &SVector<f64, 2>) -> SVector<f64, 1> {
        SVector::<f64, 1>::new(q.norm() - self.r)
    }
    fn gap_jacobian(&self, _t: f64, q: &SVector<f64, 2>) -> SMatrix<f64, 1, 2> {
        (q / q.norm()).transpose()
    }
    fn gap_velocities(
        &self,
        _t: f64,
        q: &SVector<f64, 2>,
        qd: &SVector<f64, 2>,
    ) -> SVector<f64, 1> {
        SVector::<f64, 1>::new(q.dot(qd) / q.norm())
    }
    fn gap_bias(&self, _t: f64, q: &SVector<f64, 2>, qd: &SVector<f64, 2>) -> SVector<f64, 1> {
        // d/dt (q/|q|) · q̇ = (|q̇|² − ṙ²)/|q|, ṙ = q·q̇/|q|.
        let r = q.norm();
        let rdot = q.dot(qd) / r;
        SVector::<f64, 1>::new((qd.norm_squared() - rdot * rdot) / r)
    }
    fn contact_laws(&self) -> [ContactLaw<f64>; 1] {
        [ContactLaw::frictionless(0.0)]
    }
}

/// A uniform ladder of mass `m` and length `l` between a frictionless
/// floor (`y = 0`) and wall (`x = 0`), in the coordinates of its centre
/// `(x, y)` and its angle `θ` from the floor: the top `(x − l/2 cos θ,
/// y + l/2 sin θ)` against the wall, the foot `(x + l/2 cos θ, y − l/2 sin
/// θ)` on the floor.
pub struct Ladder {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

impl Ladder {
    /// At rest at angle `θ₀`, touching both.
    pub fn at_rest(&self, theta0: f64) -> (Vector3<f64>, Vector3<f64>) {
        let h = self.l / 2.0;
        (
            Vector3::new(h * theta0.cos(), h * theta0.sin(), theta0),
            Vector3::zeros(),
        )
    }
}

impl Lagrangian<3> for Ladder {
    type Scalar = f64;
    const COORDINATES: [&'static str; 3] = ["x", "y", "theta"];
    fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 3>) -> SMatrix<f64, 3, 3> {
        SMatrix::<f64, 3, 3>::from_diagonal(&Vector3::new(
            self.m,
            self.m,
            self.m * self.l * self.l / 12.0,
        ))
    }
    fn forcing(&self, _t: f64, _q: &SVector<f64, 3>, _qd: &SVector<f64, 3>) -> Vector3<f64> {
        Vector3::new(0.0, -self.m * self.g, 0.0)
    }
    fn kinetic_energy(&self, t: f64, q: &SVector<f64, 3>, qd: &SVector<f64, 3>) -> f64 {
        0.5 * qd.dot(&(self.mass_matrix(t, q) * qd))
    }
    fn potential_energy(&self, _t: f64, q: &SVector<f64, 3>) -> f64 {
        self.m * self.g * q[1]
    }
}

impl Contacts<3, 2> for Ladder {
    const CONTACTS: [&'static str; 2] = ["wall", "floor"];
    fn gaps(&self, _t: f64, q: &SVector<f64, 3>) -> SVector<f64, 2> {
        let h = self.l / 2.0;
        Vector2::new(q[0] - h * q[2].cos(), q[1] - h * q[2].sin())
    }
    fn gap_jacobian(&self, _t: f64, q: &SVector<f64, 3>) -> SMatrix<f64, 2, 3> {
        let h = self.l / 2.0;
        let (s, c) = q[2].sin_cos();
        SMatrix::<f64, 2, 3>::new(1.0, 0.0, h * s, 0.0, 1.0, -h * c)
    }
    fn gap_velocities(&self, t: f64, q: &SVector<f64, 3>, qd: &SVector<f64, 3>) -> SVector<f64, 2> {
        self.gap_jacobian(t, q) * qd
    }
    fn gap_bias(&self, _t: f64, q: &SVector<f64, 3>, qd: &SVector<f64, 3>) -> SVector<f64, 2> {
        let h = self.l / 2.0;
        let (s, c) = q[2].sin_cos();
        let w2 = qd[2] * qd[2];
        Vector2::new(h * c * w2, h * s * w2)
    }
    fn contact_laws(&self) -> [ContactLaw<f64>; 2] {
        [ContactLaw::frictionless(0.0); 2]
    }
}

/// A stop at `x = −l sin β` (β = 0.2) that the Cartesian pendulum's bob
/// strikes, restitution 0.5: a contact on a model with a constraint of
/// its own (the rod), held together with it.
impl Contacts<2, 1> for CartesianPendulum<f64> {
    const CONTACTS: [&'static str; 1] = ["stop"];
    fn gaps(&self, _t: f64, q: &SVector<f64, 2>) -> SVector<f64, 1> {
        SVector::<f64, 1>::new(q[0] + self.l * STOP.sin())
    }
    fn gap_jacobian(&self, _t: f64, _q: &SVector<f64, 2>) -> SMatrix<f64, 1, 2> {
        SMatrix::<f64, 1, 2>::new(1.0, 0.0)
    }
    fn gap_velocities(
        &self,
        _t: f64,
        _q: &SVector<f64, 2>,
        qd: &SVector<f64, 2>,
    ) -> SVector<f64, 1> {
        SVector::<f64, 1>::new(qd[0])
    }
    fn gap_bias(&self, _t: f64, _q: &SVector<f64, 2>, _qd: &SVector<f64, 2>) -> SVector<f64, 1> {
        SVector::<f64, 1>::zeros()
    }
    fn contact_laws(&self) -> [ContactLaw<f64>; 1] {
        [ContactLaw::frictionless(0.5)]
    }
}

/// The stop's angle β: the Cartesian pendulum's stop is at `θ = −β`.
pub const STOP: f64 = 0.2;
