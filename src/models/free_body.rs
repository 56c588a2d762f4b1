//! A torque-free rigid body whose orientation is a unit quaternion: no
//! chart, so no pole where the coordinates lock (Euler angles lock where
//! two of their axes line up). Its kinetic energy sees three of the four
//! quaternion rates, so `M` alone is singular (rank 3 of 4); the constraint
//! `|q| = 1` fixes the fourth, and `lagrangian!` accepts the model because
//! `M` is regular on the rates the constraint allows.

use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3, Vector4};

use crate::lagrangian;

lagrangian! {
    /// A rigid body with principal moments of inertia `i1`, `i2`, `i3`
    /// about its mass centre, free of torques, its orientation the unit
    /// quaternion `w + x i + y j + z k` (body to space). The body rates
    /// `ω = 2 Im(q̄ q̇)` are three `let`s, and the kinetic energy is
    /// Euler's `½ (i1 ω1² + i2 ω2² + i3 ω3²)`.
    ///
    /// ```
    /// use lagrange::models::FreeBody;
    /// use lagrange::nalgebra::{UnitQuaternion, Vector3};
    /// use lagrange::prelude::*;
    ///
    /// let body = FreeBody::new(1.0, 2.0, 3.0);
    /// // Spun about its intermediate axis, with a small perturbation.
    /// let (q0, v0) = FreeBody::state(&UnitQuaternion::identity(), &Vector3::new(0.01, 2.0, 0.01));
    /// let run = Dop853::new().rtol(1e-10).atol(1e-10).integrate(&body, 0.0, q0, v0, &[10.0])?;
    /// let end = run.last().unwrap();
    /// // The angular momentum in space is kept; |q| = 1 by the projection.
    /// let l0 = body.angular_momentum(&q0, &v0);
    /// assert!((body.angular_momentum(&end.q, &end.qdot) - l0).norm() < 1e-7 * l0.norm());
    /// assert!((end.q.norm() - 1.0).abs() < 1e-14);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub struct FreeBody {
        coordinates: w, x, y, z;
        parameters: i1, i2, i3;
        let omega1 = 2*(w*dot(x) - x*dot(w) - y*dot(z) + z*dot(y));
        let omega2 = 2*(w*dot(y) - y*dot(w) - z*dot(x) + x*dot(z));
        let omega3 = 2*(w*dot(z) - z*dot(w) - x*dot(y) + y*dot(x));
        kinetic: (i1*omega1^2 + i2*omega2^2 + i3*omega3^2)/2;
        potential: 0;
        constraints: unit: w^2 + x^2 + y^2 + z^2 = 1;
    }
}

impl FreeBody {
    /// The state `(q, q̇)` of the body at orientation `rotation` turning at
    /// body rates `omega`: `q̇ = ½ q (0, ω)`.
    pub fn state(
        rotation: &UnitQuaternion<f64>,
        omega: &Vector3<f64>,
    ) -> (Vector4<f64>, Vector4<f64>) {
        let q = rotation.quaternion();
        let qdot = q * Quaternion::from_imag(*omega) * 0.5;
        (
            Vector4::new(q.w, q.i, q.j, q.k),
            Vector4::new(qdot.w, qdot.i, qdot.j, qdot.k),
        )
    }

    /// The rotation (body to space) of a state's quaternion, normalized.
    pub fn rotation(q: &Vector4<f64>) -> UnitQuaternion<f64> {
        UnitQuaternion::from_quaternion(Quaternion::new(q[0], q[1], q[2], q[3]))
    }

    /// The body rates `ω = 2 Im(q̄ q̇)`.
    pub fn body_rates(q: &Vector4<f64>, qdot: &Vector4<f64>) -> Vector3<f64> {
        let q = Quaternion::new(q[0], q[1], q[2], q[3]);
        let qdot = Quaternion::new(qdot[0], qdot[1], qdot[2], qdot[3]);
        (q.conjugate() * qdot).imag() * 2.0
    }

    /// The angular momentum in space, `R(q) I ω`: constant for a free body.
    pub fn angular_momentum(&self, q: &Vector4<f64>, qdot: &Vector4<f64>) -> Vector3<f64> {
        let inertia = Matrix3::from_diagonal(&Vector3::new(self.i1, self.i2, self.i3));
        Self::rotation(q) * (inertia * Self::body_rates(q, qdot))
    }
}
