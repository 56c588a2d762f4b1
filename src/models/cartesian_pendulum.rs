//! The simple pendulum in the coordinates a user knows: the bob's `x` and
//! `y`, held on a circle by a rod. The smallest closed-loop problem, with an
//! exact answer: the θ pendulum ([`Pendulum`](super::Pendulum)), whose
//! angle is `atan2(x, −y)`, and the rod tension `m (g cos θ + l θ̇²)`.

use nalgebra::Vector2;

use crate::lagrangian;

lagrangian! {
    /// A point mass `m` on a rod of length `l` about the origin, in
    /// Cartesian coordinates, `y` up. The constraint is written in square
    /// metres, so its multiplier is the tension divided by `2 l`.
    ///
    /// ```
    /// use lagrange::models::CartesianPendulum;
    /// use lagrange::prelude::*;
    ///
    /// let pendulum = CartesianPendulum::new(1.0, 1.0, 9.81);
    /// let (q0, v0) = pendulum.state(1.0, 0.0); // released at 1 rad
    /// let times = [0.5, 1.0];
    ///
    /// // Projected back onto the rod after every step (the default).
    /// let run = Dopri5::new().integrate(&pendulum, 0.0, q0, v0, &times)?;
    /// for s in lagrange::constraints::annotate(&pendulum, &run)? {
    ///     assert!(s.residual[0].abs() < 1e-12); // x² + y² − l², at rounding
    ///     let tension = 2.0 * pendulum.l * s.multipliers[0];
    ///     assert!((tension - pendulum.tension(&s.q, &s.qdot)).abs() < 1e-9);
    /// }
    ///
    /// // No drift control: the rod stretches by the method's error.
    /// let loose = Rk4::new(1e-2).integrate(&pendulum.with_drift(Drift::None), 0.0, q0, v0, &times)?;
    /// let end = loose.last().unwrap();
    /// assert!(pendulum.constraints(end.t, &end.q)[0].abs() > 1e-12);
    ///
    /// // An inconsistent start, refused rather than projected.
    /// let strict = pendulum.with_initial_conditions(InitialConditions::Reject);
    /// let off = q0 * 1.01;
    /// assert!(Dopri5::new().integrate(&strict, 0.0, off, v0, &times).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub struct CartesianPendulum {
        coordinates: x, y;
        parameters: m, l, g;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
        constraints: rod: x^2 + y^2 = l^2;
    }
}

impl CartesianPendulum {
    /// The state `(q, q̇)` of the bob at angle `θ` from the downward
    /// vertical with angular velocity `θ̇`: on the circle, moving along it.
    pub fn state(&self, theta: f64, theta_dot: f64) -> (Vector2<f64>, Vector2<f64>) {
        let (s, c) = theta.sin_cos();
        (
            Vector2::new(self.l * s, -self.l * c),
            Vector2::new(self.l * c * theta_dot, self.l * s * theta_dot),
        )
    }

    /// The rod tension `m (g cos θ + l θ̇²)` at a state on the circle: the
    /// radial force that keeps the bob on it.
    pub fn tension(&self, q: &Vector2<f64>, qdot: &Vector2<f64>) -> f64 {
        let cos_theta = -q[1] / self.l;
        self.m * (self.g * cos_theta + qdot.norm_squared() / self.l)
    }
}
