//! The Chaplygin sleigh: a knife edge, the simplest velocity constraint,
//! with a closed form (Neimark & Fufaev, Dynamics of Nonholonomic Systems,
//! ch. 3; Bloch, Nonholonomic Mechanics and Control, §1.7).

use nalgebra::Vector3;

use crate::lagrangian;

lagrangian! {
    /// A body of mass `m` and moment of inertia `i` about its mass centre
    /// `(x, y)`, heading `theta`, on a knife edge at distance `a` behind the
    /// mass centre that cannot slide sideways: the edge's velocity across
    /// the heading is zero, a constraint on the velocities. Its multiplier
    /// is the edge's sideways force.
    ///
    /// ```
    /// use lagrange::models::ChaplyginSleigh;
    /// use lagrange::prelude::*;
    ///
    /// let sleigh = ChaplyginSleigh::new(2.0, 0.3, 0.4);
    /// let (q0, v0) = sleigh.state(0.5, 1.5); // speed 0.5 m/s, turning at 1.5 rad/s
    /// let run = Dop853::new().rtol(1e-12).atol(1e-12).integrate(&sleigh, 0.0, q0, v0, &[3.0])?;
    /// let end = run.last().unwrap();
    /// let (v, omega) = sleigh.closed_form(0.5, 1.5, 3.0);
    /// assert!((ChaplyginSleigh::speed(&end.q, &end.qdot) - v).abs() < 1e-9);
    /// assert!((end.qdot[2] - omega).abs() < 1e-9);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub struct ChaplyginSleigh {
        coordinates: x, y, theta;
        parameters: m, i, a;
        kinetic: m/2*(dot(x)^2 + dot(y)^2) + i/2*dot(theta)^2;
        potential: 0;
        constraints: edge: cos(theta)*dot(y) - sin(theta)*dot(x) = a*dot(theta);
    }
}

impl ChaplyginSleigh {
    /// A state at the origin heading along `x`, moving forward at `speed`
    /// and turning at `turning` (the edge's constraint holding).
    pub fn state(&self, speed: f64, turning: f64) -> (Vector3<f64>, Vector3<f64>) {
        (
            Vector3::zeros(),
            Vector3::new(speed, self.a * turning, turning),
        )
    }

    /// The forward speed of the mass centre, `cos θ ẋ + sin θ ẏ`.
    pub fn speed(q: &Vector3<f64>, qdot: &Vector3<f64>) -> f64 {
        q[2].cos() * qdot[0] + q[2].sin() * qdot[1]
    }

    /// The speed `v` and turning rate `ω` at `t` from `(v0, ω0)`: with
    /// `J = i + m a²`, the equations `v̇ = a ω²`, `J ω̇ = −m a v ω` keep the
    /// energy `½ m v² + ½ J ω²`, so with `V² = v0² + J ω0² / m` and
    /// `λ = m a V / J`, `v = V tanh(λ t + c)` and
    /// `ω = ω0 cosh c / cosh(λ t + c)`, `tanh c = v0 / V` (`|v0| < V`, i.e.
    /// `ω0 ≠ 0`).
    pub fn closed_form(&self, v0: f64, w0: f64, t: f64) -> (f64, f64) {
        let j = self.i + self.m * self.a * self.a;
        let speed = (v0 * v0 + j * w0 * w0 / self.m).sqrt();
        let lambda = self.m * self.a * speed / j;
        let c = (v0 / speed).atanh();
        (
            speed * (lambda * t + c).tanh(),
            w0 * c.cosh() / (lambda * t + c).cosh(),
        )
    }
}
