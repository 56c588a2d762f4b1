//! A pendulum swinging against a wall: impacts on a nonlinear motion, whose
//! arcs between impacts are exact pendulum swings (Jacobi elliptic
//! functions), so that the impact times have an answer independent of any
//! integrator.

use lagrange_runtime::events::Event;
use nalgebra::SVector;

/// A wall at the angle `-beta` (`beta > 0`: left of the lowest point) that
/// a [`Pendulum`](super::Pendulum) hits, bouncing back with its angular velocity reversed
/// and scaled by the restitution `e`.
///
/// Released from rest at `A > beta`, the pendulum swings through the
/// bottom, hits the wall at `−β`, and swings back with the amplitude
/// [`amplitude_after`](PendulumWall::amplitude_after) from energy; every
/// arc between impacts is the swing of a pendulum released from rest at
/// that amplitude, run forward and back. Impacts never accumulate: the
/// amplitude falls towards `β`, where an arc lasts a full period.
///
/// ```
/// use lagrange::models::{Pendulum, PendulumWall};
/// use lagrange::prelude::*;
/// use lagrange::nalgebra::Vector1;
///
/// let pendulum = Pendulum::new(1.0, 1.0, 9.81);
/// let wall = PendulumWall { beta: 0.2, restitution: 0.8 };
/// let events = Events::new().with(wall.event());
/// let run = Dop853::new().rtol(1e-10).atol(1e-10).integrate_with_events(
///     &pendulum, 0.0, Vector1::new(1.0), Vector1::new(0.0), &[5.0], &events,
/// )?;
/// let first = &run.events()[0];
/// assert!((first.q[0] + 0.2).abs() < 1e-12); // at the wall
/// let (_, rebound) = first.after.unwrap();
/// assert!((rebound[0] + 0.8 * first.qdot[0]).abs() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PendulumWall {
    /// The wall's angle below the pivot, on the negative side: the wall is
    /// at `θ = −beta`.
    pub beta: f64,
    /// The coefficient of restitution, `θ̇⁺ = −e θ̇⁻`.
    pub restitution: f64,
}

impl PendulumWall {
    /// The impact: `θ + β` falling through zero, the velocity reversed.
    pub fn event(&self) -> Event<'static, f64, 1> {
        let (beta, e) = (self.beta, self.restitution);
        let gap = move |_t: f64, q: &SVector<f64, 1>, _qdot: &SVector<f64, 1>| q[0] + beta;
        Event::new("wall", gap)
            .falling()
            .reset(move |_t, q, qdot| (*q, -e * qdot))
    }

    /// The amplitude after an impact at amplitude `a`: energy conservation
    /// on both sides of the impact, `θ̇² = 2 ω₀² (cos θ − cos a)`, with
    /// `θ̇⁺ = −e θ̇⁻` at `θ = −β`, so
    /// `cos a⁺ = cos β − e² (cos β − cos a)`.
    pub fn amplitude_after(&self, a: f64) -> f64 {
        let cos_beta = self.beta.cos();
        let e2 = self.restitution * self.restitution;
        (cos_beta - e2 * (cos_beta - a.cos())).acos()
    }
}
