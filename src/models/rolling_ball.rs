//! A uniform ball rolling without slipping on a horizontal plane: its
//! orientation a unit quaternion (so its `M` alone is singular, regular on
//! the rates `|q| = 1` allows) and two velocity constraints (the contact
//! point at rest). Both kinds of constraint in one small model, with a
//! closed form: it rolls in a straight line at constant speed, turning at
//! a constant rate in space.

use nalgebra::{Quaternion, UnitQuaternion, Vector2, Vector3, Vector6};

use crate::lagrangian;

lagrangian! {
    /// A solid uniform ball of mass `m` and radius `r`, its centre at
    /// `(x, y, r)`, its orientation the unit quaternion `w + a i + b j + c k`
    /// (body to space); `sx`, `sy`, `sz` its angular velocity in space,
    /// `2 Im(q̇ q̄)`. Rolling: the ball's point at the contact is at rest,
    /// `ẋ = r ω_y`, `ẏ = −r ω_x`; the multipliers are the friction force
    /// there (zero on a free roll).
    ///
    /// ```
    /// use lagrange::models::RollingBall;
    /// use lagrange::nalgebra::{UnitQuaternion, Vector2};
    /// use lagrange::prelude::*;
    ///
    /// let ball = RollingBall::new(1.0, 0.1);
    /// let (q0, v0) = ball.state(&UnitQuaternion::identity(), &Vector2::new(0.3, -0.2), 1.5);
    /// let run = Dop853::new().rtol(1e-12).atol(1e-12).integrate(&ball, 0.0, q0, v0, &[2.0])?;
    /// let end = run.last().unwrap();
    /// let exact = ball.rotation_at(&UnitQuaternion::identity(), &Vector2::new(0.3, -0.2), 1.5, 2.0);
    /// assert!((RollingBall::rotation(&end.q).angle_to(&exact)) < 1e-9);
    /// assert!((end.q[0] - 0.6).abs() < 1e-9 && (end.q[1] + 0.4).abs() < 1e-9);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub struct RollingBall {
        coordinates: x, y, w, a, b, c;
        parameters: m, r;
        let sx = 2*(w*dot(a) - a*dot(w) + b*dot(c) - c*dot(b));
        let sy = 2*(w*dot(b) - b*dot(w) + c*dot(a) - a*dot(c));
        let sz = 2*(w*dot(c) - c*dot(w) + a*dot(b) - b*dot(a));
        kinetic: m/2*(dot(x)^2 + dot(y)^2) + m*r^2/5*(sx^2 + sy^2 + sz^2);
        potential: 0;
        constraints:
            unit: w^2 + a^2 + b^2 + c^2 = 1,
            roll_x: dot(x) = r*sy,
            roll_y: dot(y) = -r*sx;
    }
}

impl RollingBall {
    /// The angular velocity in space of a ball rolling at `velocity` and
    /// turning about the vertical at `spin`: `(−v_y / r, v_x / r, spin)`.
    pub fn angular_velocity(&self, velocity: &Vector2<f64>, spin: f64) -> Vector3<f64> {
        Vector3::new(-velocity[1] / self.r, velocity[0] / self.r, spin)
    }

    /// A rolling state at the origin: orientation `rotation`, the centre
    /// moving at `velocity`, turning about the vertical at `spin`
    /// (`q̇ = ½ (0, ω) q`, `ω` in space).
    pub fn state(
        &self,
        rotation: &UnitQuaternion<f64>,
        velocity: &Vector2<f64>,
        spin: f64,
    ) -> (Vector6<f64>, Vector6<f64>) {
        let q = rotation.quaternion();
        let omega = self.angular_velocity(velocity, spin);
        let qdot = Quaternion::from_imag(omega) * q * 0.5;
        (
            Vector6::new(0.0, 0.0, q.w, q.i, q.j, q.k),
            Vector6::new(velocity[0], velocity[1], qdot.w, qdot.i, qdot.j, qdot.k),
        )
    }

    /// The rotation (body to space) of a state, normalized.
    pub fn rotation(q: &Vector6<f64>) -> UnitQuaternion<f64> {
        UnitQuaternion::from_quaternion(Quaternion::new(q[2], q[3], q[4], q[5]))
    }

    /// The exact rotation at `t` of the roll started by
    /// [`state`](Self::state): with no force but the contact's, the ball
    /// rolls in a straight line at constant speed and constant angular
    /// velocity `ω`, so `R(t) = exp(t ω) R(0)`.
    pub fn rotation_at(
        &self,
        rotation: &UnitQuaternion<f64>,
        velocity: &Vector2<f64>,
        spin: f64,
        t: f64,
    ) -> UnitQuaternion<f64> {
        UnitQuaternion::from_scaled_axis(self.angular_velocity(velocity, spin) * t) * rotation
    }
}
