//! A ball bouncing on a floor: the event problem with a closed form, its
//! bounce times, and the Zeno limit where infinitely many bounces
//! accumulate in finite time.

use lagrange_runtime::events::Event;
use nalgebra::SVector;

use crate::lagrangian;

lagrangian! {
    /// A ball of mass `m` in one dimension, height `z` above the floor,
    /// under gravity `g`: `z̈ = −g`. The floor is an event
    /// ([`BouncingBall::floor`]), not part of the Lagrangian.
    ///
    /// ```
    /// use lagrange::models::BouncingBall;
    /// use lagrange::prelude::*;
    /// use lagrange::nalgebra::Vector1;
    ///
    /// let ball = BouncingBall::new(1.0, 9.81);
    /// let events = Events::new().with(BouncingBall::floor(0.9));
    /// let run = Dopri5::new()
    ///     .integrate_with_events(&ball, 0.0, Vector1::new(1.0), Vector1::new(0.0), &[3.0], &events)?;
    /// let exact = ball.bounce_times(1.0, 0.9, 3);
    /// for (bounce, t) in run.events().iter().zip(exact) {
    ///     assert!((bounce.t - t).abs() < 1e-12 * t);
    /// }
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub struct BouncingBall {
        coordinates: z;
        parameters: m, g;
        kinetic: m/2*dot(z)^2;
        potential: m*g*z;
    }
}

impl BouncingBall<f64> {
    /// The floor `z = 0`, met falling: the velocity reversed and scaled by
    /// the coefficient of restitution `e` (`ż⁺ = −e ż⁻`).
    pub fn floor(restitution: f64) -> Event<'static, f64, 1> {
        let height = |_t: f64, q: &SVector<f64, 1>, _qdot: &SVector<f64, 1>| q[0];
        Event::new("floor", height)
            .falling()
            .reset(move |_t, q, qdot| (*q, -restitution * qdot))
    }

    /// The time of the first fall from rest at height `h`: `√(2h/g)`.
    pub fn first_landing(&self, h: f64) -> f64 {
        (2.0 * h / self.g).sqrt()
    }

    /// The first `n` bounce times after a release from rest at height `h`,
    /// restitution `e`: `t₁ = √(2h/g)` and flights of `2 t₁ eᵏ` between
    /// bounce `k` and `k + 1`, summed in order (each time to a few ulps).
    pub fn bounce_times(&self, h: f64, e: f64, n: usize) -> Vec<f64> {
        let t1 = self.first_landing(h);
        let (mut t, mut flight) = (t1, 2.0 * t1);
        (0..n)
            .map(|_| {
                let bounce = t;
                flight *= e;
                t += flight;
                bounce
            })
            .collect()
    }

    /// The time the bounces accumulate at, the ball then at rest:
    /// `t∞ = t₁ (1 + 2e / (1 − e))`, the sum of all the flights.
    pub fn rest_time(&self, h: f64, e: f64) -> f64 {
        self.first_landing(h) * (1.0 + 2.0 * e / (1.0 - e))
    }
}
